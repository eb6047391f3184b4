//! `danescu-stereo` and `danescu-mono`: the lane tracker of Danescu & Nedevschi 2011 with the
//! 11-parameter 3-D lane ([`crate::lane::Lane3d`]).
//!
//! One frame (Sec. III), each step also available on its own (per-step mode):
//! 1. **resample** from the previous weights, keeping N - R particles, and draw R
//!    initialisation particles from the generic distribution ([`model::Initial`]);
//! 2. **drift and diffusion**: the ego motion (speed, yaw rate, timestamps, from
//!    [`Tracker::set_ego_motion`]; zero when unknown) moves every particle, then Gaussian noise
//!    ([`model::Motion`]);
//! 3. **weigh**: the particles mapped into the image (and the 3-D space) and compared with the
//!    cues ([`cues`], [`model::Measurement`]); degenerate lanes get weight zero;
//! 4. **estimate** (Sec. VIII): MBSAS clusters on X_CW over the resampled particles, the
//!    estimate by eq. 15 from the most populous cluster's above-average-weight particles.
//!
//! The cues are computed when the frame begins: HG, the markings and DT^S, the road edges and
//! DT^E (and, for the stereo tracker, the disparity, the preliminary pitch, the road points and
//! the density image DT^D).
//!
//! `danescu-mono` is our extension for a single camera: the same lane model and image-space
//! cues with a flat-road prior: pitch, roll, Y_0 and C_V are held at the calibration (no
//! diffusion, no density cue), and all edges count as road edges.
//!
//! Lane changes (our addition; the paper does not say) follow the rule every tracker shares
//! ([`super::lane_change`]): when the estimate's lane centre is further from the car than a
//! marking's centre (|X_CW| > (W_0 + that marking's width) / 2) by the rule's margin, the car
//! is in the next lane; every particle moves by one lane (X_CW +- (W_0 + the crossed marking's
//! width), the crossed marking becoming the new near one) and the change is reported. When
//! the estimate moves to the neighbouring lane without crossing (the most populous MBSAS
//! cluster is that lane), `danescu.change` reports the jump too ([`super::lane_change::jump`]).
//!
//! Output: the boundaries `ego-left` and `ego-right` are the markings' centre lines (the
//! road edge where a marking's width is 0), as for every tracker, so that evaluation compares
//! like with like, and `lane_width_m` is the distance between them, W_0 + (W_L + W_R) / 2;
//! `danescu.w0` is the width the paper defines (Sec. II: between the inner edges) with or
//! without the marking widths. With `marking_widths: false` (the paper's previous approach)
//! the model has no marking widths: its delimiters are the inner edges, so `lane_width_m` is
//! W_0 (a marking's width short of the centres: the approach cannot see it, which is the
//! paper's point in Fig. 10), and `danescu.wl_mark` / `danescu.wr_mark` are left out of the
//! state instead of reported as 0 (which the paper reserves for a lane without markings); `delimiters` adds the inner and outer edge of each marking (eqs. 2-3) as
//! image and road polylines with the same roles and a `side`. All are drawn from 1 m to
//! `far_m` on the estimate's own vertical profile.
//!
//! A frame is valid when the chosen cluster holds at least `valid_cluster_share` of the
//! resampled particles and, on each side, at least `valid_support` of the estimate's
//! inner-edge points are within `valid_distance_px` of a road edge (our definition, as for
//! `lee-cpf`; the paper's validation step is not spelled out; `valid_support_frames`, ours,
//! lets a side between a dashed line's dashes count on its recent support; with a positive
//! `valid_marking_factor`, ours, a point counts only with a marking edge near it as well, so
//! that shadow edges do not hold a lane through an unmarked crossing; with
//! `valid_marking_sides` 1 that paint is needed on one side only, so a kerb may bound the
//! other).
//!
//! With a positive `relock_share` (ours, off by default) a share of the particles is drawn each frame,
//! after the drift, around the ego pair a bottom-up line detector finds ([`super::relock`]),
//! beside the paper's generic `init_fraction`.

