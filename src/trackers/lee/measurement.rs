//! The two measurement models of Lee et al. (Fig. 3).
//!
//! Approximated model (stage 1, eqs. 27-33): at M longitudinal positions x of the near range,
//! the boundary points y_L(x), y_R(x) (eqs. 27-28) and the inside points
//! y_LN = y_L - tau, y_RN = y_R + tau (eqs. 29-30) are read from the likelihood map D
//! (eq. 31) and summed,
//!
//! ```text
//! q = 1/M sum_x alpha [D(x, y_L) + D(x, y_R)] + beta [D(x, y_LN) + D(x, y_RN)]   (eq. 32)
//! p(x_t | z_t) = N(q; mu, sigma^2),  mu = 2 alpha                                 (eq. 33)
//! ```
//!
//! The paper sums over x = 1..M; dividing by M (our choice) keeps sigma meaningful for any
//! number of points, and mu = 2 alpha is the q of a perfect lane (both boundaries on
//! candidates all along, nothing inside). beta is negative by default: a candidate inside the
//! lane speaks against the particle.
//!
//! Residual model (stage 2): at far positions x, the boundary points of the full clothoid lane
//! are projected into the image and looked up in the Canny edge map ([`FarEdges::hit`]); with
//! f the fraction of visible points that hit, p = N(f; 1, sigma_far^2) (the paper gives no
//! formula for stage 2; we use the form of eq. 33 on the hit fraction).

use super::clothoid::{Curve, LaneState};
use super::far_edges::FarEdges;
use super::likelihood_map::LikelihoodMap;
use crate::camera::Camera;
use crate::math;

/// The evaluation points and weights of both models.
#[derive(Debug, Clone)]
pub struct Measurement {
    near_x: Vec<f64>,
    far_x: Vec<f64>,
    /// Half search window in pixels at each far position.
    far_half_px: Vec<f64>,
    alpha: f64,
    beta: f64,
    tau: f64,
    sigma_q: f64,
    sigma_far: f64,
}

/// Settings of [`Measurement::new`].
#[derive(Debug, Clone, Copy)]
pub struct MeasurementSettings {
    /// Near range [start, end) and spacing, metres.
    pub near: [f64; 3],
    /// Far range [start, end] and spacing, metres.
    pub far: [f64; 3],
    /// Marking width for the far search window, metres.
    pub marking_width: f64,
    /// alpha, beta, tau of eqs. 29-32.
    pub alpha: f64,
    /// See `alpha`.
    pub beta: f64,
    /// See `alpha`.
    pub tau: f64,
    /// sigma of eq. 33.
    pub sigma_q: f64,
    /// sigma of the stage-2 Gaussian.
    pub sigma_far: f64,
}

fn positions(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).floor() as usize + 1;
    (0..n).map(|k| from + k as f64 * step).collect()
}

impl Measurement {
    /// Evaluation points for `camera` (its focal length sets the far search windows).
    pub fn new(camera: &Camera, s: MeasurementSettings) -> Self {
        let near_x = positions(s.near[0], s.near[1], s.near[2]);
        let far_x = positions(s.far[0], s.far[1], s.far[2]);
        let fx = camera.focal()[0];
        let far_half_px = far_x
            .iter()
            .map(|&x| fx * s.marking_width / 2.0 / x + 1.0)
            .collect();
        Self {
            near_x,
            far_x,
            far_half_px,
            alpha: s.alpha,
            beta: s.beta,
            tau: s.tau,
            sigma_q: s.sigma_q,
            sigma_far: s.sigma_far,
        }
    }

    /// The near evaluation positions x.
    pub fn near_positions(&self) -> &[f64] {
        &self.near_x
    }

    /// q of eq. 32 (divided by M).
    pub fn near_q(&self, s: &LaneState, curve: Option<&Curve>, map: &LikelihoodMap) -> f64 {
        let mut q = 0.0;
        let slope = math::tan(s.psi);
        for &x in &self.near_x {
            let c = s.centre_with(x, slope, curve);
            let h = s.half_width(x);
            let (yl, yr) = (c + h, c - h);
            q += self.alpha * (map.at(x, yl) + map.at(x, yr))
                + self.beta * (map.at(x, yl - self.tau) + map.at(x, yr + self.tau));
        }
        q / self.near_x.len() as f64
    }

    /// ln N(q; 2 alpha, sigma^2) up to a constant (eq. 33).
    pub fn near_log_likelihood(
        &self,
        s: &LaneState,
        curve: Option<&Curve>,
        map: &LikelihoodMap,
    ) -> f64 {
        let e = self.near_q(s, curve, map) - 2.0 * self.alpha;
        -e * e / (2.0 * self.sigma_q * self.sigma_q)
    }

    /// Fraction of the near points of each boundary (left, right) with D >= exp(-1/2) (within
    /// sigma_D of a candidate): the support used for the validity flag; and how far beyond the
    /// first near point the nearest supported point of either boundary lies, metres (infinite
    /// when none is; `reacquire_near_m`).
    pub fn near_support(
        &self,
        s: &LaneState,
        curve: Option<&Curve>,
        map: &LikelihoodMap,
    ) -> ([f64; 2], f64) {
        let threshold = math::exp(-0.5) - 1e-9;
        let (mut left, mut right) = (0usize, 0usize);
        let mut nearest = f64::INFINITY;
        for &x in &self.near_x {
            let c = s.centre(x, curve);
            let h = s.half_width(x);
            let hits = [map.at(x, c + h), map.at(x, c - h)].map(|d| d >= threshold);
            left += usize::from(hits[0]);
            right += usize::from(hits[1]);
            if (hits[0] || hits[1]) && nearest.is_infinite() {
                nearest = x - self.near_x[0];
            }
        }
        let m = self.near_x.len() as f64;
        ([left as f64 / m, right as f64 / m], nearest)
    }

    /// Fraction of the far boundary points (both sides) that are visible and hit an edge, and
    /// the number visible.
    pub fn far_fraction(
        &self,
        s: &LaneState,
        curve: &Curve,
        camera: &Camera,
        edges: &FarEdges,
    ) -> (f64, usize) {
        let (mut hits, mut seen) = (0usize, 0usize);
        let slope = math::tan(s.psi);
        for (&x, &half) in self.far_x.iter().zip(&self.far_half_px) {
            let c = s.centre_with(x, slope, Some(curve));
            let h = s.half_width(x);
            for y in [c + h, c - h] {
                let Some(p) = camera.road_to_pixel(x, y) else {
                    continue;
                };
                if let Some(hit) = edges.hit(p, half) {
                    seen += 1;
                    hits += usize::from(hit);
                }
            }
        }
        if seen == 0 {
            (0.0, 0)
        } else {
            (hits as f64 / seen as f64, seen)
        }
    }

    /// ln N(f; 1, sigma_far^2) up to a constant.
    pub fn far_log_likelihood(
        &self,
        s: &LaneState,
        curve: &Curve,
        camera: &Camera,
        edges: &FarEdges,
    ) -> f64 {
        let e = self.far_fraction(s, curve, camera, edges).0 - 1.0;
        -e * e / (2.0 * self.sigma_far * self.sigma_far)
    }
}
