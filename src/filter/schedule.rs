//! A filter schedule: one frame of a tracker as named steps, each a short list of operations
//! on the tracker's filters. The tracker supplies the models (what "predict stage 1" moves,
//! what "weigh stage 2" reads); the schedule says in which order the operations run, and the
//! [`Stepper`](super::Stepper) runs them, one step per `advance` or all at once.
//!
//! The operations ([`Op`]), on stage k (a filter of a cascade, or a partition of a
//! partitioned filter; the tracker says which):
//!
//! | op | what it does | timed as |
//! |---|---|---|
//! | `Resample(k)` | resample by the filter's policy; with injection on, keep N - k' ([`ParticleFilter::resample`](super::ParticleFilter::resample)) | resample |
//! | `Inject(k)` | draw the k' initialisation particles into the front of the set | predict |
//! | `Predict(k)` | move stage k by its motion model (and a tracker's data-driven proposal) | predict |
//! | `Weigh(k)` | weigh by stage k's likelihood and normalise | weigh |
//! | `ResampleBetween(k)` | resample unconditionally before partition k (Liu IV-D) | resample |
//! | `StageEstimate(k)` | stage k's estimate, which later stages condition on (Lee Algorithm 2) | estimate |
//! | `Estimate` | the frame's estimate: always the last operation, once | estimate |
//!
//! The first frame ([`FirstFrame`]): a schedule either runs it like any other (Liu: the
//! initial set is resampled, injected and moved like last frame's), or
//! [`FirstFrame::WeighFirst`]: the particles come from the initial distribution, so each stage
//! is weighed before anything moves it (its `Resample`, `Inject` and `Predict` before its first
//! `Weigh` are skipped), and each `Weigh(k)` is followed by the tracker's start-up rounds
//! ([`Scheduled::start_rounds`](super::Scheduled::start_rounds)): `Resample(k)`,
//! `Predict(k)` (told it is round r of R, [`Pass::StartRound`]), `Weigh(k)` on the same cues.
//!
//! The four papers' schedules (the step names the demo shows are the trackers'):
//!
//! ```text
//! adachi-mmpf     [Resample 0] [Predict 0] [Weigh 0] [Estimate]                     weigh first, start rounds
//! danescu-*       [Resample 0, Inject 0] [Predict 0] [Weigh 0] [Estimate]           weigh first   (Sec. III)
//! liu-ppf(-nok.)  [Resample 0, Inject 0] [Predict 0] [Weigh 0] [ResampleBetween 1]
//!                 [Predict 1] [Weigh 1] [Estimate]                                  (Sec. IV-D to IV-F)
//! lee-cpf         [Predict 0] [Weigh 0] [StageEstimate 0, Resample 0]                (Algorithm 1, s = 1)
//!                 [Predict 1] [Weigh 1] [StageEstimate 1, Resample 1]                (s = 2, Algorithm 2)
//!                 [Estimate]                                        weigh first, start rounds
//! ```

/// One operation of a frame on stage k (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// Resample stage k's filter by its policy.
    Resample(usize),
    /// Draw stage k's initialisation particles.
    Inject(usize),
    /// Move stage k.
    Predict(usize),
    /// Weigh by stage k's likelihood.
    Weigh(usize),
    /// Resample unconditionally before partition k.
    ResampleBetween(usize),
    /// Stage k's estimate, for the stages after it.
    StageEstimate(usize),
    /// The frame's estimate (the last operation).
    Estimate,
}

impl Op {
    /// The stage the operation works on (`None` for [`Op::Estimate`]).
    pub const fn stage(self) -> Option<usize> {
        match self {
            Op::Resample(k)
            | Op::Inject(k)
            | Op::Predict(k)
            | Op::Weigh(k)
            | Op::ResampleBetween(k)
            | Op::StageEstimate(k) => Some(k),
            Op::Estimate => None,
        }
    }

