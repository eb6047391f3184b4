//! Partitioned sampling (MacCormick & Isard 2000): a state space split into sub-spaces
//! estimated in sequence, with weighted resampling between the stages.
//!
//! For stages k = 1..K of a frame: move only sub-space k of every particle, weigh with stage
//! k's likelihood (which depends on the sub-spaces estimated so far), normalise, and resample
//! before the next stage, so that stage k + 1 starts from particles that are good in
//! sub-spaces 1..k. The final weights are those of the last stage.
//!
//! - Liu et al. 2013 (Sec. IV): K = 2 per boundary group: the linear part (rho, theta) of the
//!   linear-parabolic model, weighted by the line kernel density, then the parabolic part d,
//!   weighted by the parabolic kernel density.
//! - Lee et al. 2015 (Algorithms 1-2) run a cascade: stage 1 estimates [psi, y0, w, w'] with
//!   its own particles and ESS-triggered resampling, stage 2 estimates [c, delta] given stage
//!   1's estimate. That is two [`super::ParticleFilter`]s over different state types, the
//!   second fed the first's estimate, rather than one partitioned set; both use this core.

use super::particle_filter::ParticleFilter;
use super::rng::Rng;

/// A model split into stages over sub-spaces of the state.
pub trait PartitionedModel<S> {
    /// What the likelihoods read from the frame.
    type Cues: ?Sized;
    /// Number of stages K.
    fn stages(&self) -> usize;
    /// Moves sub-space `stage` of `state`.
    fn propagate(&self, stage: usize, state: &mut S, rng: &mut Rng);
    /// ln p(z | x) as seen by stage `stage`.
    fn log_likelihood(&self, stage: usize, state: &S, cues: &Self::Cues) -> f64;
}

/// Adapts one stage of a partitioned model to the single-stage traits.
struct Stage<'a, M> {
    model: &'a M,
    stage: usize,
}

impl<S, M: PartitionedModel<S>> super::MotionModel<S> for Stage<'_, M> {
    fn propagate(&self, state: &mut S, rng: &mut Rng) {
        self.model.propagate(self.stage, state, rng);
    }
}

impl<S, M: PartitionedModel<S>> super::MeasurementModel<S> for Stage<'_, M> {
    type Cues = M::Cues;
    fn log_likelihood(&self, state: &S, cues: &M::Cues) -> f64 {
        self.model.log_likelihood(self.stage, state, cues)
    }
}

impl<S: Clone> ParticleFilter<S> {
    /// One frame of partitioned sampling: resample and inject as in
    /// [`ParticleFilter::step`], then for every stage propagate its sub-space and weigh,
    /// resampling (by the filter's scheme, unconditionally) between stages.
    pub fn partitioned_step<M: PartitionedModel<S>>(
        &mut self,
        model: &M,
        cues: &M::Cues,
        init: &impl super::InitialDistribution<S>,
    ) {
        self.resample();
        self.inject(init);
        for stage in 0..model.stages() {
            if stage > 0 {
                self.resample_between_stages();
            }
            self.partitioned_predict(model, stage);
            self.partitioned_weigh(model, stage, cues);
        }
    }

    /// Moves sub-space `stage` of every particle (one step of [`ParticleFilter::partitioned_step`],
    /// for trackers that run the stages one at a time).
    pub fn partitioned_predict<M: PartitionedModel<S>>(&mut self, model: &M, stage: usize) {
        self.predict(&Stage { model, stage });
    }

