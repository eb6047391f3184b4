//! `liu-ppf` and `liu-ppf-nokernel`: the partitioned particle filter of Liu, Wörgötter &
//! Markelić 2013 with its kernel-density measurement model, and the PPF-NoKernel baseline the
//! paper compares it with (Sec. V-A).
//!
//! One frame (Fig. 4):
//! 1. pre-processing ([`descriptors`]): grey, IPM top view, Sobel, gradient mask, per-pixel
//!    orientation, its variance 1/|grad I| and the intensity kernel;
//! 2. resample the last frame's N + N' weighted particles to N and add N' initialisation
//!    particles from the default straight-lane model (Sec. IV-D), so N_l = N + N';
//! 3. linear part (Sec. IV-E): random walk of (rho_k, theta_k) (eqs. 18-19), weights by the
//!    line kernel density with the orientation and intensity kernels (eqs. 20-21) after the
//!    multiple-lane checks (Sec. IV-A), resampling of all N_l particles (N_p = N_l);
//! 4. parabolic part (Sec. IV-F): random walk of d_k (eqs. 22-23), weights by the parabolic
//!    kernel density by Gauss-Hermite quadrature (eqs. 24-25, A = 1/n_k^l);
//! 5. estimate: the weighted mean of (rho, theta, d) per boundary over the parabolic weights,
//!    taken over the mode of the best particle, or with `mode_candidates` (ours) the heaviest
//!    of the modes around the K best (the paper does not say how it reads its estimate off
//!    the particles; see `LiuTracker::read_estimate`). The next frame's resampling to N gives
//!    the paper's X_t.
//!
//! The boundaries (left to right) get their roles from where their near lines cross the car's
//! axis x = 0: the nearest on the left is `ego-left`, the nearest on the right `ego-right`, the
//! next ones the adjacent boundaries (further ones are tracked but not output). The lane's
//! lateral offset and width come from the ego boundaries' near lines at the car, the heading
//! from their slope, the curvature from the far parabolas (y'' = -2 e / s at s metres per
//! pixel; the near part is straight by the model's definition).
//!
//! With a positive `relock_share` (ours, off by default) a share of the particles is replaced
//! each frame by default-model lanes on the ego pair a bottom-up line detector finds
//! ([`super::relock`]). With a positive `reacquire_near_m` (ours, off by default) a lane once
//! lost is valid again only when a strong edge supports one of its ego boundaries near the
//! top view's near end ([`super::reacquire`]). With a positive `valid_paint_contrast` (ours,
//! off by default) a frame is valid only when one ego boundary at least also shows paint, a
//! bright stripe in the top view, so that shadow edges do not hold a lane through an unmarked
//! crossing. With `snap_to_paint` (ours) the reported boundaries move onto the paint's centre
//! ([`super::paint_snap`]); with `valid_needs_paint` (ours) a frame is reported not valid
//! when no run of paint begins near the car (within a dashed line's gap) along either ego
//! boundary, and with `valid_from_paint` (ours) a frame it finds not valid is reported valid
//! when paint runs along both from near the car; with `adjacent_lanes` (ours) the neighbour on the side the partitions leave out is added where paint runs there
//! ([`super::paint_output`], [`super::adjacent_lanes`]).

pub mod atan32;
pub mod config;
pub mod descriptors;
pub mod kernels;
pub mod lanes;
pub mod model;
pub mod neg_exp;
pub mod truth;

use super::paint_output::apply_paint_options;
use super::paint_snap::move_lane_figures;
use super::reacquire::Reacquire;
use super::relock::RelockDetector;
use super::support_memory::SupportMemory;
use super::{now, spread_indices, Hypothesis, Layer, StageTimes, Tracker, TrackerConfig};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::{
    FilterConfig, FirstFrame, Injection, Op, ParticleFilter, Pass, ResampleDecision,
    ResamplePolicy, Resampler, Schedule, Scheduled, Stepper,
};
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, LinearParabolic, Role};
use crate::math;
use crate::num_text::Num;
use config::{LiuConfig, MAX_BOUNDARIES};
use descriptors::Descriptors;
use model::{DefaultLanes, LaneParticle, PpfModel};

