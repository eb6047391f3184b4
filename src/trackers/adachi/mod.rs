//! `adachi-mmpf`: the multiple-model particle filter of Adachi, Inayoshi & Kurita on a
//! one-dimensional edge-vote space.
//!
//! One frame: vote the region's edge points onto the rho axis ([`votes`]); resample; each
//! particle (r, q, w) switches its model r by the Table 1 Markov chain and random-walks q, w
//! with the wrap of eq. 9 ([`motion`]); weigh by eqs. 4-6 ([`likelihood`]); estimate. The
//! estimate is the most probable model (P(r) = the weight of its particles), and q, w as the
//! weighted mean of that model's particles, with q unwrapped around the best particle's so
//! that particles on both sides of the +-w/2 seam average correctly. Lane changes follow eq. 9
//! applied to the estimate: the estimated q is followed without wrapping (each frame takes the
//! copy q + k w nearest the previous one), and when it leaves [-w/2, w/2) of the current lane
//! by more than a 0.1 m hysteresis margin (the rule every tracker shares,
//! [`super::lane_change`], with a margin of its own), the lane index moves and an event is reported: q
//! past +w/2 is a change to the left (`change` +1), past -w/2 a change to the right (-1), the
//! sign convention of `lee.change` and `danescu.change`. (Per-particle wraps are
//! spread over several frames, so counting them gives no clean event.)
//!
//! A frame is valid when both ego boundaries of the estimate have vote support: in at least
//! `valid_support` (0.08 by default) of the voting region's rows, the boundary's edge voted
//! within 2 sd of where the template puts it ([`likelihood::Likelihood::support`]). A solid
//! line gives about 1; a dashed line of 3 m dashes every 12 m, as the dashes move through the
//! 6-22 m region, never less than 0.12 (measured on `highway-straight` at 320x240, median
//! 0.2); a blank, black or occluded road, or a line worn away, gives 0. The paper does not define a valid frame; this is our definition, and every
//! vote still counts in the likelihood whatever it says.
//!
//! Boundaries are the straight lines rho_l parallel to the car (the paper's model assumes
//! straight lanes along the driving direction), drawn from `near_m` to 3 `far_m`. With
//! `lane_shape: "curved"` (ours, see [`road_shape`]) the votes are straightened by the road's
//! bend first and the boundaries are drawn along rho_l + s1 x + s2 x^2. With a positive
//! `relock_share` (ours, off by default) a share of the particles is drawn each frame around the ego pair
//! a bottom-up line detector finds ([`super::relock`]).
//!
//! The start (the paper leaves it open): the particles are drawn uniformly over (r, q, w), and
//! on the first frame (and after a reset) `start_pair_share` (half by default) of them are
//! redrawn around the ego pairs the frame's own vote histogram forms ([`pairs`]: two peaks
//! of H_j straddling the car at an accepted width), each with a uniform model r; then
//! `start_iterations` rounds on the same votes. A uniform start alone locks in on false modes
//! the random walk of eqs. 7-8 cannot leave (Udacity `project_video`: the guard rail and the
//! yellow line as a 2.5-2.7 m lane of model 2). With a positive `vote_pair_share` (ours,
//! beyond the paper, off by default) that share is redrawn from the pairs every frame, so
//! that a cloud locked on a false mode or lost after a blackout finds the lane again. With a
//! positive `side_search_share` (ours, off by default), after a frame whose estimate had one
//! ego boundary with vote support and the other none, a share keeps the supported boundary and
//! draws w anew ([`super::side_search`]).

pub mod config;
#[cfg(test)]
mod edge_response_tests;
pub mod grid;
#[cfg(test)]
mod lane_shape_tests;
pub mod likelihood;
#[cfg(test)]
mod lockin_tests;
pub mod motion;
pub mod pairs;
#[cfg(test)]
mod reacquire_tests;
pub mod road_shape;
#[cfg(test)]
mod side_search_tests;
pub mod truth;
pub mod votes;

use super::lane_change::EgoLane;
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
    model_probabilities, FilterConfig, FirstFrame, Injection, MarkovChain, MeasurementModel, Op,
    ParticleFilter, Pass, Regime, ResampleDecision, ResamplePolicy, Resampler, Schedule, Scheduled,
    Stepper, SwitchingMotion,
};
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use crate::num_text::Num;
use config::AdachiConfig;
use likelihood::{Likelihood, COEFFICIENTS, OFFSETS};
use motion::{Initial, Lane, Motion};
use pairs::VotePairs;
use votes::Votes;

/// The tracker id.
pub const ID: &str = "adachi-mmpf";
/// Particles N when the config does not say.
pub const DEFAULT_PARTICLES: usize = 500;

struct Measure<'a>(&'a Likelihood);

