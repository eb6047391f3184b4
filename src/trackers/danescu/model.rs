//! The filter's models (Sec. III, V, VII): the generic initialisation distribution, the
//! deterministic drift from the ego motion with stochastic diffusion, and the measurement:
//! each particle mapped into image space (and into the discrete 3-D space) and compared with
//! the cues, the likelihoods multiplied, degenerate lanes given weight zero.
//!
//! **Drift** (ours; the paper defers to its ref. \[8\]): over a frame the car travels s = v dt
//! and turns by omega dt (yaw rate omega, positive to the left). The lane ahead is then seen
//! from s metres further along: X_CW <- X_C(s) = X_CW + psi s + C_H s^2 / 2,
//! psi <- psi + C_H s + omega dt (the car turning left makes the lane head to the right),
//! W_0 <- W(s) = W_0 + W_l s; the other parameters do not drift.
//!
//! **Image-space mapping** (Sec. V-A): P distances Z_k, spaced evenly in 1/Z between
//! `near_m` (or the first visible distance) and `far_m` so that the points are spread evenly
//! over the image rows; at each, the four delimiter edges (eqs. 2-3) and two negative points
//! `negative_offset_m` inside the lane from the inner edges, projected through the lane's own
//! camera ([`crate::lane::LaneCamera`]).
//!
//! **Likelihoods** (Sec. VII), each a Gaussian of a mean distance, multiplied (log-added; the
//! Gaussians' constant factors are dropped, they scale all particles alike):
//! - road edges DT^E and markings DT^S (VII-A): the positive distance D+ is the mean distance
//!   image at the inner-edge points; the paper's text stops before the negative points' formula,
//!   so we choose D- = mean over the negative points of max(0, c - DT), c =
//!   `negative_reach_px` (an edge closer than c pixels inside the lane costs), and
//!   D = (D+ + D-) / 2 as eq. 11 averages its two halves;
//! - the gradient (eqs. 9-12): the left outer and right inner points should be on 255, the
//!   left inner and right outer points on 0 (off with `marking_widths: false`, the paper's
//!   "previous approach");
//! - the density (eqs. 5-8, 13-14; stereo only): the P points of the vertical profile in the
//!   discrete 3-D space against DT^D.
//!
//! Points that fall outside the road region count with the largest distance (and a flat
//! 128 on HG), so a hypothesis cannot escape the data by leaving the image.
//!
//! **Validation** (Sec. VII-D): weight zero when the width W(Z) leaves `width_range_m` at the
//! nearest or farthest mapped distance, when the car is more than `offset_margin_m` outside
//! the lane (|X_CW| > W_0 / 2 + margin), or a marking width is outside [0, `max_marking_m`].

use super::config::DanescuConfig;
use super::cues::{ImageCues, MAX_DISTANCE_PX};
use crate::camera::Camera;
use crate::filter::{InitialDistribution, MotionModel, Rng};
use crate::lane::{Edge, Lane3d, LaneCamera};
use crate::vision::Density;

/// The generic distribution that covers all lane geometries (Sec. III).
#[derive(Debug, Clone)]
pub struct Initial {
    /// The calibrated camera's pitch and roll (the vertical profile's rest state).
    pub pitch: f64,
    /// Calibrated roll.
    pub roll: f64,
    /// Whether the vertical profile is tracked (stereo) or held flat (mono).
    pub vertical: bool,
    /// The ranges.
    pub config: DanescuConfig,
}

impl InitialDistribution<Lane3d> for Initial {
    fn sample(&self, rng: &mut Rng) -> Lane3d {
        let c = &self.config;
        let mut u = |lo: f64, hi: f64| lo + (hi - lo) * rng.uniform();
        let sym = |r: f64, u: &mut dyn FnMut(f64, f64) -> f64| u(-r, r);
        let w0 = u(c.init_width_m[0], c.init_width_m[1]);
        let xcw = sym(c.init_offset_m.min(w0 / 2.0), &mut u);
        let psi = sym(c.init_yaw_rad, &mut u);
        let ch = sym(c.init_curvature, &mut u);
        let wl = sym(c.init_width_rate, &mut u);
        let (wl_mark, wr_mark) = if c.marking_widths {
            (
                u(c.init_marking_m[0], c.init_marking_m[1]),
                u(c.init_marking_m[0], c.init_marking_m[1]),
            )
        } else {
            (0.0, 0.0)
        };
        let (alpha, y0) = if self.vertical {
            (
                self.pitch + sym(c.init_pitch_rad, &mut u),
                sym(c.init_height_m, &mut u),
            )
        } else {
            (self.pitch, 0.0)
        };
        Lane3d {
            w0,
            ch,
            wl,
            cv: 0.0,
            y0,
            xcw,
            alpha,
            gamma: self.roll,
            psi,
            wl_mark,
            wr_mark,
        }
    }
}