pub mod config;
pub mod cues;
pub mod elevation;
pub mod model;
pub mod stereo;
pub mod truth;

use super::lane_change::{self, EgoLane};
use super::paint_output::apply_paint_options;
use super::paint_snap::move_lane_figures;
use super::relock::RelockDetector;
use super::support_memory::{self, SupportMemory};
use super::{
    now, spread_indices, EgoMotion, Hypothesis, Layer, StageTimes, Tracker, TrackerConfig,
};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::{
    FilterConfig, FirstFrame, Injection, Mbsas, MeasurementModel, Op, ParticleFilter, Pass,
    ResampleDecision, ResamplePolicy, Resampler, Schedule, Scheduled, Stepper,
};
use crate::lane::{
    sample_road_curve, Boundary, Delimiter, Edge, Lane3d, LaneCamera, LaneEstimate, Role, Side,
};
use config::DanescuConfig;
use cues::ImageCues;
use model::{Initial, Measurement, Motion};
use stereo::StereoCues;

/// The stereo tracker's id.
pub const ID_STEREO: &str = "danescu-stereo";
/// The monocular tracker's id.
pub const ID_MONO: &str = "danescu-mono";
/// Particles N when the config does not say.
pub const DEFAULT_PARTICLES: usize = 500;
/// Indices of the vertical-profile parameters in `Lane3d::NAMES` (held by the mono tracker):
/// C_V, Y_0, alpha, gamma.
const VERTICAL: [usize; 4] = [3, 4, 6, 7];
/// Indices of W_L and W_R in `Lane3d::NAMES`.
const MARKING_WIDTHS: [usize; 2] = [9, 10];

/// The steps of one frame in per-step mode.
pub const STEP_NAMES: [&str; 4] = [
    "resample: N - R from the previous set, R initialisation particles (Sec. III)",
    "drift (ego motion) and diffusion",
    "weigh: road edges, markings, gradient (eqs. 9-12) and density (eqs. 13-14); validation",
    "estimate: MBSAS clusters on X_CW, eq. 15",
];

/// The frame as the filter core runs it ([`crate::filter::schedule`]), Sec. III's cycle. A
/// first frame has no previous set: its particles come from the initial distribution and are
/// only weighed.
pub static SCHEDULE: Schedule = Schedule::new(
    &STEP_NAMES,
    &[
        &[Op::Resample(0), Op::Inject(0)],
        &[Op::Predict(0)],
        &[Op::Weigh(0)],
        &[Op::Estimate],
    ],
    FirstFrame::WeighFirst,
);

/// The estimate of one frame in the paper's terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DanescuEstimate {
    /// The 11 parameters.
    pub lane: Lane3d,
    /// Whether the frame is valid (see the module docs).
    pub valid: bool,
    /// Share of the resampled particles in the chosen cluster.
    pub cluster_share: f64,
    /// Clusters found.
    pub clusters: usize,
    /// Lane change this frame: +1 to the left, -1 to the right, 0 none.
    pub change: i8,
    /// Effective sample size after weighing.
    pub ess: f64,
    /// Share of the estimate's left and right inner-edge points near a road edge.
    pub support: [f64; 2],
}

struct Weigh<'a> {
    measurement: &'a Measurement,
    camera: &'a Camera,
    cues: &'a ImageCues,
    stereo: Option<&'a StereoCues>,
}

impl MeasurementModel<Lane3d> for Weigh<'_> {
    type Cues = ();
    fn log_likelihood(&self, lane: &Lane3d, _: &()) -> f64 {
        self.measurement.log_likelihood(
            self.camera,
            lane,
            self.cues,
            self.stereo.and_then(StereoCues::usable_density),
        )
    }
}