impl MeasurementModel<Regime<Lane>> for Measure<'_> {
    type Cues = Votes;
    fn log_likelihood(&self, p: &Regime<Lane>, votes: &Votes) -> f64 {
        self.0.log_likelihood(votes, p.model, p.state.q, p.state.w)
    }
}

/// The Adachi tracker.
#[derive(Debug)]
pub struct AdachiTracker {
    camera: Camera,
    config: AdachiConfig,
    chain: MarkovChain,
    votes: Votes,
    likelihood: Likelihood,
    filter: ParticleFilter<Regime<Lane>>,
    initial: Initial,
    probabilities: [f64; 4],
    /// The frame's schedule in progress and the last frame's times.
    stepper: Stepper,
    /// Edge votes of the frame in progress.
    frame_votes: usize,
    /// The estimate's q followed without wrapping, and the lane index it implies.
    q_track: Option<f64>,
    lane_index: i64,
    /// The bottom-up detector of `relock_share` (`None` when it is off).
    detector: Option<RelockDetector>,
    /// The ego pairs of the frame's vote histogram (`start_pair_share`, `vote_pair_share`).
    pairs: VotePairs,
    /// A boundary's position minus its voting edge's, metres (by polarity).
    pair_offset: f64,
    /// The last `valid_support_frames` frames' support, for the validity.
    support_memory: SupportMemory,
    /// The validity rule after a loss (`reacquire_near_m`).
    reacquire: Reacquire,
}

/// The steps of one frame after [`AdachiTracker::begin`] (per-step mode).
pub const STEP_NAMES: [&str; 4] = [
    "resample",
    "predict: switch model r (Table 1), random walk of q and w with the wrap (eqs. 7-9)",
    "weigh: vote-histogram likelihood (eqs. 4-6)",
    "estimate: most probable model, q and w",
];

/// The frame as the filter core runs it ([`crate::filter::schedule`]): one multiple-model
/// filter, resampled at the start of the frame (Sec. 3.3). A first frame has nothing to
/// resample or predict from: its particles are weighed, then `start_iterations` rounds of
/// resample, predict (without the relock proposal) and weigh run on the same votes.
pub static SCHEDULE: Schedule = Schedule::new(
    &STEP_NAMES,
    &[
        &[Op::Resample(0)],
        &[Op::Predict(0)],
        &[Op::Weigh(0)],
        &[Op::Estimate],
    ],
    FirstFrame::WeighFirst,
);

/// Hysteresis of the shared lane-change rule ([`super::lane_change`]) for this tracker, metres:
/// q comes from per-particle wraps (eq. 9) and is noisy at the seam.
const CHANGE_MARGIN_M: f64 = 0.1;

/// The estimate of one frame in the paper's terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdachiEstimate {
    /// Lane position q, metres (rho axis, positive right).
    pub q: f64,
    /// Lane width w, metres.
    pub w: f64,
    /// Most probable model, 1..4.
    pub r: usize,
    /// Posterior probability of each model.
    pub probabilities: [f64; 4],
    /// Lane change this frame: +1 to the left, -1 to the right, 0 none (as `lee.change`).
    pub change: i8,
    /// Number of edge votes.
    pub votes: usize,
    /// Vote support of the ego-left and ego-right boundaries of the estimate (the share of
    /// the region's rows in which each one's edge voted).
    pub support: [f64; 2],
    /// Whether both ego boundaries have at least `valid_support` (see the module docs).
    pub valid: bool,
    /// Effective sample size after the frame's weighing.
    pub ess: f64,
    /// The road shape (s1, s2) the votes were straightened by: a boundary at rho_0 lies at
    /// rho_0 + s1 x + s2 x^2 (0, 0 for the paper's straight lanes).
    pub shape: [f64; 2],
}

impl AdachiTracker {
    /// Builds the tracker.
    ///
    /// # Errors
    /// Camera, particle-count and option errors, named.
    pub fn new(config: &TrackerConfig) -> Result<Self> {
        let camera = config.validate()?;
        let adachi = AdachiConfig::from_options(&config.options)?;
        let chain = MarkovChain::new(&adachi.transitions)?;
        let votes = Votes::new(&camera, &adachi)?;
        if votes.is_empty() {
            return Err(Error::Config(format!(
                "the voting region ({} to {} m ahead) is not visible in this camera's image",
                Num(adachi.near_m),
                Num(adachi.far_m)
            )));
        }
        let likelihood = Likelihood::new(&adachi);
        let initial = Initial {
            width_range: adachi.width_range_m,
        };
        let filter_config = FilterConfig {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::Always,
            injection: Injection::None,
        };
        let filter = ParticleFilter::new(
            config.particles_or(DEFAULT_PARTICLES),
            filter_config,
            config.seed,
            &initial,
        )?;
        let detector = if adachi.relock_share > 0.0 || adachi.paint_options().any() {
            Some(RelockDetector::new(&camera)?)
        } else {
            None
        };
        Ok(Self {
            camera,
            chain,
            votes,
            likelihood,
            filter,
            initial,
            probabilities: [0.25; 4],
            stepper: Stepper::new(),
            frame_votes: 0,
            q_track: None,
            lane_index: 0,
            detector,
            pairs: VotePairs::new(),
            pair_offset: match adachi.polarity {
                config::Polarity::LeftEdge => adachi.marking_width_m / 2.0,
                config::Polarity::RightEdge => -adachi.marking_width_m / 2.0,
                config::Polarity::Both => 0.0,
            },
            support_memory: SupportMemory::new(adachi.valid_support_frames),
            reacquire: Reacquire::new(adachi.reacquire_near_m),
            config: adachi,
        })
    }

