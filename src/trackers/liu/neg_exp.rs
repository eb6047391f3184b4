//! exp(-a) for a >= 0 in f32, for the kernel sums' inner loops: the same operations in a
//! scalar form and in four lanes ([`F32x4`]), so both give the same bits on every target.
//!
//! exp(-a) = 2^(-y) with y = a log2(e), split as 2^(-n) 2^(-f) with n the integer nearest y,
//! f = y - n in [-1/2, 1/2] ([`F32x4::pow2_neg_round`]): 2^(-n) is built from its exponent bits
//! and 2^(-f) is a degree-3 polynomial fitted to it for the least largest relative error on
//! [-1/2, 1/2] (Lawson's iteration, coefficients rounded to f32): an approximation, 7.5e-5
//! relative evaluated in f32, and the rounding of y adds at most 3e-6 at a = 32 (tested: 8e-5
//! over [0, 32)). (The degree-4 polynomial before it was within 5e-6 and the table with
//! linear interpolation before that within 3.1e-5; all are far below the kernels' own
//! modelling error: the kernel widths are the paper's guesses, and 1e-4 of a weight moves no
//! estimate.) The kernel sums call [`neg_exp2`] / [`neg_exp2_x4`] with y itself, log2(e)
//! folded into their constants. From a = 32 on (exp(-32) = 1.3e-14, a pixel's kernel
//! product is negligible next to any pixel near the boundary) the value is 0, as the table's
//! was; so is a NaN's. The split avoids the table's four scalar reads per four lanes, and a
//! conversion instruction (WebAssembly engines emulate the saturating one in several).

use super::lanes::F32x4;
use std::ops::{Add, Mul, Sub};

/// Largest argument with a nonzero value.
pub const RANGE: f32 = 32.0;

/// 1.5 2^23: y + ROUNDER has the integer nearest y in its last mantissa bits (|y| < 2^22).
const ROUNDER: f32 = 12_582_912.0;
/// log2(e) in f32.
pub const LOG2_E: f32 = std::f32::consts::LOG2_E;
/// 2^(-f) ~= C[0] + f (C[1] + f (C[2] + f C[3])) on [-1/2, 1/2].
const C: [f32; 4] = [0.999_928_06, -0.693_260_97, 0.242_611_17, -0.055_171_68];
/// Largest base-2 argument with a nonzero value of [`neg_exp2`]: `RANGE` log2(e) (in f32).
pub const RANGE2: f32 = RANGE * LOG2_E;

/// exp(-a) for 0 <= a < 32, 0 from 32 on and for NaN: [`neg_exp2`] of a log2(e).
#[inline]
pub fn neg_exp(a: f32) -> f32 {
    neg_exp2(a * LOG2_E)
}

/// 2^(-y) for 0 <= y < [`RANGE2`] (the argument already in base 2: a caller that folds
/// log2(e) into its own constants saves the multiplication), 0 from `RANGE2` on and for NaN.
#[inline]
pub fn neg_exp2(y: f32) -> f32 {
    if y.is_nan() || y >= RANGE2 {
        return 0.0;
    }
    // The integer n nearest y (ties to even), as `F32x4::pow2_neg_round` finds it.
    let t = y + ROUNDER;
    let n = t.to_bits().wrapping_sub(ROUNDER.to_bits());
    let f = y - (t - ROUNDER);
    let p = C[0] + f * (C[1] + f * (C[2] + f * C[3]));
    p * f32::from_bits(127u32.wrapping_sub(n) << 23)
}

/// [`neg_exp`] of four lanes, by the same operations lane by lane.
#[inline]
pub fn neg_exp_x4(a: F32x4) -> F32x4 {
    neg_exp2_x4(a.mul(F32x4::splat(LOG2_E)))
}

/// [`neg_exp2`] of four lanes, by the same operations lane by lane.
#[inline]
pub fn neg_exp2_x4(y: F32x4) -> F32x4 {
    NegExp2Lanes::splat().eval(y)
}

