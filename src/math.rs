//! Portable floating-point maths.
//!
//! `f64::exp`, `ln`, `sin`, ... call the platform's libm natively and a different implementation in
//! WebAssembly, so results may differ in the last bit between targets. lanepf promises that the
//! same seed gives bit-identical particles natively and in the browser, so the core calls these
//! wrappers over the pure-Rust `libm` crate, which is the same code on every target. `sqrt`,
//! `abs`, `floor` and the arithmetic operators are exact in IEEE 754 and are used directly.
//! `clippy.toml` forbids the std transcendental methods so that this stays true.

/// e^x.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}
/// Natural logarithm.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}
/// ln(1 + x), accurate for small x.
#[inline]
pub fn ln_1p(x: f64) -> f64 {
    libm::log1p(x)
}
/// Sine (radians).
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}
/// Cosine (radians).
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}
/// Tangent (radians).
#[inline]
pub fn tan(x: f64) -> f64 {
    libm::tan(x)
}
/// `x` limited to `lo..=hi`, as `f64::clamp` gives it (NaN stays NaN) but without its check
/// that `lo <= hi` (`hi` then): that check's panic message writes the bounds with `{:?}`, which
/// brings core's float formatting (24 kB raw) into the wasm wherever the bounds are not constants.
#[inline]
pub fn clamp(x: f64, lo: f64, hi: f64) -> f64 {
    let mut x = x;
    if x < lo {
        x = lo;
    }
    if x > hi {
        x = hi;
    }
    x
}
/// Arc tangent of y/x in (-pi, pi].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}
/// Arc tangent.
#[inline]
pub fn atan(x: f64) -> f64 {
    libm::atan(x)
}
/// x^y.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}
/// Hypotenuse sqrt(x^2 + y^2) without undue overflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}
/// Single-precision arc tangent of y/x (for per-pixel gradient orientation).
#[inline]
pub fn atan2f(y: f32, x: f32) -> f32 {
    libm::atan2f(y, x)
}
/// Single-precision arc tangent (liu-ppf's curve orientation per row).
#[inline]
pub fn atanf(x: f32) -> f32 {
    libm::atanf(x)
}
/// Single-precision e^x.
#[inline]
pub fn expf(x: f32) -> f32 {
    libm::expf(x)
}

/// Degrees to radians.
#[inline]
pub fn deg_to_rad(d: f64) -> f64 {
    d * (std::f64::consts::PI / 180.0)
}
/// Radians to degrees.
#[inline]
pub fn rad_to_deg(r: f64) -> f64 {
    r * (180.0 / std::f64::consts::PI)
}

/// Composite Simpson's rule over [a, b] with `n` (even) intervals: the slow reference that
/// tests check closed forms and quadratures against.
#[cfg(test)]
pub(crate) fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for i in 1..n {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + i as f64 * h);
    }
    sum * h / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrappers_agree_with_std_to_a_few_ulp() {
        for i in -50..50 {
            let x = i as f64 * 0.173;
            #[allow(clippy::disallowed_methods)]
            {
                assert!((exp(x) - x.exp()).abs() <= 4.0 * f64::EPSILON * x.exp());
                assert!((sin(x) - x.sin()).abs() <= 1e-15);
                assert!((atan2(x, 1.3) - x.atan2(1.3)).abs() <= 1e-15);
            }
        }
        assert!((deg_to_rad(180.0) - std::f64::consts::PI).abs() < 1e-15);
        assert!((rad_to_deg(deg_to_rad(14.0)) - 14.0).abs() < 1e-12);
    }
}
