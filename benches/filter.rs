//! Criterion benchmark of one particle-filter step (resample, inject, predict, weigh) at 100,
//! 1000 and 10 000 particles, on a 6-parameter state (the size of Lee's full model) with a
//! Gaussian likelihood, and of each resampler at 10 000. `cargo bench --bench filter`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use lanepf::filter::{
    FilterConfig, InitialDistribution, Injection, MeasurementModel, MotionModel, ParticleFilter,
    ResamplePolicy, Resampler, Rng,
};

type State = [f64; 6];

struct Model;
impl MotionModel<State> for Model {
    fn propagate(&self, x: &mut State, rng: &mut Rng) {
        for v in x.iter_mut() {
            *v += rng.gaussian(0.0, 0.05);
        }
    }
}
impl MeasurementModel<State> for Model {
    type Cues = State;
    fn log_likelihood(&self, x: &State, z: &State) -> f64 {
        x.iter()
            .zip(z)
            .map(|(a, b)| -0.5 * (a - b) * (a - b) / 0.01)
            .sum()
    }
}
impl InitialDistribution<State> for Model {
    fn sample(&self, rng: &mut Rng) -> State {
        [0.0; 6].map(|_| rng.gaussian(0.0, 1.0))
    }
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("filter_step");
    for n in [100, 1000, 10_000] {
        let config = FilterConfig {
            resampler: Resampler::Systematic,
            policy: ResamplePolicy::Always,
            injection: Injection::Fraction(0.05),
        };
        let mut pf = ParticleFilter::new(n, config, 1, &Model).expect("filter");
        let z = [0.1; 6];
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| pf.step(&Model, &Model, &z, &Model))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("resample_10000");
    for scheme in [
        Resampler::Multinomial,
        Resampler::Stratified,
        Resampler::Systematic,
        Resampler::Residual,
    ] {
        let mut rng = Rng::new(2);
        let raw: Vec<f64> = (0..10_000).map(|_| rng.uniform()).collect();
        let total: f64 = raw.iter().sum();
        let w: Vec<f64> = raw.iter().map(|x| x / total).collect();
        let mut out = Vec::with_capacity(10_000);
        group.bench_function(format!("{scheme:?}").to_lowercase(), |b| {
            b.iter(|| scheme.resample(&w, 10_000, &mut rng, &mut out))
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
