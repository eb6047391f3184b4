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
//! Before the rounds, `start_pair_share` (half by default) of the initial stage-1 particles
//! are drawn around the ego pair the bottom-up line detector of [`super::relock`] finds in
//! that frame, when it finds one (the detector runs on first frames only unless an option
//! needs it on every frame). What it cannot fix: where a solid line lies a lane beyond two
//! dashed ones, eq. 33 itself can prefer a lane at the width limit with one boundary on the
//! solid line to the true lane on the dashes (`shadows` seed 6, frame 0: q 0.79 against
//! 0.54, ln-likelihood -11.8 against -17.1; CHANGELOG.md, 2026-11-28).
//! With a positive `relock_share` (ours, off by default) a share of stage 1's particles is drawn each
//! frame around the ego pair a bottom-up line detector finds ([`super::relock`]). With a
//! positive `side_search_share` (ours, off by default), after a frame whose estimate had one
//! boundary on markings and the other bare, a share keeps the supported boundary's line and
//! draws w and w' anew ([`super::side_search`]): without it a lane that widens faster than the
//! process noise moves w (a turn pocket) keeps one boundary and loses the other. With a
//! positive `reacquire_near_m` (ours, off by default) a lane once lost is valid again only
//! when a marking supports it near the car ([`super::reacquire`]): markings that begin past an
//! unmarked crossing are not yet the car's lane. With a
//! positive `curvature_prior_sd` (ours, off by default) stage 2 weighs each (c, delta) by a
//! zero-mean Gaussian prior on delta too, so that a bend needs far-band evidence to win: the
//! paper's uniform curvature let the far stage follow a barrier's top or shadow edges where
//! the band held little of the markings (a low, level camera; `shadows`).
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
pub mod truth;

use super::lane_change::{self, EgoLane};
use super::paint_output::apply_paint_options;
use super::paint_snap::move_lane_figures;
use super::reacquire::Reacquire;
use super::relock::RelockDetector;
use super::side_search::{self, Kept};
use super::support_memory::SupportMemory;
use super::{now, spread_indices, Hypothesis, Layer, StageTimes, Tracker, TrackerConfig};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::{
    expectation, FilterConfig, FirstFrame, InitialDistribution, Injection, MeasurementModel, Op,
    ParticleFilter, Pass, ResampleDecision, ResamplePolicy, Resampler, Schedule, Scheduled,
    Stepper,
};
use crate::image::{luma, Image};
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use crate::num_text::Num;
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

const CASCADE_STEP_NAMES: [&str; 7] = [
    "stage 1 [psi, y0, w, w']: predict",
    "stage 1: weigh (DLD distance map, eqs. 27-33)",
    "stage 1: estimate, resample if N_eff < N_thr",
    "stage 2 [c, delta]: predict",
    "stage 2: weigh (far Canny edges)",
    "stage 2: estimate, resample if N_eff < N_thr",
    "Kalman smoothing and output",
];
const SINGLE_STEP_NAMES: [&str; 4] = [
    "predict",
    "weigh",
    "estimate, resample if N_eff < N_thr",
    "Kalman smoothing and output",
];

/// The cascade's frame as the filter core runs it ([`crate::filter::schedule`]): Algorithm 1
/// for stage 1 (s = 1) and then stage 2 (s = 2), each predict, weigh, estimate (the weighted
/// mean), resample when N_eff < N_thr; stage 2 weighs its particles completed with stage 1's
/// estimate (Algorithm 2); then the Kalman smoother and the output. A first frame weighs each
/// stage before moving it, then runs `start_iterations` rounds of resample, predict (stage 1's
/// annealed, see [`LeeTracker::predict`]) and weigh on the same cues.
pub static CASCADE_SCHEDULE: Schedule = Schedule::new(
    &CASCADE_STEP_NAMES,
    &[
        &[Op::Predict(0)],
        &[Op::Weigh(0)],
        &[Op::StageEstimate(0), Op::Resample(0)],
        &[Op::Predict(1)],
        &[Op::Weigh(1)],
        &[Op::StageEstimate(1), Op::Resample(1)],
        &[Op::Estimate],
    ],
    FirstFrame::WeighFirst,
);
/// The baselines' frame (`first-order`, `full-model`): Algorithm 1 on one filter.
pub static SINGLE_SCHEDULE: Schedule = Schedule::new(
    &SINGLE_STEP_NAMES,
    &[
        &[Op::Predict(0)],
        &[Op::Weigh(0)],
        &[Op::StageEstimate(0), Op::Resample(0)],
        &[Op::Estimate],
    ],
    FirstFrame::WeighFirst,
);

