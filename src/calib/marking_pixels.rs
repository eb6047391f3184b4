//! The marking intensity and saturation of every pixel of one RGBA row (the two formulas of
//! [`super::marking_image`]), four pixels per operation: SSE2 natively on x86-64, `simd128` in
//! WebAssembly (on for every wasm32 build, `.cargo/config.toml`), pixel by pixel elsewhere.
//! All three give the bytes of [`marking_pixel`]:
//!
//! - the luma (77 R + 150 G + 29 B + 128) >> 8 and R + G - 2 B are integer sums of products
//!   in 32-bit lanes (SSE2 forms them with `pmaddwd` on each pixel's (R, B) and (G, A) 16-bit
//!   pairs);
//! - the clamp of R + G - 2 B to 0..255 is the saturating narrowing to bytes;
//! - 255 (max - min) / max(max, 40) is a single-precision division, truncated: the numerator
//!   is below 2^16 and the divisor below 2^8, so a quotient that is not an integer lies at
//!   least 1 / divisor > 2^-8 from the next integer, far more than the division's rounding
//!   error (at most 2^-24 of a quotient below 2^8), and an integer quotient is exact;
//!   truncation therefore gives the integer division's result (every colour is checked by the
//!   tests, natively and in Chromium).

/// Marking intensity and saturation of one pixel: the reference the vector paths match.
#[inline]
pub fn marking_pixel(r: u8, g: u8, b: u8) -> (u8, u8) {
    let yellow = (i32::from(r) + i32::from(g) - 2 * i32::from(b)).clamp(0, 255) as u8;
    let intensity = crate::image::luma(r, g, b).max(yellow);
    let max = u32::from(r.max(g).max(b));
    let min = u32::from(r.min(g).min(b));
    (intensity, (255 * (max - min) / max.max(40)) as u8)
}

/// Writes the marking intensity and saturation of the pixels of `rgba` (4 bytes each) into
/// `intensity` and `saturation` (one byte each; both at least as long as the pixel count).
pub fn marking_pixels(rgba: &[u8], intensity: &mut [u8], saturation: &mut [u8]) {
    let n = rgba.len() / 4;
    let (intensity, saturation) = (&mut intensity[..n], &mut saturation[..n]);
    let quads = n / 4;
    for ((block, m), s) in rgba
        .chunks_exact(16)
        .zip(intensity.chunks_exact_mut(4))
        .zip(saturation.chunks_exact_mut(4))
    {
        // Always 16 bytes (`chunks_exact`); the conversion cannot fail.
        let Ok(block) = <&[u8; 16]>::try_from(block) else {
            continue;
        };
        let (four_m, four_s) = imp::four(block);
        m.copy_from_slice(&four_m);
        s.copy_from_slice(&four_s);
    }
    for i in quads * 4..n {
        let px = &rgba[i * 4..i * 4 + 4];
        (intensity[i], saturation[i]) = marking_pixel(px[0], px[1], px[2]);
    }
}

#[cfg(target_arch = "x86_64")]
mod imp {
    use core::arch::x86_64::*;

    /// Intensity and saturation of four RGBA pixels.
    #[inline]
    pub fn four(block: &[u8; 16]) -> ([u8; 4], [u8; 4]) {
        // SAFETY: SSE2 is part of the x86-64 baseline; the unaligned load reads exactly the 16
        // bytes of `block`.
        unsafe {
            let v = _mm_loadu_si128(block.as_ptr().cast());
            // 16-bit lanes: (R, B) and (G, A) of each pixel.
            let rb = _mm_and_si128(v, _mm_set1_epi16(0x00ff));
            let ga = _mm_srli_epi16::<8>(v);
            let luma = _mm_srli_epi32::<8>(_mm_add_epi32(
                _mm_add_epi32(
                    _mm_madd_epi16(rb, _mm_set1_epi32((29 << 16) | 77)),
                    _mm_madd_epi16(ga, _mm_set1_epi32(150)),
                ),
                _mm_set1_epi32(128),
            ));
            let yellow = _mm_add_epi32(
                _mm_madd_epi16(rb, _mm_set1_epi32((-2i32 << 16) | 1)),
                _mm_madd_epi16(ga, _mm_set1_epi32(1)),
            );
            let intensity = _mm_max_epu8(bytes(luma), bytes(yellow));
            // One channel in each 32-bit lane, 0..255 with the upper half zero, so the 16-bit
            // max, min and product act on the values.
            let mask = _mm_set1_epi32(0xff);
            let r = _mm_and_si128(rb, mask);
            let b = _mm_srli_epi32::<16>(rb);
            let g = _mm_and_si128(ga, mask);
            let max = _mm_max_epi16(_mm_max_epi16(r, g), b);
            let min = _mm_min_epi16(_mm_min_epi16(r, g), b);
            let num = _mm_mullo_epi16(_mm_sub_epi32(max, min), _mm_set1_epi32(255));
            let den = _mm_max_epi16(max, _mm_set1_epi32(40));
            let sat = _mm_cvttps_epi32(_mm_div_ps(_mm_cvtepi32_ps(num), _mm_cvtepi32_ps(den)));
            (low_four(intensity), low_four(bytes(sat)))
        }
    }

