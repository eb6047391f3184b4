//! `lee-cpf`: the cascade particle filter of Lee, Jang & Sunwoo 2015, with its clothoid lane
//! model and Kalman smoothing.
//!
//! One frame (Fig. 4):
//! 1. features: grey levels of the near and far bands of rows; in the near band, DLD marking
//!    candidates (eqs. 21-26, [`candidates`]) marked on a road grid and turned into the
//!    likelihood map D by a distance transform ([`likelihood_map`]); in the far band, Canny
//!    edges ([`far_edges`]);
//! 2. stage 1 (Algorithm 1, s = 1): the particles [psi, y0, w, w'] (eq. 18) move by the free
//!    motion model (eq. 20, [`motion`]) and are weighed by the approximated measurement model
//!    on D (eqs. 27-33, [`measurement`]); the estimate is their weighted mean; resampling
//!    when N_eff < N_thr;
//! 3. stage 2 (s = 2): the particles [c, delta] (eq. 19) move the same way and are weighed by
//!    the residual model on the far edges, each completed with the stage-1 estimate into the
//!    full clothoid lane ([`clothoid`]); weighted mean; resampling when N_eff < N_thr;
//! 4. the six estimated states pass the Kalman smoother ([`kalman`]) and become boundaries.
//!
//! Start and restart (ours; the paper does not say how the filter starts): on a first frame
//! stage 1 runs `start_iterations` rounds on the same cues, its process noise annealed from
//! `start_spread` times Q down to Q, with a share `start_fresh` of the cloud drawn anew from
//! the initial distribution in the first half of the rounds; and after `lost_restart`
//! consecutive frames with no marking near either boundary the filter starts again. Without
//! them a cold start on a dashed-line scene locked half a lane off, at the width limit, from
//! about half of its start frames (see `a_cold_start_finds_the_lane_from_almost_any_frame`).
//! With a positive `relock_share` (ours, off by default) a share of stage 1's particles is drawn each
//! frame around the ego pair a bottom-up line detector finds ([`super::relock`]).
//!
//! Lane changes (our addition; the paper shows the lateral offset jumping by a lane width at
//! each change, Fig. 10, without saying how): when the stage-1 estimate of y0 leaves
//! [-w/2, w/2) by the margin of the rule every tracker shares ([`super::lane_change`]), the
//! car has crossed a boundary, and every particle moves by one lane width so
//! that the filter goes on with the lane the car is now in. Re-centring the whole cloud, rather
//! than wrapping particles one by one, keeps the cloud in one piece: per-particle wrapping
//! split it at the seam, and the half that kept the old lane (whose outer boundary was a solid
//! line, which eq. 32 favours over two dashed ones) held on by tilting psi and widening w.
//!
//! The baselines of the paper share the cues and the particle count: `first-order` (PF1, stage
//! 1 alone, straight lanes) and `full-model` (one filter over all six states weighed by both
//! models). A frame is valid when, on each of the two boundaries, at least `valid_fraction`
//! of the estimate's near points lie within sigma_D of a marking candidate (0.15 by default; a
//! dashed line of 3 m dashes every 12 m gives about 0.25); the paper counts "valid frames"
//! without defining them, and this is our definition.

pub mod candidates;
pub mod clothoid;
pub mod config;
pub mod far_edges;
pub mod kalman;
pub mod likelihood_map;
pub mod measurement;
pub mod motion;

use super::adjacent_lanes::adjacent_boundaries;
use super::lane_change::{self, EgoLane};
use super::relock::RelockDetector;
use super::{now, spread_indices, Hypothesis, Layer, StageTimes, Tracker, TrackerConfig};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::{
    FilterConfig, InitialDistribution, Injection, MeasurementModel, ParticleFilter, ResamplePolicy,
    Resampler,
};
use crate::image::{luma, Image};
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use candidates::Candidates;
use clothoid::{Curve, LaneState};
use config::{LeeConfig, Variant};
use far_edges::FarEdges;
use kalman::Smoother;
use likelihood_map::LikelihoodMap;
use measurement::{Measurement, MeasurementSettings};
use motion::{Initial, Limits, Motion, Part};