/// The constants of [`neg_exp2_x4`] (and of the orientation fold) as lanes, made once before
/// a loop and passed through [`std::hint::black_box`]: otherwise they are constants at every
/// use, which WebAssembly engines may build anew in each iteration. The same operations, so
/// the same bits.
#[derive(Clone, Copy, Debug)]
pub struct NegExp2Lanes {
    c: [F32x4; 4],
    range: F32x4,
    rounder: F32x4,
    bias: F32x4,
    /// 1 / pi and pi, for the orientation fold of the kernels.
    pub frac_1_pi: F32x4,
    /// pi.
    pub pi: F32x4,
}

impl NegExp2Lanes {
    /// The constants, as values the compiler cannot see through (once per kernel batch).
    #[inline]
    pub fn opaque() -> Self {
        std::hint::black_box(Self::splat())
    }

    #[inline]
    fn splat() -> Self {
        Self {
            c: C.map(F32x4::splat),
            range: F32x4::splat(RANGE2),
            rounder: F32x4::splat(ROUNDER),
            bias: F32x4::splat(f32::from_bits(127)),
            frac_1_pi: F32x4::splat(std::f32::consts::FRAC_1_PI),
            pi: F32x4::splat(std::f32::consts::PI),
        }
    }

    /// 1.5 2^23 in every lane ([`F32x4::round_small_by`]).
    #[inline]
    pub fn rounder(&self) -> F32x4 {
        self.rounder
    }

    /// 2^(-y) for each lane, as [`neg_exp2`].
    #[inline]
    pub fn eval(&self, y: F32x4) -> F32x4 {
        let (n, scale) = y.pow2_neg_round_by(self.rounder, self.bias);
        let f = y.sub(n);
        let c = self.c;
        let p = c[0].add(f.mul(c[1].add(f.mul(c[2].add(f.mul(c[3]))))));
        // Lanes at or beyond the range (or NaN) computed garbage: 0 there (the mask's bits
        // and-ed with the value: all ones keep it, zeros give +0).
        y.lt(self.range) & p.mul(scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math;

    #[test]
    fn matches_exp_to_the_polynomial_bound() {
        let mut worst: f64 = 0.0;
        for k in 0..200_000 {
            let a = k as f32 * RANGE / 200_000.0;
            let exact = math::exp(-f64::from(a));
            worst = worst.max((f64::from(neg_exp(a)) - exact).abs() / exact);
        }
        assert!(worst <= 8e-5, "{worst}");
        assert_eq!(neg_exp(RANGE), 0.0);
        assert_eq!(neg_exp(40.0), 0.0);
        assert_eq!(neg_exp(f32::NAN), 0.0);
        assert_eq!(neg_exp(f32::INFINITY), 0.0);
    }

    #[test]
    fn the_lanes_give_the_scalar_bits() {
        for k in 0..20_000 {
            let a = [0.0, 1.0, 2.0, 3.0].map(|j: f32| (k as f32 * 4.0 + j) * 0.0004);
            let v = neg_exp_x4(F32x4::from_array(a)).to_array();
            for j in 0..4 {
                assert_eq!(v[j].to_bits(), neg_exp(a[j]).to_bits(), "{}", a[j]);
            }
        }
        for k in 0..20_000 {
            let y = [0.0, 1.0, 2.0, 3.0].map(|j: f32| (k as f32 * 4.0 + j) * 0.000_6);
            let v = neg_exp2_x4(F32x4::from_array(y)).to_array();
            for j in 0..4 {
                assert_eq!(v[j].to_bits(), neg_exp2(y[j]).to_bits(), "{}", y[j]);
            }
        }
        let odd2 = [f32::NAN, RANGE2, 1e12, f32::INFINITY];
        assert_eq!(neg_exp2_x4(F32x4::from_array(odd2)).to_array(), [0.0; 4]);
        let odd = [f32::NAN, RANGE, 1e12, f32::INFINITY];
        assert_eq!(neg_exp_x4(F32x4::from_array(odd)).to_array(), [0.0; 4]);
    }
}
