//! Four f32 lanes for liu-ppf's kernel sums: SSE2 on x86_64 (every x86_64 CPU has it),
//! `simd128` in WebAssembly (on for every wasm32 build, .cargo/config.toml), four plain floats
//! elsewhere.
//!
//! Every operation is the IEEE operation the scalar code performs, lane by lane (no fused
//! multiply-add, no reordering), and the integer steps of [`F32x4::pow2_neg_round`] are exact,
//! so a sum written with these lanes has the same bits on every target (tests/web.rs compares
//! liu-ppf in Chromium with the native bits). Masks are lanes of all ones (true) or all zeros
//! (false).

/// 1.5 2^23: y + ROUNDER has the integer nearest y in its last mantissa bits (|y| < 2^22).
const ROUNDER: f32 = 12_582_912.0;

/// Four f32 lanes (or a mask of four lanes).
#[derive(Clone, Copy, Debug)]
pub struct F32x4(imp::Raw);

impl F32x4 {
    /// The lanes of `a`.
    #[inline]
    pub fn from_array(a: [f32; 4]) -> Self {
        Self(imp::from_array(a))
    }
    /// The four lanes.
    #[inline]
    pub fn to_array(self) -> [f32; 4] {
        imp::to_array(self.0)
    }
    /// `v` in every lane.
    #[inline]
    pub fn splat(v: f32) -> Self {
        Self(imp::splat(v))
    }
    /// The four floats `v[j..j + 4]` (panics, as slicing does, when they are not all there).
    #[inline]
    pub fn load(v: &[f32], j: usize) -> Self {
        let four = [v[j], v[j + 1], v[j + 2], v[j + 3]];
        Self(imp::load(&four))
    }
    /// The four floats of `four` (one load).
    #[inline]
    pub fn load_array(four: &[f32; 4]) -> Self {
        Self(imp::load(four))
    }
    /// Stores the four lanes in `four` (one store).
    #[inline]
    pub fn store(self, four: &mut [f32; 4]) {
        imp::store(self.0, four);
    }
    /// Mask of `self > b` (false where either is NaN).
    #[inline]
    pub fn gt(self, b: Self) -> Self {
        Self(imp::gt(self.0, b.0))
    }
    /// Mask of `self <= b` (false where either is NaN).
    #[inline]
    pub fn le(self, b: Self) -> Self {
        Self(imp::le(self.0, b.0))
    }
    /// Mask of `self >= b` (false where either is NaN).
    #[inline]
    pub fn ge(self, b: Self) -> Self {
        Self(imp::ge(self.0, b.0))
    }
    /// Lane-wise `if mask { a } else { b }`, `self` being the mask.
    #[inline]
    pub fn select(self, a: Self, b: Self) -> Self {
        Self(imp::select(self.0, a.0, b.0))
    }
    /// Whether every lane of the mask `self` is true.
    #[inline]
    pub fn all(self) -> bool {
        imp::all(self.0)
    }
    /// The lanes of the mask `self` as booleans.
    #[inline]
    pub fn mask_to_array(self) -> [bool; 4] {
        imp::mask_to_array(self.0)
    }
    /// The transpose of the 4 x 4 matrix whose rows are `rows`: lane k of row i becomes lane
    /// i of row k (data movement only).
    #[inline]
    pub fn transpose(rows: [Self; 4]) -> [Self; 4] {
        imp::transpose(rows.map(|r| r.0)).map(Self)
    }
    /// Mask of `self < b` (false where either is NaN).
    #[inline]
    pub fn lt(self, b: Self) -> Self {
        Self(imp::lt(self.0, b.0))
    }
    /// For lanes in (-2^22, 2^22): the integer nearest (ties to even), by the IEEE sum and
    /// difference with 1.5 2^23 (exact). Other lanes give unspecified values.
    #[inline]
    pub fn round_small(self) -> Self {
        self.round_small_by(Self::splat(ROUNDER))
    }
    /// [`F32x4::round_small`] with `rounder` = 1.5 2^23 in every lane given.
    #[inline]
    pub fn round_small_by(self, rounder: Self) -> Self {
        Self(imp::sub(imp::add(self.0, rounder.0), rounder.0))
    }
    /// For lanes y in (-2^22, 2^22): (n, 2^-n) with n the integer nearest y (ties to even),
    /// both exact (-126 <= n <= 126 for 2^-n to be a normal float), by the IEEE sum y + 1.5 2^23,
    /// whose last mantissa bits are then n, not by a conversion (which WebAssembly engines
    /// emulate in several instructions). Other lanes give unspecified values.
    #[inline]
    pub fn pow2_neg_round(self) -> (Self, Self) {
        self.pow2_neg_round_by(Self::splat(ROUNDER), Self::splat(f32::from_bits(127)))
    }
    /// [`F32x4::pow2_neg_round`] with its constants given as lanes: `rounder` 1.5 2^23 and
    /// `bias` the bits of the integer 127 in every lane (for loops that make them once).
    #[inline]
    pub fn pow2_neg_round_by(self, rounder: Self, bias: Self) -> (Self, Self) {
        let (n, scale) = imp::pow2_neg_round(self.0, rounder.0, bias.0);
        (Self(n), Self(scale))
    }
}