/// The tracker id.
pub const ID: &str = "lee-cpf";
/// Particles N (per stage) when the config does not say.
pub const DEFAULT_PARTICLES: usize = 500;

/// Support (share of near points on a marking) under which a boundary has no marking at all.
const LOST_SUPPORT: f64 = 0.05;

/// Stage 1's model: eq. 33 on the near map, first-order lane (the full-model baseline uses
/// [`FarModel`] with the near map instead).
struct NearModel<'a> {
    measurement: &'a Measurement,
    map: &'a LikelihoodMap,
}

impl MeasurementModel<LaneState> for NearModel<'_> {
    type Cues = ();
    fn log_likelihood(&self, s: &LaneState, _: &()) -> f64 {
        self.measurement.near_log_likelihood(s, None, self.map)
    }
}

/// One step of a frame (see [`LeeTracker::step_names`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Predict1,
    Weigh1,
    Finish1,
    Predict2,
    Weigh2,
    Finish2,
    Output,
}

const CASCADE_STEPS: [Step; 7] = [
    Step::Predict1,
    Step::Weigh1,
    Step::Finish1,
    Step::Predict2,
    Step::Weigh2,
    Step::Finish2,
    Step::Output,
];
const CASCADE_STEP_NAMES: [&str; 7] = [
    "stage 1 [psi, y0, w, w']: predict",
    "stage 1: weigh (DLD distance map, eqs. 27-33)",
    "stage 1: estimate, resample if N_eff < N_thr",
    "stage 2 [c, delta]: predict",
    "stage 2: weigh (far Canny edges)",
    "stage 2: estimate, resample if N_eff < N_thr",
    "Kalman smoothing and output",
];
const SINGLE_STEPS: [Step; 4] = [Step::Predict1, Step::Weigh1, Step::Finish1, Step::Output];
const SINGLE_STEP_NAMES: [&str; 4] = [
    "predict",
    "weigh",
    "estimate, resample if N_eff < N_thr",
    "Kalman smoothing and output",
];

/// A frame in progress in per-step mode.
#[derive(Debug, Clone)]
struct Frame {
    /// Index of the next step.
    next: usize,
    /// Whether this is the first frame (after construction or a reset).
    first: bool,
    estimate: LaneState,
    ess: [f64; 2],
    change: i8,
    times: StageTimes,
}

/// Stage 2's model: the far edges, for the lane made of `first` (the stage-1 estimate, or the
/// particle's own first-order states when `None`) and the particle's (c, delta); plus the near
/// model in the full-model baseline.
struct FarModel<'a> {
    measurement: &'a Measurement,
    camera: &'a Camera,
    edges: &'a FarEdges,
    spiral: f64,
    first: Option<LaneState>,
    near: Option<&'a LikelihoodMap>,
}

impl MeasurementModel<LaneState> for FarModel<'_> {
    type Cues = ();
    fn log_likelihood(&self, s: &LaneState, _: &()) -> f64 {
        let lane = match self.first {
            Some(f) => LaneState {
                c: s.c,
                delta: s.delta,
                ..f
            },
            None => *s,
        };
        let curve = Curve::new(lane.c, lane.delta, self.spiral);
        let far = self
            .measurement
            .far_log_likelihood(&lane, &curve, self.camera, self.edges);
        let near = self.near.map_or(0.0, |map| {
            self.measurement
                .near_log_likelihood(&lane, Some(&curve), map)
        });
        far + near
    }
}

