//! Criterion benchmark of the scene renderer: one frame of `highway-curve` and `urban` at
//! 640x480 and 1280x720 through the default camera. `cargo bench --bench synth`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use lanepf::synth::{default_camera, scenario, Eye, Scene};

fn render(c: &mut Criterion) {
    let mut group = c.benchmark_group("synth");
    group.sample_size(20);
    for (w, h) in [(640, 480), (1280, 720)] {
        for name in ["highway-curve", "urban"] {
            let mut scene = Scene::new(
                scenario(name).expect("scenario"),
                default_camera(w, h).expect("camera"),
                1,
            )
            .expect("scene");
            let mut rgba = vec![0u8; w * h * 4];
            let mut frame = 0;
            group.bench_function(BenchmarkId::new(name, format!("{w}x{h}")), |b| {
                b.iter(|| {
                    frame = (frame + 1) % 300;
                    scene
                        .render(frame, Eye::Left, &mut rgba, None)
                        .expect("render")
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