/// The id of PPF-Kernel.
pub const ID: &str = "liu-ppf";
/// The id of PPF-NoKernel.
pub const ID_NOKERNEL: &str = "liu-ppf-nokernel";
/// Particles N when the config does not say (the paper gives only N' = 50): 200, with which
/// PPF-Kernel takes about 5 ms per 640x480 frame natively (RESULTS.md); N_l = N + N' in the linear part.
pub const DEFAULT_PARTICLES: usize = 200;

/// Orientation tolerance of a supporting edge pixel (see `LiuTracker::support`), radians.
pub const SUPPORT_ORIENTATION_RAD: f64 = 0.1;
/// A supporting edge pixel's gradient, in multiples of the mask threshold.
pub const SUPPORT_GRADIENT_FACTOR: f64 = 2.0;
/// Length of a marking piece for the reach of `reacquire_near_m` (see `LiuTracker::support`),
/// metres.
pub const REACH_PIECE_M: f64 = 1.0;
/// Share of a marking piece's rows with a supporting edge pixel.
pub const REACH_PIECE_SHARE: f64 = 0.8;
/// `valid_paint_contrast`: where the road beside a marking is read, metres from the pixel
/// (beyond the half-width of a 0.15-0.3 m line).
pub const PAINT_REACH_M: f64 = 0.3;
/// `valid_paint_contrast`: columns either side of a boundary's line searched for the paint
/// (the support's 1-pixel band, widened for a line a pixel or two off its paint).
pub const PAINT_COLUMNS: i64 = 2;

/// The steps of one frame after [`LiuTracker::begin`] (per-step mode).
pub const STEP_NAMES: [&str; 7] = [
    "resample to N and add N' initialisation particles from the default lane model (Sec. IV-D)",
    "linear part: random walk of rho, theta (eqs. 18-19)",
    "linear part: weigh by the line kernel density and lane checks (eqs. 20-21, Sec. IV-A)",
    "resample the N_l particles for the parabolic part",
    "parabolic part: random walk of d (eqs. 22-23)",
    "parabolic part: weigh by the parabolic kernel density (eqs. 24-25)",
    "estimate: weighted mean of (rho, theta, d) per boundary over the best particle's mode (with mode_candidates: the heaviest mode)",
];

/// The steps of PPF-NoKernel.
pub const STEP_NAMES_NOKERNEL: [&str; 7] = [
    STEP_NAMES[0],
    STEP_NAMES[1],
    "linear part: weigh by the intensity of the edge pixels and lane checks (eq. 26, Sec. IV-A)",
    STEP_NAMES[3],
    STEP_NAMES[4],
    "parabolic part: weigh by the intensity of the edge pixels (eq. 27)",
    STEP_NAMES[6],
];

/// The operations of a frame (Sec. IV-D to IV-F): one filter of N + N' particles whose two
/// partitions, the linear part (stage 0) and the parabolic part (stage 1), are moved and
/// weighed in turn, with resampling between them. The first frame runs like any other (the
/// initial set is resampled, injected and moved).
const STEPS: [&[Op]; 7] = [
    &[Op::Resample(0), Op::Inject(0)],
    &[Op::Predict(0)],
    &[Op::Weigh(0)],
    &[Op::ResampleBetween(1)],
    &[Op::Predict(1)],
    &[Op::Weigh(1)],
    &[Op::Estimate],
];

/// PPF-Kernel's frame as the filter core runs it ([`crate::filter::schedule`]).
pub static SCHEDULE: Schedule = Schedule::new(&STEP_NAMES, &STEPS, FirstFrame::AsAnyOther);
/// PPF-NoKernel's: the same operations, its own weighing named.
pub static SCHEDULE_NOKERNEL: Schedule =
    Schedule::new(&STEP_NAMES_NOKERNEL, &STEPS, FirstFrame::AsAnyOther);

/// The estimate of one frame in the paper's terms.
#[derive(Debug, Clone, PartialEq)]
pub struct LiuEstimate {
    /// The boundaries, left to right, on the top view.
    pub boundaries: Vec<LinearParabolic>,
    /// Fraction of near rows with a strong edge pixel on each boundary (`LiuTracker::support`).
    pub support: Vec<f64>,
    /// Whether the ego boundaries are supported (`valid_fraction`, `reacquire_near_m`).
    pub valid: bool,
    /// Effective sample size after the second partition's weighing.
    pub ess: f64,
}

