//! What the filter decided at each resampling, as it decided it: the ESS it tested, the
//! threshold, the rule, and whether it resampled. For the pages that teach the filter ("skipped:
//! ESS 394 > 250"), so that they show the tracker's own decision instead of re-deriving it from
//! each paper's rules.
//!
//! [`ParticleFilter::resample`](super::ParticleFilter::resample) and
//! [`ParticleFilter::resample_between_stages`](super::ParticleFilter::resample_between_stages)
//! note every decision here; [`recorded`] runs a closure (e.g. a tracker's `step` or `advance`)
//! and returns the decisions made inside it, in order. Outside [`recorded`] nothing is kept.
//! The record is per thread and only observes: a filter decides and draws exactly the same with
//! or without it, so the runs stay bit-identical.
//!
//! Why a record beside the filter rather than a method of every tracker: the decision is the
//! core's, and each tracker composes one or more filters (Lee's cascade has two) in its own
//! schedule; the record sees every filter a call runs without each tracker re-exporting it.

use serde::Serialize;
use std::cell::RefCell;

/// The rule a resampling decision followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ResampleRule {
    /// [`ResamplePolicy::Always`](super::ResamplePolicy::Always): every time.
    Always,
    /// [`ResamplePolicy::EssBelow`](super::ResamplePolicy::EssBelow): when the ESS is below the
    /// threshold (Lee, Algorithm 1).
    EssBelow,
    /// [`ResamplePolicy::Never`](super::ResamplePolicy::Never).
    Never,
    /// Injection is on: every time, keeping N - k particles for the k fresh ones.
    Injection,
    /// Between the stages of partitioned sampling: every time (Liu Sec. IV-D).
    BetweenStages,
}

/// One resampling decision of a filter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ResampleDecision {
    /// The rule it followed.
    pub rule: ResampleRule,
    /// The effective sample size of the weights it decided on.
    pub ess: f64,
    /// The particle count N.
    pub particles: usize,
    /// The ESS below which it resamples (particles), for [`ResampleRule::EssBelow`].
    pub threshold: Option<f64>,
    /// Whether it resampled.
    pub resampled: bool,
}

thread_local! {
    /// The decisions of the [`recorded`] call in progress (`None`: none is).
    static LOG: RefCell<Option<Vec<ResampleDecision>>> = const { RefCell::new(None) };
}

/// Notes a decision when a [`recorded`] call is in progress.
pub(super) fn note(decision: ResampleDecision) {
    LOG.with(|log| {
        if let Some(list) = log.borrow_mut().as_mut() {
            list.push(decision);
        }
    });
}

/// Runs `f` and returns its result with every resampling decision made inside it, in order.
/// A call inside another keeps its own decisions (the outer call does not see them).
pub fn recorded<R>(f: impl FnOnce() -> R) -> (R, Vec<ResampleDecision>) {
    /// Puts the outer call's record back, also when `f` unwinds.
    struct Restore(Option<Vec<ResampleDecision>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let outer = self.0.take();
            LOG.with(|log| *log.borrow_mut() = outer);
        }
    }
    let outer = LOG.with(|log| log.borrow_mut().replace(Vec::new()));
    let restore = Restore(outer);
    let result = f();
    let mine = LOG.with(|log| log.borrow_mut().take()).unwrap_or_default();
    drop(restore);
    (result, mine)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{
        FilterConfig, InitialDistribution, Injection, ParticleFilter, ResamplePolicy, Rng,
    };

    struct Uniform;
    impl InitialDistribution<f64> for Uniform {
        fn sample(&self, rng: &mut Rng) -> f64 {
            rng.uniform()
        }
    }

    fn filter(policy: ResamplePolicy, injection: Injection) -> ParticleFilter<f64> {
        let config = FilterConfig {
            policy,
            injection,
            ..Default::default()
        };
        ParticleFilter::new(100, config, 3, &Uniform).unwrap()
    }

    /// One heavy particle and 99 light ones: ESS well below N/2.
    fn skew(pf: &mut ParticleFilter<f64>) {
        let ll: Vec<f64> = (0..100).map(|i| if i == 7 { 0.0 } else { -3.0 }).collect();
        pf.weigh_with(&ll).unwrap();
    }

    #[test]
    fn each_decision_is_recorded_with_the_ess_it_tested() {
        let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::None);
        let (skipped, log) = recorded(|| pf.resample());
        assert!(!skipped);
        assert_eq!(
            log,
            [ResampleDecision {
                rule: ResampleRule::EssBelow,
                ess: 100.0,
                particles: 100,
                threshold: Some(50.0),
                resampled: false,
            }]
        );
        skew(&mut pf);
        let ess = pf.ess();
        assert!(ess < 50.0, "ESS {ess}");
        let (done, log) = recorded(|| {
            let a = pf.resample();
            pf.resample_between_stages();
            a
        });
        assert!(done);
        assert_eq!(log.len(), 2);
        assert_eq!((log[0].ess, log[0].resampled), (ess, true));
        assert_eq!(log[1].rule, ResampleRule::BetweenStages);
        assert_eq!((log[1].ess, log[1].threshold), (100.0, None));

        let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::Count(10));
        let (_, log) = recorded(|| pf.resample());
        assert_eq!(log[0].rule, ResampleRule::Injection);
        assert!(log[0].resampled && log[0].threshold.is_none());
        let mut pf = filter(ResamplePolicy::Never, Injection::None);
        skew(&mut pf);
        let (_, log) = recorded(|| pf.resample());
        assert_eq!(
            (log[0].rule, log[0].resampled),
            (ResampleRule::Never, false)
        );
    }

    #[test]
    fn nothing_is_kept_outside_a_recorded_call_and_nested_calls_keep_their_own() {
        let mut pf = filter(ResamplePolicy::Always, Injection::None);
        pf.resample();
        let ((inner, ()), outer) = recorded(|| {
            pf.resample();
            let inner = recorded(|| {
                pf.resample();
                pf.resample();
            });
            pf.resample();
            (inner.1, inner.0)
        });
        assert_eq!(inner.len(), 2);
        assert_eq!(
            outer.len(),
            2,
            "the outer call sees its own two, not the inner ones"
        );
        assert!(outer
            .iter()
            .all(|d| d.rule == ResampleRule::Always && d.resampled));
        assert!(recorded(|| ()).1.is_empty());
    }

    #[test]
    fn recording_changes_nothing_the_filter_does() {
        let run = |record: bool| {
            let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::Count(5));
            for _ in 0..4 {
                skew(&mut pf);
                if record {
                    recorded(|| pf.resample());
                } else {
                    pf.resample();
                }
                pf.inject(&Uniform);
            }
            pf.states().to_vec()
        };
        assert_eq!(run(true), run(false));
    }
}