/// The Danescu tracker.
#[derive(Debug)]
pub struct DanescuTracker {
    id: &'static str,
    camera: Camera,
    config: DanescuConfig,
    cues: ImageCues,
    /// The stereo cues (danescu-stereo only).
    stereo: Option<StereoCues>,
    /// The right frame of the next step (danescu-stereo only).
    right: Vec<u8>,
    right_ready: bool,
    measurement: Measurement,
    filter: ParticleFilter<Lane3d>,
    initial: Initial,
    diffusion: [f64; 11],
    mbsas: Mbsas<11>,
    /// Whether `mbsas`'s labels belong to the particles as they are now (not after a
    /// resampling that reordered them).
    labels_current: bool,
    motion: Option<EgoMotion>,
    last_time: Option<f64>,
    /// The drift and diffusion of the frame in progress (from the ego motion given for it).
    drift: Motion,
    /// The previous frame's estimate (for [`lane_change::jump`]).
    last_lane: Option<Lane3d>,
    /// The bottom-up detector of `relock_share` (`None` when it is off).
    detector: Option<RelockDetector>,
    /// The last `valid_support_frames` frames' support, for the validity.
    support_memory: SupportMemory,
    /// The last `valid_support_frames` frames' painted shares (`valid_marking_sides` 1).
    painted_memory: SupportMemory,
    /// The frame's schedule in progress and the last frame's times.
    stepper: Stepper,
}

impl DanescuTracker {
    /// Builds the tracker `id`: [`ID_STEREO`] or [`ID_MONO`].
    ///
    /// # Errors
    /// Camera, particle-count and option errors, named; for the stereo tracker, a camera
    /// without `baseline_m`.
    pub fn new(config: &TrackerConfig, id: &'static str) -> Result<Self> {
        if id != ID_MONO && id != ID_STEREO {
            return Err(Error::UnknownTracker {
                id: id.to_string(),
                available: format!("{ID_MONO}, {ID_STEREO}"),
            });
        }
        let camera = config.validate()?;
        let danescu = DanescuConfig::from_options(&config.options, id)?;
        let cues = ImageCues::new(&camera, &danescu)?;
        let detector = if danescu.relock_share > 0.0 || danescu.paint_options().any() {
            Some(RelockDetector::new(&camera)?)
        } else {
            None
        };
        let is_stereo = id == ID_STEREO;
        let n_pixels = camera.width() * camera.height();
        let stereo = if is_stereo {
            Some(StereoCues::new(&camera, &danescu)?)
        } else {
            None
        };
        let measurement = Measurement::new(&camera, &danescu);
        let n = config.particles_or(DEFAULT_PARTICLES);
        let initial = Initial {
            pitch: camera.pitch(),
            roll: camera.roll(),
            vertical: is_stereo,
            config: danescu.clone(),
        };
        let mut diffusion = danescu.diffusion;
        if !is_stereo {
            for k in VERTICAL {
                diffusion[k] = 0.0;
            }
        }
        if !danescu.marking_widths {
            diffusion[MARKING_WIDTHS[0]] = 0.0;
            diffusion[MARKING_WIDTHS[1]] = 0.0;
        }
        let filter = ParticleFilter::new(
            n,
            FilterConfig {
                resampler: Resampler::Systematic,
                policy: ResamplePolicy::Always,
                injection: Injection::Fraction(danescu.init_fraction),
            },
            config.seed,
            &initial,
        )?;
        let mbsas = Mbsas::new(danescu.cluster_threshold_m, danescu.max_clusters)?;
        Ok(Self {
            id,
            camera,
            support_memory: SupportMemory::new(danescu.valid_support_frames),
            painted_memory: SupportMemory::new(danescu.valid_support_frames),
            config: danescu,
            right: if is_stereo {
                vec![0; n_pixels * 4]
            } else {
                Vec::new()
            },
            right_ready: false,
            cues,
            stereo,
            measurement,
            filter,
            initial,
            diffusion,
            mbsas,
            labels_current: false,
            motion: None,
            last_time: None,
            drift: Motion {
                travelled_m: 0.0,
                turned_rad: 0.0,
                diffusion,
            },
            last_lane: None,
            detector,
            stepper: Stepper::new(),
        })
    }