/// The Liu tracker (either variant).
#[derive(Debug)]
pub struct LiuTracker {
    id: &'static str,
    camera: Camera,
    config: LiuConfig,
    descriptors: Descriptors,
    model: PpfModel,
    initial: DefaultLanes,
    filter: ParticleFilter<LaneParticle>,
    /// The bottom-up detector of `relock_share` and the output options (`snap_to_paint`,
    /// `valid_needs_paint`, `valid_from_paint`, `adjacent_lanes`; `None` when they are off).
    detector: Option<RelockDetector>,
    /// The validity rule after a loss (`reacquire_near_m`).
    reacquire: Reacquire,
    /// The ego pair's support over the last frames (`valid_support_frames`).
    support_memory: SupportMemory,
    /// The particle indices the estimate's mode candidates are chosen from (all of them,
    /// allocated once).
    by_weight: Vec<usize>,
    /// Each particle's boundaries at the bottom row and at y_m, for the estimate's modes
    /// (allocated once).
    positions: Vec<[f64; 2 * MAX_BOUNDARIES]>,
    /// The frame's schedule in progress and the last frame's times.
    stepper: Stepper,
}

impl LiuTracker {
    /// Builds `liu-ppf` (`kernel` true) or `liu-ppf-nokernel`.
    ///
    /// # Errors
    /// Camera, particle-count and option errors, named; [`Error::Config`] when the top view is
    /// not visible in the camera.
    pub fn new(config: &TrackerConfig, kernel: bool) -> Result<Self> {
        let id = if kernel { ID } else { ID_NOKERNEL };
        let camera = config.validate()?;
        let mut liu = LiuConfig::from_options(id, &config.options)?;
        liu.top_view = liu.fitted_top_view(camera.focal()[0]);
        let descriptors = Descriptors::new(
            &camera,
            liu.top_view,
            liu.gradient_threshold,
            (liu.intensity_mean, liu.intensity_variance),
            kernel,
        )?;
        let (w, h) = (descriptors.width(), descriptors.height());
        let visible = descriptors
            .ipm()
            .valid()
            .data()
            .iter()
            .filter(|&&v| v == 1)
            .count();
        if visible < w * h / 10 {
            return Err(Error::Config(format!(
                "the top view ({} to {} m ahead) is hardly visible in this camera's image \
                 ({visible} of {} pixels); check the camera height and pitch or the top_view",
                Num(liu.top_view.x_min_m),
                Num(liu.top_view.x_max_m),
                w * h
            )));
        }
        let model = PpfModel::new(&liu, w, h, kernel);
        let initial = DefaultLanes::new(&liu, h);
        let filter_config = FilterConfig {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::Always,
            injection: if liu.init_particles == 0 {
                Injection::None
            } else {
                Injection::Count(liu.init_particles)
            },
        };
        let filter = ParticleFilter::new(
            config.particles_or(DEFAULT_PARTICLES) + liu.init_particles,
            filter_config,
            config.seed,
            &initial,
        )?;
        let detector = if liu.relock_share > 0.0 {
            Some(RelockDetector::new(&camera)?)
        } else if liu.paint_options().any() {
            // Output only: frames too small for the detector (under 32x16) go unsnapped and
            // without neighbours found beside the partitions'.
            RelockDetector::new(&camera).ok()
        } else {
            None
        };
        Ok(Self {
            id,
            camera,
            reacquire: Reacquire::new(liu.reacquire_near_m),
            support_memory: SupportMemory::new(liu.valid_support_frames),
            by_weight: Vec::with_capacity(filter.len()),
            positions: Vec::with_capacity(filter.len()),
            config: liu,
            descriptors,
            model,
            initial,
            filter,
            detector,
            stepper: Stepper::new(),
        })
    }

    /// The settings.
    pub fn config(&self) -> &LiuConfig {
        &self.config
    }
    /// The partitioned model.
    pub fn model(&self) -> &PpfModel {
        &self.model
    }
    /// The last frame's descriptors.
    pub fn descriptors(&self) -> &Descriptors {
        &self.descriptors
    }