/// The estimate of one frame in the paper's terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeeEstimate {
    /// The six states after the Kalman smoother (equal to `raw` when it is off).
    pub state: LaneState,
    /// The particle filter's own estimate.
    pub raw: LaneState,
    /// Whether the frame is valid (see the module docs).
    pub valid: bool,
    /// Fraction of the near points of the left and right boundary supported by candidates.
    pub support: [f64; 2],
    /// Lane change this frame: +1 to the left, -1 to the right, 0 none.
    pub change: i8,
    /// Marking candidates found.
    pub candidates: usize,
    /// Effective sample sizes of stage 1 and stage 2 after weighing.
    pub ess: [f64; 2],
}

/// The Lee tracker.
#[derive(Debug)]
pub struct LeeTracker {
    camera: Camera,
    config: LeeConfig,
    gray: Image<u8>,
    gray_rows: std::ops::Range<usize>,
    near_m: f64,
    map: LikelihoodMap,
    candidates: Candidates,
    far: FarEdges,
    measurement: Measurement,
    /// Stage 1 (or the single filter of a baseline).
    stage1: ParticleFilter<LaneState>,
    /// Stage 2 of the cascade.
    stage2: Option<ParticleFilter<LaneState>>,
    initial: Initial,
    limits: Limits,
    smoother: Smoother,
    times: StageTimes,
    first: bool,
    /// Consecutive frames whose estimate no marking supports (see `lost_restart`).
    lost: usize,
    /// The bottom-up detector of `relock_share` (`None` when it is off).
    detector: Option<RelockDetector>,
    frame: Option<Frame>,
}

/// Image rows whose road point (at the left, centre or right column) lies in [from, to).
fn band_rows(camera: &Camera, from: f64, to: f64) -> std::ops::Range<usize> {
    let (w, h) = (camera.width(), camera.height());
    let (mut first, mut last) = (h, 0);
    for v in 0..h {
        for u in [0.0, (w as f64 - 1.0) / 2.0, w as f64 - 1.0] {
            if let Ok([x, _]) = camera.pixel_to_road(u, v as f64) {
                if x >= from && x < to {
                    first = first.min(v);
                    last = last.max(v);
                }
            }
        }
    }
    if first > last {
        0..0
    } else {
        first..last + 1
    }
}

impl LeeTracker {
    /// Builds the tracker.
    ///
    /// # Errors
    /// Camera, particle-count and option errors, named; [`Error::Config`] when the near range
    /// is not visible in the camera's image.
    pub fn new(config: &TrackerConfig) -> Result<Self> {
        let camera = config.validate()?;
        let lee = LeeConfig::from_options(&config.options)?;
        // The nearest visible road distance (bottom centre of the image).
        let (w, h) = (camera.width(), camera.height());
        let bottom = camera
            .pixel_to_road((w as f64 - 1.0) / 2.0, h as f64 - 1.0)
            .map(|p| p[0])
            .unwrap_or(f64::INFINITY);
        let near_m = lee.near_m.max(bottom);
        let near_rows = band_rows(&camera, near_m, lee.split_m);
        if near_m >= lee.split_m || near_rows.len() < 2 {
            return Err(Error::Config(format!(
                "the near range ({} to {} m ahead) is not visible in this camera's image",
                lee.near_m, lee.split_m
            )));
        }
        let far_rows = band_rows(&camera, lee.split_m, lee.far_m);
        let gray_rows = far_rows.start.min(near_rows.start)..near_rows.end.max(far_rows.end);
        let map = LikelihoodMap::new(
            near_m,
            lee.split_m,
            lee.lateral_range_m,
            lee.cell_m,
            lee.map_sigma_m,
        )?;
        let candidates = Candidates::new(lee.dld, near_rows, lee.max_marking_width_m)?;
        let far = FarEdges::new(lee.canny, far_rows)?;
        let measurement = Measurement::new(
            &camera,
            MeasurementSettings {
                near: [near_m, lee.split_m, lee.near_step_m],
                far: [lee.split_m, lee.far_m, lee.far_step_m],
                marking_width: lee.marking_width_m,
                alpha: lee.alpha,
                beta: lee.beta,
                tau: lee.tau_m,
                sigma_q: lee.sigma_q,
                sigma_far: lee.sigma_far,
            },
        );
        let limits = Limits {
            heading: lee.max_heading_rad,
            width: lee.width_range_m,
            width_rate: lee.max_width_rate,
            transition: [-lee.spiral_length_m, lee.max_transition_m],
            curvature: lee.max_curvature,
        };
        let initial = Initial { limits };
        let filter_config = FilterConfig {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::EssBelow(lee.ess_threshold),
            injection: Injection::None,
        };
        let stage1 = ParticleFilter::new(
            config.particles_or(DEFAULT_PARTICLES),
            filter_config,
            config.seed,
            &initial,
        )?;
        let stage2 = if lee.variant == Variant::Cascade {
            let n2 = if lee.stage2_particles == 0 {
                config.particles_or(DEFAULT_PARTICLES)
            } else {
                lee.stage2_particles
            };
            // A different stream for stage 2, derived from the seed.
            Some(ParticleFilter::new(
                n2,
                filter_config,
                config.seed ^ 0x9e37_79b9_7f4a_7c15,
                &initial,
            )?)
        } else {
            None
        };
        let smoother = Smoother::new(lee.kalman_process_sd, lee.kalman_measurement_sd);
        let detector = if lee.relock_share > 0.0 || lee.adjacent_lanes {
            Some(RelockDetector::new(&camera)?)
        } else {
            None
        };
        Ok(Self {
            gray: Image::new(w, h)?,
            gray_rows,
            near_m,
            map,
            candidates,
            far,
            measurement,
            stage1,
            stage2,
            initial,
            limits,
            smoother,
            times: StageTimes::default(),
            first: true,
            lost: 0,
            detector,
            frame: None,
            camera,
            config: lee,
        })
    }

