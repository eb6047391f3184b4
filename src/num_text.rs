//! Text for numbers in messages, without core's float formatting.
//!
//! Rust's `{}`, `{:?}`, `{:e}` and `{:.N}` of an `f64` bring core's shortest and exact
//! float-to-decimal conversions (Grisu with a Dragon fallback and their big-number tables) into
//! the wasm: 24 kB of the main module raw, 10 kB gzip -9 (2026-11-28), there only for the values
//! named in error messages. [`Num`], [`Fixed`] and [`Exp`] write those values with a little
//! integer arithmetic instead. Their text is for a person, not for reading back exactly: six
//! significant digits at most. Every `f64` (or `f32`) formatted into a message by code in the
//! wasm goes through them; one `{}` of an `f64` there brings the 24 kB back, which
//! `scripts/build-pkg.sh` refuses.

use std::fmt;

/// An `f64` as a message shows it: integers as integers (`2`, `-3`, `0`, also for `-0.0`) up
/// to 1e15, other values to 6 significant digits with trailing zeros trimmed, in plain decimals
/// from 1e-4 up to 1e15 (`0.15`, `3.14159`, `0.0001`) and with an exponent otherwise (`1e300`,
/// `1.5e-7`, `-2.25e20`); `NaN`, `inf` and `-inf` as Rust writes them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

/// An `f64` as [`Num`] writes it, but always with an exponent (what `{:e}` writes, to 6
/// significant digits): `1e6`, `2.5e-3`, `0e0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exp(pub f64);

/// An `f64` with exactly `self.1` decimals, as `{:.N}` writes it but for halves: `x * 10^N`
/// rounded in `f64` arithmetic, halves away from zero (`Fixed(0.15, 1)` is `0.2`, where core
/// rounds the binary value 0.1499... to `0.1`). Values with `|x| * 10^N` from 9e15 up (and
/// more than 30 decimals) as [`Num`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fixed(pub f64, pub usize);

/// Room for any text written here: a sign, 16 digits and up to 31 zeros, a point.
const CAP: usize = 56;

/// Text built right to left in a fixed buffer.
struct Buf {
    bytes: [u8; CAP],
    start: usize,
}

impl Buf {
    fn new() -> Self {
        Buf {
            bytes: [0; CAP],
            start: CAP,
        }
    }

    fn push(&mut self, b: u8) {
        self.start -= 1;
        self.bytes[self.start] = b;
    }

    /// The decimal digits of `n`, at least `min` of them (zeros in front).
    fn push_digits(&mut self, mut n: u64, min: usize) {
        let mut count = 0;
        while n > 0 || count < min.max(1) {
            self.push(b'0' + (n % 10) as u8);
            n /= 10;
            count += 1;
        }
    }

    fn as_str(&self) -> &str {
        // Only ASCII digits, signs, points and `e` are pushed.
        std::str::from_utf8(&self.bytes[self.start..]).unwrap_or("?")
    }
}

/// Writes `s`, padded to the formatter's width if it has one.
fn emit(f: &mut fmt::Formatter<'_>, s: &str) -> fmt::Result {
    if f.precision().is_none() {
        f.pad(s)
    } else {
        f.write_str(s)
    }
}

/// `NaN`, `inf` or `-inf` for a value that is not finite.
fn not_finite(x: f64) -> Option<&'static str> {
    if x.is_nan() {
        Some("NaN")
    } else if x == f64::INFINITY {
        Some("inf")
    } else if x == f64::NEG_INFINITY {
        Some("-inf")
    } else {
        None
    }
}

/// `a * 10^k` for finite `a > 0`, in two steps where one power would overflow or underflow.
fn scale(a: f64, k: i32) -> f64 {
    if k > 300 {
        a * 1e300 * 10f64.powi(k - 300)
    } else if k >= 0 {
        a * 10f64.powi(k)
    } else if k >= -300 {
        a / 10f64.powi(-k)
    } else {
        a / 1e300 / 10f64.powi(-k - 300)
    }
}