    /// Four i32 lanes saturated to bytes, in the low four bytes.
    #[inline]
    unsafe fn bytes(v: __m128i) -> __m128i {
        let zero = _mm_setzero_si128();
        _mm_packus_epi16(_mm_packs_epi32(v, zero), zero)
    }

    /// The low four bytes.
    #[inline]
    unsafe fn low_four(v: __m128i) -> [u8; 4] {
        (_mm_cvtsi128_si32(v) as u32).to_le_bytes()
    }
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod imp {
    use core::arch::wasm32::*;

    /// Intensity and saturation of four RGBA pixels.
    #[inline]
    pub fn four(block: &[u8; 16]) -> ([u8; 4], [u8; 4]) {
        // SAFETY: reads exactly the 16 bytes of `block`; WebAssembly loads need no alignment.
        let v = unsafe { v128_load(block.as_ptr().cast()) };
        let mask = u32x4_splat(0xff);
        let r = v128_and(v, mask);
        let g = v128_and(u32x4_shr(v, 8), mask);
        let b = v128_and(u32x4_shr(v, 16), mask);
        let luma = u32x4_shr(
            i32x4_add(
                i32x4_add(
                    i32x4_mul(r, i32x4_splat(77)),
                    i32x4_mul(g, i32x4_splat(150)),
                ),
                i32x4_add(i32x4_mul(b, i32x4_splat(29)), i32x4_splat(128)),
            ),
            8,
        );
        let yellow = i32x4_sub(i32x4_add(r, g), i32x4_shl(b, 1));
        let intensity = u8x16_max(bytes(luma), bytes(yellow));
        let max = i32x4_max(i32x4_max(r, g), b);
        let min = i32x4_min(i32x4_min(r, g), b);
        let num = i32x4_mul(i32x4_sub(max, min), i32x4_splat(255));
        let den = i32x4_max(max, i32x4_splat(40));
        let sat = i32x4_trunc_sat_f32x4(f32x4_div(
            f32x4_convert_i32x4(num),
            f32x4_convert_i32x4(den),
        ));
        (low_four(intensity), low_four(bytes(sat)))
    }

    /// Four i32 lanes saturated to bytes, in the low four bytes.
    #[inline]
    fn bytes(v: v128) -> v128 {
        let zero = i32x4_splat(0);
        u8x16_narrow_i16x8(i16x8_narrow_i32x4(v, zero), zero)
    }

    /// The low four bytes.
    #[inline]
    fn low_four(v: v128) -> [u8; 4] {
        (i32x4_extract_lane::<0>(v) as u32).to_le_bytes()
    }
}

#[cfg(not(any(
    target_arch = "x86_64",
    all(target_arch = "wasm32", target_feature = "simd128")
)))]
mod imp {
    /// Intensity and saturation of four RGBA pixels, one by one.
    #[inline]
    pub fn four(block: &[u8; 16]) -> ([u8; 4], [u8; 4]) {
        let (mut m, mut s) = ([0; 4], [0; 4]);
        for (i, px) in block.chunks_exact(4).enumerate() {
            (m[i], s[i]) = super::marking_pixel(px[0], px[1], px[2]);
        }
        (m, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every colour through the row function (alpha varying: it must not count), and a tail
    /// of three pixels that does not fill four.
    #[test]
    fn every_colour_matches_the_per_pixel_formulas() {
        let mut rgba = Vec::with_capacity(256 * 256 * 4 + 12);
        let (mut m, mut s) = (vec![0; 256 * 256 + 3], vec![0; 256 * 256 + 3]);
        for r in 0..=255u8 {
            rgba.clear();
            for g in 0..=255u8 {
                for b in 0..=255u8 {
                    rgba.extend_from_slice(&[r, g, b, g ^ b]);
                }
            }
            rgba.extend_from_slice(&[r, 255, 0, 0, r, 0, 255, 7, 255, r, 40, 255]);
            marking_pixels(&rgba, &mut m, &mut s);
            for (i, px) in rgba.chunks_exact(4).enumerate() {
                let want = marking_pixel(px[0], px[1], px[2]);
                assert_eq!((m[i], s[i]), want, "rgb {:?}", &px[..3]);
            }
        }
    }

    #[test]
    fn the_reference_gives_the_documented_values() {
        // Grey road: the luma, no saturation.
        assert_eq!(marking_pixel(120, 120, 120), (120, 0));
        // Yellow paint: R + G - 2 B clamped; saturation 255 * 170 / 220.
        assert_eq!(marking_pixel(220, 200, 50), (255, 197));
        // Dark noise: the floor of 40 keeps the saturation down.
        assert_eq!(marking_pixel(10, 0, 0), (10, 63));
        assert_eq!(marking_pixel(0, 0, 0), (0, 0));
    }
}