    /// The particles (N + N') with their normalised weights.
    pub fn particle_states(&self) -> impl Iterator<Item = (&LaneParticle, f64)> + '_ {
        self.filter
            .states()
            .iter()
            .zip(self.filter.weights().iter().copied())
    }

    /// One frame: [`LiuTracker::begin`], then every step in order ([`Scheduled::step_frame`]).
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn track(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LiuEstimate> {
        self.step_frame(|t| t.begin(rgba, width, height))
    }

    /// Starts a frame: checks it and computes its descriptors. A frame still in progress is
    /// abandoned where it stands.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn begin(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        super::check_frame(&self.camera, rgba, width, height)?;
        let t0 = now();
        self.descriptors.compute(rgba, width, height)?;
        if let Some(d) = self.detector.as_mut() {
            let lines = self.config.relock_share > 0.0;
            d.feed_as_needed(&self.camera, rgba, width, height, lines)?;
        }
        self.stepper.begin(StageTimes {
            preprocess: now() - t0,
            ..StageTimes::default()
        });
        Ok(())
    }

    /// Replaces `relock_share` of the particles by default-model lanes on the detector's ego
    /// pair (see `relock_share`), when it found one of a default-model width.
    fn relock(&mut self) {
        let Some(d) = self.detector.as_ref().and_then(RelockDetector::detection) else {
            return;
        };
        let [lo, hi] = self.config.default_width_m;
        if !(lo..=hi).contains(&d.width()) {
            return;
        }
        let initial = &self.initial;
        self.filter
            .replace_share(self.config.relock_share, |_, rng| {
                initial.on_ego_pair(&d, rng)
            });
    }

    /// The weighted mean of (rho, theta, d) over a mode: the particles whose every boundary
    /// lies within half the minimum lane spacing of a centre particle's, at the bottom row and
    /// at y_m. The centre is the heaviest particle, or with `mode_candidates` K > 1 the one of
    /// the K heaviest whose mode weighs most. (A plain mean would average modes that explain
    /// different sets of n_l boundaries of a wider road, e.g. the three left and the three
    /// right boundaries of a three-lane road, into lines between the markings.)
    fn read_estimate(&mut self) -> LiuEstimate {
        let n = self.model.boundaries();
        let states = self.filter.states();
        let weights = self.filter.weights();
        let rows = [
            self.descriptors.height() as f64 - 1.0,
            self.model.split_row(),
        ];
        let radius = self.config.min_spacing_m / 2.0 / self.config.top_view.m_per_px;
        // Each particle's boundaries at the two rows, boundary by boundary.
        self.positions.clear();
        self.positions.extend(states.iter().map(|p| {
            let mut at = [0.0; 2 * MAX_BOUNDARIES];
            for k in 0..n {
                let b = self.model.boundary(p, k);
                at[2 * k] = b.x_at(rows[0]);
                at[2 * k + 1] = b.x_at(rows[1]);
            }
            at
        }));
        let positions = &self.positions;
        let near = |i: usize, centre: usize| {
            let (a, b) = (&positions[i][..2 * n], &positions[centre][..2 * n]);
            a.iter().zip(b).all(|(x, y)| (x - y).abs() < radius)
        };
        let centre = mode_centre(
            weights,
            self.config.mode_candidates,
            &mut self.by_weight,
            |c| {
                (0..states.len())
                    .filter(|&i| near(i, c))
                    .map(|i| weights[i])
                    .sum()
            },
        );
        let best = &states[centre];
        let mut mean = [[0.0; 3]; MAX_BOUNDARIES];
        let mut total = 0.0;
        for (i, (p, w)) in self.particle_states().enumerate() {
            if !near(i, centre) {
                continue;
            }
            total += w;
            for (m, b) in mean.iter_mut().zip(&p.boundaries).take(n) {
                for (mv, bv) in m.iter_mut().zip(b) {
                    *mv += w * bv;
                }
            }
        }
        let particle = if total > 0.0 {
            for b in mean.iter_mut() {
                for v in b.iter_mut() {
                    *v /= total;
                }
            }
            LaneParticle { boundaries: mean }
        } else {
            *best
        };
        let boundaries: Vec<LinearParabolic> =
            (0..n).map(|k| self.model.boundary(&particle, k)).collect();
        let (support, reach): (Vec<f64>, Vec<f64>) =
            boundaries.iter().map(|b| self.support(b)).unzip();
        let contrast = self.config.valid_paint_contrast;
        let roles = self.roles(&boundaries);
        let ego = |role: Role| roles.iter().find(|r| r.1 == role).map(|r| r.0);
        let valid = if let (Some(l), Some(r)) = (ego(Role::EgoLeft), ego(Role::EgoRight)) {
            let pair = [support[l], support[r]];
            let near = reach[l].min(reach[r]);
            // `valid_paint_contrast`: paint on one side at least (read only when on).
            let paint = contrast <= 0.0
                || [l, r]
                    .iter()
                    .any(|&k| self.painted(&boundaries[k], contrast) >= self.config.valid_fraction);
            let remembered = self.support_memory.push(pair);
            self.reacquire
                .valid(pair, remembered, self.config.valid_fraction, near)
                && paint
        } else {
            // No ego pair: a frame without support, so that the memory holds the last frames.
            self.support_memory.push([0.0; 2]);
            self.reacquire.no_lane()
        };
        LiuEstimate {
            boundaries,
            support,
            valid,
            ess: self.filter.ess(),
        }
    }

    /// Fraction of near rows ([`LiuConfig::support_first_row`]) with a strong edge pixel on the
    /// boundary's line: within one pixel, its orientation within [`SUPPORT_ORIENTATION_RAD`] of
    /// the line's and its gradient at least [`SUPPORT_GRADIENT_FACTOR`] times the mask
    /// threshold. (Any mask pixel would not do: the paper's threshold passes asphalt texture,
    /// and half the top view.) And the reach (`reacquire_near_m`): how far beyond the view's
    /// nearest row the nearest marking piece begins, metres (infinite without one). A piece is
    /// [`REACH_PIECE_M`] of rows (at most 64) of which [`REACH_PIECE_SHARE`] have such a pixel:
    /// one textured patch of asphalt lines up with a boundary in a row or two, a marking in
    /// nearly every row.
    fn support(&self, b: &LinearParabolic) -> (f64, f64) {
        let d = &self.descriptors;
        let (w, h) = (d.width(), d.height());
        let first = self.config.support_first_row(h, self.model.split_row());
        let (a, slope) = (b.a(), b.b());
        let strong = (SUPPORT_GRADIENT_FACTOR * self.config.gradient_threshold) as f32;
        let s = self.config.top_view.m_per_px;
        let piece = ((REACH_PIECE_M / s).round() as u32).clamp(1, 64);
        let needed = (REACH_PIECE_SHARE * f64::from(piece)).ceil() as u32;
        let mask = u64::MAX >> (64 - piece);
        // The last `piece` rows, the nearest in bit 0: 1 where the row has a supporting pixel.
        let mut recent = 0u64;
        let mut hits = 0;
        let mut nearest = None;
        for (k, y) in (first..h).enumerate() {
            let x = (a + slope * y as f64).round();
            let hit = x >= 0.0 && x < w as f64 && {
                let x = x as usize;
                let span = d.span(y, x.saturating_sub(1), (x + 1).min(w - 1));
                d.pixels[span].iter().any(|px| {
                    px.precision >= strong
                        && descriptors::wrap_half_turn(b.theta - f64::from(px.theta)).abs()
                            < SUPPORT_ORIENTATION_RAD
                })
            };
            hits += usize::from(hit);
            recent = (recent << 1 | u64::from(hit)) & mask;
            if k + 1 >= piece as usize && recent.count_ones() >= needed {
                nearest = Some(y);
            }
        }
        let reach = nearest.map_or(f64::INFINITY, |y| (h - 1 - y) as f64 * s);
        (hits as f64 / (h - first).max(1) as f64, reach)
    }

    /// The share of `support`'s rows where the top view shows paint on boundary `b`'s line: a
    /// pixel within [`PAINT_COLUMNS`] columns of it brighter by `contrast` grey levels than
    /// both pixels [`PAINT_REACH_M`] to its sides (`valid_paint_contrast`).
    fn painted(&self, b: &LinearParabolic, contrast: f64) -> f64 {
        let d = &self.descriptors;
        let top = d.top_view();
        let (w, h) = (d.width(), d.height());
        let first = self.config.support_first_row(h, self.model.split_row());
        let (a, slope) = (b.a(), b.b());
        let reach = (PAINT_REACH_M / self.config.top_view.m_per_px).ceil() as i64;
        let mut hits = 0;
        for y in first..h {
            let x = (a + slope * y as f64).round() as i64;
            let row = top.row(y);
            let at = |x: i64| (x >= 0 && (x as usize) < w).then(|| row[x as usize] as f64);
            let hit = (x - PAINT_COLUMNS..=x + PAINT_COLUMNS).any(|c| {
                match (at(c), at(c - reach), at(c + reach)) {
                    (Some(m), Some(l), Some(r)) => m - l >= contrast && m - r >= contrast,
                    _ => false,
                }
            });
            hits += usize::from(hit);
        }
        hits as f64 / (h - first).max(1) as f64
    }

    /// Lateral position y (m, left positive) of top-view boundary `b` at `x` metres ahead (the
    /// near line extended below the top view).
    fn road_y(&self, b: &LinearParabolic, x: f64) -> f64 {
        let v = &self.config.top_view;
        let s = v.m_per_px;
        let r = (v.x_max_m - x) / s - 0.5;
        v.y_left_m - (b.x_at(r) + 0.5) * s
    }

    /// The boundaries nearest the car (left to right on the top view) and their roles: the
    /// first one right of the car is the ego lane's right boundary.
    fn roles(&self, boundaries: &[LinearParabolic]) -> Vec<(usize, Role)> {
        let at_car: Vec<f64> = boundaries.iter().map(|b| self.road_y(b, 0.0)).collect();
        // Boundaries are ordered left to right; find the first one right of the car.
        let right = at_car
            .iter()
            .position(|&y| y <= 0.0)
            .unwrap_or(at_car.len());
        let mut roles: Vec<(usize, Role)> = Vec::new();
        if right >= 1 {
            roles.push((right - 1, Role::EgoLeft));
        }
        if right >= 2 {
            roles.push((right - 2, Role::LeftAdjacent));
        }
        if right < at_car.len() {
            roles.push((right, Role::EgoRight));
        }
        if right + 1 < at_car.len() {
            roles.push((right + 1, Role::RightAdjacent));
        }
        roles
    }

    /// Boundary `b` of the top view as image and road polylines.
    fn boundary(&self, b: &LinearParabolic, role: Role) -> Boundary {
        let (points, road_points) = sample_road_curve(
            |x| self.road_y(b, x),
            |x, y| self.camera.road_to_pixel(x, y),
            1.0,
            self.config.top_view.x_max_m,
            self.camera.width(),
            self.camera.height(),
        );
        Boundary {
            role,
            points,
            road_points,
        }
    }

    /// The estimate as the shared output type.
    pub fn to_lane_estimate(&self, e: &LiuEstimate) -> LaneEstimate {
        let at_car: Vec<f64> = e.boundaries.iter().map(|b| self.road_y(b, 0.0)).collect();
        let roles = self.roles(&e.boundaries);
        let v = &self.config.top_view;
        let mut boundaries = Vec::new();
        let mut state = std::collections::BTreeMap::new();
        for &(k, role) in &roles {
            let b = &e.boundaries[k];
            boundaries.push(self.boundary(b, role));
            let name = role.as_str();
            state.insert(format!("liu.{name}.rho"), b.rho);
            state.insert(format!("liu.{name}.theta"), b.theta);
            state.insert(format!("liu.{name}.d"), b.d);
        }
        let ego = |role: Role| roles.iter().find(|r| r.1 == role).map(|r| r.0);
        let s = v.m_per_px;
        let (mut offset, mut heading, mut curvature, mut width) = (0.0, 0.0, 0.0, 0.0);
        if let (Some(l), Some(r)) = (ego(Role::EgoLeft), ego(Role::EgoRight)) {
            let (bl, br) = (&e.boundaries[l], &e.boundaries[r]);
            heading = (math::atan(bl.b()) + math::atan(br.b())) / 2.0;
            offset = -(at_car[l] + at_car[r]) / 2.0;
            width = (at_car[l] - at_car[r]) * math::cos(heading);
            curvature = -(bl.e() + br.e()) / s;
        }
        let (valid, snapped) = apply_paint_options(
            &self.camera,
            &mut boundaries,
            self.detector.as_ref(),
            e.valid,
            self.config.paint_options(),
        );
        state.insert(
            "liu.mask_pixels".to_string(),
            self.descriptors.count() as f64,
        );
        state.insert("liu.ess".to_string(), e.ess);
        let mut estimate = LaneEstimate {
            frame: String::new(),
            valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: offset,
            heading_rad: heading,
            curvature_per_m: curvature,
            lane_width_m: width,
            delimiters: Vec::new(),
            state,
        };
        move_lane_figures(&mut estimate, snapped.moved_at_car);
        estimate
    }
}