/// The 6 significant digits of finite `a > 0` as an integer in 100 000..=999 999 and the
/// decimal exponent of its first digit: `a` is about `digits * 10^(exp - 5)`.
fn six_digits(a: f64) -> (u64, i32) {
    // log10 of a normal number from its binary exponent, within one of the decimal exponent.
    let bits = a.to_bits();
    let binary = ((bits >> 52) & 0x7ff) as i32;
    let mut exp = if binary == 0 {
        // Subnormal: below 2.3e-308.
        -316
    } else {
        (((binary - 1023) as f64) * std::f64::consts::LOG10_2).floor() as i32
    };
    // At most 9 steps (from a subnormal's first guess); the bound only guards the loop.
    let mut m = 0.0;
    for _ in 0..16 {
        m = (scale(a, 5 - exp) + 0.5).floor();
        if m >= 1_000_000.0 {
            exp += 1;
        } else if m < 100_000.0 {
            exp -= 1;
        } else {
            break;
        }
    }
    ((m as u64).clamp(100_000, 999_999), exp)
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        general(f, self.0, false)
    }
}

impl fmt::Display for Exp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        general(f, self.0, true)
    }
}

/// [`Num`]'s text, or with `exponent` always [`Exp`]'s.
fn general(f: &mut fmt::Formatter<'_>, x: f64, exponent: bool) -> fmt::Result {
    if let Some(s) = not_finite(x) {
        return emit(f, s);
    }
    let a = x.abs();
    let mut buf = Buf::new();
    if a == 0.0 && exponent {
        return emit(f, "0e0");
    }
    if a < 1e15 && a == a.floor() && !exponent {
        buf.push_digits(a as u64, 1);
        if x < 0.0 {
            buf.push(b'-');
        }
        return emit(f, buf.as_str());
    }
    let (mut digits, exp) = six_digits(a);
    let mut count = 6;
    while digits % 10 == 0 {
        digits /= 10;
        count -= 1;
    }
    if (-4..15).contains(&exp) && !exponent {
        if exp >= count - 1 {
            // Whole (only from 1e5 up, where six digits end before the point).
            for _ in 0..exp - (count - 1) {
                buf.push(b'0');
            }
            buf.push_digits(digits, 1);
        } else if exp >= 0 {
            let after = (count - 1 - exp) as u32;
            let p = 10u64.pow(after);
            buf.push_digits(digits % p, after as usize);
            buf.push(b'.');
            buf.push_digits(digits / p, 1);
        } else {
            buf.push_digits(digits, count as usize);
            for _ in 0..-exp - 1 {
                buf.push(b'0');
            }
            buf.push(b'.');
            buf.push(b'0');
        }
    } else {
        buf.push_digits(u64::from(exp.unsigned_abs()), 1);
        if exp < 0 {
            buf.push(b'-');
        }
        buf.push(b'e');
        if count > 1 {
            let p = 10u64.pow((count - 1) as u32);
            buf.push_digits(digits % p, (count - 1) as usize);
            buf.push(b'.');
            buf.push_digits(digits / p, 1);
        } else {
            buf.push_digits(digits, 1);
        }
    }
    if x < 0.0 {
        buf.push(b'-');
    }
    emit(f, buf.as_str())
}

