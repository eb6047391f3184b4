//! Exact Euclidean distance transform (Felzenszwalb & Huttenlocher 2012), optionally capped.
//!
//! For a binary map with feature pixels F (non-zero), D(p) = min_{q in F} |p - q|. The squared
//! distance separates into two passes of the 1-D transform
//!
//! ```text
//! d(x) = min_q ((x - q)^2 + f(q))
//! ```
//!
//! first down every column (f = 0 on features, infinity elsewhere), then along every row (f =
//! the column result). Down a column that 1-D transform is just the squared distance to the
//! nearest feature above or below, g(y)^2, which two sweeps over the rows give (g = 0 on a
//! feature, else one more than the row above; then the least of that and one more than the row
//! below): row-major and vectorisable. Along a row, d is the lower envelope of the parabolas
//! rooted at (q, f(q)), built left to right in O(n): a new parabola q intersects the rightmost
//! one v at s = ((f(q) + q^2) - (f(v) + v^2)) / (2q - 2v) and hides it when s <= the
//! envelope's last boundary. Distances are exact (integer squared distances in f64). A map with
//! no feature has D = infinity everywhere. Lee et al. turn D into likelihoods (eq. 31).
//!
//! **Capped** ([`DistanceTransform::apply_capped`]): min(D, cap) exactly, faster. A column
//! distance g(q) > cap can only give (x - q)^2 + g(q)^2 > cap^2, so those parabolas are left out
//! of the row pass: wherever D <= cap its minimiser is kept and the envelope is exact; elsewhere
//! the envelope is above cap (or empty) and the output is cap. On sparse maps (markings, edges)
//! most parabolas are left out.

use crate::error::Result;
use crate::image::{Image, ImageView};

/// Column distance of a pixel with no feature in its column.
const FAR: u16 = u16::MAX;

/// The distance-transform executor with its scratch buffers.
#[derive(Debug, Clone, Default)]
pub struct DistanceTransform {
    /// Distance to the nearest feature in the same column, pixels ([`FAR`]: none).
    column: Vec<u16>,
    /// One row's squared column distances ([`NONE`]: no parabola).
    f: Vec<u32>,
    /// The envelope's parabola roots and its boundaries as fractions zn / zd (zd > 0).
    v: Vec<usize>,
    zn: Vec<i64>,
    zd: Vec<i64>,
    /// (sqrt(d) as f32).min(cap) for the squared distances d <= cap^2 of a finite cap.
    roots: Vec<f32>,
    /// The cap `roots` was made for.
    roots_cap: Option<f32>,
}

/// No parabola in a row (no feature in the column, or one beyond the cap).
const NONE: u32 = u32::MAX;
/// Largest squared cap tabulated.
const MAX_TABLE: f64 = 1e6;

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
        self.apply_capped(features, f32::INFINITY, out)
    }

    /// As [`DistanceTransform::apply`], but every distance above `cap` (>= 0) is `cap`: the
    /// same values as `min(D, cap)`, bit for bit.
    ///
    /// # Errors
    /// Only if resizing fails (it cannot for a valid view).
    pub fn apply_capped(
        &mut self,
        features: &ImageView<'_, u8>,
        cap: f32,
        out: &mut Image<f32>,
    ) -> Result<()> {
        let (w, h) = (features.width(), features.height());
        out.resize(w, h)?;
        self.column.resize(w * h, FAR);
        self.f.resize(w, NONE);
        self.v.resize(w, 0);
        self.zn.resize(w + 1, 0);
        self.zd.resize(w + 1, 1);
        let table = f64::from(cap) * f64::from(cap) <= MAX_TABLE;
        if table && self.roots_cap != Some(cap) {
            let n = (f64::from(cap) * f64::from(cap)).floor() as usize + 1;
            self.roots.clear();
            self.roots
                .extend((0..n).map(|d| ((d as f64).sqrt() as f32).min(cap)));
            self.roots_cap = Some(cap);
        }
        // Columns: nearest feature above (down the rows), then below (up the rows). Image
        // heights stay far below FAR, and FAR + 1 saturates.
        for y in 0..h {
            let (done, rest) = self.column.split_at_mut(y * w);
            let above = if y > 0 {
                Some(&done[(y - 1) * w..])
            } else {
                None
            };
            let row = &mut rest[..w];
            let src = features.row(y);
            match above {
                Some(above) => {
                    for ((g, &a), &p) in row.iter_mut().zip(above).zip(src) {
                        *g = if p != 0 { 0 } else { a.saturating_add(1) };
                    }
                }
                None => {
                    for (g, &p) in row.iter_mut().zip(src) {
                        *g = if p != 0 { 0 } else { FAR };
                    }
                }
            }
        }
        for y in (0..h.saturating_sub(1)).rev() {
            let (head, below) = self.column.split_at_mut((y + 1) * w);
            for (g, &b) in head[y * w..].iter_mut().zip(&below[..w]) {
                *g = (*g).min(b.saturating_add(1));
            }
        }
        // Rows: the lower envelope of the parabolas with g <= cap.
        let cap64 = f64::from(cap);
        for y in 0..h {
            let g = &self.column[y * w..(y + 1) * w];
            for (f, &g) in self.f.iter_mut().zip(g) {
                *f = if g != FAR && f64::from(g) <= cap64 {
                    u32::from(g) * u32::from(g)
                } else {
                    NONE
                };
            }
            let out = out.row_mut(y);
            let Some(k) = lower_envelope(&self.f, &mut self.v, &mut self.zn, &mut self.zd) else {
                out.fill(cap);
                continue;
            };
            let (v, zn, zd, f) = (&self.v, &self.zn, &self.zd, &self.f);
            // Squared distance at x from the envelope's parabolas, left to right.
            let mut j = 0;
            let mut at = |x: usize| -> u64 {
                while j < k && zn[j + 1] < x as i64 * zd[j + 1] {
                    j += 1;
                }
                let dx = x.abs_diff(v[j]) as u64;
                dx * dx + u64::from(f[v[j]])
            };
            if table {
                let last = self.roots.len() as u64 - 1;
                for (x, o) in out.iter_mut().enumerate() {
                    let d = at(x);
                    *o = if d <= last {
                        self.roots[d as usize]
                    } else {
                        cap
                    };
                }
            } else {
                for (x, o) in out.iter_mut().enumerate() {
                    *o = ((at(x) as f64).sqrt() as f32).min(cap);
                }
            }
        }
        Ok(())
    }
}