impl std::ops::Add for F32x4 {
    type Output = Self;
    /// Lane-wise `self + b`.
    #[inline]
    fn add(self, b: Self) -> Self {
        Self(imp::add(self.0, b.0))
    }
}

impl std::ops::Sub for F32x4 {
    type Output = Self;
    /// Lane-wise `self - b`.
    #[inline]
    fn sub(self, b: Self) -> Self {
        Self(imp::sub(self.0, b.0))
    }
}

impl std::ops::Div for F32x4 {
    type Output = Self;
    /// Lane-wise `self / b`.
    #[inline]
    fn div(self, b: Self) -> Self {
        Self(imp::div(self.0, b.0))
    }
}

impl std::ops::BitAnd for F32x4 {
    type Output = Self;
    /// The bits of `self` and `b`, and-ed.
    #[inline]
    fn bitand(self, b: Self) -> Self {
        Self(imp::and(self.0, b.0))
    }
}

impl std::ops::BitOr for F32x4 {
    type Output = Self;
    /// The bits of `self` and `b`, or-ed.
    #[inline]
    fn bitor(self, b: Self) -> Self {
        Self(imp::or(self.0, b.0))
    }
}

impl std::ops::Mul for F32x4 {
    type Output = Self;
    /// Lane-wise `self * b`.
    #[inline]
    fn mul(self, b: Self) -> Self {
        Self(imp::mul(self.0, b.0))
    }
}

#[cfg(target_arch = "x86_64")]
mod imp {
    use core::arch::x86_64::*;
    pub type Raw = __m128;

