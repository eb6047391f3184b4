//! The particle filter: a set of weighted particles and the steps that move it through a
//! frame.
//!
//! One frame of [`ParticleFilter::step`], in order (Danescu III; Liu IV-D; the standard SIR
//! filter when injection is off):
//!
//! 1. **resample** from the previous weights (when the policy says so, or always when
//!    injection is on), keeping N - k particles;
//! 2. **inject** k initialisation particles drawn from the initial distribution into the
//!    front of the set (indices 0..k), so a lost track can be recovered;
//! 3. **predict**: every particle moves by the motion model;
//! 4. **weigh**: l_i += ln p(z | x_i), then normalisation (log-sum-exp) and the ESS.
//!
//! Each step is also a public method, so a teaching page can call them one at a time and read
//! the cloud and weights in between. All buffers are allocated at construction; a step
//! allocates nothing (for states without heap data).

use super::model::{InitialDistribution, MeasurementModel, MotionModel};
use super::resample::{ResamplePolicy, Resampler};
use super::resampling_log::{ResampleDecision, ResampleRule};
use super::rng::Rng;
use super::weights::{effective_sample_size, normalise};
use crate::error::{require_finite, Error, Result};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// How many initialisation particles to inject per frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Injection {
    /// None.
    None,
    /// This many.
    Count(usize),
    /// This fraction of N (rounded down).
    Fraction(f64),
}

/// Filter settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilterConfig {
    /// Resampling scheme.
    pub resampler: Resampler,
    /// When to resample (ignored while injection is on: then every frame).
    pub policy: ResamplePolicy,
    /// Initialisation particles per frame.
    pub injection: Injection,
}

impl Default for FilterConfig {
    fn default() -> Self {
        Self {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::Always,
            injection: Injection::None,
        }
    }
}

/// Largest accepted particle count.
pub const MAX_PARTICLES: usize = 1 << 20;

/// A weighted particle set with its generator and scratch buffers.
#[derive(Debug, Clone)]
pub struct ParticleFilter<S> {
    states: Vec<S>,
    scratch: Vec<S>,
    log_weights: Vec<f64>,
    weights: Vec<f64>,
    ancestors: Vec<usize>,
    rng: Rng,
    config: FilterConfig,
    injected_count: usize,
    injected: usize,
    ess: f64,
    log_total: f64,
    degenerate: bool,
    /// The last resampling decision, until [`ParticleFilter::take_decision`].
    decision: Option<ResampleDecision>,
}

impl<S: Clone> ParticleFilter<S> {
    /// N particles drawn from `init`, equally weighted, with a generator seeded by `seed`.
    ///
    /// # Errors
    /// [`Error::Parameter`] for N = 0 or above [`MAX_PARTICLES`], an injection that is
    /// negative, NaN or not below N, or an ESS threshold outside [0, 1].
    pub fn new(
        n: usize,
        config: FilterConfig,
        seed: u64,
        init: &impl InitialDistribution<S>,
    ) -> Result<Self> {
        if n == 0 || n > MAX_PARTICLES {
            return Err(Error::parameter(
                "particles",
                n,
                &format!("must be between 1 and {MAX_PARTICLES}"),
            ));
        }
        let injected_count = match config.injection {
            Injection::None => 0,
            Injection::Count(k) => k,
            Injection::Fraction(f) => {
                require_finite("injection", f)?;
                if !(0.0..1.0).contains(&f) {
                    return Err(Error::parameter(
                        "injection",
                        Num(f),
                        "a fraction must be in [0, 1)",
                    ));
                }
                (f * n as f64).floor() as usize
            }
        };
        if injected_count >= n {
            return Err(Error::parameter(
                "injection",
                injected_count,
                "must be fewer than the particles",
            ));
        }
        if let ResamplePolicy::EssBelow(f) = config.policy {
            require_finite("ess_threshold", f)?;
            if !(0.0..=1.0).contains(&f) {
                return Err(Error::parameter(
                    "ess_threshold",
                    Num(f),
                    "must be a fraction in [0, 1]",
                ));
            }
        }
        let mut rng = Rng::new(seed);
        let states: Vec<S> = (0..n).map(|_| init.sample(&mut rng)).collect();
        let scratch = states.clone();
        Ok(Self {
            states,
            scratch,
            log_weights: vec![0.0; n],
            weights: vec![1.0 / n as f64; n],
            ancestors: Vec::with_capacity(n),
            rng,
            config,
            injected_count,
            injected: 0,
            ess: n as f64,
            log_total: 0.0,
            degenerate: false,
            decision: None,
        })
    }