    /// Replaces `relock_share` of the particles by draws around the detector's ego pair (see
    /// `relock_share`), when it found one of an accepted width. q is the pair's centre where
    /// the votes place it: mid-region for straight lanes, at the car for curved ones (whose
    /// votes are straightened to x = 0).
    fn relock(&mut self) {
        let Some(d) = self.detector.as_ref().and_then(RelockDetector::detection) else {
            return;
        };
        let [lo, hi] = self.config.width_range_m;
        let w = d.width();
        if !(lo..=hi).contains(&w) {
            return;
        }
        let x = match self.config.lane_shape {
            config::LaneShape::Straight => 0.5 * (self.config.near_m + self.config.far_m),
            config::LaneShape::Curved => 0.0,
        };
        let q = -(d.centre() + x * crate::math::tan(d.heading()));
        let (sq, sw) = (self.config.sigma_q_m, self.config.sigma_w_m);
        self.filter
            .replace_share(self.config.relock_share, |old, rng| Regime {
                model: old.model,
                state: Lane {
                    q: rng.gaussian(q, sq),
                    w: crate::math::clamp(rng.gaussian(w, sw), lo, hi),
                    change: 0,
                },
            });
    }

    /// Replaces `share` of the particles by draws around the ego pairs of the frame's vote
    /// histogram ([`pairs`]), each with a uniformly drawn model r (so that a cloud locked on
    /// the wrong model as well as the wrong lane can leave it). Nothing when there is no pair.
    fn draw_from_pairs(&mut self, share: f64) {
        if share <= 0.0 {
            return;
        }
        let found = self
            .pairs
            .find(&self.votes, self.pair_offset, self.config.width_range_m);
        if found == 0 {
            return;
        }
        let [lo, hi] = self.config.width_range_m;
        let (sq, sw) = (self.config.sigma_q_m, self.config.sigma_w_m);
        let pairs = &self.pairs;
        self.filter.replace_share(share, |old, rng| {
            let Some((q, w)) = pairs.draw(rng) else {
                return *old;
            };
            let w = crate::math::clamp(rng.gaussian(w, sw), lo, hi);
            let (q, _) = motion::wrap(rng.gaussian(q, sq), w);
            Regime {
                model: rng.below(4),
                state: Lane { q, w, change: 0 },
            }
        });
    }

    /// `side_search_share`: after a frame whose estimate had one boundary supported and the
    /// other bare, replaces that share of the particles by lanes that keep the supported
    /// boundary at q +- w / 2 (q positive right: the left boundary at q - w / 2) and draw w
    /// uniformly over the width limits.
    fn search_lost_side(&mut self) {
        let share = self.config.side_search_share;
        if share <= 0.0 {
            return;
        }
        let held = self.config.valid_support;
        let side = match side_search::kept_side(self.support_memory.last(), held) {
            Some(Kept::Left) => OFFSETS[0],
            Some(Kept::Right) => OFFSETS[1],
            None => return,
        };
        let [lo, hi] = self.config.width_range_m;
        self.filter.replace_share(share, |old, rng| {
            let kept = old.state.q + side * old.state.w / 2.0;
            let w = lo + (hi - lo) * rng.uniform();
            Regime {
                model: old.model,
                state: Lane {
                    q: kept - side * w / 2.0,
                    w,
                    change: 0,
                },
            }
        });
    }

    /// The vote histogram H_j of the last frame and the rho of its first bin and bin size.
    pub fn histogram(&self) -> (&[f64], f64, f64) {
        (
            &self.votes.histogram,
            self.votes.rho_min(),
            self.votes.bin_m(),
        )
    }

    /// The per-frame maximum-likelihood baseline on the last frame's votes: (model 1..4, q,
    /// w, log-likelihood), q searched in steps of the bin size and w in 2 cm steps.
    pub fn grid_estimate(&self) -> (usize, f64, f64, f64) {
        self.grid_estimate_with(self.votes.bin_m(), 0.02)
    }

