//! A fixed small filter run whose FNV-1a hash checks that the same seed gives bit-identical
//! results on every target (the native and the wasm tests assert the same golden value,
//! `tests/common/goldens.rs`).

use super::{
    FilterConfig, InitialDistribution, Injection, MeasurementModel, MotionModel, ParticleFilter,
    ResamplePolicy, Resampler, Rng,
};

struct Walk;
impl MotionModel<f64> for Walk {
    fn propagate(&self, x: &mut f64, rng: &mut Rng) {
        *x += rng.gaussian(0.1, 0.3);
    }
}
impl MeasurementModel<f64> for Walk {
    type Cues = f64;
    fn log_likelihood(&self, x: &f64, z: &f64) -> f64 {
        // A Gaussian and a heavier tail, through exp and ln, so libm is exercised.
        let e = x - z;
        crate::math::ln(
            0.9 * crate::math::exp(-0.5 * e * e / 0.04) + 0.1 * crate::math::exp(-e.abs()),
        )
    }
}
impl InitialDistribution<f64> for Walk {
    fn sample(&self, rng: &mut Rng) -> f64 {
        rng.gaussian(0.0, 2.0) + crate::math::sin(rng.uniform())
    }
}

/// Runs 256 particles for 20 frames (seed 42, systematic resampling, 8 injected particles per
/// frame, then 5 frames of residual resampling at ESS < 0.5) and hashes every state and weight.
pub fn determinism_fingerprint() -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |v: f64| {
        for b in v.to_bits().to_le_bytes() {
            hash = (hash ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    };
    let config = FilterConfig {
        resampler: Resampler::Systematic,
        policy: ResamplePolicy::Always,
        injection: Injection::Count(8),
    };
    let Ok(mut pf) = ParticleFilter::new(256, config, 42, &Walk) else {
        return 0;
    };
    for t in 0..20 {
        pf.step(&Walk, &Walk, &(0.1 * t as f64), &Walk);
        pf.states().iter().chain(pf.weights()).for_each(|&v| eat(v));
    }
    let config = FilterConfig {
        resampler: Resampler::Residual,
        policy: ResamplePolicy::EssBelow(0.5),
        injection: Injection::None,
    };
    let Ok(mut pf2) = ParticleFilter::new(256, config, 43, &Walk) else {
        return 0;
    };
    for t in 0..5 {
        pf2.step(&Walk, &Walk, &(2.0 - 0.2 * t as f64), &Walk);
        pf2.states()
            .iter()
            .chain(pf2.weights())
            .for_each(|&v| eat(v));
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::goldens::DETERMINISM_FINGERPRINT;

    #[test]
    fn fingerprint_matches_the_golden_value() {
        assert_eq!(
            determinism_fingerprint(),
            DETERMINISM_FINGERPRINT,
            "{:#x}",
            determinism_fingerprint()
        );
    }
}
