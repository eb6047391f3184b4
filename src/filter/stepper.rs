//! The one stepper, timer and step-by-step driver of every tracker's frame.
//!
//! A tracker implements [`Scheduled`]: its [`Schedule`], where its [`Stepper`] lives, and
//! what each operation means for its filters and models (its motion and measurement models,
//! its estimator). The trait's provided methods then drive the frame:
//!
//! - [`Scheduled::advance_step`] runs the next step's operations, timing each into its
//!   [`StageTimes`] bucket, and returns the estimate after the last step;
//! - [`Scheduled::step_frame`] is the tracker's `begin` (its image cues, ending in
//!   [`Stepper::begin`]) followed by every `advance_step`, so a whole frame and a frame
//!   stepped through one step at a time run the same operations in the same order, by
//!   construction (tested here on a toy filter, and for every tracker in `trackers/tests.rs`).
//!
//! The stepper also keeps whether the next frame is a first frame (after construction,
//! [`Stepper::restart`] or a tracker's own restart), which a [`FirstFrame::WeighFirst`]
//! schedule runs differently (see [`super::schedule`]), and the record of the resampling
//! decisions of the last `step_frame` or `advance_step` ([`Stepper::resamplings`]): after
//! every `Resample` and `ResampleBetween` it takes the filter's decision
//! ([`ParticleFilter::take_decision`]), in the order the filters made them.

use super::particle_filter::ParticleFilter;
use super::resampling_log::ResampleDecision;
use super::schedule::{FirstFrame, Op, Pass, Schedule};
use super::stage_times::{now, StageTimes};
use crate::error::{Error, Result};

/// A frame in progress.
#[derive(Debug, Clone, Copy)]
struct Progress {
    /// Index of the next step.
    next: usize,
    /// Whether this is a first frame.
    first: bool,
    /// Bit k: stage k has been weighed this frame.
    weighed: u64,
    times: StageTimes,
}

/// Where a tracker is in its frame, and the times of the last finished frame.
#[derive(Debug, Clone)]
pub struct Stepper {
    frame: Option<Progress>,
    first_next: bool,
    last: StageTimes,
    /// The resampling decisions of the frame (in progress or last).
    resamplings: Vec<ResampleDecision>,
    /// Where the last call's decisions start in `resamplings` (0 after a whole frame).
    call_from: usize,
}

impl Default for Stepper {
    fn default() -> Self {
        Self::new()
    }
}

impl Stepper {
    /// No frame in progress; the next frame is a first frame.
    pub fn new() -> Self {
        Self {
            frame: None,
            first_next: true,
            last: StageTimes::default(),
            resamplings: Vec::new(),
            call_from: 0,
        }
    }

    /// Starts a frame whose image cues took `cues` (its `preprocess` and `disparity`); a
    /// frame in progress is abandoned where it stands.
    pub fn begin(&mut self, cues: StageTimes) {
        let first = self.first_next;
        self.first_next = false;
        self.resamplings.clear();
        self.call_from = 0;
        self.frame = Some(Progress {
            next: 0,
            first,
            weighed: 0,
            times: cues,
        });
    }

    /// The next frame is a first frame (the filter starts again from its initial
    /// distribution); a frame in progress goes on as it started.
    pub fn restart(&mut self) {
        self.first_next = true;
    }

    /// Forgets the frame in progress and the resampling decisions.
    pub fn abandon(&mut self) {
        self.frame = None;
        self.resamplings.clear();
        self.call_from = 0;
    }

    /// The resampling decisions of the last [`Scheduled::advance_step`] (that step's) or
    /// [`Scheduled::step_frame`] (the whole frame's), in the order the filters made them;
    /// empty after [`Stepper::begin`] and [`Stepper::abandon`]. A first frame's start-up
    /// rounds report theirs; an operation a first frame skips reports none.
    pub fn resamplings(&self) -> &[ResampleDecision] {
        &self.resamplings[self.call_from..]
    }

    /// Index of the next step of the frame in progress; `None` when none is in progress.
    pub fn next_step(&self) -> Option<usize> {
        self.frame.map(|f| f.next)
    }

    /// Whether a frame is in progress.
    pub fn in_progress(&self) -> bool {
        self.frame.is_some()
    }

    /// Whether the next frame to begin will be a first frame.
    pub fn next_is_first(&self) -> bool {
        self.first_next
    }

