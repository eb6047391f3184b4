//! The generic particle-filter core, shared by all four trackers.
//!
//! A filter is a [`ParticleFilter`] over a tracker's state type, driven by the tracker's
//! [`MotionModel`] (drift + diffusion), [`MeasurementModel`] (log-likelihood of a state given
//! the frame's cues) and [`InitialDistribution`]. One frame: resample (by a [`Resampler`] and
//! a [`ResamplePolicy`]), inject initialisation particles, predict, weigh in the log domain
//! (log-sum-exp normalisation, ESS); every resampling decision is kept as the filter made it
//! ([`ResampleDecision`]). Variants: [`PartitionedModel`] for partitioned sampling (Liu),
//! several filters in cascade (Lee), [`Regime`] particles with a [`MarkovChain`] (Adachi),
//! and the estimators [`weighted_mean`], [`expectation`], [`map_index`] and [`Mbsas`]
//! (Danescu eq. 15).
//!
//! A tracker's frame is a [`Schedule`]: named steps of operations ([`Op`]: resample, inject,
//! predict(k), weigh(k), resample-between, stage estimate, estimate) on its filters, run by
//! the one [`Stepper`] through the tracker's [`Scheduled`] implementation (its models), one
//! step per `advance` or the whole frame at once, each operation timed ([`StageTimes`]) and
//! each resampling decision recorded ([`Stepper::resamplings`]).
//!
//! The [`Rng`] is seeded and owned by the filter, so runs repeat bit for bit on every target
//! ([`determinism_fingerprint`]).

mod estimate;
mod fingerprint;
mod model;
mod multimodel;
mod particle_filter;
mod partitioned;
mod resample;
mod resampling_log;
mod rng;
pub mod schedule;
mod stage_times;
mod stepper;
mod weights;

pub use estimate::{expectation, map_index, weighted_mean, Mbsas};
pub use fingerprint::determinism_fingerprint;
pub use model::{InitialDistribution, MeasurementModel, MotionModel};
pub use multimodel::{model_probabilities, MarkovChain, ModelMotion, Regime, SwitchingMotion};
pub use particle_filter::{FilterConfig, Injection, ParticleFilter, MAX_PARTICLES};
pub use partitioned::PartitionedModel;
pub use resample::{ResamplePolicy, Resampler};
pub use resampling_log::{ResampleDecision, ResampleRule};
pub use rng::Rng;
pub use schedule::{FirstFrame, Op, Pass, Schedule};
pub(crate) use stage_times::now;
pub use stage_times::StageTimes;
pub use stepper::{Scheduled, Stepper};
pub use weights::{effective_sample_size, log_sum_exp, normalise, Normalised};
