//! Criterion benchmarks of the vision operations at 640x480 and 1280x720, on a rendered frame
//! of the synthetic test road (so edges and markings are realistic in number).
//! Run with `make bench` or `cargo bench --bench vision`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use lanepf::camera::Camera;
use lanepf::image::{rgba_to_gray, Image};
use lanepf::synth::{default_camera, scenario, Eye, Scene, TestRoad, TestRoadConfig};
use lanepf::vision::{
    Canny, CannyConfig, DisparityConfig, DistanceTransform, Dld, DldConfig, Gradients, Ipm,
    StereoMatcher, TopViewConfig,
};
use std::hint::black_box;

const SIZES: [(usize, usize); 2] = [(640, 480), (1280, 720)];

/// A camera for a `w` x `h` image: 60 degrees horizontal field of view, 1.5 m high, 5 degrees
/// down.
fn camera(w: usize, h: usize) -> Camera {
    let f = w as f64 / 2.0 / lanepf::math::tan(lanepf::math::deg_to_rad(30.0));
    Camera::from_json_str(&format!(
        r#"{{"width": {w}, "height": {h}, "fx": {f}, "fy": {f}, "cx": {cx}, "cy": {cy},
            "height_m": 1.5, "pitch_deg": 5.0}}"#,
        cx = w as f64 / 2.0,
        cy = h as f64 / 2.0
    ))
    .expect("valid camera")
}

fn frame(camera: &Camera) -> Image<u8> {
    let (w, h) = (camera.width(), camera.height());
    let road = TestRoad::new(camera.clone(), TestRoadConfig::default()).expect("road");
    let mut rgba = vec![0; w * h * 4];
    road.render(10, &mut rgba).expect("render");
    let mut gray = Image::new(w, h).expect("size");
    rgba_to_gray(&rgba, w, h, &mut gray).expect("gray");
    gray
}

/// A rendered stereo pair (left, right) of the `highway-straight` scenario, grey.
fn stereo_pair(w: usize, h: usize) -> (Image<u8>, Image<u8>) {
    let camera = default_camera(w, h).expect("camera");
    let mut scene =
        Scene::new(scenario("highway-straight").expect("scenario"), camera, 1).expect("scene");
    let mut rgba = vec![0; w * h * 4];
    let mut pair = [
        Image::new(w, h).expect("size"),
        Image::new(w, h).expect("size"),
    ];
    for (eye, gray) in [Eye::Left, Eye::Right].into_iter().zip(pair.iter_mut()) {
        scene.render(30, eye, &mut rgba, None).expect("render");
        rgba_to_gray(&rgba, w, h, gray).expect("gray");
    }
    let [left, right] = pair;
    (left, right)
}

fn vision(c: &mut Criterion) {
    for (w, h) in SIZES {
        let cam = camera(w, h);
        let gray = frame(&cam);
        let size = format!("{w}x{h}");
        let mut group = c.benchmark_group("vision");

        let ipm = Ipm::new(&cam, TopViewConfig::default()).expect("ipm");
        let mut top = Image::new(1, 1).expect("size");
        group.bench_with_input(BenchmarkId::new("ipm_320x800", &size), &gray, |b, g| {
            b.iter(|| ipm.apply(&g.view(), 0, &mut top).expect("ipm"))
        });

        let mut grads = Gradients::new(w, h).expect("size");
        group.bench_with_input(BenchmarkId::new("sobel", &size), &gray, |b, g| {
            b.iter(|| grads.compute(&g.view()).expect("sobel"))
        });
        group.bench_with_input(
            BenchmarkId::new("sobel_orientation", &size),
            &gray,
            |b, _| b.iter(|| grads.compute_orientation()),
        );

        let mut canny = Canny::new(CannyConfig::default()).expect("canny");
        let mut edges = Image::new(1, 1).expect("size");
        group.bench_with_input(BenchmarkId::new("canny", &size), &gray, |b, g| {
            b.iter(|| canny.apply(&g.view(), &mut edges).expect("canny"))
        });

        let mut dld = Dld::new(DldConfig::default()).expect("dld");
        group.bench_with_input(BenchmarkId::new("dld", &size), &gray, |b, g| {
            b.iter(|| dld.apply(&g.view()).expect("dld"))
        });

        let mut dt = DistanceTransform::new();
        let mut dist = Image::new(1, 1).expect("size");
        group.bench_with_input(
            BenchmarkId::new("distance_transform", &size),
            &edges,
            |b, e| b.iter(|| dt.apply(&e.view(), &mut dist).expect("dt")),
        );

        // Census block matching of the lower half (the road), 64 disparities.
        let (left, right) = stereo_pair(w, h);
        let mut stereo = StereoMatcher::new(w, h, DisparityConfig::default()).expect("stereo");
        group.bench_with_input(
            BenchmarkId::new("disparity_lower_half_d64", &size),
            &(left, right),
            |b, (l, r)| b.iter(|| stereo.compute(&l.view(), &r.view(), h / 2).expect("stereo")),
        );
        black_box((&top, &dist, stereo.disparity()));
        group.finish();
    }
}

criterion_group!(benches, vision);
criterion_main!(benches);