/// Drift over one frame and diffusion.
#[derive(Debug, Clone, Copy)]
pub struct Motion {
    /// Distance travelled s = v dt, metres.
    pub travelled_m: f64,
    /// Turn omega dt, radians (positive left).
    pub turned_rad: f64,
    /// Per-parameter standard deviations (`Lane3d::NAMES` order; vertical ones 0 for mono).
    pub diffusion: [f64; 11],
}

impl Motion {
    /// The deterministic drift alone.
    pub fn drift(&self, lane: &mut Lane3d) {
        let s = self.travelled_m;
        lane.xcw += lane.psi * s + lane.ch * s * s / 2.0;
        lane.psi += lane.ch * s + self.turned_rad;
        lane.w0 += lane.wl * s;
    }
}

impl MotionModel<Lane3d> for Motion {
    fn propagate(&self, lane: &mut Lane3d, rng: &mut Rng) {
        self.drift(lane);
        let mut a = lane.to_array();
        for (v, &sd) in a.iter_mut().zip(&self.diffusion) {
            if sd > 0.0 {
                *v += rng.gaussian(0.0, sd);
            }
        }
        *lane = Lane3d::from_array(a);
        // Marking widths are magnitudes: reflect at zero.
        lane.wl_mark = lane.wl_mark.abs();
        lane.wr_mark = lane.wr_mark.abs();
    }
}

/// The per-particle measurement: mapping and likelihoods.
#[derive(Debug, Clone)]
pub struct Measurement {
    /// Z_k of the image-space mapping.
    distances: Vec<f64>,
    /// Z_k of the 3-D mapping (eq. 5).
    distances_3d: Vec<f64>,
    /// The calibrated pitch (eq. 4's reference).
    pitch: f64,
    /// Per Z_k: how near a road edge an inner-edge point counts as supported, pixels.
    support_px: Vec<f64>,
    config: DanescuConfig,
}

/// The distances of one particle against the cues (for tests and the validity check).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Distances {
    /// D^E: road edges (positive, negative).
    pub edge: [f64; 2],
    /// D^S: markings (positive, negative).
    pub marking: [f64; 2],
    /// D^G (eq. 11).
    pub gradient: f64,
    /// D^D (eq. 13), when the density cue is on.
    pub density: Option<f64>,
    /// Share of the left and right inner-edge points within `valid_distance_px` of a road
    /// edge (and, with `valid_marking_factor` on both sides, of a marking edge; the validity
    /// check).
    pub support: [f64; 2],
    /// Share of the left and right inner-edge points near a road edge and, within
    /// `valid_marking_factor` times the tolerance, a marking edge (0 with the factor off).
    pub painted: [f64; 2],
}

impl Measurement {
    /// The mapping for `camera`.
    pub fn new(camera: &Camera, config: &DanescuConfig) -> Self {
        // The first distance visible at the bottom of the image.
        let [cx, _] = camera.principal_point();
        let bottom = camera
            .pixel_to_road(cx, camera.height() as f64 - 1.0)
            .map_or(config.near_m, |[x, _]| x);
        let near = config.near_m.max(bottom + 0.5).min(config.far_m * 0.5);
        let p = config.points;
        let (a, b) = (1.0 / near, 1.0 / config.far_m);
        let distances: Vec<f64> = (0..p)
            .map(|k| 1.0 / (a + (b - a) * k as f64 / (p - 1) as f64))
            .collect();
        let zb = bottom.max(0.5).min(config.range_3d_m * 0.5);
        let distances_3d = (1..=p)
            .map(|k| zb + (config.range_3d_m - zb) * k as f64 / p as f64)
            .collect();
        let fx = camera.focal()[0];
        let support_px = distances
            .iter()
            .map(|&z| {
                config
                    .valid_distance_px
                    .max(fx * config.valid_distance_m / z)
            })
            .collect();
        Self {
            distances,
            distances_3d,
            pitch: camera.pitch(),
            support_px,
            config: config.clone(),
        }
    }