    /// [`AdachiTracker::grid_estimate`] with the grid's q and w steps in metres (steps under
    /// 1 mm are taken as 1 mm).
    pub fn grid_estimate_with(&self, q_step: f64, w_step: f64) -> (usize, f64, f64, f64) {
        grid::grid_search(
            &self.votes,
            &self.likelihood,
            self.config.width_range_m,
            q_step,
            w_step,
        )
    }

    /// The particles: (model 1..4, q, w) with their weights.
    pub fn particle_states(&self) -> impl Iterator<Item = (usize, f64, f64, f64)> + '_ {
        self.filter
            .states()
            .iter()
            .zip(self.filter.weights())
            .map(|(p, &wt)| (p.model + 1, p.state.q, p.state.w, wt))
    }

    /// One frame, returning the estimate in the paper's terms: [`AdachiTracker::begin`], then
    /// every step of [`SCHEDULE`] in order ([`Scheduled::step_frame`]).
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn track(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<AdachiEstimate> {
        self.step_frame(|t| t.begin(rgba, width, height))
    }

    /// Starts a frame: checks it and votes its edge points (H_j, Sec. 3.2). A frame still in
    /// progress is abandoned where it stands.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    pub fn begin(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        super::check_frame(&self.camera, rgba, width, height)?;
        let t0 = now();
        self.frame_votes = self.votes.vote(rgba);
        if let Some(d) = self.detector.as_mut() {
            let lines = self.config.relock_share > 0.0;
            d.feed_as_needed(&self.camera, rgba, width, height, lines)?;
        }
        self.votes_ready(t0);
        Ok(())
    }

    /// The rest of [`AdachiTracker::begin`] once H_j is voted (`t0`: when the frame began).
    fn votes_ready(&mut self, t0: f64) {
        self.likelihood.prepare(&self.votes);
        self.stepper.begin(StageTimes {
            preprocess: now() - t0,
            ..StageTimes::default()
        });
        if self.stepper.is_first_frame() {
            // The start (ours; the paper leaves it open): `start_pair_share` of the initial
            // particles around the first frame's vote pairs, the rest uniform.
            self.draw_from_pairs(self.config.start_pair_share);
        }
    }

    fn read_estimate(&mut self, votes: usize) -> AdachiEstimate {
        let states = self.filter.states();
        let weights = self.filter.weights();
        model_probabilities(states, weights, &mut self.probabilities);
        let best_model = (0..4)
            .max_by(|&a, &b| self.probabilities[a].total_cmp(&self.probabilities[b]))
            .unwrap_or(0);
        let best = crate::filter::map_index(weights);
        let q_ref = states[best].state.q;
        let (mut q, mut w, mut total) = (0.0, 0.0, 0.0);
        for (p, &wt) in states.iter().zip(weights) {
            if p.model != best_model {
                continue;
            }
            // Unwrap q to the copy nearest the best particle's.
            let k = ((q_ref - p.state.q) / p.state.w).round();
            q += wt * (p.state.q + k * p.state.w);
            w += wt * p.state.w;
            total += wt;
        }
        let (q, w) = if total > 0.0 {
            (q / total, w / total)
        } else {
            (q_ref, states[best].state.w)
        };
        let (q, _) = motion::wrap(q, w);
        // Eq. 9 on the estimate, with hysteresis.
        let track = match self.q_track {
            None => q,
            Some(prev) => q + ((prev - q) / w).round() * w,
        };
        self.q_track = Some(track);
        // The shared lane-change rule (`super::lane_change`) on the lane the index says;
        // q is to the right, the rule's lane centre to the left.
        let local = track - self.lane_index as f64 * w;
        let change = EgoLane::symmetric(-local, w).change(CHANGE_MARGIN_M);
        self.lane_index += i64::from(change);
        let rhos = [q + OFFSETS[0] * w / 2.0, q + OFFSETS[1] * w / 2.0];
        let support = rhos.map(|rho| self.likelihood.support(&self.votes, rho));
        let reach = rhos
            .iter()
            .map(|&rho| self.likelihood.reach(&self.votes, rho))
            .fold(f64::INFINITY, f64::min);
        let remembered = self.support_memory.push(support);
        let valid = self
            .reacquire
            .valid(support, remembered, self.config.valid_support, reach);
        AdachiEstimate {
            q,
            w,
            r: best_model + 1,
            probabilities: self.probabilities,
            change,
            votes,
            support,
            valid,
            ess: self.filter.ess(),
            shape: self.votes.shape(),
        }
    }

    /// The boundaries model `r` (1..4) has at lane position `q` and width `w` (eq. 1), bent by
    /// the road `shape`.
    fn boundaries(&self, r: usize, q: f64, w: f64, shape: [f64; 2]) -> Vec<Boundary> {
        let roles = [
            Role::EgoLeft,
            Role::EgoRight,
            Role::LeftAdjacent,
            Role::RightAdjacent,
        ];
        let mut boundaries = Vec::new();
        for l in 0..4 {
            if !COEFFICIENTS[r - 1][l] {
                continue;
            }
            let rho = q + OFFSETS[l] * w / 2.0;
            let (points, road_points) = sample_road_curve(
                |x| -(rho + shape[0] * x + shape[1] * x * x),
                |x, y| self.camera.road_to_pixel(x, y),
                self.config.near_m.min(3.0),
                self.config.far_m * 3.0,
                self.camera.width(),
                self.camera.height(),
            );
            boundaries.push(Boundary {
                role: roles[l],
                points,
                road_points,
            });
        }
        boundaries
    }

    /// The estimate as the shared output type.
    pub fn to_lane_estimate(&self, e: &AdachiEstimate) -> LaneEstimate {
        let mut boundaries = self.boundaries(e.r, e.q, e.w, e.shape);
        let (valid, snapped) = apply_paint_options(
            &self.camera,
            &mut boundaries,
            self.detector.as_ref(),
            e.valid,
            self.config.paint_options(),
        );
        let state = [
            ("adachi.q", e.q),
            ("adachi.w", e.w),
            ("adachi.r", e.r as f64),
            ("adachi.p1", e.probabilities[0]),
            ("adachi.p2", e.probabilities[1]),
            ("adachi.p3", e.probabilities[2]),
            ("adachi.p4", e.probabilities[3]),
            ("adachi.change", e.change as f64),
            ("adachi.votes", e.votes as f64),
            ("adachi.support_left", e.support[0]),
            ("adachi.support_right", e.support[1]),
            ("adachi.ess", e.ess),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        let mut estimate = LaneEstimate {
            frame: String::new(),
            valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: e.q,
            heading_rad: -e.shape[0],
            curvature_per_m: -2.0 * e.shape[1],
            lane_width_m: e.w,
            delimiters: Vec::new(),
            state,
        };
        move_lane_figures(&mut estimate, snapped.moved_at_car);
        estimate
    }
}