impl Tracker for LiuTracker {
    fn id(&self) -> &'static str {
        self.id
    }

    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate> {
        let e = self.track(rgba, width, height)?;
        Ok(self.to_lane_estimate(&e))
    }

    fn reset(&mut self) {
        self.filter.reset(&self.initial);
        self.support_memory.clear();
        self.reacquire.reset();
        if let Some(d) = self.detector.as_mut() {
            d.reset();
        }
        self.stepper.abandon();
    }

    fn stage_times(&self) -> StageTimes {
        self.stepper.times()
    }

    /// 3 n_l + 1 numbers per particle: (rho px, theta rad, d) of each boundary on the top
    /// view, left to right, then the normalised weight. The first N' particles are the frame's
    /// initialisation particles until the linear part has resampled them.
    fn particles(&self) -> Vec<f32> {
        let n = self.model.boundaries();
        let mut out = Vec::with_capacity(self.filter.len() * (3 * n + 1));
        for (p, w) in self.particle_states() {
            for b in &p.boundaries[..n] {
                out.extend(b.iter().map(|&v| v as f32));
            }
            out.push(w as f32);
        }
        out
    }

    fn particle_stride(&self) -> usize {
        3 * self.model.boundaries() + 1
    }

    /// Group: 0 (one cloud).
    fn hypotheses(&self, max: usize) -> Vec<Hypothesis> {
        let n = self.model.boundaries();
        let states = self.filter.states();
        let weights = self.filter.weights();
        spread_indices(states.len(), max)
            .map(|i| {
                let bs: Vec<LinearParabolic> =
                    (0..n).map(|k| self.model.boundary(&states[i], k)).collect();
                Hypothesis {
                    weight: weights[i],
                    group: 0,
                    boundaries: self
                        .roles(&bs)
                        .into_iter()
                        .map(|(k, role)| self.boundary(&bs[k], role))
                        .collect(),
                }
            })
            .collect()
    }

    fn step_names(&self) -> &'static [&'static str] {
        self.schedule().names()
    }

    /// The measurement pixels' weights and the top view itself (grey / 255). PPF-Kernel's
    /// weights K_c sqrt(|grad I| / 2 pi) relative to half the frame's largest, clipped at 1 (the
    /// gradient term has a long tail); PPF-NoKernel's, the intensity kernel K_c alone, relative
    /// to the largest (no clipping: K_c is bounded, and half of it saturates nearly every pixel).
    fn layers(&self) -> Vec<Layer> {
        let d = &self.descriptors;
        let (w, h) = (d.width(), d.height());
        let v = &self.config.top_view;
        let kernel = self.id == ID;
        let max = d.weight.iter().copied().fold(0.0f32, f32::max);
        let top_share = if kernel { 0.5 } else { 1.0 };
        let scale = if max > 0.0 {
            1.0 / (top_share * max)
        } else {
            0.0
        };
        let measurement = if kernel {
            "measurement pixels: intensity and orientation kernel weight"
        } else {
            "measurement pixels: intensity kernel K_c alone (PPF-NoKernel, eqs. 26-27: no position or orientation kernel)"
        };
        // Grid rows run from near to far: flip the top view's rows.
        let flip = |f: &dyn Fn(usize) -> f32| -> Vec<f32> {
            (0..h)
                .rev()
                .flat_map(|r| (0..w).map(move |c| r * w + c))
                .map(f)
                .collect()
        };
        let grid = |name: &str, values: Vec<f32>| Layer::Grid {
            name: name.to_string(),
            width: w,
            height: h,
            x0: v.x_max_m - h as f64 * v.m_per_px,
            y0: v.y_left_m,
            cell: v.m_per_px,
            values,
        };
        let top = d.top_view().data();
        vec![
            grid(measurement, flip(&|i| (d.weight[i] * scale).min(1.0))),
            grid(
                "top view (grey / 255)",
                flip(&|i| f32::from(top[i]) / 255.0),
            ),
        ]
    }

    fn begin_frame(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        self.begin(rgba, width, height)
    }

    fn advance(&mut self) -> Result<Option<LaneEstimate>> {
        super::advance_scheduled(self, Self::to_lane_estimate)
    }

    fn next_step(&self) -> Option<usize> {
        self.stepper.next_step()
    }

    fn resamplings(&self) -> &[ResampleDecision] {
        self.stepper.resamplings()
    }
}