    /// Z_k of the image-space mapping.
    pub fn distances(&self) -> &[f64] {
        &self.distances
    }

    /// Whether the paint the validity asks for is there, given each side's `painted` share
    /// averaged over the last `valid_support_frames` frames (`valid_marking_factor` with
    /// `valid_marking_sides` 1: one side's mean reaches `valid_support`; otherwise always, the
    /// support itself carries the rule).
    pub fn paint_seen(&self, painted: [f64; 2]) -> bool {
        let c = &self.config;
        c.valid_marking_factor <= 0.0
            || c.valid_marking_sides >= 2
            || painted[0].max(painted[1]) >= c.valid_support
    }

    /// Whether the lane passes the validation of Sec. VII-D.
    pub fn is_valid(&self, lane: &Lane3d) -> bool {
        let c = &self.config;
        let [lo, hi] = c.width_range_m;
        let near = self.distances[0];
        let far = self.distances[self.distances.len() - 1];
        let ok_width = |w: f64| w >= lo && w <= hi;
        lane.to_array().iter().all(|v| v.is_finite())
            && ok_width(lane.width(near))
            && ok_width(lane.width(far))
            && ok_width(lane.w0)
            && lane.xcw.abs() <= lane.w0 / 2.0 + c.offset_margin_m
            && (0.0..=c.max_marking_m).contains(&lane.wl_mark)
            && (0.0..=c.max_marking_m).contains(&lane.wr_mark)
    }

    /// The distances of `lane` to the cues.
    pub fn distances_of(
        &self,
        camera: &Camera,
        lane: &Lane3d,
        cues: &ImageCues,
        density: Option<&Density>,
    ) -> Distances {
        let lc = LaneCamera::new(camera, lane);
        let far = MAX_DISTANCE_PX as f64;
        let reach = self.config.negative_reach_px;
        let inset = self.config.negative_offset_m;
        let marking = self.config.valid_marking_factor;
        // Whether each side's support counts only painted points.
        let painted_only = marking > 0.0 && self.config.valid_marking_sides >= 2;
        let mut sums = [0.0f64; 6];
        let mut n = 0.0;
        let mut support = [0.0f64; 2];
        let mut painted = [0.0f64; 2];
        for (&z, &near) in self.distances.iter().zip(&self.support_px) {
            let x_li = lane.edge_x(Edge::LeftInner, z);
            let x_ri = lane.edge_x(Edge::RightInner, z);
            let x_lo = lane.edge_x(Edge::LeftOuter, z);
            let x_ro = lane.edge_x(Edge::RightOuter, z);
            let at = |x: f64| lc.project(x, z);
            let pos = [at(x_li), at(x_ri)];
            let neg = [at(x_li + inset), at(x_ri - inset)];
            for (side, p) in pos.into_iter().enumerate() {
                let (e, m) = p.map_or((far, far), |[u, v]| {
                    (
                        cues.edge_distance(u, v).map_or(far, f64::from),
                        cues.marking_distance(u, v).map_or(far, f64::from),
                    )
                });
                sums[0] += e;
                sums[2] += m;
                // A road edge, and with `valid_marking_factor` a marking edge near it too.
                let paint = marking > 0.0 && m <= marking * near;
                if e <= near && (paint || !painted_only) {
                    support[side] += 1.0;
                }
                if e <= near && paint {
                    painted[side] += 1.0;
                }
            }
            for p in neg {
                let (e, m) = p.map_or((far, far), |[u, v]| {
                    (
                        cues.edge_distance(u, v).map_or(far, f64::from),
                        cues.marking_distance(u, v).map_or(far, f64::from),
                    )
                });
                sums[1] += (reach - e).max(0.0);
                sums[3] += (reach - m).max(0.0);
            }
            // Eqs. 9-10: + points on dark-to-light (255), - points on light-to-dark (0).
            let hg = |x: f64| at(x).and_then(|[u, v]| cues.gradient(u, v)).unwrap_or(128) as f64;
            sums[4] += (255.0 - hg(x_lo)) + (255.0 - hg(x_ri));
            sums[5] += hg(x_li) + hg(x_ro);
            n += 2.0;
        }
        let gradient = (sums[4] / n + sums[5] / n) / 2.0; // eq. 11
        let density = density.map(|d| self.density_distance(lane, d));
        Distances {
            edge: [sums[0] / n, sums[1] / n],
            marking: [sums[2] / n, sums[3] / n],
            gradient,
            density,
            support: support.map(|c| c / self.distances.len() as f64),
            painted: painted.map(|c| c / self.distances.len() as f64),
        }
    }