    /// The settings in use.
    pub fn config(&self) -> &LeeConfig {
        &self.config
    }

    /// The likelihood map D of the last frame: values (rows along x from the near distance,
    /// columns from +lateral_range to -lateral_range), its width and height.
    pub fn likelihood_map(&self) -> (&[f32], usize, usize) {
        (
            &self.map.likelihood,
            self.map.marks.width(),
            self.map.marks.height(),
        )
    }

    /// The particles of both stages: (stage 1 or 2, or 0 for a single-stage baseline, the full
    /// lane the particle stands for, weight). Stage-1 particles carry the last stage-2
    /// estimate's (c, delta); stage-2 particles the stage-1 estimate's first-order states.
    pub fn particle_states(&self) -> Vec<(u8, LaneState, f64)> {
        let single = self.stage2.is_none();
        let mut out: Vec<(u8, LaneState, f64)> = self
            .stage1
            .states()
            .iter()
            .zip(self.stage1.weights())
            .map(|(s, &w)| (if single { 0 } else { 1 }, *s, w))
            .collect();
        if let Some(f) = &self.stage2 {
            out.extend(f.states().iter().zip(f.weights()).map(|(s, &w)| (2, *s, w)));
        }
        out
    }

    /// Back to the initial distribution: the next frame is a first frame.
    fn restart(&mut self) {
        self.stage1.reset(&self.initial);
        if let Some(f) = self.stage2.as_mut() {
            f.reset(&self.initial);
        }
        self.smoother.reset();
        self.first = true;
        self.lost = 0;
    }

    /// Replaces every k-th stage-1 particle (k = 1 / `start_fresh`) with a draw from the
    /// initial distribution: spread over the resampled cloud, whose copies of one ancestor sit
    /// side by side, so no ancestor loses more than its share.
    fn refresh_start_particles(&mut self) {
        if self.config.start_fresh <= 0.0 {
            return;
        }
        let every = (1.0 / self.config.start_fresh).round().max(1.0) as usize;
        let n = self.stage1.len();
        for i in (0..n).step_by(every) {
            let fresh = self.initial.sample(self.stage1.rng_mut());
            self.stage1.states_mut()[i] = fresh;
        }
    }