/// What the stages of the frame in progress found, for the stages after them and the output.
#[derive(Debug, Clone, Copy, Default)]
struct StageResults {
    estimate: LaneState,
    ess: [f64; 2],
    change: i8,
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
    /// Standard deviation of the curvature prior (`curvature_prior_sd`; 0: none).
    curvature_sd: f64,
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
        // The curvature prior N(delta; 0, sd^2) (ours; `curvature_prior_sd`).
        let prior = if self.curvature_sd > 0.0 {
            let z = lane.delta / self.curvature_sd;
            -0.5 * z * z
        } else {
            0.0
        };
        far + near + prior
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
    /// The frame's schedule in progress and the last frame's times.
    stepper: Stepper,
    /// The stage estimates of the frame in progress.
    stages: StageResults,
    /// Consecutive frames whose estimate no marking supports (see `lost_restart`).
    lost: usize,
    /// The validity rule after a loss (`reacquire_near_m`).
    reacquire: Reacquire,
    /// The last `valid_support_frames` frames' support, for the validity.
    support_memory: SupportMemory,
    /// The bottom-up detector of `relock_share` (`None` when it is off).
    detector: Option<RelockDetector>,
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
                Num(lee.near_m),
                Num(lee.split_m)
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
        let detector = if lee.detector_every_frame() {
            Some(RelockDetector::new(&camera)?)
        } else if lee.start_pair_share > 0.0 {
            // The default start only: where the detector cannot run (frames under 32x16),
            // the start is the uniform one rather than an error.
            RelockDetector::new(&camera).ok()
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
            stepper: Stepper::new(),
            stages: StageResults::default(),
            lost: 0,
            reacquire: Reacquire::new(lee.reacquire_near_m),
            detector,
            camera,
            support_memory: SupportMemory::new(lee.valid_support_frames),
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
        self.stepper.restart();
        self.lost = 0;
        self.support_memory.clear();
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

    /// Replaces `share` of the stage-1 particles by draws around the detector's ego pair of
    /// this frame (`relock_share` each frame, `start_pair_share` on a first frame), when it
    /// found one within the state limits.
    fn draw_around_detection(&mut self, share: f64) {
        if share <= 0.0 {
            return;
        }
        let Some(d) = self.detector.as_ref().and_then(RelockDetector::detection) else {
            return;
        };
        let (psi, y0, w) = (d.heading(), d.centre(), d.width());
        let l = self.limits;
        if psi.abs() > l.heading || w < l.width[0] || w > l.width[1] {
            return;
        }
        let sd = self.config.process_sd;
        self.stage1.replace_share(share, |old, rng| LaneState {
            psi: crate::math::clamp(rng.gaussian(psi, sd[0]), -l.heading, l.heading),
            y0: rng.gaussian(y0, sd[1]),
            w: crate::math::clamp(rng.gaussian(w, sd[2]), l.width[0], l.width[1]),
            ..*old
        });
    }

    /// `side_search_share`: when the last frame's estimate had one boundary supported and the
    /// other not, replaces `share` of the stage-1 particles by lanes that keep the supported
    /// boundary's line (its offset y0 +- w / 2 and slope psi +- w' / 2, positive left) and
    /// draw the width and its rate uniformly over their limits, so that the cloud can find the
    /// lost side at a width the process noise would take many frames to reach. The line is
    /// kept exactly, so a drawn psi may pass `max_heading_rad` for the frame it is weighed on;
    /// the next prediction clamps it, as it clamps every state (clamping at the draw instead,
    /// which bends the kept line: Caltech tracker seeds 1-5 97.7 / 2.6 -> 97.2 / 2.8 %, the
    /// pocket's heading is near the limit).
    fn search_lost_side(&mut self, share: f64) {
        if share <= 0.0 {
            return;
        }
        // y0 and psi are positive left.
        let side =
            match side_search::kept_side(self.support_memory.last(), self.config.valid_fraction) {
                Some(Kept::Left) => 1.0,
                Some(Kept::Right) => -1.0,
                None => return,
            };
        let [lo, hi] = self.limits.width;
        let rate = self.limits.width_rate;
        self.stage1.replace_share(share, |old, rng| {
            let offset = old.y0 + side * old.w / 2.0;
            let slope = old.psi + side * old.w1 / 2.0;
            let w = lo + (hi - lo) * rng.uniform();
            let w1 = rate * (2.0 * rng.uniform() - 1.0);
            LaneState {
                y0: offset - side * w / 2.0,
                psi: slope - side * w1 / 2.0,
                w,
                w1,
                ..*old
            }
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
    /// every step of its schedule in order ([`Scheduled::step_frame`]).
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn track(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LeeEstimate> {
        self.step_frame(|t| t.begin(rgba, width, height))
    }

    /// The steps of one frame after [`LeeTracker::begin`], for teaching.
    pub fn step_names(&self) -> &'static [&'static str] {
        self.schedule().names()
    }

    /// Index of the next step of the frame in progress (`None` when no frame is in progress).
    pub fn next_step(&self) -> Option<usize> {
        self.stepper.next_step()
    }

    /// Stage 1's motion: the first-order states, or all six in the full-model baseline.
    fn stage1_part(&self) -> Part {
        if self.config.variant == Variant::FullModel {
            Part::Full
        } else {
            Part::FirstOrder
        }
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
        let every_frame = self.config.detector_every_frame();
        if let Some(d) = self.detector.as_mut() {
            // The start on the detected pair needs the first frame's lines.
            let first = self.stepper.next_is_first();
            let lines =
                self.config.relock_share > 0.0 || (first && self.config.start_pair_share > 0.0);
            if every_frame || first {
                d.feed_as_needed(&self.camera, rgba, width, height, lines)?;
            }
        }
        self.stages = StageResults::default();
        self.stepper.begin(StageTimes {
            preprocess: now() - t,
            ..StageTimes::default()
        });
        if self.stepper.is_first_frame() {
            self.draw_around_detection(self.config.start_pair_share);
        }
        Ok(())
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
        let (valid, snapped) = apply_paint_options(
            &self.camera,
            &mut boundaries,
            self.detector.as_ref(),
            e.valid,
            self.config.paint_options(),
        );
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
        let mut estimate = LaneEstimate {
            frame: String::new(),
            valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: -s.y0,
            heading_rad: s.psi,
            curvature_per_m: curve.curvature_at_car(),
            lane_width_m: s.w,
            delimiters: Vec::new(),
            state,
        };
        move_lane_figures(&mut estimate, snapped.moved_at_car);
        estimate
    }
}

/// Algorithm 1's estimate of psi, y0, w and w' (c and delta 0): the expectation over the
/// normalised weights.
fn estimate_first_order(states: &[LaneState], weights: &[f64]) -> LaneState {
    let [psi, y0, w, w1] = expectation(states, weights, |s| [s.psi, s.y0, s.w, s.w1]);
    LaneState {
        psi,
        y0,
        w,
        w1,
        ..LaneState::default()
    }
}

/// Algorithm 1's estimate of (c, delta).
fn mean_curve(states: &[LaneState], weights: &[f64]) -> (f64, f64) {
    let [c, delta] = expectation(states, weights, |s| [s.c, s.delta]);
    (c, delta)
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
        self.reacquire.reset();
        if let Some(d) = self.detector.as_mut() {
            d.reset();
        }
        self.stepper.abandon();
    }

    fn stage_times(&self) -> StageTimes {
        self.stepper.times()
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
        super::advance_scheduled(self, Self::to_lane_estimate)
    }

    fn next_step(&self) -> Option<usize> {
        LeeTracker::next_step(self)
    }

    fn resamplings(&self) -> &[ResampleDecision] {
        self.stepper.resamplings()
    }
}

/// The models of the schedule's operations: stage 0 is stage 1 of the paper (or the single
/// filter of a baseline), stage 1 the cascade's stage 2.
impl Scheduled for LeeTracker {
    type State = LaneState;
    type Estimate = LeeEstimate;

    fn schedule(&self) -> &'static Schedule {
        if self.stage2.is_some() {
            &CASCADE_SCHEDULE
        } else {
            &SINGLE_SCHEDULE
        }
    }
    fn stepper(&self) -> &Stepper {
        &self.stepper
    }
    fn stepper_mut(&mut self) -> &mut Stepper {
        &mut self.stepper
    }
    fn filter_mut(&mut self, stage: usize) -> Option<&mut ParticleFilter<LaneState>> {
        match stage {
            0 => Some(&mut self.stage1),
            1 => self.stage2.as_mut(),
            _ => None,
        }
    }
    fn start_rounds(&self) -> usize {
        self.config.start_iterations
    }
    fn inject(&mut self, stage: usize) {
        let filter = match stage {
            0 => Some(&mut self.stage1),
            _ => self.stage2.as_mut(),
        };
        if let Some(f) = filter {
            f.inject(&self.initial);
        }
    }
    /// Eq. 20 on the stage's states. Stage 1's frame pass adds the relock proposal. Its
    /// start-up rounds are annealed: the process noise starts `start_spread` times wider and
    /// narrows linearly to Q, and in the first half of the rounds every 1 / `start_fresh`-th
    /// particle of the resampled cloud is first drawn anew from the initial distribution, so
    /// that the search goes on beyond the uniform start's first draw.
    fn predict(&mut self, stage: usize, pass: Pass) {
        if stage > 0 {
            let motion = self.motion(Part::Curve);
            if let Some(stage2) = self.stage2.as_mut() {
                stage2.predict(&motion);
            }
            return;
        }
        let mut motion = self.motion(self.stage1_part());
        match pass {
            Pass::Frame => {
                self.stage1.predict(&motion);
                self.draw_around_detection(self.config.relock_share);
                self.search_lost_side(self.config.side_search_share);
            }
            Pass::StartRound { round, rounds } => {
                let left = 1.0 - round as f64 / rounds as f64;
                let scale = 1.0 + (self.config.start_spread - 1.0) * left;
                motion.sd = motion.sd.map(|sd| sd * scale);
                if 2 * round <= rounds {
                    self.refresh_start_particles();
                }
                self.stage1.predict(&motion);
            }
        }
    }
    /// Stage 1: eq. 33 on the map D (the full-model baseline adds the far edges of each
    /// particle's own lane); stage 2: the far edges of the lane completed with stage 1's
    /// estimate.
    fn weigh(&mut self, stage: usize) {
        let spiral = self.config.spiral_length_m;
        if stage > 0 {
            if let Some(stage2) = self.stage2.as_mut() {
                let model = FarModel {
                    measurement: &self.measurement,
                    camera: &self.camera,
                    edges: &self.far,
                    spiral,
                    first: Some(self.stages.estimate),
                    near: None,
                    curvature_sd: self.config.curvature_prior_sd,
                };
                stage2.weigh(&model, &());
            }
        } else if self.config.variant == Variant::FullModel {
            let model = FarModel {
                measurement: &self.measurement,
                camera: &self.camera,
                edges: &self.far,
                spiral,
                first: None,
                near: Some(&self.map),
                curvature_sd: self.config.curvature_prior_sd,
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
    /// Algorithm 1's weighted mean of the stage. Stage 1's goes through the lane-change rule
    /// (the whole cloud re-centred on the lane the car is in); stage 2's completes the lane,
    /// and each stage's particles then stand for full lanes with the other stage's estimate.
    fn stage_estimate(&mut self, stage: usize) {
        if stage == 0 {
            let mut estimate = estimate_first_order(self.stage1.states(), self.stage1.weights());
            self.stages.ess[0] = self.stage1.ess();
            // Lane change (the shared rule, `super::lane_change`): the car has crossed a
            // boundary's centre, so it is in the neighbouring lane; the whole cloud moves
            // one lane width.
            let change = EgoLane::symmetric(estimate.y0, estimate.w).change(lane_change::MARGIN_M);
            if change != 0 {
                let (y0, _) = motion::wrap(estimate.y0, estimate.w);
                let shift = y0 - estimate.y0;
                estimate.y0 = y0;
                for s in self.stage1.states_mut() {
                    s.y0 += shift;
                }
            }
            // (On a first frame there is no lane to have changed from: re-centre only.)
            self.stages.change = if self.stepper.is_first_frame() {
                0
            } else {
                change
            };
            if self.config.variant == Variant::FullModel {
                let (c, delta) = mean_curve(self.stage1.states(), self.stage1.weights());
                estimate.c = c;
                estimate.delta = delta;
            }
            self.stages.estimate = estimate;
        } else if let Some(stage2) = self.stage2.as_mut() {
            let (c, delta) = mean_curve(stage2.states(), stage2.weights());
            self.stages.estimate.c = c;
            self.stages.estimate.delta = delta;
            self.stages.ess[1] = stage2.ess();
            let e = self.stages.estimate;
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
        }
    }
    /// The Kalman smoother, the support, the lost count (after `lost_restart` frames without a
    /// marking near either boundary the filter starts again on the next frame: a cloud that
    /// has lost the lane does not find it again by diffusing with Q) and the output.
    fn estimate(&mut self) -> LeeEstimate {
        let raw = self.stages.estimate;
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
        let (support, reach) = self.measurement.near_support(&raw, None, &self.map);
        let remembered = self.support_memory.push(support);
        let valid = self
            .reacquire
            .valid(support, remembered, self.config.valid_fraction, reach);
        let lost = support[0].max(support[1]) < LOST_SUPPORT;
        self.lost = if lost { self.lost + 1 } else { 0 };
        if self.config.lost_restart > 0 && self.lost >= self.config.lost_restart {
            self.restart();
        }
        LeeEstimate {
            state,
            raw,
            valid,
            support,
            change: self.stages.change,
            candidates: self.candidates.count,
            ess: self.stages.ess,
        }
    }
}

#[cfg(test)]
mod curvature_prior_tests;
#[cfg(test)]
mod reacquire_tests;
#[cfg(test)]
mod side_search_tests;
#[cfg(test)]
mod start_pair_tests;
#[cfg(test)]
mod tests;