/// The index of the estimate's centre particle: the heaviest of `weights` for `candidates` <= 1;
/// otherwise, of the `candidates` heaviest particles (`by_weight`: a buffer), the one whose mode
/// weighs most (`mode_weight`; the heavier particle on a tie).
fn mode_centre(
    weights: &[f64],
    candidates: usize,
    by_weight: &mut Vec<usize>,
    mode_weight: impl Fn(usize) -> f64,
) -> usize {
    let best = crate::filter::map_index(weights);
    let k = candidates.min(weights.len());
    if k <= 1 {
        return best;
    }
    // The k heaviest first, by a partial selection sort: k N steps for a few dozen candidates,
    // and no sorting routine in the wasm module.
    by_weight.clear();
    by_weight.extend(0..weights.len());
    let heavier =
        |i: usize, j: usize| weights[i] > weights[j] || (weights[i] == weights[j] && i < j);
    for r in 0..k {
        let mut top = r;
        for j in r + 1..by_weight.len() {
            if heavier(by_weight[j], by_weight[top]) {
                top = j;
            }
        }
        by_weight.swap(r, top);
    }
    let mut centre = (best, mode_weight(best));
    for &c in by_weight[..k].iter().filter(|&&c| c != best) {
        let w = mode_weight(c);
        if w > centre.1 {
            centre = (c, w);
        }
    }
    centre.0
}