    /// Replaces `relock_share` of the stage-1 particles by draws around the detector's ego
    /// pair (see `relock_share`), when it found one within the state limits.
    fn relock(&mut self) {
        let Some(d) = self.detector.as_ref().and_then(RelockDetector::detection) else {
            return;
        };
        let (psi, y0, w) = (d.heading(), d.centre(), d.width());
        let l = self.limits;
        if psi.abs() > l.heading || w < l.width[0] || w > l.width[1] {
            return;
        }
        let sd = self.config.process_sd;
        self.stage1
            .replace_share(self.config.relock_share, |old, rng| LaneState {
                psi: rng.gaussian(psi, sd[0]).clamp(-l.heading, l.heading),
                y0: rng.gaussian(y0, sd[1]),
                w: rng.gaussian(w, sd[2]).clamp(l.width[0], l.width[1]),
                ..*old
            });
    }

    fn motion(&self, part: Part) -> Motion {
        Motion {
            part,
            sd: self.config.process_sd,
            limits: self.limits,
        }
    }

    /// Grey levels of the rows the cues read.
    fn convert(&mut self, rgba: &[u8]) {
        let w = self.gray.width();
        for v in self.gray_rows.clone() {
            let src = &rgba[v * w * 4..(v + 1) * w * 4];
            for (g, p) in self.gray.row_mut(v).iter_mut().zip(src.chunks_exact(4)) {
                *g = luma(p[0], p[1], p[2]);
            }
        }
    }