    /// Whether the frame in progress is a first frame (false when none is in progress).
    pub fn is_first_frame(&self) -> bool {
        self.frame.is_some_and(|f| f.first)
    }

    /// Milliseconds per stage of the last finished frame.
    pub fn times(&self) -> StageTimes {
        self.last
    }

    /// Adds `ms` to the bucket of `op` in the frame in progress.
    fn charge(&mut self, op: Op, ms: f64) {
        if let Some(f) = self.frame.as_mut() {
            let t = &mut f.times;
            match op {
                Op::Resample(_) | Op::ResampleBetween(_) => t.resample += ms,
                Op::Inject(_) | Op::Predict(_) => t.predict += ms,
                Op::Weigh(_) => t.weigh += ms,
                Op::StageEstimate(_) | Op::Estimate => t.estimate += ms,
            }
        }
    }

    /// Whether `op` runs now: on a first frame of a weigh-first schedule, a stage is not
    /// moved before it has been weighed.
    fn runs(&self, schedule: &Schedule, op: Op) -> bool {
        match (self.frame, op.stage()) {
            (Some(f), Some(k)) if f.first && schedule.first_frame() == FirstFrame::WeighFirst => {
                !op.moves_particles() || f.weighed & (1 << k) != 0
            }
            _ => true,
        }
    }

    fn weighed(&mut self, stage: usize) {
        if let Some(f) = self.frame.as_mut() {
            f.weighed |= 1 << stage;
        }
    }

    /// Ends the frame in progress: its times become the last frame's.
    fn finish(&mut self) {
        if let Some(f) = self.frame.take() {
            self.last = f.times;
        }
    }
}

/// A tracker's filters and models under a [`Schedule`]: what each operation does (see the
/// module docs); the provided methods are the driver.
pub trait Scheduled {
    /// The particle state of the tracker's filters.
    type State: Clone;
    /// The frame's estimate.
    type Estimate;

    /// The tracker's schedule.
    fn schedule(&self) -> &'static Schedule;
    /// The tracker's stepper.
    fn stepper(&self) -> &Stepper;
    /// The tracker's stepper, mutable.
    fn stepper_mut(&mut self) -> &mut Stepper;
    /// Stage k's filter (`None` for a stage without one of its own).
    fn filter_mut(&mut self, stage: usize) -> Option<&mut ParticleFilter<Self::State>>;
    /// Start-up rounds after each weigh of a first frame (see [`FirstFrame::WeighFirst`]).
    fn start_rounds(&self) -> usize {
        0
    }

    /// [`Op::Resample`]: by the filter's policy.
    fn resample(&mut self, stage: usize) {
        if let Some(f) = self.filter_mut(stage) {
            f.resample();
        }
    }
    /// [`Op::Inject`]: the filter's initialisation particles from the tracker's initial
    /// distribution.
    fn inject(&mut self, stage: usize);
    /// [`Op::Predict`]: stage k's motion model.
    fn predict(&mut self, stage: usize, pass: Pass);
    /// [`Op::Weigh`]: stage k's measurement model.
    fn weigh(&mut self, stage: usize);
    /// [`Op::ResampleBetween`]: unconditionally.
    fn resample_between(&mut self, stage: usize) {
        if let Some(f) = self.filter_mut(stage) {
            f.resample_between_stages();
        }
    }
    /// [`Op::StageEstimate`]: keeps stage k's estimate for the later stages (nothing for a
    /// schedule without one).
    fn stage_estimate(&mut self, _stage: usize) {}
    /// [`Op::Estimate`]: the frame's estimate.
    fn estimate(&mut self) -> Self::Estimate;

    /// Runs the next step of the frame in progress; returns the estimate after the last
    /// step, `None` before it or when no frame is in progress.
    fn advance_step(&mut self) -> Option<Self::Estimate> {
        let schedule = self.schedule();
        let stepper = self.stepper_mut();
        stepper.call_from = stepper.resamplings.len();
        let frame = stepper.frame.as_mut()?;
        let step = frame.next;
        frame.next += 1;
        let first = frame.first;
        let ops = schedule
            .steps()
            .get(step)
            .copied()
            .unwrap_or(&[Op::Estimate]);
        for &op in ops {
            if !self.stepper().runs(schedule, op) {
                continue;
            }
            if let Some(estimate) = run(self, op, Pass::Frame) {
                self.stepper_mut().finish();
                return Some(estimate);
            }
            if let Op::Weigh(k) = op {
                self.stepper_mut().weighed(k);
                let rounds = self.start_rounds();
                if first && schedule.first_frame() == FirstFrame::WeighFirst && rounds > 0 {
                    for round in 1..=rounds {
                        let pass = Pass::StartRound { round, rounds };
                        for op in [Op::Resample(k), Op::Predict(k), Op::Weigh(k)] {
                            run(self, op, pass);
                        }
                    }
                }
            }
        }
        None
    }

