//! Multiple models (Adachi et al. eq. 1-2, Table 1): each particle carries a discrete model
//! index r besides its continuous state x. Prediction first switches the model by a Markov
//! chain, P(r_k = j | r_{k-1} = i) = pi_ij, then moves x with model j's motion; the weights
//! then give the model probabilities P(r = j | Z) = sum of the weights of particles in model j.

use super::model::MotionModel;
use super::rng::Rng;
use crate::error::{Error, Result};
use crate::num_text::Num;

/// A validated K x K row-stochastic transition matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct MarkovChain {
    k: usize,
    /// Row-major cumulative rows, for sampling.
    cumulative: Vec<f64>,
    matrix: Vec<f64>,
}

impl MarkovChain {
    /// A chain from its rows (row i: probabilities of moving from model i to each model).
    ///
    /// # Errors
    /// [`Error::Config`] for an empty or non-square matrix, a negative or non-finite entry, or
    /// a row that does not sum to 1 (within 1e-9).
    pub fn new(rows: &[Vec<f64>]) -> Result<Self> {
        let k = rows.len();
        if k == 0 || rows.iter().any(|r| r.len() != k) {
            return Err(Error::Config(format!(
                "a transition matrix must be square and non-empty ({k} rows)"
            )));
        }
        let mut matrix = Vec::with_capacity(k * k);
        let mut cumulative = Vec::with_capacity(k * k);
        for (i, row) in rows.iter().enumerate() {
            if row.iter().any(|p| !p.is_finite() || *p < 0.0) {
                return Err(Error::Config(format!(
                    "transition row {i} has a negative or non-finite entry"
                )));
            }
            let sum: f64 = row.iter().sum();
            if (sum - 1.0).abs() > 1e-9 {
                return Err(Error::Config(format!(
                    "transition row {i} sums to {}, not 1",
                    Num(sum)
                )));
            }
            let mut acc = 0.0;
            for &p in row {
                matrix.push(p);
                acc += p;
                cumulative.push(acc);
            }
        }
        Ok(Self {
            k,
            cumulative,
            matrix,
        })
    }

    /// Number of models K.
    pub fn models(&self) -> usize {
        self.k
    }
    /// pi_ij.
    pub fn probability(&self, i: usize, j: usize) -> f64 {
        self.matrix[i * self.k + j]
    }

    /// Draws the next model from model `current`.
    pub fn next(&self, current: usize, rng: &mut Rng) -> usize {
        let row = &self.cumulative[current * self.k..(current + 1) * self.k];
        let u = rng.uniform() * row[self.k - 1];
        row.iter().position(|&c| u < c).unwrap_or(self.k - 1)
    }
}

/// A particle of a multiple-model filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Regime<S> {
    /// Model index r.
    pub model: usize,
    /// Continuous state x.
    pub state: S,
}

/// Model-specific motion: moves x under model `model`.
pub trait ModelMotion<S> {
    /// Drift and diffusion of `state` under model `model`.
    fn propagate(&self, model: usize, state: &mut S, rng: &mut Rng);
}

/// Motion of a multiple-model filter: switch the model by the chain, then move the state.
pub struct SwitchingMotion<'a, M> {
    /// The transition matrix.
    pub chain: &'a MarkovChain,
    /// The per-model motion.
    pub motion: M,
}

impl<S, M: ModelMotion<S>> MotionModel<Regime<S>> for SwitchingMotion<'_, M> {
    fn propagate(&self, p: &mut Regime<S>, rng: &mut Rng) {
        p.model = self.chain.next(p.model, rng);
        self.motion.propagate(p.model, &mut p.state, rng);
    }
}

/// Writes P(r = j) = sum of the weights of the particles in model j into `out` (length K).
pub fn model_probabilities<S>(particles: &[Regime<S>], weights: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    for (p, &w) in particles.iter().zip(weights) {
        if let Some(o) = out.get_mut(p.model) {
            *o += w;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{FilterConfig, InitialDistribution, MeasurementModel, ParticleFilter};

    #[test]
    fn bad_matrices_are_errors() {
        assert!(MarkovChain::new(&[]).is_err());
        assert!(MarkovChain::new(&[vec![0.5, 0.5], vec![1.0]]).is_err());
        assert!(MarkovChain::new(&[vec![0.5, 0.6], vec![0.5, 0.5]])
            .unwrap_err()
            .to_string()
            .contains("row 0"));
        assert!(MarkovChain::new(&[vec![1.5, -0.5], vec![0.5, 0.5]]).is_err());
        assert!(MarkovChain::new(&[vec![f64::NAN, 1.0], vec![0.5, 0.5]]).is_err());
    }

    #[test]
    fn transitions_follow_the_matrix() {
        // 100 000 draws per row: standard error of a frequency <= 0.0016; tolerance 0.008.
        let chain = MarkovChain::new(&[
            vec![0.7, 0.2, 0.1],
            vec![0.0, 1.0, 0.0],
            vec![0.25, 0.25, 0.5],
        ])
        .unwrap();
        let mut rng = Rng::new(2);
        for i in 0..3 {
            let mut counts = [0usize; 3];
            for _ in 0..100_000 {
                counts[chain.next(i, &mut rng)] += 1;
            }
            for (j, &c) in counts.iter().enumerate() {
                let f = c as f64 / 100_000.0;
                assert!((f - chain.probability(i, j)).abs() < 0.008, "{i}->{j}: {f}");
            }
        }
    }

    /// Two models of a scalar: model 0 says the observation is near +2, model 1 near -2.
    struct Obs;
    impl MeasurementModel<Regime<f64>> for Obs {
        type Cues = f64;
        fn log_likelihood(&self, p: &Regime<f64>, z: &f64) -> f64 {
            let centre = if p.model == 0 { 2.0 } else { -2.0 };
            let e = (p.state + centre - z) / 0.5;
            -0.5 * e * e
        }
    }
    struct Walk;
    impl ModelMotion<f64> for Walk {
        fn propagate(&self, _: usize, x: &mut f64, rng: &mut Rng) {
            *x += rng.gaussian(0.0, 0.1);
        }
    }
    struct Start;
    impl InitialDistribution<Regime<f64>> for Start {
        fn sample(&self, rng: &mut Rng) -> Regime<f64> {
            Regime {
                model: rng.below(2),
                state: rng.gaussian(0.0, 0.3),
            }
        }
    }

    #[test]
    fn model_probability_follows_the_data() {
        let chain = MarkovChain::new(&[vec![0.9, 0.1], vec![0.1, 0.9]]).unwrap();
        let motion = SwitchingMotion {
            chain: &chain,
            motion: Walk,
        };
        let mut pf = ParticleFilter::new(1000, FilterConfig::default(), 4, &Start).unwrap();
        let mut p = [0.0; 2];
        for _ in 0..10 {
            pf.step(&motion, &Obs, &2.0, &Start);
        }
        model_probabilities(pf.states(), pf.weights(), &mut p);
        assert!(p[0] > 0.95, "{p:?}");
        for _ in 0..10 {
            pf.step(&motion, &Obs, &-2.0, &Start);
        }
        model_probabilities(pf.states(), pf.weights(), &mut p);
        assert!(p[1] > 0.95, "{p:?}");
        assert!((p[0] + p[1] - 1.0).abs() < 1e-9);
    }
}