/// The models of the schedule's operations: stage k is partition k of the one filter.
impl Scheduled for LiuTracker {
    type State = LaneParticle;
    type Estimate = LiuEstimate;

    fn schedule(&self) -> &'static Schedule {
        if self.id == ID {
            &SCHEDULE
        } else {
            &SCHEDULE_NOKERNEL
        }
    }
    fn stepper(&self) -> &Stepper {
        &self.stepper
    }
    fn stepper_mut(&mut self) -> &mut Stepper {
        &mut self.stepper
    }
    fn filter_mut(&mut self, _stage: usize) -> Option<&mut ParticleFilter<LaneParticle>> {
        Some(&mut self.filter)
    }
    /// N' straight default lanes.
    fn inject(&mut self, _stage: usize) {
        self.filter.inject(&self.initial);
    }
    /// The random walk of partition k (eqs. 18-19, 22-23); after the linear part's, the
    /// relock proposal.
    fn predict(&mut self, stage: usize, _pass: Pass) {
        self.filter.partitioned_predict(&self.model, stage);
        if stage == 0 {
            self.relock();
        }
    }
    /// The kernel density of partition k (eqs. 20-21, 24-25; 26-27 without the kernels).
    fn weigh(&mut self, stage: usize) {
        self.filter
            .partitioned_weigh(&self.model, stage, &self.descriptors);
    }
    fn estimate(&mut self) -> LiuEstimate {
        self.read_estimate()
    }
}

#[cfg(test)]
mod paint_tests;
#[cfg(test)]
mod reacquire_tests;
#[cfg(test)]
mod resolved_view_tests;
#[cfg(test)]
mod tests;
