//! What the filter decided at each resampling, as it decided it: the ESS it tested, the
//! threshold, the rule, and whether it resampled. For the pages that teach the filter ("skipped:
//! ESS 394 > 250"), so that they show the tracker's own decision instead of re-deriving it from
//! each paper's rules.
//!
//! [`ParticleFilter::resample`](super::ParticleFilter::resample) and
//! [`ParticleFilter::resample_between_stages`](super::ParticleFilter::resample_between_stages)
//! keep their decision until [`ParticleFilter::take_decision`](super::ParticleFilter::take_decision);
//! the [`Stepper`](super::Stepper) takes it after every resampling operation of a tracker's
//! schedule and keeps the decisions of the last `step` or `advance` in order
//! ([`Stepper::resamplings`](super::Stepper::resamplings), `Tracker::resamplings`). The record
//! only observes: a filter decides and draws exactly the same whether or not it is read.
//!
//! Why the schedule owns the record: the decision is the core's, and the schedule is where the
//! core knows which filter resamples when (Lee's cascade has two filters, a first frame has its
//! start-up rounds), so no tracker re-exports its filters' decisions.

use serde::Serialize;

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

    /// `resample` then the decision it left.
    fn decide(pf: &mut ParticleFilter<f64>) -> (bool, Option<ResampleDecision>) {
        let resampled = pf.resample();
        (resampled, pf.take_decision())
    }

    #[test]
    fn each_decision_is_kept_with_the_ess_it_tested_and_taken_once() {
        let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::None);
        assert_eq!(pf.take_decision(), None, "nothing decided yet");
        let (skipped, decision) = decide(&mut pf);
        assert!(!skipped);
        assert_eq!(
            decision,
            Some(ResampleDecision {
                rule: ResampleRule::EssBelow,
                ess: 100.0,
                particles: 100,
                threshold: Some(50.0),
                resampled: false,
            })
        );
        assert_eq!(pf.take_decision(), None, "taken once");
        skew(&mut pf);
        let ess = pf.ess();
        assert!(ess < 50.0, "ESS {ess}");
        let (done, decision) = decide(&mut pf);
        assert!(done);
        let d = decision.unwrap();
        assert_eq!((d.ess, d.resampled), (ess, true));
        pf.resample_between_stages();
        let d = pf.take_decision().unwrap();
        assert_eq!(d.rule, ResampleRule::BetweenStages);
        assert_eq!((d.ess, d.threshold), (100.0, None));

        let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::Count(10));
        let d = decide(&mut pf).1.unwrap();
        assert_eq!(d.rule, ResampleRule::Injection);
        assert!(d.resampled && d.threshold.is_none());
        let mut pf = filter(ResamplePolicy::Never, Injection::None);
        skew(&mut pf);
        let d = decide(&mut pf).1.unwrap();
        assert_eq!((d.rule, d.resampled), (ResampleRule::Never, false));
    }

    #[test]
    fn reading_the_decisions_changes_nothing_the_filter_does() {
        let run = |read: bool| {
            let mut pf = filter(ResamplePolicy::EssBelow(0.5), Injection::Count(5));
            for _ in 0..4 {
                skew(&mut pf);
                pf.resample();
                if read {
                    assert!(pf.take_decision().is_some());
                }
                pf.inject(&Uniform);
            }
            pf.states().to_vec()
        };
        assert_eq!(run(true), run(false));
    }
}
