//! Exact Euclidean distance transform (Felzenszwalb & Huttenlocher 2012).
//!
//! For a binary map with feature pixels F (non-zero), D(p) = min_{q in F} |p - q|. The squared
//! distance separates into two passes of the 1-D transform
//!
//! ```text
//! d(x) = min_q ((x - q)^2 + f(q))
//! ```
//!
//! first down every column (f = 0 on features, infinity elsewhere), then along every row (f =
//! the column result). Each 1-D pass is the lower envelope of the parabolas rooted at
//! (q, f(q)), built left to right in O(n): a new parabola q intersects the rightmost one v at
//! s = ((f(q) + q^2) - (f(v) + v^2)) / (2q - 2v) and hides it when s <= the envelope's last
//! boundary. Distances are exact (integer squared distances in f64). A map with no feature has
//! D = infinity everywhere. Lee et al. turn D into likelihoods (eq. 31).

use crate::error::Result;
use crate::image::{Image, ImageView};

/// The distance-transform executor with its scratch buffers.
#[derive(Debug, Clone, Default)]
pub struct DistanceTransform {
    squared: Vec<f64>,
    f: Vec<f64>,
    d: Vec<f64>,
    v: Vec<usize>,
    z: Vec<f64>,
}

impl DistanceTransform {
    /// A new executor (buffers grow on the first frame and are then reused).
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes into `out` the Euclidean distance of every pixel to the nearest non-zero pixel
    /// of `features` (`out` is resized to the same size).
    ///
    /// # Errors
    /// Only if resizing fails (it cannot for a valid view).
    pub fn apply(&mut self, features: &ImageView<'_, u8>, out: &mut Image<f32>) -> Result<()> {
        let (w, h) = (features.width(), features.height());
        out.resize(w, h)?;
        let n = w.max(h);
        self.squared.resize(w * h, 0.0);
        for buf in [&mut self.f, &mut self.d, &mut self.z] {
            buf.resize(n + 1, 0.0);
        }
        self.v.resize(n, 0);
        // Columns.
        for x in 0..w {
            for y in 0..h {
                self.f[y] = if features.get(x, y) != 0 {
                    0.0
                } else {
                    f64::INFINITY
                };
            }
            lower_envelope(&self.f[..h], &mut self.d[..h], &mut self.v, &mut self.z);
            for y in 0..h {
                self.squared[y * w + x] = self.d[y];
            }
        }
        // Rows.
        for y in 0..h {
            self.f[..w].copy_from_slice(&self.squared[y * w..(y + 1) * w]);
            lower_envelope(&self.f[..w], &mut self.d[..w], &mut self.v, &mut self.z);
            for (o, &d) in out.row_mut(y).iter_mut().zip(&self.d[..w]) {
                *o = d.sqrt() as f32;
            }
        }
        Ok(())
    }
}

/// The 1-D squared-distance transform d(x) = min_q ((x - q)^2 + f(q)) of `f` into `d`;
/// `v` (parabola roots) and `z` (envelope boundaries) are scratch of length >= n and n + 1.
fn lower_envelope(f: &[f64], d: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    // Skip leading infinite parabolas: the envelope starts at the first finite one.
    let Some(first) = f.iter().position(|x| x.is_finite()) else {
        d.fill(f64::INFINITY);
        return;
    };
    let mut k = 0;
    v[0] = first;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in first + 1..n {
        if !f[q].is_finite() {
            continue;
        }
        let qf = q as f64;
        loop {
            let vk = v[k] as f64;
            let s = ((f[q] + qf * qf) - (f[v[k]] + vk * vk)) / (2.0 * qf - 2.0 * vk);
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                // k == 0 and z[0] = -inf: cannot happen, s is finite.
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (x, out) in d.iter_mut().enumerate() {
        let xf = x as f64;
        while z[k + 1] < xf {
            k += 1;
        }
        let dx = xf - v[k] as f64;
        *out = dx * dx + f[v[k]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the distance to every feature pixel.
    fn brute_force(img: &Image<u8>) -> Vec<f32> {
        let (w, h) = (img.width(), img.height());
        let features: Vec<(usize, usize)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| img.get(x, y) != 0)
            .collect();
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                features
                    .iter()
                    .map(|&(fx, fy)| {
                        let (dx, dy) = (fx as f64 - x as f64, fy as f64 - y as f64);
                        (dx * dx + dy * dy).sqrt() as f32
                    })
                    .fold(f32::INFINITY, f32::min)
            })
            .collect()
    }

    #[test]
    fn equals_brute_force_on_random_images() {
        let mut state = 99u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) as u32
        };
        let mut dt = DistanceTransform::new();
        let mut out = Image::new(1, 1).unwrap();
        for trial in 0..40 {
            let (w, h) = (1 + next() as usize % 37, 1 + next() as usize % 29);
            // Densities from very sparse (often a single pixel or none) to dense.
            let density = [1u32, 5, 30, 200, 600][trial % 5];
            let data = (0..w * h)
                .map(|_| u8::from(next() % 1000 < density))
                .collect();
            let img = Image::from_vec(w, h, data).unwrap();
            dt.apply(&img.view(), &mut out).unwrap();
            assert_eq!(
                out.data(),
                brute_force(&img).as_slice(),
                "trial {trial}: {w}x{h}"
            );
        }
    }

    #[test]
    fn no_features_means_infinitely_far_and_a_single_point_gives_circles() {
        let mut dt = DistanceTransform::new();
        let mut out = Image::new(1, 1).unwrap();
        let empty = Image::<u8>::new(8, 6).unwrap();
        dt.apply(&empty.view(), &mut out).unwrap();
        assert!(out.data().iter().all(|d| d.is_infinite()));
        let mut one = Image::<u8>::new(50, 40).unwrap();
        one.set(10, 30, 1);
        dt.apply(&one.view(), &mut out).unwrap();
        assert_eq!(out.get(10, 30), 0.0);
        assert_eq!(out.get(13, 34), 5.0);
        assert_eq!(
            out.get(49, 0),
            ((39.0f64 * 39.0 + 30.0 * 30.0).sqrt()) as f32
        );
    }
}