    /// One frame in the paper's terms: [`DanescuTracker::begin`], then every step of
    /// [`SCHEDULE`] ([`Scheduled::step_frame`]).
    ///
    /// # Errors
    /// As [`DanescuTracker::begin`].
    pub fn track(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<DanescuEstimate> {
        self.step_frame(|t| t.begin(rgba, width, height))
    }

    /// Gives the right frame of the next step (danescu-stereo).
    ///
    /// # Errors
    /// [`Error::State`] for the monocular tracker; buffer and size errors as for a frame.
    pub fn set_right(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        if self.stereo.is_none() {
            return Err(Error::State(format!(
                "{} takes one camera; a right image is for {ID_STEREO}",
                self.id
            )));
        }
        super::check_frame(&self.camera, rgba, width, height)?;
        self.right.copy_from_slice(rgba);
        self.right_ready = true;
        Ok(())
    }

    /// Starts a frame: checks it, computes the cues (with the right frame given by
    /// [`DanescuTracker::set_right`] for the stereo tracker) and the drift from the ego
    /// motion given since the last frame.
    ///
    /// # Errors
    /// [`crate::error::Error::BufferSize`] / [`crate::error::Error::Dimensions`] for a frame
    /// that does not match the camera; [`Error::State`] for the stereo tracker without a
    /// right frame.
    pub fn begin(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        super::check_frame(&self.camera, rgba, width, height)?;
        if self.stereo.is_some() && !self.right_ready {
            return Err(Error::State(format!(
                "{ID_STEREO} needs the right image of every frame: give it with the frame (JS: \
                 step(left, {{ right }}); Rust: set_right before each step), or use {ID_MONO} \
                 for one camera"
            )));
        }
        let t0 = now();
        self.cues.begin(rgba)?;
        let mut disparity = 0.0;
        if let Some(stereo) = self.stereo.as_mut() {
            self.right_ready = false;
            disparity = stereo.process(&self.right, &mut self.cues)?;
        }
        self.cues.finish()?;
        if let Some(d) = self.detector.as_mut() {
            let lines = self.config.relock_share > 0.0;
            d.feed_as_needed(&self.camera, rgba, width, height, lines)?;
        }
        let (travelled_m, turned_rad) = match self.motion.take() {
            Some(m) => {
                let dt = self
                    .last_time
                    .map(|t| m.t_s - t)
                    .filter(|dt| *dt > 0.0 && *dt <= 1.0)
                    .unwrap_or(0.0);
                self.last_time = Some(m.t_s);
                (m.speed_mps * dt, m.yaw_rate * dt)
            }
            None => (0.0, 0.0),
        };
        self.drift = Motion {
            travelled_m,
            turned_rad,
            diffusion: self.diffusion,
        };
        self.stepper.begin(StageTimes {
            preprocess: now() - t0,
            disparity,
            ..StageTimes::default()
        });
        Ok(())
    }

    /// Replaces `relock_share` of the particles by draws around the detector's ego pair (see
    /// `relock_share`), when it found one of an accepted width. The detector measures marking
    /// centres; W_0 is between the inner edges, so each draw keeps its particle's marking
    /// widths and subtracts their halves.
    fn relock(&mut self, motion: &Motion) {
        let Some(d) = self.detector.as_ref().and_then(RelockDetector::detection) else {
            return;
        };
        let [lo, hi] = self.config.width_range_m;
        if !(lo..=hi).contains(&d.width()) {
            return;
        }
        // Lane3d is positive to the right, the road frame to the left.
        let (xcw, psi, width) = (-d.centre(), -crate::math::tan(d.heading()), d.width());
        let sd = motion.diffusion;
        self.filter
            .replace_share(self.config.relock_share, |old, rng| {
                let mut lane = *old;
                lane.xcw = rng.gaussian(xcw, sd[5]);
                lane.psi = rng.gaussian(psi, sd[8]);
                lane.w0 = rng.gaussian(width - 0.5 * (old.wl_mark + old.wr_mark), sd[0]);
                lane
            });
    }

    fn read_estimate(&mut self) -> DanescuEstimate {
        let first = self.filter.injected();
        let states = self.filter.states();
        let weights = self.filter.weights();
        let f = |l: &Lane3d| l.to_array();
        self.mbsas
            .cluster(states, first, &f, &|a, b| (a[5] - b[5]).abs());
        self.labels_current = true;
        let resampled = (states.len() - first).max(1);
        let best_count = self.mbsas.counts().iter().copied().max().unwrap_or(0);
        let lane = self
            .mbsas
            .estimate(states, weights, &f)
            .map(Lane3d::from_array)
            .unwrap_or_else(|| states[crate::filter::map_index(weights)]);
        let ess = self.filter.ess();
        let mut e = DanescuEstimate {
            lane,
            valid: false,
            cluster_share: best_count as f64 / resampled as f64,
            clusters: self.mbsas.counts().len(),
            change: 0,
            ess,
            support: [0.0; 2],
        };
        let d = self.measurement.distances_of(
            &self.camera,
            &e.lane,
            &self.cues,
            self.stereo.as_ref().and_then(StereoCues::usable_density),
        );
        e.support = d.support;
        let remembered = self.support_memory.push(d.support);
        let painted = self.painted_memory.push(d.painted);
        e.valid = e.cluster_share >= self.config.valid_cluster_share
            && support_memory::supported(d.support, remembered, self.config.valid_support)
            && self.measurement.paint_seen(painted)
            && self.measurement.is_valid(&e.lane);
        // Lane change (the shared rule, `super::lane_change`): the car has crossed the
        // centre of a marking; re-centre the cloud on the lane the car is now in.
        let change = ego_lane(&e.lane).change(lane_change::MARGIN_M);
        if change != 0 {
            for l in self.filter.states_mut().iter_mut().chain([&mut e.lane]) {
                recentre(l, change);
            }
            e.change = change;
        } else if let Some(last) = self.last_lane {
            // The chosen cluster may itself be the neighbouring lane (eq. 15 takes the most
            // populous one): the estimate then moves a lane with no boundary crossed. Report
            // it as the change the output shows, so that the flag and the offset agree.
            let width = (ego_lane(&last).width_m() + ego_lane(&e.lane).width_m()) / 2.0;
            e.change = lane_change::jump(-last.xcw, -e.lane.xcw, width);
        }
        self.last_lane = Some(e.lane);
        e
    }

    /// The marking centres of `lane` as image and road polylines (eqs. 1-4).
    fn boundaries(&self, lane: &Lane3d) -> Vec<Boundary> {
        [(Role::EgoLeft, false), (Role::EgoRight, true)]
            .into_iter()
            .map(|(role, right)| self.polyline(lane, role, |z| lane.marking_centre_x(right, z)))
            .collect()
    }

    /// The inner and outer delimiters of both markings (eqs. 2-3) as image and road
    /// polylines, left marking first, inner before outer.
    fn delimiters(&self, lane: &Lane3d) -> Vec<Delimiter> {
        [
            (Role::EgoLeft, Side::Inner, Edge::LeftInner),
            (Role::EgoLeft, Side::Outer, Edge::LeftOuter),
            (Role::EgoRight, Side::Inner, Edge::RightInner),
            (Role::EgoRight, Side::Outer, Edge::RightOuter),
        ]
        .into_iter()
        .map(|(role, side, edge)| Delimiter {
            side,
            boundary: self.polyline(lane, role, |z| lane.edge_x(edge, z)),
        })
        .collect()
    }

    /// The curve at X = `lateral(Z)` (the paper's X, to the right) on `lane`'s vertical
    /// profile from 1 m to `far_m`, as the boundary `role`.
    fn polyline(&self, lane: &Lane3d, role: Role, lateral: impl Fn(f64) -> f64) -> Boundary {
        let lc = LaneCamera::new(&self.camera, lane);
        let (points, road_points) = sample_road_curve(
            |x| -lateral(x),
            |x, y| lc.project(-y, x),
            1.0,
            self.config.far_m,
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
    pub fn to_lane_estimate(&self, e: &DanescuEstimate) -> LaneEstimate {
        let lane = &e.lane;
        let mut boundaries = self.boundaries(lane);
        let (valid, snapped) = apply_paint_options(
            &self.camera,
            &mut boundaries,
            self.detector.as_ref(),
            e.valid,
            self.config.paint_options(),
        );
        // Inserted, not collected: `collect` into a map sorts its pairs first, one more
        // instance of the stable sort in the wasm for eleven keys (issue 21 part 5).
        let mut state = std::collections::BTreeMap::new();
        for (n, v) in Lane3d::NAMES.iter().zip(lane.to_array()) {
            state.insert(format!("danescu.{n}"), v);
        }
        for (k, v) in [
            ("danescu.cluster_share", e.cluster_share),
            ("danescu.clusters", e.clusters as f64),
            ("danescu.change", e.change as f64),
            ("danescu.ess", e.ess),
            ("danescu.support_left", e.support[0]),
            ("danescu.support_right", e.support[1]),
            ("danescu.marking_pixels", self.cues.counts().0 as f64),
        ] {
            state.insert(k.to_string(), v);
        }
        if !self.config.marking_widths {
            // The previous approach has no marking widths: W_L = W_R = 0 is the model's
            // assumption, not an estimate, and 0 means "no marking" in the paper (Sec. II).
            // They are left out rather than reported as measured.
            state.remove("danescu.wl_mark");
            state.remove("danescu.wr_mark");
        }
        if let Some(stereo) = self.stereo.as_ref() {
            state.insert(
                "danescu.pitch_detected".into(),
                self.camera.pitch() + stereo.pitch_change(),
            );
            state.insert("danescu.road_points".into(), stereo.road_points() as f64);
        }
        let mut estimate = LaneEstimate {
            frame: String::new(),
            valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: lane.xcw,
            heading_rad: -lane.psi,
            curvature_per_m: -lane.ch,
            lane_width_m: lane.w0 + (lane.wl_mark + lane.wr_mark) / 2.0,
            state,
            delimiters: self.delimiters(lane),
        };
        move_lane_figures(&mut estimate, snapped.moved_at_car);
        estimate
    }

    /// The particles with their weights and cluster labels (`usize::MAX` for none: an
    /// initialisation particle, or a frame between resampling and the estimate step).
    pub fn particle_states(&self) -> impl Iterator<Item = (&Lane3d, f64, usize)> + '_ {
        let labels: &[usize] = if self.labels_current {
            self.mbsas.labels()
        } else {
            &[]
        };
        self.filter
            .states()
            .iter()
            .zip(self.filter.weights())
            .enumerate()
            .map(move |(i, (s, &w))| (s, w, labels.get(i).copied().unwrap_or(usize::MAX)))
    }
}

/// `lane` for the shared lane-change rule: X_CW is to the right, the road frame's y to the
/// left, and each boundary's centre is half its marking's width beyond the inner edge.
fn ego_lane(lane: &Lane3d) -> EgoLane {
    EgoLane {
        centre_left_m: -lane.xcw,
        to_left_m: (lane.w0 + lane.wl_mark) / 2.0,
        to_right_m: (lane.w0 + lane.wr_mark) / 2.0,
    }
}

/// Moves a lane hypothesis to the neighbouring lane: `change` -1 when the car moved into the
/// lane on the right, +1 into the lane on the left.
fn recentre(l: &mut Lane3d, change: i8) {
    if change < 0 {
        l.xcw += l.w0 + l.wr_mark;
        l.wl_mark = l.wr_mark;
    } else {
        l.xcw -= l.w0 + l.wl_mark;
        l.wr_mark = l.wl_mark;
    }
}

impl Tracker for DanescuTracker {
    fn id(&self) -> &'static str {
        self.id
    }

    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate> {
        let e = self.track(rgba, width, height)?;
        Ok(self.to_lane_estimate(&e))
    }

    fn reset(&mut self) {
        self.filter.reset(&self.initial);
        if let Some(d) = self.detector.as_mut() {
            d.reset();
        }
        self.labels_current = false;
        self.right_ready = false;
        self.stepper.restart();
        self.stepper.abandon();
        self.last_lane = None;
        self.support_memory.clear();
        self.painted_memory.clear();
        self.motion = None;
        self.last_time = None;
    }

    fn is_stereo(&self) -> bool {
        self.stereo.is_some()
    }

    fn set_right(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        DanescuTracker::set_right(self, rgba, width, height)
    }

    fn set_ego_motion(&mut self, motion: EgoMotion) -> Result<()> {
        motion.check()?;
        self.motion = Some(motion);
        Ok(())
    }

    fn stage_times(&self) -> StageTimes {
        self.stepper.times()
    }

    /// 13 numbers per particle: the 11 parameters in `Lane3d::NAMES` order, the normalised
    /// weight, and the MBSAS cluster (-1 for an initialisation particle, and for all of them
    /// between the resampling and the estimate of a frame in per-step mode).
    fn particles(&self) -> Vec<f32> {
        let mut out = Vec::with_capacity(self.filter.len() * 13);
        for (s, w, label) in self.particle_states() {
            out.extend(s.to_array().iter().map(|&v| v as f32));
            out.push(w as f32);
            out.push(if label == usize::MAX {
                -1.0
            } else {
                label as f32
            });
        }
        out
    }

    fn particle_stride(&self) -> usize {
        13
    }

    /// Group: the MBSAS cluster, -1 for none.
    fn hypotheses(&self, max: usize) -> Vec<Hypothesis> {
        let states: Vec<(&Lane3d, f64, usize)> = self.particle_states().collect();
        spread_indices(states.len(), max)
            .map(|i| {
                let (lane, weight, label) = states[i];
                Hypothesis {
                    weight,
                    group: i32::try_from(label).unwrap_or(-1),
                    boundaries: self.boundaries(lane),
                }
            })
            .collect()
    }

    /// The marking and road-edge cues seen on the road: exp(-DT^2 / 2) of DT^S and DT^E
    /// sampled on a 0.1 m grid from `near_m` to `far_m` and +-6 m (1 on an edge pixel); for
    /// danescu-stereo also the elevation map's cell classes on the same grid, and the density
    /// image and its column maxima on the lateral plane.
    fn layers(&self) -> Vec<Layer> {
        const CELL: f64 = 0.1;
        const HALF_WIDTH_M: f64 = 6.0;
        let (x0, x1) = (self.config.near_m, self.config.far_m);
        let height = ((x1 - x0) / CELL).round() as usize;
        let width = (2.0 * HALF_WIDTH_M / CELL).round() as usize;
        // A layer of `value(x, y)` at every road cell.
        let grid = |name: &str, value: &dyn Fn(f64, f64) -> f32| {
            let mut values = vec![0.0f32; width * height];
            for r in 0..height {
                let x = x0 + (r as f64 + 0.5) * CELL;
                for c in 0..width {
                    let y = HALF_WIDTH_M - (c as f64 + 0.5) * CELL;
                    values[r * width + c] = value(x, y);
                }
            }
            Layer::Grid {
                name: name.to_string(),
                width,
                height,
                x0,
                y0: HALF_WIDTH_M,
                cell: CELL,
                values,
            }
        };
        // exp(-DT^2 / 2) of a distance image at the cell's pixel (0 off the image).
        let closeness = |distance: &dyn Fn(f64, f64) -> Option<f32>, x: f64, y: f64| {
            self.camera
                .road_to_pixel(x, y)
                .and_then(|[u, v]| distance(u, v))
                .map_or(0.0, |d| crate::math::exp(-0.5 * (d * d) as f64) as f32)
        };
        let mut layers = vec![
            grid("marking and curb edges: exp(-DT^S^2 / 2)", &|x, y| {
                closeness(&|u, v| self.cues.marking_distance(u, v), x, y)
            }),
            grid("road edges: exp(-DT^E^2 / 2)", &|x, y| {
                closeness(&|u, v| self.cues.edge_distance(u, v), x, y)
            }),
        ];
        if let Some(map) = self.stereo.as_ref().and_then(|s| s.elevation()) {
            layers.push(grid(
                "elevation map: road 1/3, curb 2/3, obstacle 1 (Sec. VI-A b)",
                &|x, y| f32::from(map.class_at(x, y)) / 3.0,
            ));
        }
        if let Some(stereo) = &self.stereo {
            let density = stereo.density();
            let c = density.config();
            let axes = super::PlaneAxes {
                x_axis: "Z (m, ahead)".into(),
                x0: -c.dz_m / 2.0,
                dx: c.dz_m,
                y_axis: "Y (m, up, calibrated road frame)".into(),
                y0: -((c.rows / 2) as f64 + 0.5) * c.dy_m,
                dy: c.dy_m,
            };
            let plane = |name: &str, values: Vec<f32>| Layer::Plane {
                name: name.to_string(),
                width: c.cols,
                height: c.rows,
                axes: axes.clone(),
                values,
            };
            layers.push(plane(
                "3-D point density, triangular filter (Sec. VI-B)",
                density.density().data().to_vec(),
            ));
            layers.push(plane(
                "density column maxima (the road profile DT^D measures from)",
                density
                    .edges()
                    .data()
                    .iter()
                    .map(|&e| f32::from(e))
                    .collect(),
            ));
        }
        layers
    }

    fn step_names(&self) -> &'static [&'static str] {
        SCHEDULE.names()
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

/// The models of the schedule's operations.
impl Scheduled for DanescuTracker {
    type State = Lane3d;
    type Estimate = DanescuEstimate;

    fn schedule(&self) -> &'static Schedule {
        &SCHEDULE
    }
    fn stepper(&self) -> &Stepper {
        &self.stepper
    }
    fn stepper_mut(&mut self) -> &mut Stepper {
        &mut self.stepper
    }
    fn filter_mut(&mut self, _stage: usize) -> Option<&mut ParticleFilter<Lane3d>> {
        Some(&mut self.filter)
    }
    /// N - R particles from the previous set; the cluster labels belonged to the old order.
    fn resample(&mut self, _stage: usize) {
        self.filter.resample();
        self.labels_current = false;
    }
    /// R initialisation particles from the generic distribution.
    fn inject(&mut self, _stage: usize) {
        self.filter.inject(&self.initial);
    }
    /// `start_iterations` (ours; 0 in the paper's filter).
    fn start_rounds(&self) -> usize {
        self.config.start_iterations
    }
    /// Drift by the ego motion and diffusion, then the relock proposal. A start round (same
    /// frame) first injects the R initialisation particles, as a frame's `Inject` does, and
    /// diffuses without ego motion.
    fn predict(&mut self, _stage: usize, pass: Pass) {
        let drift = match pass {
            Pass::Frame => self.drift,
            Pass::StartRound { .. } => {
                self.filter.inject(&self.initial);
                Motion {
                    travelled_m: 0.0,
                    turned_rad: 0.0,
                    ..self.drift
                }
            }
        };
        self.filter.predict(&drift);
        self.relock(&drift);
    }
    /// Eqs. 9-14 and the validation.
    fn weigh(&mut self, _stage: usize) {
        let weigh = Weigh {
            measurement: &self.measurement,
            camera: &self.camera,
            cues: &self.cues,
            stereo: self.stereo.as_ref(),
        };
        self.filter.weigh(&weigh, &());
    }
    /// MBSAS and eq. 15.
    fn estimate(&mut self) -> DanescuEstimate {
        self.read_estimate()
    }
}

#[cfg(test)]
mod marking_support_tests;
#[cfg(test)]
mod start_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod width_range_tests;