impl Tracker for AdachiTracker {
    fn id(&self) -> &'static str {
        ID
    }

    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate> {
        let e = self.track(rgba, width, height)?;
        Ok(self.to_lane_estimate(&e))
    }

    fn reset(&mut self) {
        self.filter.reset(&self.initial);
        self.votes.reset_shape();
        if let Some(d) = self.detector.as_mut() {
            d.reset();
        }
        self.stepper.restart();
        self.stepper.abandon();
        self.q_track = None;
        self.lane_index = 0;
        self.support_memory.clear();
        self.reacquire.reset();
    }

    fn stage_times(&self) -> StageTimes {
        self.stepper.times()
    }

    /// Four numbers per particle: model r (1..4), q (m), w (m), normalised weight.
    fn particles(&self) -> Vec<f32> {
        self.particle_states()
            .flat_map(|(r, q, w, wt)| [r as f32, q as f32, w as f32, wt as f32])
            .collect()
    }

    fn particle_stride(&self) -> usize {
        4
    }

    /// Group: the particle's model r.
    fn hypotheses(&self, max: usize) -> Vec<Hypothesis> {
        let states = self.filter.states();
        let weights = self.filter.weights();
        spread_indices(states.len(), max)
            .map(|i| {
                let p = &states[i];
                Hypothesis {
                    weight: weights[i],
                    group: p.model as i32 + 1,
                    boundaries: self.boundaries(
                        p.model + 1,
                        p.state.q,
                        p.state.w,
                        self.votes.shape(),
                    ),
                }
            })
            .collect()
    }

    fn step_names(&self) -> &'static [&'static str] {
        SCHEDULE.names()
    }

    /// The vote histogram H_j and the noise histogram N_j (Sec. 3.2, eq. 4).
    fn layers(&self) -> Vec<Layer> {
        let histogram = |name: &str, values: &[f64]| Layer::Histogram {
            name: name.to_string(),
            axis: "rho (m, positive right)".to_string(),
            start: self.votes.rho_min(),
            step: self.votes.bin_m(),
            values: values.iter().map(|&v| v as f32).collect(),
        };
        vec![
            histogram("edge votes H_j", &self.votes.histogram),
            histogram(
                "noise N_j (all region pixels, normalised)",
                &self.votes.noise,
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

/// The models of the schedule's operations.
impl Scheduled for AdachiTracker {
    type State = Regime<Lane>;
    type Estimate = AdachiEstimate;

    fn schedule(&self) -> &'static Schedule {
        &SCHEDULE
    }
    fn stepper(&self) -> &Stepper {
        &self.stepper
    }
    fn stepper_mut(&mut self) -> &mut Stepper {
        &mut self.stepper
    }
    fn filter_mut(&mut self, _stage: usize) -> Option<&mut ParticleFilter<Regime<Lane>>> {
        Some(&mut self.filter)
    }
    fn start_rounds(&self) -> usize {
        self.config.start_iterations
    }
    fn inject(&mut self, _stage: usize) {
        self.filter.inject(&self.initial);
    }
    /// The Table 1 model switch and the random walk of q and w (eqs. 7-9); on a frame's own
    /// pass, then the relock proposal.
    fn predict(&mut self, _stage: usize, pass: Pass) {
        let motion = SwitchingMotion {
            chain: &self.chain,
            motion: Motion {
                sigma_q: self.config.sigma_q_m,
                sigma_w: self.config.sigma_w_m,
                width_range: self.config.width_range_m,
            },
        };
        self.filter.predict(&motion);
        if pass == Pass::Frame {
            self.relock();
            self.draw_from_pairs(self.config.vote_pair_share);
            self.search_lost_side();
        }
    }
    fn weigh(&mut self, _stage: usize) {
        self.filter.weigh(&Measure(&self.likelihood), &self.votes);
    }
    fn estimate(&mut self) -> AdachiEstimate {
        self.read_estimate(self.frame_votes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Eye, Scene};

    pub(super) fn config(extra: &str) -> TrackerConfig {
        let cam = serde_json::to_string(&default_camera(320, 240).unwrap().to_file()).unwrap();
        TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {cam}, "particles": 400, "seed": 2 {extra}}}"#
        ))
        .unwrap()
    }

    /// Runs the tracker over `frames` frames of a scenario; returns (truth, estimate) pairs.
    fn run(name: &str, frames: u32) -> Vec<(LaneEstimate, AdachiEstimate)> {
        run_seeded(name, 1, 2, frames)
    }

    /// [`run`] with the scene's and the tracker's seeds.
    fn run_seeded(
        name: &str,
        scene_seed: u64,
        tracker_seed: u64,
        frames: u32,
    ) -> Vec<(LaneEstimate, AdachiEstimate)> {
        let mut scene = Scene::new(
            scenario(name).unwrap(),
            default_camera(320, 240).unwrap(),
            scene_seed,
        )
        .unwrap();
        let cam = serde_json::to_string(&default_camera(320, 240).unwrap().to_file()).unwrap();
        let config = TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {cam}, "particles": 400, "seed": {tracker_seed}}}"#
        ))
        .unwrap();
        let mut tracker = AdachiTracker::new(&config).unwrap();
        let mut rgba = vec![0; 320 * 240 * 4];
        (0..frames)
            .map(|f| {
                scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                (
                    crate::trackers::scene_truth(&scene, f),
                    tracker.track(&rgba, 320, 240).unwrap(),
                )
            })
            .collect()
    }

    #[test]
    fn likelihood_peaks_at_the_true_lane() {
        let mut c = scenario("highway-straight").unwrap();
        c.ego.sway_amplitude_m = 0.0;
        let mut scene = Scene::new(c, default_camera(320, 240).unwrap(), 1).unwrap();
        let mut rgba = vec![0; 320 * 240 * 4];
        scene.render(0, Eye::Left, &mut rgba, None).unwrap();
        let mut tracker = AdachiTracker::new(&config("")).unwrap();
        tracker.track(&rgba, 320, 240).unwrap();
        let (r, q, w, _) = tracker.grid_estimate();
        // Three lanes, the car centred in the middle one: model 4, q = 0, w = 3.6.
        assert_eq!(r, 4);
        assert!(q.abs() < 0.1 && (w - 3.6).abs() < 0.06, "q {q} w {w}");
        // Removing a boundary the data has costs likelihood.
        let full = tracker
            .likelihood
            .log_likelihood(&tracker.votes, 3, 0.0, 3.6);
        let fewer = tracker
            .likelihood
            .log_likelihood(&tracker.votes, 0, 0.0, 3.6);
        let shifted = tracker
            .likelihood
            .log_likelihood(&tracker.votes, 3, 0.5, 3.6);
        assert!(full > fewer && full > shifted);
    }

    #[test]
    fn tracks_a_straight_highway() {
        let out = run("highway-straight", 60);
        let n = out.len() as f64;
        let rmse_q = (out
            .iter()
            .map(|(t, e)| (e.q - t.state["adachi.q"]).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        let rmse_w = (out
            .iter()
            .map(|(t, e)| (e.w - t.lane_width_m).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        let model = out
            .iter()
            .filter(|(t, e)| e.r as f64 == t.state["adachi.r"])
            .count() as f64
            / n;
        assert!(
            rmse_q < 0.15 && rmse_w < 0.05 && model > 0.95,
            "q {rmse_q} w {rmse_w} model {model}"
        );
    }

    #[test]
    fn lane_changes_are_reported_once_in_the_right_direction() {
        let out = run("lane-change", 330);
        let truth: Vec<usize> = out
            .iter()
            .enumerate()
            .filter(|(_, (t, _))| t.state["lane_change"] == 1.0)
            .map(|(i, _)| i)
            .collect();
        let events: Vec<(usize, i8)> = out
            .iter()
            .enumerate()
            .filter(|(_, (_, e))| e.change != 0)
            .map(|(i, (_, e))| (i, e.change))
            .collect();
        assert_eq!(truth.len(), 2);
        assert_eq!(events.len(), 2, "{events:?} vs {truth:?}");
        // First to the right (lane 1 -> 2), then back to the left, each within 0.5 s.
        assert_eq!((events[0].1, events[1].1), (-1, 1));
        for (e, t) in events.iter().zip(&truth) {
            assert!(e.0.abs_diff(*t) <= 15, "{events:?} vs {truth:?}");
        }
    }

    /// Error of q against the truth, modulo the lane width (q and q +- w describe the same
    /// lanes).
    fn q_error(t: &LaneEstimate, e: &AdachiEstimate) -> f64 {
        let d = e.q - t.state["adachi.q"];
        d - (d / e.w).round() * e.w
    }

    /// Share of `out` (among the frames `select` keeps) where `hit` holds, and how many
    /// frames were kept.
    fn share(
        out: &[(LaneEstimate, AdachiEstimate)],
        select: impl Fn(usize, &LaneEstimate) -> bool,
        hit: impl Fn(&LaneEstimate, &AdachiEstimate) -> bool,
    ) -> (f64, usize) {
        let kept: Vec<_> = out
            .iter()
            .enumerate()
            .filter(|(i, (t, _))| select(*i, t))
            .collect();
        let n = kept.iter().filter(|(_, (t, e))| hit(t, e)).count();
        (n as f64 / kept.len().max(1) as f64, kept.len())
    }

    /// `multi-lane`: four lanes, the car in the second; the lane on its left is missing for
    /// s = 90-200 m (frames 84-216), so the true model goes 4 -> 3 -> 4. Measured at 320x240
    /// over all 300 frames, scene seeds 1-4 with tracker seeds 11-14 (2026-11-24): model r
    /// right in 64-67 % of the frames (model 4: 80-83 %, model 3: 42-46 %), the presence of the
    /// left lane right in 92-93 %. Thresholds: 60 % and 85 % (always answering 4 would give
    /// 56 %, a left lane always present 56 %). What the tracker misses is the lane on the
    /// right while its outer boundary, 5.4 m out, is a dashed line (s = 70-230): it votes only
    /// in the far rows of the region and model 1 or 2 wins, the failure of the paper's
    /// Fig. 5 (c).
    #[test]
    fn multi_lane_model_follows_the_adjacent_lanes() {
        let out = run("multi-lane", 300);
        let truth_r = |t: &LaneEstimate| t.state["adachi.r"] as usize;
        let (model, _) = share(&out, |_, _| true, |t, e| e.r == truth_r(t));
        // Models 2 and 4 have a lane on the left.
        let (left, _) = share(
            &out,
            |_, _| true,
            |t, e| (e.r % 2 == 0) == (truth_r(t) % 2 == 0),
        );
        let (without_left, n) = share(&out, |_, t| truth_r(t) == 3, |t, e| e.r == truth_r(t));
        assert!(n > 100, "the left lane disappears for {n} frames");
        assert!(
            model >= 0.6 && left >= 0.85,
            "model r {model:.3}, left lane {left:.3}, model 3 {without_left:.3}"
        );
    }

    /// `worn-markings`, the paper's known failure (faded and dashed lines): all paint faded to
    /// 35 % for s = 60-140 m, the ego-left line gone for s = 160-220 and the ego-right line for
    /// s = 240-290, the inner lines dashed (3 m every 12 m) throughout. A line is gone from the
    /// whole 6-22 m voting region in frames 161-213 (left) and 257-297 (right). Measured at
    /// 320x240 over 300 frames, scene seeds 1-4 with tracker seeds 11-14 (2026-11-24): q error
    /// (modulo w) RMSE 0.092-0.094 m and at most 0.23 m, w RMSE 0.011-0.013 m; model r right in
    /// 69-70 % of the frames (4 is true throughout; while the paint is faded the dashed lines
    /// 5.4 m out give too few votes and model 1 wins, as in the paper); valid in 95-99 % of
    /// frames 0-143 and in none where an ego line is gone from the whole region. Thresholds:
    /// RMSE 0.12 m, max 0.3 m, model 60 %, valid 85 % and at most 5 %.
    #[test]
    fn worn_and_dashed_markings_keep_the_position_and_lose_validity_where_a_line_is_gone() {
        let out = run("worn-markings", 300);
        let n = out.len() as f64;
        let rmse_q = (out.iter().map(|(t, e)| q_error(t, e).powi(2)).sum::<f64>() / n).sqrt();
        let max_q = out
            .iter()
            .map(|(t, e)| q_error(t, e).abs())
            .fold(0.0, f64::max);
        let (model, _) = share(&out, |_, _| true, |t, e| e.r as f64 == t.state["adachi.r"]);
        let (valid_painted, _) = share(&out, |i, _| i < 144, |_, e| e.valid);
        let gone = |i: usize| (161..=213).contains(&i) || (257..=297).contains(&i);
        let (valid_gone, _) = share(&out, |i, _| gone(i), |_, e| e.valid);
        // The gone line is the one without support.
        assert!(out[161..=213]
            .iter()
            .all(|(_, e)| e.support[0] < e.support[1]));
        assert!(out[257..=297]
            .iter()
            .all(|(_, e)| e.support[1] < e.support[0]));
        assert!(
            rmse_q < 0.12
                && max_q < 0.3
                && model >= 0.6
                && valid_painted >= 0.85
                && valid_gone <= 0.05,
            "q RMSE {rmse_q:.3} max {max_q:.3}, model {model:.3}, valid {valid_painted:.3} \
             painted, {valid_gone:.3} gone"
        );
    }

    /// `valid` needs vote support on both ego lines: a marked road is valid, a blank, a black
    /// and an occluded frame (a truck's flat back over the road region) are not.
    #[test]
    fn valid_means_both_ego_lines_have_votes() {
        let mut c = scenario("highway-straight").unwrap();
        c.ego.sway_amplitude_m = 0.0;
        let mut scene = Scene::new(c, default_camera(320, 240).unwrap(), 1).unwrap();
        let mut tracker = AdachiTracker::new(&config("")).unwrap();
        let mut rgba = vec![0; 320 * 240 * 4];
        for f in 0..10 {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            let e = tracker.track(&rgba, 320, 240).unwrap();
            assert!(e.valid, "frame {f}: support {:?}", e.support);
            assert!(tracker.to_lane_estimate(&e).valid);
        }
        // The truck: rows from 40 % of the height down, columns 10-90 %.
        let mut occluded = rgba.clone();
        for v in 96..240 {
            for u in 32..288 {
                occluded[(v * 320 + u) * 4..(v * 320 + u) * 4 + 3].copy_from_slice(&[70, 70, 76]);
            }
        }
        let black: Vec<u8> = (0..320 * 240 * 4)
            .map(|i| if i % 4 == 3 { 255 } else { 0 })
            .collect();
        let blank = vec![120; 320 * 240 * 4];
        for (name, frame) in [
            ("occluded", &occluded),
            ("black", &black),
            ("blank", &blank),
        ] {
            let e = tracker.track(frame, 320, 240).unwrap();
            assert!(
                !e.valid && !tracker.to_lane_estimate(&e).valid,
                "{name}: support {:?}",
                e.support
            );
        }
        // And the road again.
        scene.render(10, Eye::Left, &mut rgba, None).unwrap();
        assert!(tracker.track(&rgba, 320, 240).unwrap().valid);
    }

    /// q after 5 frames of `highway-curve` (seed 1, 320x240, 400 particles, seed 2), as
    /// bits; `tests/web.rs` asserts the same value in headless Chromium.
    const CROSS_TARGET_Q_BITS: u64 = 0x3fb9_011a_d511_3817;

    #[test]
    fn same_result_as_the_browser_build() {
        let out = run("highway-curve", 5);
        let q = out[4].1.q;
        assert_eq!(q.to_bits(), CROSS_TARGET_Q_BITS, "{:#x} ({q})", q.to_bits());
    }

    #[test]
    fn bad_input_is_an_error_and_the_tracker_goes_on() {
        assert!(AdachiTracker::new(&config(r#", "bin_m": -1"#))
            .unwrap_err()
            .to_string()
            .contains("bin_m"));
        assert!(AdachiTracker::new(&config(r#", "valid_support": 1.5"#))
            .unwrap_err()
            .to_string()
            .contains("valid_support"));
        assert!(AdachiTracker::new(&config(r#", "colour": 1"#))
            .unwrap_err()
            .to_string()
            .contains("unknown field"));
        let mut t = AdachiTracker::new(&config("")).unwrap();
        assert!(t.track(&[0; 16], 2, 2).is_err());
        assert!(t.track(&[0; 100], 320, 240).is_err());
        let frame = vec![90; 320 * 240 * 4];
        let e = t.track(&frame, 320, 240).unwrap();
        assert_eq!(e.votes, 0);
        assert!(
            !t.to_lane_estimate(&e).valid,
            "no votes, no confident estimate"
        );
    }
}