/// The lower envelope of the parabolas (x - q)^2 + f(q) (entries [`NONE`] are none) in integer
/// arithmetic: roots `v[0..=k]`, boundary j between v[j - 1] and v[j] at zn[j] / zd[j]. Returns
/// k, or `None` without parabolas. `v`, `zn` and `zd` are scratch of length >= n.
fn lower_envelope(f: &[u32], v: &mut [usize], zn: &mut [i64], zd: &mut [i64]) -> Option<usize> {
    let first = f.iter().position(|&x| x != NONE)?;
    let mut k = 0;
    v[0] = first;
    for (q, &fq) in f.iter().enumerate().skip(first + 1) {
        if fq == NONE {
            continue;
        }
        // The intersection with the rightmost parabola v[k] is at s = num / den; it hides v[k]
        // when s <= the boundary zn[k] / zd[k] (boundary 0 is at minus infinity).
        let cq = i64::from(fq) + (q * q) as i64;
        let (num, den) = loop {
            let p = v[k];
            let num = cq - (i64::from(f[p]) + (p * p) as i64);
            let den = 2 * (q - p) as i64;
            if k > 0 && num * zd[k] <= zn[k] * den {
                k -= 1;
            } else {
                break (num, den);
            }
        };
        k += 1;
        v[k] = q;
        zn[k] = num;
        zd[k] = den;
    }
    Some(k)
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
            let want = brute_force(&img);
            assert_eq!(out.data(), want.as_slice(), "trial {trial}: {w}x{h}");
            // Capped: min(D, cap) bit for bit, for integer and fractional caps.
            let caps = [0.0f32, 1.0, 2.5, 5.0, 12.3, 50.0];
            assert_capped(
                &mut dt,
                &img,
                &want,
                &caps,
                &format!("trial {trial}: {w}x{h}"),
            );
        }
    }

    /// `apply_capped` with each of `caps` gives min(brute force, cap), bit for bit.
    fn assert_capped(
        dt: &mut DistanceTransform,
        img: &Image<u8>,
        want: &[f32],
        caps: &[f32],
        what: &str,
    ) {
        let mut capped = Image::<f32>::new(1, 1).unwrap();
        for &cap in caps {
            dt.apply_capped(&img.view(), cap, &mut capped).unwrap();
            let same = capped
                .data()
                .iter()
                .zip(want)
                .all(|(a, b)| a.to_bits() == b.min(cap).to_bits());
            assert!(same, "{what}, cap {cap}");
        }
    }

    #[test]
    fn capped_equals_brute_force_on_large_sparse_maps() {
        // Distances well beyond the cap, and rows whose parabolas are all left out.
        let (w, h) = (230, 170);
        let mut dt = DistanceTransform::new();
        let mut out = Image::new(1, 1).unwrap();
        for (trial, points) in [(0usize, 3usize), (1, 40), (2, 400)] {
            let mut img = Image::<u8>::new(w, h).unwrap();
            for i in 0..points {
                let k = (i * 7919 + trial * 104_729) % (w * h);
                img.set(k % w, k / w, 1);
            }
            let want = brute_force(&img);
            dt.apply(&img.view(), &mut out).unwrap();
            assert_eq!(out.data(), want.as_slice(), "trial {trial}");
            assert_capped(
                &mut dt,
                &img,
                &want,
                &[50.0, 7.5],
                &format!("trial {trial}"),
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