impl fmt::Display for Fixed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Fixed(x, decimals) = *self;
        if let Some(s) = not_finite(x) {
            return emit(f, s);
        }
        let scaled = scale(x.abs(), decimals as i32);
        if decimals > 30 || scaled >= 9e15 {
            return Num(x).fmt(f);
        }
        let m = (scaled + 0.5).floor() as u64;
        let mut buf = Buf::new();
        // All of m's digits and at least one before the point.
        let mut rest = m;
        for _ in 0..decimals {
            buf.push(b'0' + (rest % 10) as u8);
            rest /= 10;
        }
        if decimals > 0 {
            buf.push(b'.');
        }
        buf.push_digits(rest, 1);
        if x.is_sign_negative() {
            buf.push(b'-');
        }
        emit(f, buf.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(x: f64) -> String {
        Num(x).to_string()
    }

    #[test]
    fn writes_numbers_as_messages_show_them() {
        let cases: &[(f64, &str)] = &[
            (0.15, "0.15"),
            (0.1 + 0.2, "0.3"),
            (2.0, "2"),
            (-3.0, "-3"),
            (0.0, "0"),
            (-0.0, "0"),
            (1e300, "1e300"),
            (1.5e-7, "1.5e-7"),
            (-2.25e20, "-2.25e20"),
            (123456.7, "123457"),
            (999999.5, "1000000"),
            (999999.4, "999999"),
            (0.000123456, "0.000123456"),
            (0.0001, "0.0001"),
            (0.00009999999, "0.0001"),
            (0.00001, "1e-5"),
            (std::f64::consts::PI, "3.14159"),
            (4.56789123, "4.56789"),
            (1.23456789e-3, "0.00123457"),
            (-0.95, "-0.95"),
            (12.5, "12.5"),
            (1234.5678, "1234.57"),
            (99.99999, "100"),
            (9.9999996, "10"),
            (0.5, "0.5"),
            (1e15, "1e15"),
            (999999999999999.0, "999999999999999"),
            (123456789.0, "123456789"),
            (1.0e16, "1e16"),
            (1.2345678e17, "1.23457e17"),
            (f64::MAX, "1.79769e308"),
            (f64::MIN_POSITIVE, "2.22507e-308"),
            (5e-324, "4.94066e-324"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (std::f64::consts::PI * 1e-10, "3.14159e-10"),
        ];
        for &(x, text) in cases {
            assert_eq!(num(x), text, "{x:e}");
        }
    }

    #[test]
    fn writes_exponents() {
        for (x, text) in [
            (1e6, "1e6"),
            (1e-9, "1e-9"),
            (0.0025, "2.5e-3"),
            (-123456789.0, "-1.23457e8"),
            (0.0, "0e0"),
            (f64::NAN, "NaN"),
        ] {
            assert_eq!(Exp(x).to_string(), text);
        }
    }

    #[test]
    fn writes_fixed_decimals() {
        let cases: &[(f64, usize, &str)] = &[
            (0.15, 1, "0.2"),
            (2.0, 0, "2"),
            (2.5, 0, "3"),
            (-3.0, 2, "-3.00"),
            (0.1 + 0.2, 3, "0.300"),
            (123456.7, 1, "123456.7"),
            (0.000123456, 4, "0.0001"),
            (-0.001, 2, "-0.00"),
            (1e300, 2, "1e300"),
            (f64::NAN, 2, "NaN"),
            (f64::NEG_INFINITY, 1, "-inf"),
            (1.5e-7, 10, "0.0000001500"),
        ];
        for &(x, n, text) in cases {
            assert_eq!(Fixed(x, n).to_string(), text, "{x:e} {n}");
        }
    }

    #[test]
    fn honours_width() {
        assert_eq!(format!("{:>6}", Num(1.5)), "   1.5");
        assert_eq!(format!("{:<5}|", Fixed(2.0, 1)), "2.0  |");
    }

    /// A 64-bit linear congruential generator (Knuth's MMIX constants).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            self.0
        }

        /// In [0, 1).
        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn num_reads_back_within_six_digits() {
        let mut rng = Lcg(0x5eed);
        for i in 0..5000 {
            let x = match i % 3 {
                // Any bit pattern that is a finite number.
                0 => f64::from_bits(rng.next()),
                // Decimals of every size.
                1 => (rng.unit() - 0.5) * 10f64.powi((rng.next() % 40) as i32 - 20),
                // Whole numbers and near-whole ones.
                _ => {
                    ((rng.next() % 2_000_001) as f64 - 1e6)
                        * if i % 2 == 0 { 1.0 } else { 1.0 + 1e-9 }
                }
            };
            if !x.is_finite() {
                continue;
            }
            let text = num(x);
            let back: f64 = text.parse().unwrap_or_else(|_| panic!("{text} from {x:e}"));
            let error = if x == 0.0 {
                back.abs()
            } else {
                ((back - x) / x).abs()
            };
            assert!(error <= 1e-5, "{x:e} written {text}");
        }
    }

    #[test]
    fn fixed_matches_core_for_moderate_values() {
        let mut rng = Lcg(17);
        for _ in 0..5000 {
            let x = (rng.unit() - 0.5) * 10f64.powi((rng.next() % 9) as i32 - 4);
            let n = (rng.next() % 6) as usize;
            assert_eq!(Fixed(x, n).to_string(), format!("{x:.n$}"), "{x:e} {n}");
        }
    }
}