    /// Whether a [`FirstFrame::WeighFirst`] schedule skips the operation on a first frame
    /// while its stage has not been weighed yet.
    pub const fn moves_particles(self) -> bool {
        matches!(self, Op::Resample(_) | Op::Inject(_) | Op::Predict(_))
    }
}

/// What a first frame (after construction or a reset) runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FirstFrame {
    /// Every operation, like any other frame.
    AsAnyOther,
    /// Each stage weighed before it moves, then the start-up rounds (see the module docs).
    WeighFirst,
}

/// Which pass of an operation is running.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// The operation as the schedule names it.
    Frame,
    /// Start-up round `round` of `rounds` (1-based) on a first frame.
    StartRound {
        /// This round, 1..=rounds.
        round: usize,
        /// The number of rounds.
        rounds: usize,
    },
}

/// A tracker's frame as named steps of operations.
#[derive(Debug, Clone, Copy)]
pub struct Schedule {
    names: &'static [&'static str],
    steps: &'static [&'static [Op]],
    first_frame: FirstFrame,
}

impl Schedule {
    /// The schedule of `steps`, step i named `names[i]`. Checked when it is built (a
    /// schedule is a constant, so at compile time): one name per step, no empty step, and
    /// [`Op::Estimate`] exactly once, as the last operation of the last step.
    pub const fn new(
        names: &'static [&'static str],
        steps: &'static [&'static [Op]],
        first_frame: FirstFrame,
    ) -> Self {
        assert!(names.len() == steps.len(), "one name per step");
        assert!(!steps.is_empty(), "a schedule has steps");
        let mut i = 0;
        while i < steps.len() {
            let ops = steps[i];
            assert!(!ops.is_empty(), "a step runs at least one operation");
            let mut j = 0;
            while j < ops.len() {
                let last = i + 1 == steps.len() && j + 1 == ops.len();
                assert!(
                    matches!(ops[j], Op::Estimate) == last,
                    "Estimate is the last operation, and only there"
                );
                j += 1;
            }
            i += 1;
        }
        Self {
            names,
            steps,
            first_frame,
        }
    }

    /// The steps' names, in order.
    pub const fn names(&self) -> &'static [&'static str] {
        self.names
    }
    /// The operations of each step, in order.
    pub const fn steps(&self) -> &'static [&'static [Op]] {
        self.steps
    }
    /// Number of steps.
    pub const fn len(&self) -> usize {
        self.steps.len()
    }
    /// Always false (a schedule ends with its estimate).
    pub const fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }
    /// What a first frame runs.
    pub const fn first_frame(&self) -> FirstFrame {
        self.first_frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_know_their_stage_and_whether_they_move_particles() {
        assert_eq!(Op::Weigh(1).stage(), Some(1));
        assert_eq!(Op::Estimate.stage(), None);
        let moving: Vec<Op> = [
            Op::Resample(0),
            Op::Inject(0),
            Op::Predict(0),
            Op::Weigh(0),
            Op::ResampleBetween(1),
            Op::StageEstimate(0),
            Op::Estimate,
        ]
        .into_iter()
        .filter(|op| op.moves_particles())
        .collect();
        assert_eq!(moving, [Op::Resample(0), Op::Inject(0), Op::Predict(0)]);
        const S: Schedule = Schedule::new(
            &["move", "weigh", "estimate"],
            &[
                &[Op::Resample(0), Op::Predict(0)],
                &[Op::Weigh(0)],
                &[Op::Estimate],
            ],
            FirstFrame::AsAnyOther,
        );
        assert_eq!((S.len(), S.names()[1]), (3, "weigh"));
        assert_eq!(S.steps()[0], [Op::Resample(0), Op::Predict(0)]);
    }

    #[test]
    #[should_panic(expected = "Estimate is the last operation")]
    fn a_schedule_without_its_estimate_last_is_refused() {
        // (At compile time for a constant; at run time here.)
        let _ = Schedule::new(
            &["estimate", "weigh"],
            &[&[Op::Estimate], &[Op::Weigh(0)]],
            FirstFrame::AsAnyOther,
        );
    }
}