    /// One whole frame: `begin` (the tracker's image cues, ending in [`Stepper::begin`]),
    /// then every step of the schedule.
    ///
    /// # Errors
    /// What `begin` returns; [`Error::State`] when it started no frame.
    fn step_frame(&mut self, begin: impl FnOnce(&mut Self) -> Result<()>) -> Result<Self::Estimate>
    where
        Self: Sized,
    {
        begin(self)?;
        if !self.stepper().in_progress() {
            return Err(Error::State("the frame's cues started no frame".into()));
        }
        loop {
            if let Some(estimate) = self.advance_step() {
                self.stepper_mut().call_from = 0;
                return Ok(estimate);
            }
        }
    }
}

/// Runs one operation, timed into its bucket; the estimate for [`Op::Estimate`].
fn run<T: Scheduled + ?Sized>(tracker: &mut T, op: Op, pass: Pass) -> Option<T::Estimate> {
    let t = now();
    let mut estimate = None;
    match op {
        Op::Resample(k) => tracker.resample(k),
        Op::Inject(k) => tracker.inject(k),
        Op::Predict(k) => tracker.predict(k, pass),
        Op::Weigh(k) => tracker.weigh(k),
        Op::ResampleBetween(k) => tracker.resample_between(k),
        Op::StageEstimate(k) => tracker.stage_estimate(k),
        Op::Estimate => estimate = Some(tracker.estimate()),
    }
    tracker.stepper_mut().charge(op, now() - t);
    if let Op::Resample(k) | Op::ResampleBetween(k) = op {
        if let Some(d) = tracker
            .filter_mut(k)
            .and_then(ParticleFilter::take_decision)
        {
            tracker.stepper_mut().resamplings.push(d);
        }
    }
    estimate
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{
        FilterConfig, InitialDistribution, Injection, MeasurementModel, MotionModel,
        ResamplePolicy, Rng,
    };

    /// A two-stage cascade over one scalar each, in the shape of Lee's (weigh first, start
    /// rounds, stage 2 conditioned on stage 1's estimate), with injection on stage 1; every
    /// operation it runs is logged.
    struct Toy {
        filters: [ParticleFilter<f64>; 2],
        stepper: Stepper,
        truth: [f64; 2],
        stage1: f64,
        log: Vec<(Op, Pass)>,
    }

    struct Uniform;
    impl InitialDistribution<f64> for Uniform {
        fn sample(&self, rng: &mut Rng) -> f64 {
            10.0 * rng.uniform() - 5.0
        }
    }
    struct Walk(f64);
    impl MotionModel<f64> for Walk {
        fn propagate(&self, x: &mut f64, rng: &mut Rng) {
            *x += rng.gaussian(0.0, self.0);
        }
    }
    struct Near(f64);
    impl MeasurementModel<f64> for Near {
        type Cues = ();
        fn log_likelihood(&self, x: &f64, _: &()) -> f64 {
            -0.5 * (x - self.0) * (x - self.0) / 0.04
        }
    }

    const NAMES: [&str; 6] = [
        "predict 1",
        "weigh 1",
        "estimate 1",
        "move 2",
        "weigh 2",
        "out",
    ];
    const STEPS: [&[Op]; 6] = [
        &[Op::Resample(0), Op::Inject(0), Op::Predict(0)],
        &[Op::Weigh(0)],
        &[Op::StageEstimate(0)],
        &[Op::Predict(1)],
        &[Op::Weigh(1)],
        &[Op::StageEstimate(1), Op::Resample(1), Op::Estimate],
    ];
    static SCHEDULE: Schedule = Schedule::new(&NAMES, &STEPS, FirstFrame::WeighFirst);

    impl Toy {
        fn new() -> Self {
            let config = |injection| FilterConfig {
                policy: ResamplePolicy::EssBelow(0.5),
                injection,
                ..FilterConfig::default()
            };
            Self {
                filters: [
                    ParticleFilter::new(50, config(Injection::Count(5)), 1, &Uniform).unwrap(),
                    ParticleFilter::new(40, config(Injection::None), 2, &Uniform).unwrap(),
                ],
                stepper: Stepper::new(),
                truth: [1.0, -2.0],
                stage1: 0.0,
                log: Vec::new(),
            }
        }
        fn begin(&mut self, frame: u32) -> Result<()> {
            if frame == 99 {
                return Err(Error::State("a bad frame".into()));
            }
            self.truth[0] += 0.1;
            self.stepper.begin(StageTimes::default());
            Ok(())
        }
    }

    impl Scheduled for Toy {
        type State = f64;
        type Estimate = [f64; 2];
        fn schedule(&self) -> &'static Schedule {
            &SCHEDULE
        }
        fn stepper(&self) -> &Stepper {
            &self.stepper
        }
        fn stepper_mut(&mut self) -> &mut Stepper {
            &mut self.stepper
        }
        fn filter_mut(&mut self, stage: usize) -> Option<&mut ParticleFilter<f64>> {
            self.filters.get_mut(stage)
        }
        fn resample(&mut self, stage: usize) {
            self.log.push((Op::Resample(stage), Pass::Frame));
            self.filters[stage].resample();
        }
        fn start_rounds(&self) -> usize {
            2
        }
        fn inject(&mut self, stage: usize) {
            self.log.push((Op::Inject(stage), Pass::Frame));
            self.filters[stage].inject(&Uniform);
        }
        fn predict(&mut self, stage: usize, pass: Pass) {
            self.log.push((Op::Predict(stage), pass));
            let sd = match pass {
                Pass::Frame => 0.2,
                Pass::StartRound { round, rounds } => 0.2 * (1 + rounds - round) as f64,
            };
            self.filters[stage].predict(&Walk(sd));
        }
        fn weigh(&mut self, stage: usize) {
            self.log.push((Op::Weigh(stage), Pass::Frame));
            let target = self.truth[stage] + if stage == 1 { self.stage1 } else { 0.0 };
            self.filters[stage].weigh(&Near(target), &());
        }
        fn stage_estimate(&mut self, stage: usize) {
            self.log.push((Op::StageEstimate(stage), Pass::Frame));
            let f = &self.filters[stage];
            let [m] = crate::filter::weighted_mean(f.states(), f.weights(), |&x| [x]);
            if stage == 0 {
                self.stage1 = m;
            }
        }
        fn estimate(&mut self) -> [f64; 2] {
            self.log.push((Op::Estimate, Pass::Frame));
            let f = &self.filters[1];
            let [m] = crate::filter::weighted_mean(f.states(), f.weights(), |&x| [x]);
            [self.stage1, m]
        }
    }

    /// The whole state a frame leaves behind.
    fn snapshot(t: &Toy) -> Vec<Vec<f64>> {
        t.filters
            .iter()
            .flat_map(|f| [f.states().to_vec(), f.weights().to_vec()])
            .collect()
    }

    #[test]
    fn a_whole_frame_is_begin_and_every_advance() {
        let (mut whole, mut stepped) = (Toy::new(), Toy::new());
        assert!(stepped.advance_step().is_none(), "no frame in progress");
        assert_eq!(stepped.stepper().next_step(), None);
        for frame in 0..4 {
            let expected = whole.step_frame(|t| t.begin(frame)).unwrap();
            stepped.begin(frame).unwrap();
            let mut out = Vec::new();
            for i in 0..SCHEDULE.len() {
                assert_eq!(stepped.stepper().next_step(), Some(i));
                out.push(stepped.advance_step());
            }
            assert!(out[..out.len() - 1].iter().all(Option::is_none));
            assert_eq!(out.last(), Some(&Some(expected)), "frame {frame}");
            assert_eq!(stepped.stepper().next_step(), None);
            assert_eq!(snapshot(&stepped), snapshot(&whole), "frame {frame}");
            assert_eq!(stepped.log, whole.log, "frame {frame}");
        }
        // A cue error starts no frame and changes nothing.
        let before = snapshot(&whole);
        assert!(whole.step_frame(|t| t.begin(99)).is_err());
        assert_eq!(snapshot(&whole), before);
        assert!(!whole.stepper().in_progress());
    }

    #[test]
    fn a_first_frame_weighs_each_stage_before_moving_it_then_runs_the_start_rounds() {
        use Op::*;
        let mut t = Toy::new();
        t.step_frame(|t| t.begin(0)).unwrap();
        let round = |k, round| {
            [
                (Resample(k), Pass::Frame),
                (Predict(k), Pass::StartRound { round, rounds: 2 }),
                (Weigh(k), Pass::Frame),
            ]
        };
        let mut first = vec![(Weigh(0), Pass::Frame)];
        first.extend(round(0, 1));
        first.extend(round(0, 2));
        first.push((StageEstimate(0), Pass::Frame));
        first.push((Weigh(1), Pass::Frame));
        first.extend(round(1, 1));
        first.extend(round(1, 2));
        first.extend([
            (StageEstimate(1), Pass::Frame),
            (Resample(1), Pass::Frame),
            (Estimate, Pass::Frame),
        ]);
        assert_eq!(t.log, first);
        // Any other frame runs every operation once, as named.
        t.log.clear();
        let e = t.step_frame(|t| t.begin(1)).unwrap();
        let any: Vec<(Op, Pass)> = STEPS
            .iter()
            .flat_map(|ops| ops.iter().map(|&op| (op, Pass::Frame)))
            .collect();
        assert_eq!(t.log, any);
        assert!(
            (e[0] - 1.2).abs() < 0.2 && (e[1] - (e[0] - 2.0)).abs() < 0.2,
            "{e:?}"
        );
        // A restart makes the next frame a first frame again; one in progress goes on.
        t.stepper_mut().begin(StageTimes::default());
        t.stepper_mut().restart();
        assert!(!t.stepper().is_first_frame());
        t.log.clear();
        while t.advance_step().is_none() {}
        assert_eq!(t.log, any);
        t.log.clear();
        t.step_frame(|t| t.begin(2)).unwrap();
        assert_eq!(t.log.len(), first.len());
    }

    #[test]
    fn each_operation_is_timed_into_its_bucket_and_an_abandoned_frame_keeps_no_times() {
        let mut t = Toy::new();
        t.step_frame(|t| t.begin(0)).unwrap();
        let s = t.stepper().times();
        assert!(s.resample > 0.0 && s.predict > 0.0 && s.weigh > 0.0 && s.estimate > 0.0);
        assert_eq!((s.preprocess, s.disparity), (0.0, 0.0));
        t.begin(1).unwrap();
        t.advance_step();
        t.stepper_mut().abandon();
        assert!(t.advance_step().is_none() && !t.stepper().in_progress());
        assert_eq!(t.stepper().times(), s, "the last finished frame's");
    }

    #[test]
    fn the_resampling_decisions_of_the_last_call_are_kept_in_order() {
        use crate::filter::ResampleRule;
        let mut t = Toy::new();
        t.step_frame(|t| t.begin(0)).unwrap();
        // First frame: the start rounds' resamplings of stage 1, of stage 2, then stage 2's
        // own (stage 1's own is skipped: nothing weighed yet).
        let rules: Vec<(ResampleRule, usize)> = t
            .stepper()
            .resamplings()
            .iter()
            .map(|d| (d.rule, d.particles))
            .collect();
        let (inject, ess) = ((ResampleRule::Injection, 50), (ResampleRule::EssBelow, 40));
        assert_eq!(rules, [inject, inject, ess, ess, ess]);
        t.begin(1).unwrap();
        assert!(
            t.stepper().resamplings().is_empty(),
            "begin resamples nothing"
        );
        let mut per_step = Vec::new();
        while {
            let done = t.advance_step().is_some();
            per_step.push(t.stepper().resamplings().to_vec());
            !done
        } {}
        let counts: Vec<usize> = per_step.iter().map(Vec::len).collect();
        assert_eq!(counts, [1, 0, 0, 0, 0, 1]);
        assert_eq!(per_step[0][0].rule, ResampleRule::Injection);
        let d = per_step[5][0];
        assert_eq!(d.threshold, Some(20.0));
        assert_eq!(d.resampled, d.ess < 20.0);
        // The same frame whole gives the same decisions, all of them.
        let mut whole = Toy::new();
        whole.step_frame(|t| t.begin(0)).unwrap();
        whole.step_frame(|t| t.begin(1)).unwrap();
        assert_eq!(whole.stepper().resamplings(), [per_step[0][0], d]);
        whole.stepper_mut().abandon();
        assert!(whole.stepper().resamplings().is_empty());
    }
}