    /// One frame, returning the estimate in the paper's terms: [`LeeTracker::begin`], then
    /// every step of [`LeeTracker::step_names`] in order.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn track(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LeeEstimate> {
        self.begin(rgba, width, height)?;
        loop {
            if let Some(e) = self.advance_step() {
                return Ok(e);
            }
        }
    }

    /// The steps of one frame after [`LeeTracker::begin`], for teaching.
    pub fn step_names(&self) -> &'static [&'static str] {
        if self.stage2.is_some() {
            &CASCADE_STEP_NAMES
        } else {
            &SINGLE_STEP_NAMES
        }
    }

    fn steps(&self) -> &'static [Step] {
        if self.stage2.is_some() {
            &CASCADE_STEPS
        } else {
            &SINGLE_STEPS
        }
    }

    /// Index of the next step of the frame in progress (`None` when no frame is in progress).
    pub fn next_step(&self) -> Option<usize> {
        self.frame.as_ref().map(|f| f.next)
    }

    /// Starts a frame: checks it and computes the image cues (the DLD candidates and their map
    /// D, the far Canny edges). A frame still in progress is abandoned where it stands.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn begin(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        super::check_frame(&self.camera, rgba, width, height)?;
        let t = now();
        self.convert(rgba);
        self.candidates
            .detect(&self.gray, &self.camera, &mut self.map)?;
        self.far.detect(&self.gray)?;
        if let Some(d) = self.detector.as_mut() {
            d.feed(&self.camera, rgba, width, height)?;
        }
        let first = self.first;
        self.first = false;
        self.frame = Some(Frame {
            next: 0,
            first,
            estimate: LaneState::default(),
            ess: [0.0; 2],
            change: 0,
            times: StageTimes {
                preprocess: now() - t,
                ..StageTimes::default()
            },
        });
        Ok(())
    }

    /// Runs the next step of the frame in progress; returns the estimate after the last one
    /// (and `None` before, or when no frame is in progress).
    pub fn advance_step(&mut self) -> Option<LeeEstimate> {
        let mut frame = self.frame.take()?;
        let step = self.steps()[frame.next];
        frame.next += 1;
        let t = now();
        let spiral = self.config.spiral_length_m;
        let starts = if frame.first {
            self.config.start_iterations
        } else {
            0
        };
        match step {
            Step::Predict1 => {
                if !frame.first {
                    let part = if self.config.variant == Variant::FullModel {
                        Part::Full
                    } else {
                        Part::FirstOrder
                    };
                    self.stage1.predict(&self.motion(part));
                    self.relock();
                }
                frame.times.predict += now() - t;
            }
            Step::Weigh1 => {
                let part = if self.config.variant == Variant::FullModel {
                    Part::Full
                } else {
                    Part::FirstOrder
                };
                // The first frame: more rounds on the same cues (see `start_iterations`),
                // annealed: the process noise starts `start_spread` times wider and narrows
                // linearly to Q, and in the first half of the rounds every
                // 1 / `start_fresh`-th particle is drawn anew from the initial distribution,
                // so that the search goes on beyond the uniform start's first draw.
                for round in 0..=starts {
                    if round > 0 {
                        let left = 1.0 - round as f64 / starts as f64;
                        let scale = 1.0 + (self.config.start_spread - 1.0) * left;
                        let mut motion = self.motion(part);
                        motion.sd = motion.sd.map(|sd| sd * scale);
                        self.stage1.resample();
                        if 2 * round <= starts {
                            self.refresh_start_particles();
                        }
                        self.stage1.predict(&motion);
                    }
                    if self.config.variant == Variant::FullModel {
                        let model = FarModel {
                            measurement: &self.measurement,
                            camera: &self.camera,
                            edges: &self.far,
                            spiral,
                            first: None,
                            near: Some(&self.map),
                        };
                        self.stage1.weigh(&model, &());
                    } else {
                        let model = NearModel {
                            measurement: &self.measurement,
                            map: &self.map,
                        };
                        self.stage1.weigh(&model, &());
                    }
                }
                frame.times.weigh += now() - t;
            }
            Step::Finish1 => {
                let mut estimate =
                    estimate_first_order(self.stage1.states(), self.stage1.weights());
                frame.ess[0] = self.stage1.ess();
                // Lane change (the shared rule, `super::lane_change`): the car has crossed a
                // boundary's centre, so it is in the neighbouring lane; the whole cloud moves
                // one lane width.
                let change =
                    EgoLane::symmetric(estimate.y0, estimate.w).change(lane_change::MARGIN_M);
                if change != 0 {
                    let (y0, _) = motion::wrap(estimate.y0, estimate.w);
                    let shift = y0 - estimate.y0;
                    estimate.y0 = y0;
                    for s in self.stage1.states_mut() {
                        s.y0 += shift;
                    }
                }
                // (On a first frame there is no lane to have changed from: re-centre only.)
                frame.change = if frame.first { 0 } else { change };
                if self.config.variant == Variant::FullModel {
                    let (c, delta) = mean_curve(self.stage1.states(), self.stage1.weights());
                    estimate.c = c;
                    estimate.delta = delta;
                }
                frame.estimate = estimate;
                let t1 = now();
                frame.times.estimate += t1 - t;
                self.stage1.resample();
                frame.times.resample += now() - t1;
            }
            Step::Predict2 => {
                let motion = self.motion(Part::Curve);
                if let (Some(stage2), false) = (self.stage2.as_mut(), frame.first) {
                    stage2.predict(&motion);
                }
                frame.times.predict += now() - t;
            }
            Step::Weigh2 => {
                let motion = self.motion(Part::Curve);
                if let Some(stage2) = self.stage2.as_mut() {
                    let model = FarModel {
                        measurement: &self.measurement,
                        camera: &self.camera,
                        edges: &self.far,
                        spiral,
                        first: Some(frame.estimate),
                        near: None,
                    };
                    for round in 0..=starts {
                        if round > 0 {
                            stage2.resample();
                            stage2.predict(&motion);
                        }
                        stage2.weigh(&model, &());
                    }
                }
                frame.times.weigh += now() - t;
            }
            Step::Finish2 => {
                if let Some(stage2) = self.stage2.as_mut() {
                    let (c, delta) = mean_curve(stage2.states(), stage2.weights());
                    frame.estimate.c = c;
                    frame.estimate.delta = delta;
                    frame.ess[1] = stage2.ess();
                    // Stage-2 particles stand for full lanes with stage 1's first-order states,
                    // stage-1 particles for full lanes with the curve estimate.
                    let e = frame.estimate;
                    for s in stage2.states_mut() {
                        *s = LaneState {
                            c: s.c,
                            delta: s.delta,
                            ..e
                        };
                    }
                    for s in self.stage1.states_mut() {
                        s.c = e.c;
                        s.delta = e.delta;
                    }
                    let t1 = now();
                    frame.times.estimate += t1 - t;
                    stage2.resample();
                    frame.times.resample += now() - t1;
                }
            }
            Step::Output => {
                let raw = frame.estimate;
                let state = if self.config.kalman {
                    let x = self
                        .smoother
                        .update([raw.psi, raw.y0, raw.w, raw.w1, raw.c, raw.delta]);
                    LaneState {
                        psi: x[0],
                        y0: x[1],
                        w: x[2],
                        w1: x[3],
                        c: x[4],
                        delta: x[5],
                    }
                } else {
                    raw
                };
                let support = self.measurement.near_support(&raw, None, &self.map);
                // Lost: no marking near either boundary. After `lost_restart` such frames the
                // filter starts again from the initial distribution (with the start
                // iterations) on the next frame; a cloud that has lost the lane does not find
                // it again by diffusing with Q.
                let lost = support[0].max(support[1]) < LOST_SUPPORT;
                self.lost = if lost { self.lost + 1 } else { 0 };
                if self.config.lost_restart > 0 && self.lost >= self.config.lost_restart {
                    self.restart();
                }
                frame.times.estimate += now() - t;
                self.times = frame.times;
                return Some(LeeEstimate {
                    state,
                    raw,
                    valid: support[0].min(support[1]) >= self.config.valid_fraction,
                    support,
                    change: frame.change,
                    candidates: self.candidates.count,
                    ess: frame.ess,
                });
            }
        }
        self.frame = Some(frame);
        None
    }

    /// The ego boundaries of lane state `s` (eqs. 27-28).
    fn boundaries(&self, s: &LaneState) -> Vec<Boundary> {
        let curve = Curve::new(s.c, s.delta, self.config.spiral_length_m);
        let mut boundaries = Vec::new();
        for (role, sign) in [(Role::EgoLeft, 1.0), (Role::EgoRight, -1.0)] {
            let (points, road_points) = sample_road_curve(
                |x| s.centre(x, Some(&curve)) + sign * s.half_width(x),
                |x, y| self.camera.road_to_pixel(x, y),
                self.near_m.min(3.0),
                self.config.far_m,
                self.camera.width(),
                self.camera.height(),
            );
            boundaries.push(Boundary {
                role,
                points,
                road_points,
            });
        }
        boundaries
    }

    /// The estimate as the shared output type.
    pub fn to_lane_estimate(&self, e: &LeeEstimate) -> LaneEstimate {
        let s = e.state;
        let curve = Curve::new(s.c, s.delta, self.config.spiral_length_m);
        let mut boundaries = self.boundaries(&s);
        if let Some(d) = self
            .detector
            .as_ref()
            .filter(|_| e.valid && self.config.adjacent_lanes)
        {
            let adjacent = adjacent_boundaries(&self.camera, &boundaries, d.working_images());
            boundaries.extend(adjacent);
        }
        let r = e.raw;
        let state = [
            ("lee.psi", s.psi),
            ("lee.y0", s.y0),
            ("lee.w", s.w),
            ("lee.w1", s.w1),
            ("lee.c", s.c),
            ("lee.delta", s.delta),
            ("lee.raw.psi", r.psi),
            ("lee.raw.y0", r.y0),
            ("lee.raw.w", r.w),
            ("lee.raw.w1", r.w1),
            ("lee.raw.c", r.c),
            ("lee.raw.delta", r.delta),
            ("lee.support_left", e.support[0]),
            ("lee.support_right", e.support[1]),
            ("lee.change", e.change as f64),
            ("lee.candidates", e.candidates as f64),
            ("lee.ess1", e.ess[0]),
            ("lee.ess2", e.ess[1]),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        LaneEstimate {
            frame: String::new(),
            valid: e.valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: -s.y0,
            heading_rad: s.psi,
            curvature_per_m: curve.curvature_at_car(),
            lane_width_m: s.w,
            delimiters: Vec::new(),
            state,
        }
    }
}