    /// Weighs every particle by stage `stage`'s likelihood alone: the weights carried in are
    /// replaced, since resampling has absorbed them.
    pub fn partitioned_weigh<M: PartitionedModel<S>>(
        &mut self,
        model: &M,
        stage: usize,
        cues: &M::Cues,
    ) {
        self.clear_log_weights();
        self.weigh(&Stage { model, stage }, cues);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{FilterConfig, InitialDistribution, Injection, ResamplePolicy, Resampler};

    /// A 2-D state whose two coordinates are observed by separate, sharp likelihoods.
    struct TwoStage {
        truth: [f64; 2],
        sd: f64,
        step: f64,
    }

    impl PartitionedModel<[f64; 2]> for TwoStage {
        type Cues = ();
        fn stages(&self) -> usize {
            2
        }
        fn propagate(&self, stage: usize, x: &mut [f64; 2], rng: &mut Rng) {
            x[stage] += rng.gaussian(0.0, self.step);
        }
        fn log_likelihood(&self, stage: usize, x: &[f64; 2], _: &()) -> f64 {
            // Stage 1 sees x0 only; stage 2 sees both (as Liu's parabolic stage sees the line).
            let e0 = (x[0] - self.truth[0]) / self.sd;
            let e1 = (x[1] - self.truth[1]) / self.sd;
            if stage == 0 {
                -0.5 * e0 * e0
            } else {
                -0.5 * (e0 * e0 + e1 * e1)
            }
        }
    }

    struct Wide;
    impl InitialDistribution<[f64; 2]> for Wide {
        fn sample(&self, rng: &mut Rng) -> [f64; 2] {
            [rng.gaussian(0.0, 5.0), rng.gaussian(0.0, 5.0)]
        }
    }

    #[test]
    fn each_stage_moves_only_its_sub_space_and_the_estimate_converges() {
        let model = TwoStage {
            truth: [3.0, -2.0],
            sd: 0.2,
            step: 0.3,
        };
        let config = FilterConfig {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::Always,
            injection: Injection::None,
        };
        let mut pf = ParticleFilter::new(500, config, 9, &Wide).unwrap();
        // Stage propagation touches only its coordinate.
        let mut x = [1.0, 1.0];
        model.propagate(0, &mut x, pf.rng_mut());
        assert_eq!(x[1], 1.0);
        for _ in 0..15 {
            pf.partitioned_step(&model, &(), &Wide);
        }
        let m = crate::filter::weighted_mean(pf.states(), pf.weights(), |s| *s);
        assert!(
            (m[0] - 3.0).abs() < 0.1 && (m[1] + 2.0).abs() < 0.1,
            "{m:?}"
        );
    }

    #[test]
    fn partitioning_beats_joint_sampling_on_a_sharp_separable_likelihood() {
        // The same particle budget; the joint filter moves both coordinates at once and
        // weighs with the full likelihood. Mean error over 10 seeds after 8 frames.
        let model = TwoStage {
            truth: [3.0, -2.0],
            sd: 0.05,
            step: 0.3,
        };
        struct Joint<'a>(&'a TwoStage);
        impl crate::filter::MotionModel<[f64; 2]> for Joint<'_> {
            fn propagate(&self, x: &mut [f64; 2], rng: &mut Rng) {
                x[0] += rng.gaussian(0.0, self.0.step);
                x[1] += rng.gaussian(0.0, self.0.step);
            }
        }
        impl crate::filter::MeasurementModel<[f64; 2]> for Joint<'_> {
            type Cues = ();
            fn log_likelihood(&self, x: &[f64; 2], c: &()) -> f64 {
                self.0.log_likelihood(1, x, c)
            }
        }
        let (mut err_p, mut err_j) = (0.0, 0.0);
        for seed in 0..10 {
            let mut p = ParticleFilter::new(200, FilterConfig::default(), seed, &Wide).unwrap();
            let mut j = ParticleFilter::new(200, FilterConfig::default(), seed, &Wide).unwrap();
            for _ in 0..8 {
                p.partitioned_step(&model, &(), &Wide);
                j.step(&Joint(&model), &Joint(&model), &(), &Wide);
            }
            let e = |pf: &ParticleFilter<[f64; 2]>| {
                let m = crate::filter::weighted_mean(pf.states(), pf.weights(), |s| *s);
                ((m[0] - 3.0).powi(2) + (m[1] + 2.0).powi(2)).sqrt()
            };
            err_p += e(&p);
            err_j += e(&j);
        }
        assert!(err_p < err_j, "partitioned {err_p} vs joint {err_j}");
    }
}