    // SAFETY (every block below): SSE2 is part of the x86_64 baseline, so these intrinsics
    // are always available; the loads and stores go through arrays of exactly 16 bytes.
    #[inline]
    pub fn from_array(a: [f32; 4]) -> Raw {
        unsafe { _mm_loadu_ps(a.as_ptr()) }
    }
    #[inline]
    pub fn to_array(v: Raw) -> [f32; 4] {
        let mut a = [0.0f32; 4];
        unsafe { _mm_storeu_ps(a.as_mut_ptr(), v) };
        a
    }
    #[inline]
    pub fn splat(v: f32) -> Raw {
        unsafe { _mm_set1_ps(v) }
    }
    #[inline]
    pub fn load(four: &[f32; 4]) -> Raw {
        unsafe { _mm_loadu_ps(four.as_ptr()) }
    }
    #[inline]
    pub fn store(v: Raw, four: &mut [f32; 4]) {
        unsafe { _mm_storeu_ps(four.as_mut_ptr(), v) }
    }
    #[inline]
    pub fn add(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_add_ps(a, b) }
    }
    #[inline]
    pub fn sub(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_sub_ps(a, b) }
    }
    #[inline]
    pub fn mul(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_mul_ps(a, b) }
    }
    #[inline]
    pub fn div(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_div_ps(a, b) }
    }
    #[inline]
    pub fn and(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_and_ps(a, b) }
    }
    #[inline]
    pub fn or(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_or_ps(a, b) }
    }
    #[inline]
    pub fn gt(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_cmpgt_ps(a, b) }
    }
    #[inline]
    pub fn le(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_cmple_ps(a, b) }
    }
    #[inline]
    pub fn ge(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_cmpge_ps(a, b) }
    }
    #[inline]
    pub fn select(mask: Raw, a: Raw, b: Raw) -> Raw {
        unsafe { _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)) }
    }
    #[inline]
    pub fn all(mask: Raw) -> bool {
        unsafe { _mm_movemask_ps(mask) == 0b1111 }
    }
    #[inline]
    pub fn mask_to_array(mask: Raw) -> [bool; 4] {
        let m = unsafe { _mm_movemask_ps(mask) };
        [m & 1 != 0, m & 2 != 0, m & 4 != 0, m & 8 != 0]
    }
    #[inline]
    pub fn lt(a: Raw, b: Raw) -> Raw {
        unsafe { _mm_cmplt_ps(a, b) }
    }
    #[inline]
    pub fn transpose([r0, r1, r2, r3]: [Raw; 4]) -> [Raw; 4] {
        unsafe {
            let (t0, t1) = (_mm_unpacklo_ps(r0, r1), _mm_unpacklo_ps(r2, r3));
            let (t2, t3) = (_mm_unpackhi_ps(r0, r1), _mm_unpackhi_ps(r2, r3));
            [
                _mm_movelh_ps(t0, t1),
                _mm_movehl_ps(t1, t0),
                _mm_movelh_ps(t2, t3),
                _mm_movehl_ps(t3, t2),
            ]
        }
    }
    #[inline]
    pub fn pow2_neg_round(y: Raw, rounder: Raw, bias: Raw) -> (Raw, Raw) {
        // (127 - n) << 23 is the bit pattern of 2^-n.
        unsafe {
            let t = _mm_add_ps(y, rounder);
            let n = _mm_sub_epi32(_mm_castps_si128(t), _mm_castps_si128(rounder));
            let bits = _mm_slli_epi32::<23>(_mm_sub_epi32(_mm_castps_si128(bias), n));
            (_mm_sub_ps(t, rounder), _mm_castsi128_ps(bits))
        }
    }
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod imp {
    use core::arch::wasm32::*;
    pub type Raw = v128;

    // The loads and stores go through arrays of exactly 16 bytes; the rest are plain lane
    // operations (f32x4_add is the IEEE addition lane by lane, and so on).
    #[inline]
    pub fn from_array(a: [f32; 4]) -> Raw {
        f32x4(a[0], a[1], a[2], a[3])
    }
    #[inline]
    pub fn to_array(v: Raw) -> [f32; 4] {
        [
            f32x4_extract_lane::<0>(v),
            f32x4_extract_lane::<1>(v),
            f32x4_extract_lane::<2>(v),
            f32x4_extract_lane::<3>(v),
        ]
    }
    #[inline]
    pub fn splat(v: f32) -> Raw {
        f32x4_splat(v)
    }
    #[inline]
    pub fn load(four: &[f32; 4]) -> Raw {
        // SAFETY: `four` is 16 readable bytes; v128_load allows any alignment.
        unsafe { v128_load(four.as_ptr() as *const v128) }
    }
    #[inline]
    pub fn store(v: Raw, four: &mut [f32; 4]) {
        // SAFETY: `four` is 16 writable bytes; v128_store allows any alignment.
        unsafe { v128_store(four.as_mut_ptr() as *mut v128, v) }
    }
    #[inline]
    pub fn add(a: Raw, b: Raw) -> Raw {
        f32x4_add(a, b)
    }
    #[inline]
    pub fn sub(a: Raw, b: Raw) -> Raw {
        f32x4_sub(a, b)
    }
    #[inline]
    pub fn mul(a: Raw, b: Raw) -> Raw {
        f32x4_mul(a, b)
    }
    #[inline]
    pub fn div(a: Raw, b: Raw) -> Raw {
        f32x4_div(a, b)
    }
    #[inline]
    pub fn and(a: Raw, b: Raw) -> Raw {
        v128_and(a, b)
    }
    #[inline]
    pub fn or(a: Raw, b: Raw) -> Raw {
        v128_or(a, b)
    }
    #[inline]
    pub fn gt(a: Raw, b: Raw) -> Raw {
        f32x4_gt(a, b)
    }
    #[inline]
    pub fn le(a: Raw, b: Raw) -> Raw {
        f32x4_le(a, b)
    }
    #[inline]
    pub fn ge(a: Raw, b: Raw) -> Raw {
        f32x4_ge(a, b)
    }
    #[inline]
    pub fn lt(a: Raw, b: Raw) -> Raw {
        f32x4_lt(a, b)
    }
    #[inline]
    pub fn transpose([r0, r1, r2, r3]: [Raw; 4]) -> [Raw; 4] {
        let (t0, t1) = (
            i32x4_shuffle::<0, 4, 1, 5>(r0, r1),
            i32x4_shuffle::<0, 4, 1, 5>(r2, r3),
        );
        let (t2, t3) = (
            i32x4_shuffle::<2, 6, 3, 7>(r0, r1),
            i32x4_shuffle::<2, 6, 3, 7>(r2, r3),
        );
        [
            i32x4_shuffle::<0, 1, 4, 5>(t0, t1),
            i32x4_shuffle::<2, 3, 6, 7>(t0, t1),
            i32x4_shuffle::<0, 1, 4, 5>(t2, t3),
            i32x4_shuffle::<2, 3, 6, 7>(t2, t3),
        ]
    }
    #[inline]
    pub fn select(mask: Raw, a: Raw, b: Raw) -> Raw {
        v128_bitselect(a, b, mask)
    }
    #[inline]
    pub fn all(mask: Raw) -> bool {
        i32x4_all_true(mask)
    }
    #[inline]
    pub fn mask_to_array(mask: Raw) -> [bool; 4] {
        let m = i32x4_bitmask(mask);
        [m & 1 != 0, m & 2 != 0, m & 4 != 0, m & 8 != 0]
    }
    #[inline]
    pub fn pow2_neg_round(y: Raw, rounder: Raw, bias: Raw) -> (Raw, Raw) {
        let t = f32x4_add(y, rounder);
        let n = i32x4_sub(t, rounder);
        let bits = i32x4_shl(i32x4_sub(bias, n), 23);
        (f32x4_sub(t, rounder), bits)
    }
}