/// Weighted mean of psi, y0, w and w'.
fn estimate_first_order(states: &[LaneState], weights: &[f64]) -> LaneState {
    let mut m = LaneState::default();
    for (s, &wt) in states.iter().zip(weights) {
        m.psi += wt * s.psi;
        m.y0 += wt * s.y0;
        m.w += wt * s.w;
        m.w1 += wt * s.w1;
    }
    m
}

/// Weighted mean of (c, delta).
fn mean_curve(states: &[LaneState], weights: &[f64]) -> (f64, f64) {
    states
        .iter()
        .zip(weights)
        .fold((0.0, 0.0), |(c, d), (s, &w)| (c + w * s.c, d + w * s.delta))
}

impl Tracker for LeeTracker {
    fn id(&self) -> &'static str {
        ID
    }

    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate> {
        let e = self.track(rgba, width, height)?;
        Ok(self.to_lane_estimate(&e))
    }

    fn reset(&mut self) {
        self.restart();
        if let Some(d) = self.detector.as_mut() {
            d.reset();
        }
        self.frame = None;
    }

    fn stage_times(&self) -> StageTimes {
        self.times
    }

    /// Eight numbers per particle: stage (1, 2, or 0 for a single-stage baseline), psi (rad),
    /// y0 (m), w (m), w', c (m), delta (1/m), normalised weight (within its stage).
    fn particles(&self) -> Vec<f32> {
        self.particle_states()
            .into_iter()
            .flat_map(|(stage, s, w)| {
                [
                    stage as f32,
                    s.psi as f32,
                    s.y0 as f32,
                    s.w as f32,
                    s.w1 as f32,
                    s.c as f32,
                    s.delta as f32,
                    w as f32,
                ]
            })
            .collect()
    }

    fn particle_stride(&self) -> usize {
        8
    }

    /// Group: the stage (1 or 2; 0 for a single-stage variant).
    fn hypotheses(&self, max: usize) -> Vec<Hypothesis> {
        let states = self.particle_states();
        spread_indices(states.len(), max)
            .map(|i| {
                let (stage, s, weight) = &states[i];
                Hypothesis {
                    weight: *weight,
                    group: i32::from(*stage),
                    boundaries: self.boundaries(s),
                }
            })
            .collect()
    }

    fn step_names(&self) -> &'static [&'static str] {
        LeeTracker::step_names(self)
    }

    /// The near-range likelihood map D (eq. 31) and the candidate marks it comes from.
    fn layers(&self) -> Vec<Layer> {
        let (x0, y0, cell) = self.map.geometry();
        let (width, height) = (self.map.marks.width(), self.map.marks.height());
        let grid = |name: &str, values: Vec<f32>| Layer::Grid {
            name: name.to_string(),
            width,
            height,
            x0,
            y0,
            cell,
            values,
        };
        vec![
            grid("likelihood map D (eq. 31)", self.map.likelihood.clone()),
            grid(
                "DLD marking candidates (eqs. 21-26)",
                self.map
                    .marks
                    .data()
                    .iter()
                    .map(|&m| f32::from(m))
                    .collect(),
            ),
        ]
    }

    fn begin_frame(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        self.begin(rgba, width, height)
    }

    fn advance(&mut self) -> Result<Option<LaneEstimate>> {
        if self.frame.is_none() {
            return Err(super::no_frame_in_progress());
        }
        Ok(self.advance_step().map(|e| self.to_lane_estimate(&e)))
    }

    fn next_step(&self) -> Option<usize> {
        LeeTracker::next_step(self)
    }
}

#[cfg(test)]
mod tests;
