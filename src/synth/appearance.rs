//! Image-level appearance effects applied after ray casting: exposure, sun glare, vignette,
//! the car's hood, sensor noise and blur. All randomness is a hash of (seed, frame, pixel), so
//! a frame renders identically on every target and in any order.

use super::scene::Appearance;

/// A deterministic value in [0, 1) from a seed and two integers (SplitMix64 finaliser).
pub fn hash_unit(seed: u64, a: i64, b: i64) -> f64 {
    let mut h = seed
        ^ (a as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (b as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 31;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// A cheap lattice hash in [0, 1) for texture (one multiply-xorshift round on 64 bits: good
/// enough for noise that only has to look random, about 3x cheaper than [`hash_unit`]).
#[inline]
fn lattice(seed: u64, i: i64, j: i64) -> f64 {
    let mut h = seed
        ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h = (h ^ (h >> 29)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    (h >> 40) as f64 / (1u64 << 24) as f64
}

/// Smooth value noise in [0, 1): hash values on the integer lattice, interpolated with a
/// smoothstep, so shapes are blobs instead of squares.
pub fn value_noise(seed: u64, x: f64, y: f64) -> f64 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let (i, j) = (x0 as i64, y0 as i64);
    let a = lattice(seed, i, j);
    let b = lattice(seed, i + 1, j);
    let c = lattice(seed, i, j + 1);
    let d = lattice(seed, i + 1, j + 1);
    let top = a + (b - a) * sx;
    let bottom = c + (d - c) * sx;
    top + (bottom - top) * sy
}

/// The effects of one frame.
pub struct Effects<'a> {
    /// The appearance settings.
    pub appearance: &'a Appearance,
    /// Frame index.
    pub frame: u32,
    /// Seed.
    pub seed: u64,
    /// Exposure gain of the frame.
    gain: f32,
}

impl<'a> Effects<'a> {
    /// The effects of frame `frame` at time `t`.
    pub fn new(appearance: &'a Appearance, frame: u32, t: f64, seed: u64) -> Self {
        let gain =
            1.0 + appearance.exposure * crate::math::sin(2.0 * std::f64::consts::PI * t / 4.0);
        Self {
            appearance,
            frame,
            seed,
            gain: gain as f32,
        }
    }

    /// Applies exposure, glare, vignette and hood to a linear colour at pixel (u, v) of a
    /// w x h image; returns the colour.
    pub fn pixel(&self, rgb: [f32; 3], u: usize, v: usize, w: usize, h: usize) -> [f32; 3] {
        let a = self.appearance;
        let (fu, fv) = (u as f32 / w as f32, v as f32 / h as f32);
        if a.hood > 0.0 {
            // A dark hood whose edge bulges up in the middle.
            let bulge = 1.0 - 4.0 * (fu - 0.5) * (fu - 0.5);
            if fv > 1.0 - a.hood as f32 * (0.6 + 0.4 * bulge) {
                return [30.0, 32.0, 36.0];
            }
        }
        let gain = self.gain;
        let mut out = [rgb[0] * gain, rgb[1] * gain, rgb[2] * gain];
        if let Some([gu, gv, gr]) = a.glare {
            let (du, dv) = (fu - gu as f32, (fv - gv as f32) * h as f32 / w as f32);
            let r2 = (du * du + dv * dv) / (gr as f32 * gr as f32).max(1e-6);
            let k = 1.0 / (1.0 + r2 * r2);
            for c in out.iter_mut() {
                *c += (255.0 - *c) * k;
            }
        }
        if a.vignette > 0.0 {
            let (du, dv) = (fu - 0.5, fv - 0.5);
            let k = 1.0 - a.vignette as f32 * (2.0 * (du * du + dv * dv)).min(1.0);
            for c in out.iter_mut() {
                *c *= k;
            }
        }
        out
    }

    /// Sensor noise for pixel index `i`: approximately Gaussian (the sum of four 16-bit
    /// uniforms cut from one hash, variance matched) with the configured standard deviation.
    pub fn noise(&self, i: usize, salt: u64) -> f32 {
        let sd = self.appearance.noise;
        if sd <= 0.0 {
            return 0.0;
        }
        let base = self.seed ^ salt ^ ((self.frame as u64) << 32);
        let h = (hash_unit(base, i as i64, 0) * (1u64 << 53) as f64) as u64;
        let sum: u64 = (0..4).map(|k| (h >> (13 * k)) & 0x1FFF).sum();
        // Four U(0, 1) (13-bit): mean 2, variance 1/3.
        let u = sum as f64 / 8192.0;
        ((u - 2.0) * 1.732_050_807_568_877_2 * sd) as f32
    }
}

/// Separable box blur of radius `r` on an RGBA buffer, using `tmp` (same length) as scratch.
pub fn box_blur(rgba: &mut [u8], tmp: &mut Vec<u8>, w: usize, h: usize, r: usize) {
    if r == 0 {
        return;
    }
    tmp.resize(rgba.len(), 0);
    let n = (2 * r + 1) as u32;
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut acc = 0u32;
                for k in 0..=2 * r {
                    let xi = (x + k).saturating_sub(r).min(w - 1);
                    acc += rgba[(y * w + xi) * 4 + c] as u32;
                }
                tmp[(y * w + x) * 4 + c] = ((acc + n / 2) / n) as u8;
            }
            tmp[(y * w + x) * 4 + 3] = 255;
        }
    }
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut acc = 0u32;
                for k in 0..=2 * r {
                    let yi = (y + k).saturating_sub(r).min(h - 1);
                    acc += tmp[(yi * w + x) * 4 + c] as u32;
                }
                rgba[(y * w + x) * 4 + c] = ((acc + n / 2) / n) as u8;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_is_uniform_and_noise_has_the_requested_spread() {
        let n = 20_000;
        let mean: f64 = (0..n).map(|i| hash_unit(7, i, 3)).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        let a = Appearance {
            noise: 5.0,
            ..Default::default()
        };
        let e = Effects::new(&a, 3, 0.1, 9);
        let xs: Vec<f64> = (0..n as usize).map(|i| e.noise(i, 0) as f64).collect();
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        let sd = (xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / xs.len() as f64).sqrt();
        assert!(m.abs() < 0.15 && (sd - 5.0).abs() < 0.15, "{m} {sd}");
    }

    #[test]
    fn blur_preserves_flat_areas_and_spreads_an_edge() {
        let (w, h) = (10, 4);
        let mut rgba: Vec<u8> = (0..w * h)
            .flat_map(|i| {
                let v = if i % w < 5 { 0 } else { 210 };
                [v, v, v, 255]
            })
            .collect();
        let mut tmp = Vec::new();
        box_blur(&mut rgba, &mut tmp, w, h, 1);
        assert_eq!(rgba[0], 0);
        assert_eq!(rgba[9 * 4], 210);
        assert_eq!(rgba[4 * 4], 70);
        assert_eq!(rgba[5 * 4], 140);
    }
}