#[cfg(not(any(
    target_arch = "x86_64",
    all(target_arch = "wasm32", target_feature = "simd128")
)))]
mod imp {
    //! Four plain floats, lane by lane; masks hold all-ones bit patterns as the SIMD ones do.
    pub type Raw = [f32; 4];
    const TRUE: f32 = f32::from_bits(u32::MAX);

    fn lanes(a: Raw, b: Raw, f: impl Fn(f32, f32) -> f32) -> Raw {
        [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])]
    }
    fn mask(a: Raw, b: Raw, f: impl Fn(f32, f32) -> bool) -> Raw {
        lanes(a, b, |x, y| if f(x, y) { TRUE } else { 0.0 })
    }
    #[inline]
    pub fn from_array(a: [f32; 4]) -> Raw {
        a
    }
    #[inline]
    pub fn to_array(v: Raw) -> [f32; 4] {
        v
    }
    #[inline]
    pub fn splat(v: f32) -> Raw {
        [v; 4]
    }
    #[inline]
    pub fn load(four: &[f32; 4]) -> Raw {
        *four
    }
    #[inline]
    pub fn store(v: Raw, four: &mut [f32; 4]) {
        *four = v;
    }
    #[inline]
    pub fn add(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| x + y)
    }
    #[inline]
    pub fn sub(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| x - y)
    }
    #[inline]
    pub fn mul(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| x * y)
    }
    #[inline]
    pub fn div(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| x / y)
    }
    #[inline]
    pub fn and(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| f32::from_bits(x.to_bits() & y.to_bits()))
    }
    #[inline]
    pub fn or(a: Raw, b: Raw) -> Raw {
        lanes(a, b, |x, y| f32::from_bits(x.to_bits() | y.to_bits()))
    }
    #[inline]
    pub fn gt(a: Raw, b: Raw) -> Raw {
        mask(a, b, |x, y| x > y)
    }
    #[inline]
    pub fn le(a: Raw, b: Raw) -> Raw {
        mask(a, b, |x, y| x <= y)
    }
    #[inline]
    pub fn ge(a: Raw, b: Raw) -> Raw {
        mask(a, b, |x, y| x >= y)
    }
    #[inline]
    pub fn select(mask: Raw, a: Raw, b: Raw) -> Raw {
        [0, 1, 2, 3].map(|k| if mask[k].to_bits() != 0 { a[k] } else { b[k] })
    }
    #[inline]
    pub fn all(mask: Raw) -> bool {
        mask.iter().all(|m| m.to_bits() != 0)
    }
    #[inline]
    pub fn mask_to_array(mask: Raw) -> [bool; 4] {
        mask.map(|m| m.to_bits() != 0)
    }
    #[inline]
    pub fn lt(a: Raw, b: Raw) -> Raw {
        mask(a, b, |x, y| x < y)
    }
    #[inline]
    pub fn transpose(rows: [Raw; 4]) -> [Raw; 4] {
        [0, 1, 2, 3].map(|k| rows.map(|r| r[k]))
    }
    #[inline]
    pub fn pow2_neg_round(y: Raw, rounder: Raw, bias: Raw) -> (Raw, Raw) {
        let t = [0, 1, 2, 3].map(|k| y[k] + rounder[k]);
        let n = [0, 1, 2, 3].map(|k| t[k].to_bits().wrapping_sub(rounder[k].to_bits()));
        (
            [0, 1, 2, 3].map(|k| t[k] - rounder[k]),
            [0, 1, 2, 3].map(|k| f32::from_bits(bias[k].to_bits().wrapping_sub(n[k]) << 23)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ops::{Add, BitAnd, BitOr, Div, Mul, Sub};

    #[test]
    fn lanes_compute_what_the_scalar_operations_compute() {
        let a = [1.5f32, -2.25, f32::NAN, 3.0e7];
        let b = [0.5f32, -2.25, 1.0, -1.0e-3];
        let (va, vb) = (F32x4::from_array(a), F32x4::from_array(b));
        for k in 0..4 {
            assert_eq!(va.add(vb).to_array()[k].to_bits(), (a[k] + b[k]).to_bits());
            assert_eq!(va.sub(vb).to_array()[k].to_bits(), (a[k] - b[k]).to_bits());
            assert_eq!(va.mul(vb).to_array()[k].to_bits(), (a[k] * b[k]).to_bits());
            assert_eq!(va.div(vb).to_array()[k].to_bits(), (a[k] / b[k]).to_bits());
            let (x, y) = (a[k].to_bits(), b[k].to_bits());
            assert_eq!(va.bitand(vb).to_array()[k].to_bits(), x & y);
            assert_eq!(va.bitor(vb).to_array()[k].to_bits(), x | y);
            assert_eq!(va.gt(vb).mask_to_array()[k], a[k] > b[k]);
            assert_eq!(va.le(vb).mask_to_array()[k], a[k] <= b[k]);
            assert_eq!(va.ge(vb).mask_to_array()[k], a[k] >= b[k]);
            assert_eq!(va.lt(vb).mask_to_array()[k], a[k] < b[k]);
        }
        let picked = va.gt(vb).select(va, vb).to_array();
        assert_eq!(picked[0], 1.5);
        assert_eq!(picked[1], -2.25);
        assert_eq!(picked[2], 1.0); // NaN > 1 is false
        assert!(!va.gt(vb).all());
        assert!(F32x4::splat(1.0).ge(F32x4::splat(1.0)).all());
        assert_eq!(
            F32x4::load(&[0.0, 9.0, 8.0, 7.0, 6.0], 1).to_array(),
            [9.0, 8.0, 7.0, 6.0]
        );
        let mut four = [0.0; 4];
        va.store(&mut four);
        assert_eq!(four.map(f32::to_bits), a.map(f32::to_bits));
    }

    #[test]
    fn transposes() {
        let rows =
            [0, 1, 2, 3].map(|i| F32x4::from_array([0, 1, 2, 3].map(|k| (4 * i + k) as f32)));
        let cols = F32x4::transpose(rows).map(F32x4::to_array);
        for (k, col) in cols.iter().enumerate() {
            for (i, &v) in col.iter().enumerate() {
                assert_eq!(v, (4 * i + k) as f32);
            }
        }
    }

    #[test]
    fn rounds_small_values_to_the_nearest_integer() {
        let v = [0.49, -0.5, 1.5, -2.7];
        let r = F32x4::from_array(v).round_small().to_array();
        assert_eq!(r, [0.0, -0.0, 2.0, -3.0]);
    }

    #[test]
    fn powers_of_two_are_exact() {
        let y = [0.0f32, 0.499, 5.75, 46.2];
        let (n, scale) = F32x4::from_array(y).pow2_neg_round();
        for ((y, n), scale) in y.iter().zip(n.to_array()).zip(scale.to_array()) {
            let whole = y.round();
            assert_eq!(n, whole);
            assert_eq!(f64::from(scale), 2f64.powi(-(whole as i32)));
        }
    }
}
