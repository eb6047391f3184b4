//! exp(-a) for a >= 0 by a table with linear interpolation, for the kernel sums' inner loops.
//!
//! Nodes every h = 1/64 on [0, 32]; between nodes the chord of a convex function overestimates
//! it by at most h^2 / 8 relative (3.1e-5): far below the kernels' own modelling error.
//! From a = 32 on (exp(-32) = 1.3e-14, a pixel's kernel product is negligible next to any pixel
//! near the boundary) the value is 0. The table is filled with `crate::math::exp` and read with
//! plain arithmetic, so the results are bit-identical natively and in wasm.

use super::lanes::F32x4;
use crate::math;
use std::ops::{Add, Mul, Sub};

/// Largest tabulated argument.
pub const RANGE: f64 = 32.0;
/// Table nodes per unit of the argument.
const PER_UNIT: f64 = 64.0;

/// Table entries: the nodes i h for i < 32 / h, and the (0, 0) entry at a = 32.
const LEN: usize = RANGE as usize * PER_UNIT as usize + 1;
/// The index of the last entry (a clamped index is at most this, so reads need no bounds check).
const LAST: u32 = LEN as u32 - 1;

/// The table.
#[derive(Debug, Clone)]
pub struct ExpTable {
    /// (exp(-i h), exp(-(i + 1) h) - exp(-i h)) per node i; the last entry, at a = 32, is
    /// (0, 0) so that every larger argument reads 0 without a branch. (Fixed-size, so that an
    /// index clamped to [`LAST`] reads without a bounds check.)
    segments: Box<[[f64; 2]; LEN]>,
    /// The same in f32, for the parabolic sums.
    segments32: Box<[[f32; 2]; LEN]>,
}

impl Default for ExpTable {
    fn default() -> Self {
        let node = |i: usize| math::exp(-(i as f64) / PER_UNIT);
        let mut segments = Box::new([[0.0f64; 2]; LEN]);
        let mut segments32 = Box::new([[0.0f32; 2]; LEN]);
        for i in 0..LEN - 1 {
            segments[i] = [node(i), node(i + 1) - node(i)];
            let (a, b) = (node(i) as f32, node(i + 1) as f32);
            segments32[i] = [a, b - a];
        }
        Self {
            segments,
            segments32,
        }
    }
}

impl ExpTable {
    /// exp(-a) for a >= 0 (0 from a = 32 on; NaN stays NaN).
    #[inline]
    pub fn neg_exp(&self, a: f64) -> f64 {
        let t = a * PER_UNIT;
        // `as` saturates: negative and NaN arguments give 0, huge ones the last entry. (A u32
        // index converts in a few instructions, a usize one in many; the value is the same.)
        let i = (t as u32).min(LAST);
        let [value, slope] = self.segments[i as usize];
        value + (t - f64::from(i)) * slope
    }
}

impl ExpTable {
    /// [`ExpTable::neg_exp`] in f32 (the interpolation bound holds to f32 rounding).
    #[inline]
    pub fn neg_exp32(&self, a: f32) -> f32 {
        let t = a * PER_UNIT as f32;
        let i = (t as u32).min(LAST);
        let [value, slope] = self.segments32[i as usize];
        value + (t - i as f32) * slope
    }

    /// [`ExpTable::neg_exp32`] of the first three lanes of a WebAssembly SIMD vector, by the
    /// same operations lane by lane (the fourth lane of the answer is unspecified).
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    #[inline]
    pub fn neg_exp_v3(&self, a: core::arch::wasm32::v128) -> core::arch::wasm32::v128 {
        use core::arch::wasm32::*;
        let t = f32x4_mul(a, f32x4_splat(PER_UNIT as f32));
        // `as u32` saturates as this conversion does (negative and NaN give 0).
        let i = u32x4_min(u32x4_trunc_sat_f32x4(t), u32x4_splat(LAST));
        let entry = |k: u32| self.segments32[k.min(LAST) as usize];
        let (s0, s1, s2) = (
            entry(u32x4_extract_lane::<0>(i)),
            entry(u32x4_extract_lane::<1>(i)),
            entry(u32x4_extract_lane::<2>(i)),
        );
        let frac = f32x4_sub(t, f32x4_convert_u32x4(i));
        f32x4_add(
            f32x4(s0[0], s1[0], s2[0], 0.0),
            f32x4_mul(frac, f32x4(s0[1], s1[1], s2[1], 0.0)),
        )
    }

    /// [`ExpTable::neg_exp32`] of four lanes, by the same operations lane by lane (the index
    /// and its f32 value are exact; the table read is one scalar load per lane).
    #[inline]
    pub fn neg_exp_x4(&self, a: F32x4) -> F32x4 {
        let t = a.mul(F32x4::splat(PER_UNIT as f32));
        let (i, i_f32) = t.index_below(LAST);
        let [s0, s1, s2, s3] = i.map(|k| self.segments32[(k.min(LAST)) as usize]);
        let frac = t.sub(i_f32);
        F32x4::from_array([s0[0], s1[0], s2[0], s3[0]])
            .add(frac.mul(F32x4::from_array([s0[1], s1[1], s2[1], s3[1]])))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_exp_to_the_interpolation_bound() {
        let table = ExpTable::default();
        let mut worst: f64 = 0.0;
        for k in 0..100_000 {
            let a = k as f64 * RANGE / 100_000.0;
            let exact = math::exp(-a);
            worst = worst.max((table.neg_exp(a) - exact).abs() / exact);
        }
        // The chord bound h^2 / 8, to first order in h (the exact maximum is a hair above).
        assert!(worst <= 1.01 / (8.0 * PER_UNIT * PER_UNIT), "{worst}");
        assert_eq!(table.neg_exp(0.0), 1.0);
        assert_eq!(table.neg_exp(40.0), 0.0);
        assert_eq!(table.neg_exp(32.0), 0.0);
        assert!(table.neg_exp(f64::NAN).is_nan());
        let mut worst32: f64 = 0.0;
        for k in 0..100_000 {
            let a = k as f32 * RANGE as f32 / 100_000.0;
            let exact = math::exp(-f64::from(a));
            worst32 = worst32.max((f64::from(table.neg_exp32(a)) - exact).abs() / exact);
        }
        // The chord bound plus f32 rounding of the table and of the interpolation.
        assert!(
            worst32 <= 1.01 / (8.0 * PER_UNIT * PER_UNIT) + 1e-6,
            "{worst32}"
        );
        assert_eq!(table.neg_exp32(0.0), 1.0);
        assert_eq!(table.neg_exp32(40.0), 0.0);
    }
}
