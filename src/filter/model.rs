//! The model traits a tracker implements and the filter borrows.
//!
//! A tracker's filter is a motion model (deterministic drift plus stochastic diffusion), a
//! measurement model (the log-likelihood of a state given the frame's cues) and an initial
//! distribution (for the first frame, resets and injected initialisation particles).

use super::rng::Rng;

/// p(x_t | x_{t-1}): moves one particle in place.
pub trait MotionModel<S> {
    /// Applies drift and diffusion to `state`.
    fn propagate(&self, state: &mut S, rng: &mut Rng);
}

/// p(z_t | x_t): scores one particle against the frame's cues.
pub trait MeasurementModel<S> {
    /// What the model reads from the frame (gradient images, edge maps, ...).
    type Cues: ?Sized;
    /// ln p(z | x); -infinity for an impossible state.
    fn log_likelihood(&self, state: &S, cues: &Self::Cues) -> f64;
}

/// p(x_0): draws a fresh particle.
pub trait InitialDistribution<S> {
    /// One draw.
    fn sample(&self, rng: &mut Rng) -> S;
}