    /// Redraws every particle from `init` with equal weights (the generator continues).
    pub fn reset(&mut self, init: &impl InitialDistribution<S>) {
        let n = self.len();
        for s in self.states.iter_mut() {
            *s = init.sample(&mut self.rng);
        }
        self.log_weights.fill(0.0);
        self.weights.fill(1.0 / n as f64);
        self.ess = n as f64;
        self.injected = 0;
    }

    /// Number of particles N.
    pub fn len(&self) -> usize {
        self.states.len()
    }
    /// Always false (a filter has at least one particle).
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }
    /// The particles.
    pub fn states(&self) -> &[S] {
        &self.states
    }
    /// The particles, mutable (e.g. for a tracker's own constraints).
    pub fn states_mut(&mut self) -> &mut [S] {
        &mut self.states
    }
    /// Normalised weights (after the last weigh or resample).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// Unnormalised log-weights.
    pub fn log_weights(&self) -> &[f64] {
        &self.log_weights
    }
    /// Effective sample size of the current weights.
    pub fn ess(&self) -> f64 {
        self.ess
    }
    /// ln of the total unnormalised weight at the last weigh (the frame's log evidence,
    /// up to the weights carried over).
    pub fn log_total(&self) -> f64 {
        self.log_total
    }
    /// True when the last weigh gave every particle zero likelihood (weights set uniform).
    pub fn degenerate(&self) -> bool {
        self.degenerate
    }
    /// How many particles at the front of the set are this frame's initialisation particles
    /// (Danescu eq. 15 leaves them out of the estimate).
    pub fn injected(&self) -> usize {
        self.injected
    }
    /// The decision of the last [`ParticleFilter::resample`] or
    /// [`ParticleFilter::resample_between_stages`], once (`None` until the next one): the
    /// [`Stepper`](super::Stepper) takes it after each resampling operation of a schedule.
    pub fn take_decision(&mut self) -> Option<ResampleDecision> {
        self.decision.take()
    }
    /// The settings.
    pub fn config(&self) -> &FilterConfig {
        &self.config
    }
    /// The filter's generator.
    pub fn rng_mut(&mut self) -> &mut Rng {
        &mut self.rng
    }

    /// Moves every particle by `motion`.
    pub fn predict(&mut self, motion: &impl MotionModel<S>) {
        for s in self.states.iter_mut() {
            motion.propagate(s, &mut self.rng);
        }
    }

    /// Multiplies the weights by the likelihoods of `cues` and normalises.
    pub fn weigh<M: MeasurementModel<S>>(&mut self, measurement: &M, cues: &M::Cues) {
        for (l, s) in self.log_weights.iter_mut().zip(&self.states) {
            *l += measurement.log_likelihood(s, cues);
        }
        self.normalise();
    }

    /// Adds precomputed log-likelihoods (one per particle) to the weights and normalises.
    ///
    /// # Errors
    /// [`Error::BufferSize`] when the slice does not have one value per particle.
    pub fn weigh_with(&mut self, log_likelihoods: &[f64]) -> Result<()> {
        if log_likelihoods.len() != self.len() {
            return Err(Error::BufferSize {
                what: format!("log-likelihoods for {} particles", self.len()),
                expected: self.len(),
                actual: log_likelihoods.len(),
            });
        }
        for (l, &ll) in self.log_weights.iter_mut().zip(log_likelihoods) {
            *l += ll;
        }
        self.normalise();
        Ok(())
    }

    fn normalise(&mut self) {
        let r = normalise(&self.log_weights, &mut self.weights);
        self.log_total = r.log_total;
        self.degenerate = r.degenerate;
        // Keep log-weights bounded: store them relative to their total.
        for (l, &w) in self.log_weights.iter_mut().zip(&self.weights) {
            *l = if w > 0.0 {
                crate::math::ln(w)
            } else {
                f64::NEG_INFINITY
            };
        }
        self.ess = effective_sample_size(&self.weights);
    }

    /// Resets the log-weights to equal (the normalised weights keep their values until the
    /// next weigh).
    pub(super) fn clear_log_weights(&mut self) {
        self.log_weights.fill(0.0);
    }

    /// Resamples all N particles unconditionally (between partitioned stages): afterwards the
    /// weights are equal and no particle counts as injected.
    pub fn resample_between_stages(&mut self) {
        let n = self.len();
        self.decision = Some(ResampleDecision {
            rule: ResampleRule::BetweenStages,
            ess: self.ess,
            particles: n,
            threshold: None,
            resampled: true,
        });
        self.config
            .resampler
            .resample(&self.weights, n, &mut self.rng, &mut self.ancestors);
        self.scratch.clear();
        for &a in &self.ancestors {
            self.scratch.push(self.states[a].clone());
        }
        std::mem::swap(&mut self.states, &mut self.scratch);
        self.log_weights.fill(0.0);
        self.weights.fill(1.0 / n as f64);
        self.ess = n as f64;
        // Initialisation particles are now mixed into the set.
        self.injected = 0;
    }

    /// Resamples by the policy (always when injection is on); returns whether it did.
    /// Keeps N - k particles and leaves the first k slots for [`ParticleFilter::inject`].
    pub fn resample(&mut self) -> bool {
        let n = self.len();
        let k = self.injected_count;
        let resampled = k > 0 || self.config.policy.should_resample(self.ess, n);
        let (rule, threshold) = match (k, self.config.policy) {
            (1.., _) => (ResampleRule::Injection, None),
            (0, ResamplePolicy::Always) => (ResampleRule::Always, None),
            (0, ResamplePolicy::EssBelow(f)) => (ResampleRule::EssBelow, Some(f * n as f64)),
            (0, ResamplePolicy::Never) => (ResampleRule::Never, None),
        };
        self.decision = Some(ResampleDecision {
            rule,
            ess: self.ess,
            particles: n,
            threshold,
            resampled,
        });
        if !resampled {
            return false;
        }
        self.config
            .resampler
            .resample(&self.weights, n - k, &mut self.rng, &mut self.ancestors);
        self.scratch.clear();
        // The first k slots are placeholders (copies of the best particle) until injection.
        let best = super::estimate::map_index(&self.weights);
        for _ in 0..k {
            self.scratch.push(self.states[best].clone());
        }
        for &a in &self.ancestors {
            self.scratch.push(self.states[a].clone());
        }
        std::mem::swap(&mut self.states, &mut self.scratch);
        self.log_weights.fill(0.0);
        self.weights.fill(1.0 / n as f64);
        self.ess = n as f64;
        true
    }

    /// Replaces the first k particles by draws from `init` (k from the configured injection);
    /// they carry the average weight.
    pub fn inject(&mut self, init: &impl InitialDistribution<S>) {
        let k = self.injected_count;
        if k == 0 {
            self.injected = 0;
            return;
        }
        for s in self.states[..k].iter_mut() {
            *s = init.sample(&mut self.rng);
        }
        let mean = 1.0 / self.len() as f64;
        for (l, w) in self.log_weights[..k].iter_mut().zip(&mut self.weights[..k]) {
            *w = mean;
            *l = crate::math::ln(mean);
        }
        self.renormalise_replaced();
        self.injected = k;
    }

    /// Data-driven injection: replaces every k-th particle (k = round(1 / `share`), spread
    /// over the cloud so that no ancestor's run of copies loses more than its share) by
    /// `draw(old, rng)`, a draw from a proposal the caller builds from the frame (e.g. a
    /// bottom-up detection). The new particles carry the average weight; returns how many
    /// were replaced (0 for `share` <= 0 or an empty filter).
    pub fn replace_share(&mut self, share: f64, mut draw: impl FnMut(&S, &mut Rng) -> S) -> usize {
        let n = self.len();
        let positive = share > 0.0;
        if !positive || n == 0 {
            return 0;
        }
        let every = (1.0 / share.min(1.0)).round().max(1.0) as usize;
        let mean = 1.0 / n as f64;
        let mut count = 0;
        for i in (0..n).step_by(every) {
            self.states[i] = draw(&self.states[i], &mut self.rng);
            self.weights[i] = mean;
            count += 1;
        }
        self.renormalise_replaced();
        count
    }

    /// Weights back to a sum of 1 (and their logs and the ESS) after some particles were
    /// given a new weight.
    fn renormalise_replaced(&mut self) {
        let total: f64 = self.weights.iter().sum();
        for (l, w) in self.log_weights.iter_mut().zip(self.weights.iter_mut()) {
            *w /= total;
            *l = if *w > 0.0 {
                crate::math::ln(*w)
            } else {
                f64::NEG_INFINITY
            };
        }
        self.ess = effective_sample_size(&self.weights);
    }

    /// One frame: resample, inject, predict, weigh (see the module docs).
    pub fn step<M: MeasurementModel<S>>(
        &mut self,
        motion: &impl MotionModel<S>,
        measurement: &M,
        cues: &M::Cues,
        init: &impl InitialDistribution<S>,
    ) {
        self.resample();
        self.inject(init);
        self.predict(motion);
        self.weigh(measurement, cues);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{weighted_mean, InitialDistribution, MeasurementModel, MotionModel};

    /// x_t = a x_{t-1} + v, v ~ N(0, q);  y_t = x_t + w, w ~ N(0, r);  x_0 ~ N(0, p0).
    struct Linear {
        a: f64,
        q: f64,
        r: f64,
        p0: f64,
    }
    impl MotionModel<f64> for Linear {
        fn propagate(&self, x: &mut f64, rng: &mut Rng) {
            *x = self.a * *x + rng.gaussian(0.0, self.q.sqrt());
        }
    }
    impl MeasurementModel<f64> for Linear {
        type Cues = f64;
        fn log_likelihood(&self, x: &f64, y: &f64) -> f64 {
            -0.5 * (y - x) * (y - x) / self.r
        }
    }
    impl InitialDistribution<f64> for Linear {
        fn sample(&self, rng: &mut Rng) -> f64 {
            rng.gaussian(0.0, self.p0.sqrt())
        }
    }

    #[test]
    fn bootstrap_filter_tracks_the_exact_kalman_filter() {
        let m = Linear {
            a: 0.95,
            q: 0.5,
            r: 1.0,
            p0: 4.0,
        };
        // Simulated data.
        let mut sim = Rng::new(100);
        let mut x = sim.gaussian(0.0, 2.0);
        let ys: Vec<f64> = (0..100)
            .map(|_| {
                x = m.a * x + sim.gaussian(0.0, m.q.sqrt());
                x + sim.gaussian(0.0, 1.0)
            })
            .collect();
        let mut pf = ParticleFilter::new(2000, FilterConfig::default(), 1, &m).unwrap();
        let (mut mean, mut var) = (0.0, m.p0);
        let mut total = 0.0;
        for (t, y) in ys.iter().enumerate() {
            // Kalman: predict, update.
            let (pm, pv) = (m.a * mean, m.a * m.a * var + m.q);
            let k = pv / (pv + m.r);
            mean = pm + k * (y - pm);
            var = (1.0 - k) * pv;
            // Particle filter: the first frame has no resampling to do, the rest do.
            if t == 0 {
                pf.predict(&m);
                pf.weigh(&m, y);
            } else {
                pf.step(&m, &m, y, &m);
            }
            let [est] = weighted_mean(pf.states(), pf.weights(), |&s| [s]);
            total += (est - mean).abs() / var.sqrt();
        }
        // The Monte Carlo error of a weighted mean of ~N_eff particles is about
        // sqrt(var / N_eff) ~ 0.03 sqrt(var) at N = 2000; allow 0.1 on average.
        let mean_err = total / ys.len() as f64;
        assert!(mean_err < 0.1, "mean |PF - KF| = {mean_err} posterior sd");
    }

    #[test]
    fn separate_steps_equal_step_and_nothing_is_reallocated() {
        let m = Linear {
            a: 1.0,
            q: 0.1,
            r: 0.5,
            p0: 1.0,
        };
        let config = FilterConfig {
            injection: Injection::Count(10),
            ..Default::default()
        };
        let mut a = ParticleFilter::new(300, config, 5, &m).unwrap();
        let mut b = a.clone();
        let ptrs = (
            a.states.as_ptr(),
            a.scratch.as_ptr(),
            a.ancestors.capacity(),
        );
        for y in [0.3, 0.5, 0.1, -0.2] {
            a.step(&m, &m, &y, &m);
            b.resample();
            b.inject(&m);
            assert_eq!(b.injected(), 10);
            b.predict(&m);
            b.weigh(&m, &y);
        }
        assert_eq!(a.states(), b.states());
        assert_eq!(a.weights(), b.weights());
        // The two state buffers swap roles but neither is reallocated.
        let now = (a.states.as_ptr(), a.scratch.as_ptr());
        assert!(now == (ptrs.0, ptrs.1) || now == (ptrs.1, ptrs.0));
        assert_eq!(a.ancestors.capacity(), ptrs.2);
        assert!((a.weights().iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn ess_policy_and_bad_settings() {
        let m = Linear {
            a: 1.0,
            q: 0.1,
            r: 0.5,
            p0: 1.0,
        };
        let config = FilterConfig {
            policy: ResamplePolicy::EssBelow(0.5),
            ..Default::default()
        };
        let mut pf = ParticleFilter::new(100, config, 1, &m).unwrap();
        assert!(!pf.resample(), "uniform weights: ESS = N");
        pf.weigh_with(&[0.0; 100].map(|_| 0.0)).unwrap();
        let mut ll = [f64::NEG_INFINITY; 100];
        ll[3] = 0.0;
        pf.weigh_with(&ll).unwrap();
        assert_eq!(pf.ess(), 1.0);
        assert!(pf.resample());
        assert!(pf.states().iter().all(|s| *s == pf.states()[0]));
        assert!(pf.weigh_with(&[0.0; 3]).is_err());
        assert!(ParticleFilter::new(0, FilterConfig::default(), 1, &m).is_err());
        let nan = FilterConfig {
            injection: Injection::Fraction(f64::NAN),
            ..Default::default()
        };
        assert!(ParticleFilter::new(10, nan, 1, &m)
            .unwrap_err()
            .to_string()
            .contains("injection"));
        let all = FilterConfig {
            injection: Injection::Count(10),
            ..Default::default()
        };
        assert!(ParticleFilter::new(10, all, 1, &m).is_err());
        let bad = FilterConfig {
            policy: ResamplePolicy::EssBelow(1.5),
            ..Default::default()
        };
        assert!(ParticleFilter::new(10, bad, 1, &m).is_err());
    }

    /// A cloud stuck far from the data (every particle at 10, the data at 0, random walk too
    /// small to cross the gap) stays stuck; replacing a share by draws around a detection of
    /// the right answer re-locks it within a frame, and the replaced particles are spread over
    /// the cloud with the average weight.
    #[test]
    fn replacing_a_share_from_a_detection_relocks_a_stuck_cloud() {
        let m = Linear {
            a: 1.0,
            q: 1e-4,
            r: 0.01,
            p0: 1.0,
        };
        let config = FilterConfig {
            policy: ResamplePolicy::Always,
            ..Default::default()
        };
        let run = |share: f64| {
            let mut pf = ParticleFilter::new(200, config, 7, &m).unwrap();
            pf.states_mut().fill(10.0);
            let mut replaced = Vec::new();
            for _ in 0..3 {
                pf.resample();
                pf.predict(&m);
                replaced.push(pf.replace_share(share, |_, rng| rng.gaussian(0.0, 0.1)));
                let total: f64 = pf.weights().iter().sum();
                assert!((total - 1.0).abs() < 1e-12, "weights sum to {total}");
                pf.weigh(&m, &0.0);
            }
            (
                weighted_mean(pf.states(), pf.weights(), |x| [*x])[0],
                replaced,
            )
        };
        let (stuck, none) = run(0.0);
        assert!(
            stuck > 9.9 && none == [0, 0, 0],
            "no proposal: mean {stuck}"
        );
        let (relocked, count) = run(0.05);
        assert!(relocked.abs() < 0.1, "with the proposal: mean {relocked}");
        assert_eq!(count, [10, 10, 10], "every 20th of 200 particles");
        let mut pf = ParticleFilter::new(10, config, 7, &m).unwrap();
        let before = pf.states().to_vec();
        assert_eq!(pf.replace_share(f64::NAN, |_, _| 99.0), 0);
        assert_eq!(pf.states(), &before[..]);
        assert_eq!(pf.replace_share(0.5, |_, _| 99.0), 5);
        let at: Vec<usize> = (0..10).filter(|&i| pf.states()[i] == 99.0).collect();
        assert_eq!(at, [0, 2, 4, 6, 8], "spread over the cloud");
    }
}