    /// D^D of eq. 13: the vertical profile's P points (eqs. 5-8) on DT^D.
    fn density_distance(&self, lane: &Lane3d, density: &Density) -> f64 {
        let cap = MAX_DISTANCE_PX as f64;
        let mut sum = 0.0;
        for &z in &self.distances_3d {
            let y = lane.road_height(self.pitch, z);
            sum += density
                .cell(z, y)
                .map_or(cap, |(r, c)| (density.distance().get(c, r) as f64).min(cap));
        }
        sum / self.distances_3d.len() as f64
    }

    /// ln p(z | lane): the product of the cues' Gaussians (eqs. 12, 14), -infinity for a
    /// degenerate lane.
    pub fn log_likelihood(
        &self,
        camera: &Camera,
        lane: &Lane3d,
        cues: &ImageCues,
        density: Option<&Density>,
    ) -> f64 {
        if !self.is_valid(lane) {
            return f64::NEG_INFINITY;
        }
        let d = self.distances_of(camera, lane, cues, density);
        let c = &self.config;
        let g = |x: f64, sigma: f64| -0.5 * (x / sigma) * (x / sigma);
        let edge = (d.edge[0] + d.edge[1]) / 2.0;
        let marking = (d.marking[0] + d.marking[1]) / 2.0;
        let gradient = if c.marking_widths {
            g(d.gradient, c.sigma_gradient)
        } else {
            0.0
        };
        g(edge, c.sigma_edge_px)
            + g(marking, c.sigma_marking_px)
            + gradient
            + d.density.map_or(0.0, |x| g(x, c.sigma_density))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    /// A flat road of grey 80 with two bright (220) solid markings of `mark` metres whose
    /// inner edges are `half` metres left and right of the camera, painted by each pixel
    /// centre's road point.
    fn two_stripes(camera: &Camera, half: f64, mark: f64) -> Vec<u8> {
        let (w, h) = (camera.width(), camera.height());
        let mut rgba = vec![255; w * h * 4];
        for v in 0..h {
            for u in 0..w {
                let on = camera
                    .pixel_to_road(u as f64, v as f64)
                    .is_ok_and(|[x, y]| x > 0.0 && y.abs() >= half && y.abs() <= half + mark);
                let g = if on { 220 } else { 80 };
                rgba[(v * w + u) * 4..][..3].fill(g);
            }
        }
        rgba
    }

    /// Through a 1280x720 camera (f = 1108 px) a lane 3 cm off the markings has its inner
    /// edges 7 px from the Canny edges at 5 m and 1 px at 35 m: the 2-pixel tolerance
    /// supports only the far points, `valid_distance_m` 0.05 (at least 2 px, f 0.05 / Z) all
    /// of them; the true lane is supported either way.
    #[test]
    fn the_validity_tolerance_on_the_road_does_not_shrink_with_the_resolution() {
        let camera = default_camera(1280, 720).unwrap();
        let support = |valid_distance_m: f64, xcw: f64| {
            let config = DanescuConfig {
                valid_distance_m,
                ..DanescuConfig::default()
            };
            let mut cues = ImageCues::new(&camera, &config).unwrap();
            cues.begin(&two_stripes(&camera, 1.8, 0.15)).unwrap();
            cues.finish().unwrap();
            let lane = Lane3d {
                w0: 3.6,
                xcw,
                alpha: camera.pitch(),
                gamma: camera.roll(),
                wl_mark: 0.15,
                wr_mark: 0.15,
                ..Lane3d::default()
            };
            let m = Measurement::new(&camera, &config);
            m.distances_of(&camera, &lane, &cues, None).support
        };
        for tol in [0.0, 0.05] {
            let s = support(tol, 0.0);
            assert!(s.iter().all(|&s| s >= 0.9), "true lane, {tol} m: {s:?}");
        }
        let pixels = support(0.0, 0.03);
        let metres = support(0.05, 0.03);
        assert!(pixels.iter().all(|&s| s < 0.5), "{pixels:?}");
        assert!(metres.iter().all(|&s| s >= 0.9), "{metres:?}");
    }

    #[test]
    fn the_gradient_distance_is_least_on_the_true_marking_edges() {
        // Eqs. 9-12 on a crafted image: 0.15 m markings (17 px wide at 5 m, 2.4 px at 35 m)
        // whose inner edges are 1.8 m either side of the camera. The particle whose four
        // delimiter edges (eqs. 2-3) sit on the markings' edges has D^G near 0 (the kernel of
        // half a marking's width saturates HG at both edges of every row); moving the lane or
        // giving it the wrong marking widths puts points on flat asphalt (128) or inside a
        // marking and raises D^G. The other cues are switched off (sigmas of 1e9) so the
        // log-likelihood is the log of eq. 12 alone, largest at the true lane.
        let camera = default_camera(640, 480).unwrap();
        let config = DanescuConfig {
            sigma_edge_px: 1e9,
            sigma_marking_px: 1e9,
            ..DanescuConfig::default()
        };
        let mut cues = ImageCues::new(&camera, &config).unwrap();
        cues.begin(&two_stripes(&camera, 1.8, 0.15)).unwrap();
        cues.finish().unwrap();
        let m = Measurement::new(&camera, &config);
        let truth = Lane3d {
            w0: 3.6,
            alpha: camera.pitch(),
            gamma: camera.roll(),
            wl_mark: 0.15,
            wr_mark: 0.15,
            ..Lane3d::default()
        };
        let dg = |l: &Lane3d| m.distances_of(&camera, l, &cues, None).gradient;
        let at = dg(&truth);
        assert!(at < 5.0, "D^G of the true lane {at}");
        for (what, lane) in [
            ("0.1 m to the right", Lane3d { xcw: 0.1, ..truth }),
            ("0.1 m to the left", Lane3d { xcw: -0.1, ..truth }),
            ("0.2 m narrower", Lane3d { w0: 3.4, ..truth }),
            (
                "markings 0.05 m",
                Lane3d {
                    wl_mark: 0.05,
                    wr_mark: 0.05,
                    ..truth
                },
            ),
            (
                "markings 0.3 m",
                Lane3d {
                    wl_mark: 0.3,
                    wr_mark: 0.3,
                    ..truth
                },
            ),
            (
                "no markings",
                Lane3d {
                    wl_mark: 0.0,
                    wr_mark: 0.0,
                    ..truth
                },
            ),
        ] {
            let d = dg(&lane);
            assert!(d > at + 30.0, "{what}: D^G {d} against {at}");
        }
        // Eq. 12: with the other cues flat, ln p = -(D^G)^2 / (2 sigma_G^2) ...
        let ll = |l: &Lane3d| m.log_likelihood(&camera, l, &cues, None);
        let want = -0.5 * (at / config.sigma_gradient).powi(2);
        assert!((ll(&truth) - want).abs() < 1e-9, "{} vs {want}", ll(&truth));
        // ... and no lane on a grid of offsets and marking widths around the truth does better.
        let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
        for i in -10..=10 {
            for j in 0..=12 {
                let (xcw, mark) = (0.03 * i as f64, 0.025 * j as f64);
                let l = Lane3d {
                    xcw,
                    wl_mark: mark,
                    wr_mark: mark,
                    ..truth
                };
                if ll(&l) > best.0 {
                    best = (ll(&l), xcw, mark);
                }
            }
        }
        assert!(
            best.1.abs() < 1e-9 && (best.2 - 0.15).abs() < 1e-9,
            "the likelihood peaks at X_CW {} W_L = W_R {}",
            best.1,
            best.2
        );
    }
}
