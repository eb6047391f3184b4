//! wasm-bindgen-test suite, run in headless Chromium by `make test-wasm`:
//! `CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner cargo test --target
//! wasm32-unknown-unknown --test web`. It exercises the JS-facing classes as JavaScript sees
//! them (thrown errors and their messages, objects still usable afterwards) and checks that the
//! seeded core gives bit-identical results in the browser.
#![cfg(all(target_arch = "wasm32", feature = "wasm"))]

use lanepf::wasm::{
    scenarios, tracker_ids, version, JsCalibrator, JsCamera, JsScene, JsTestRoad, JsTracker,
};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

/// The golden values the native unit tests assert too.
mod goldens {
    include!("common/goldens.rs");
}

/// Parses a JS object literal written as JSON.
fn obj(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("test JSON")
}

const CAMERA: &str = r#"{"width": 640, "height": 480, "fx": 309.4362, "fy": 344.2161,
    "cx": 317.9034, "cy": 256.5352, "height_m": 2.1798, "pitch_deg": 14.0}"#;

/// The message of the `Error` a call threw.
fn message<T, E: Into<JsValue>>(r: Result<T, E>) -> String {
    match r {
        Ok(_) => panic!("expected a thrown Error"),
        Err(e) => {
            let v: JsValue = e.into();
            let err: js_sys::Error = v.dyn_into().expect("a JS Error object");
            err.message().into()
        }
    }
}

/// A number argument.
fn n(x: impl Into<f64>) -> JsValue {
    JsValue::from_f64(x.into())
}

/// RGBA bytes as the `Uint8Array` JavaScript passes.
fn px(bytes: &[u8]) -> JsValue {
    js_sys::Uint8Array::from(bytes).into()
}

/// Sets `obj[key] = value` on a parsed object.
fn with(json: &str, key: &str, value: JsValue) -> JsValue {
    let o = obj(json);
    js_sys::Reflect::set(&o, &key.into(), &value).unwrap();
    o
}

#[wasm_bindgen_test]
fn version_is_the_crate_version() {
    assert_eq!(version(), env!("CARGO_PKG_VERSION"));
}

#[wasm_bindgen_test]
fn camera_round_trips_and_projects() {
    let cam = JsCamera::new(obj(CAMERA)).unwrap();
    assert_eq!((cam.width(), cam.height()), (640, 480));
    let p = cam.project_road(n(20.0), n(0.0)).unwrap();
    assert!(
        (p[0] - 317.9034).abs() < 1e-6,
        "centre line projects to cx: {p:?}"
    );
    let back = cam.road_point(n(p[0]), n(p[1])).unwrap();
    assert!(
        (back[0] - 20.0).abs() < 1e-6 && back[1].abs() < 1e-6,
        "{back:?}"
    );
}

#[wasm_bindgen_test]
fn camera_rejects_nan_missing_and_absurd_values_by_name() {
    let m = message(JsCamera::new(with(
        CAMERA,
        "fx",
        JsValue::from_f64(f64::NAN),
    )));
    assert!(m.contains("invalid camera: fx is NaN"), "{m}");
    let m = message(JsCamera::new(with(
        CAMERA,
        "height_m",
        JsValue::from_f64(-2.0),
    )));
    assert!(m.contains("height_m"), "{m}");
    let m = message(JsCamera::new(with(CAMERA, "width", JsValue::from_f64(0.0))));
    assert!(m.contains("width"), "{m}");
    let m = message(JsCamera::new(with(CAMERA, "width", JsValue::from_f64(1e6))));
    assert!(m.contains("1000000"), "{m}");
    let m = message(JsCamera::new(obj(r#"{"width": 640}"#)));
    assert!(m.contains("missing field"), "{m}");
    let m = message(JsCamera::new(JsValue::UNDEFINED));
    assert!(m.contains("camera is missing"), "{m}");
}

#[wasm_bindgen_test]
fn camera_stays_usable_after_bad_calls() {
    let cam = JsCamera::new(obj(CAMERA)).unwrap();
    let m = message(cam.project_road(n(f64::NAN), n(0.0)));
    assert!(m.contains("x is NaN"), "{m}");
    let m = message(cam.road_point(n(320.0), n(10.0)));
    assert!(m.contains("horizon"), "{m}");
    assert!(cam.project_road(n(10.0), n(1.8)).is_ok());
}

#[wasm_bindgen_test]
fn test_road_renders_full_frames_and_truth() {
    let mut road = JsTestRoad::new(obj(CAMERA), JsValue::UNDEFINED).unwrap();
    let px = road.render(n(5)).unwrap();
    assert_eq!(px.length() as usize, 640 * 480 * 4);
    let truth = road.truth(n(5)).unwrap();
    let boundaries = js_sys::Reflect::get(&truth, &"boundaries".into()).unwrap();
    assert_eq!(js_sys::Array::from(&boundaries).length(), 2);
    let m = message(JsTestRoad::new(
        obj(CAMERA),
        obj(r#"{"lane_width_m": 3.6, "marking_width_m": 2.5}"#),
    ));
    assert!(m.contains("marking_width_m"), "{m}");
    let m = message(JsTestRoad::new(obj(CAMERA), obj(r#"{"lane_wdth_m": 3}"#)));
    assert!(m.contains("unknown field `lane_wdth_m`"), "{m}");
}

#[wasm_bindgen_test]
fn tracker_factory_explains_unknown_ids_and_bad_configs() {
    let config = obj(&format!(
        r#"{{"camera": {CAMERA}, "particles": 300, "seed": 7}}"#
    ));
    let m = message(JsTracker::new("no-such-tracker".into(), config));
    assert!(
        m.starts_with("unknown tracker `no-such-tracker`; available: "),
        "{m}"
    );
    for id in tracker_ids() {
        assert!(m.contains(&id), "{m} lists {id}");
    }
    let bad = obj(&format!(r#"{{"camera": {CAMERA}, "particles": 0}}"#));
    let m = message(JsTracker::new("no-such-tracker".into(), bad));
    assert!(m.contains("`particles` = 0"), "{m}");
    let m = message(JsTracker::new("no-such-tracker".into(), JsValue::NULL));
    assert!(m.contains("tracker config is missing"), "{m}");
}

#[wasm_bindgen_test]
fn scenes_render_every_scenario_with_truth_and_match_native_pixels() {
    let list = scenarios().unwrap();
    let list: js_sys::Array = list.dyn_into().unwrap();
    assert_eq!(list.length(), 12);
    let mut scene = JsScene::new(
        "s-curve".into(),
        obj(r#"{"width": 160, "height": 120, "seed": 3}"#),
    )
    .unwrap();
    assert_eq!(
        (scene.width(), scene.height(), scene.frames()),
        (160, 120, 450)
    );
    let left = scene.render(n(30)).unwrap().to_vec();
    let right = scene.render_right(n(30)).unwrap().to_vec();
    assert_eq!(left.len(), 160 * 120 * 4);
    assert_ne!(
        left, right,
        "the right camera sees the scene from elsewhere"
    );
    // The same frame rendered natively by the same code (the core is compiled for wasm here,
    // so this checks the binding copies the buffer faithfully and repeatably).
    let mut native = lanepf::synth::Scene::new(
        lanepf::synth::scenario("s-curve").unwrap(),
        lanepf::synth::default_camera(160, 120).unwrap(),
        3,
    )
    .unwrap();
    let mut rgba = vec![0; 160 * 120 * 4];
    native
        .render(30, lanepf::synth::Eye::Left, &mut rgba, None)
        .unwrap();
    assert_eq!(left, rgba);
    // Bit-identical to the native build: the native unit test asserts the same fingerprint.
    assert_eq!(
        lanepf::synth::frame_fingerprint(&left),
        goldens::SCENE_FINGERPRINT
    );
    let truth = scene.truth(n(30)).unwrap();
    let boundaries = js_sys::Reflect::get(&truth, &"boundaries".into()).unwrap();
    assert!(js_sys::Array::from(&boundaries).length() >= 2);
}

/// A scenario family member (the road, events and camera its seed draws) renders the same
/// bits as natively, through the core and through `new Scene(name, { seed, drawn: true })`:
/// the native unit test asserts the same fingerprint. Without `drawn` the same name and seed
/// is the reference road, another picture.
#[wasm_bindgen_test]
fn a_family_member_renders_the_native_fingerprint() {
    let (name, seed, frame) = goldens::FINGERPRINT_MEMBER;
    let member = lanepf::synth::draw_scenario(name, seed).unwrap();
    let mut scene = member.scene(160, 120).unwrap();
    let mut rgba = vec![0; 160 * 120 * 4];
    scene
        .render(frame, lanepf::synth::Eye::Left, &mut rgba, None)
        .unwrap();
    assert_eq!(
        lanepf::synth::frame_fingerprint(&rgba),
        goldens::FAMILY_FINGERPRINT
    );
    let options = |drawn: bool| {
        obj(&format!(
            r#"{{"width": 160, "height": 120, "seed": {seed}, "drawn": {drawn}}}"#
        ))
    };
    let mut js = JsScene::new(name.into(), options(true)).unwrap();
    assert_eq!(js.render(n(frame)).unwrap().to_vec(), rgba);
    let mut reference = JsScene::new(name.into(), options(false)).unwrap();
    assert_ne!(reference.render(n(frame)).unwrap().to_vec(), rgba);
    // `random` names a family only when drawn.
    assert!(JsScene::new("random".into(), options(true)).is_ok());
    let e = message(JsScene::new("random".into(), options(false)));
    assert!(
        e.contains("has no reference road") && e.contains("drawn: true"),
        "{e}"
    );
}

#[wasm_bindgen_test]
fn scenes_reject_unknown_names_and_bad_options() {
    let e = message(JsScene::new("moon".into(), JsValue::UNDEFINED));
    assert!(
        e.contains("unknown scenario `moon`") && e.contains("highway-straight"),
        "{e}"
    );
    let e = message(JsScene::new(
        "urban".into(),
        obj(r#"{"width": 0, "height": 10}"#),
    ));
    assert!(e.contains("0x10"), "{e}");
    let e = message(JsScene::new(
        "urban".into(),
        with("{}", "seed", JsValue::from_f64(f64::NAN)),
    ));
    assert!(e.contains("seed"), "{e}");
    let e = message(JsScene::new("urban".into(), obj(r#"{"width": 1.5}"#)));
    assert!(e.contains("width") && e.contains("1.5"), "{e}");
    let e = message(JsScene::new(
        "urban".into(),
        with("{}", "camera", with(CAMERA, "fx", JsValue::from_f64(-1.0))),
    ));
    assert!(e.contains("`fx`"), "{e}");
}

#[wasm_bindgen_test]
fn particle_filter_is_bit_identical_to_the_native_build() {
    // The native unit test asserts the same golden value.
    assert_eq!(
        lanepf::filter::determinism_fingerprint(),
        goldens::DETERMINISM_FINGERPRINT
    );
}

#[wasm_bindgen_test]
fn adachi_tracker_runs_in_the_browser_with_the_native_result() {
    // Same run as the native unit test `same_result_as_the_browser_build`, through the JS
    // classes: highway-curve seed 1 at 320x240, 400 particles, seed 2, five frames.
    let mut scene = JsScene::new(
        "highway-curve".into(),
        obj(r#"{"width": 320, "height": 240, "seed": 1}"#),
    )
    .unwrap();
    let camera = scene.camera().unwrap();
    let config = obj(r#"{"particles": 400, "seed": 2}"#);
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let mut tracker = JsTracker::new("adachi-mmpf".into(), config).unwrap();
    assert_eq!(tracker.id(), "adachi-mmpf");
    let mut last = JsValue::UNDEFINED;
    for f in 0..5 {
        let rgba = scene.render(n(f)).unwrap().to_vec();
        last = tracker.step(px(&rgba), Some(n(320)), Some(n(240))).unwrap();
    }
    let q = js_sys::Reflect::get(&last, &"lateral_offset_m".into())
        .unwrap()
        .as_f64()
        .unwrap();
    assert_eq!(q.to_bits(), 0x3fb9_011a_d511_3817, "{q}");
    // The typed fields: the ESS as `state` holds it, the model probabilities P(1..4).
    let get = |k: &str| js_sys::Reflect::get(&last, &k.into()).unwrap();
    let state = get("state");
    let adachi_ess = js_sys::Reflect::get(&state, &"adachi.ess".into()).unwrap();
    assert_eq!(get("ess").as_f64(), adachi_ess.as_f64());
    assert!(get("ess").as_f64().is_some_and(|e| e > 0.0 && e <= 400.0));
    let p: Vec<f64> = js_sys::Array::from(&get("model_probabilities"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(p.len(), 4);
    assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{p:?}");
    // The cloud: 400 particles of (r, q, w, weight), weights summing to 1.
    assert_eq!(tracker.particle_stride(), 4);
    let cloud = tracker.particles().to_vec();
    assert_eq!(cloud.len(), 400 * 4);
    let total: f32 = cloud.chunks(4).map(|p| p[3]).sum();
    assert!((total - 1.0).abs() < 1e-3, "{total}");
    assert!(cloud
        .chunks(4)
        .all(|p| (1.0..=4.0).contains(&p[0]) && p[1].abs() <= p[2] / 2.0 + 1e-4));
    // The vote histogram for the demo's view: 320 bins of 5 cm over +-8 m.
    let layers: js_sys::Array = tracker.layers().unwrap().dyn_into().unwrap();
    let first = layers.get(0);
    let field = |k: &str| js_sys::Reflect::get(&first, &k.into()).unwrap();
    assert_eq!(field("kind").as_string().unwrap(), "histogram");
    let values: js_sys::Float32Array = field("values").dyn_into().unwrap();
    assert_eq!(values.length(), 320);
    assert_eq!(field("start").as_f64(), Some(-8.0));
    // A wrong buffer throws, and the tracker carries on.
    let m = message(tracker.step(px(&[0; 12]), Some(n(320)), Some(n(240))));
    assert!(m.contains("320x240"), "{m}");
    let rgba = scene.render(n(5)).unwrap().to_vec();
    assert!(tracker.step(px(&rgba), Some(n(320)), Some(n(240))).is_ok());
}

/// `lateral_offset_m` of an estimate.
fn lateral_offset(estimate: &JsValue) -> f64 {
    js_sys::Reflect::get(estimate, &"lateral_offset_m".into())
        .unwrap()
        .as_f64()
        .unwrap()
}

/// Runs tracker `id` with `options` (plus the scene's camera) over five frames of
/// highway-curve (seed 1, 320x240), once by `step` and once in per-step mode, checking the
/// order of its `steps` steps; returns the scene, its camera, the whole-step tracker and both last estimates.
fn track_five_frames_both_ways(
    id: &str,
    options: &str,
    steps: usize,
) -> (JsScene, JsValue, JsTracker, JsValue, JsValue) {
    let mut scene = JsScene::new(
        "highway-curve".into(),
        obj(r#"{"width": 320, "height": 240, "seed": 1}"#),
    )
    .unwrap();
    let camera = scene.camera().unwrap();
    let config = obj(options);
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let mut tracker = JsTracker::new(id.into(), config.clone()).unwrap();
    let mut stepped = JsTracker::new(id.into(), config).unwrap();
    assert_eq!(stepped.step_names().len(), steps, "{id}");
    let (mut last, mut last_stepped) = (JsValue::UNDEFINED, JsValue::UNDEFINED);
    for f in 0..5 {
        let rgba = scene.render(n(f)).unwrap().to_vec();
        last = tracker.step(px(&rgba), Some(n(320)), Some(n(240))).unwrap();
        stepped
            .begin_frame(px(&rgba), Some(n(320)), Some(n(240)))
            .unwrap();
        for k in 0..steps {
            assert_eq!(stepped.next_step(), Some(k));
            last_stepped = stepped.advance().unwrap();
            assert_eq!(last_stepped.is_null(), k + 1 < steps);
        }
    }
    let m = message(stepped.advance());
    assert!(m.contains("begin_frame"), "{m}");
    (scene, camera, tracker, last, last_stepped)
}

#[wasm_bindgen_test]
fn lee_tracker_runs_in_the_browser_with_the_native_result() {
    // Same run as the native unit test `trackers::lee::tests::same_result_as_the_browser_build`:
    // highway-curve seed 1 at 320x240, 400 particles, seed 2, five frames, also step by step.
    let (mut scene, camera, mut tracker, last, last_stepped) =
        track_five_frames_both_ways("lee-cpf", r#"{"particles": 400, "seed": 2}"#, 7);
    let offset = lateral_offset;
    let o = offset(&last);
    assert_eq!(o.to_bits(), 0x3fad_3ef9_7aa7_9b72, "{o}");
    assert_eq!(offset(&last_stepped).to_bits(), o.to_bits());
    // Both stages' clouds: 400 + 400 particles of 8 numbers, each stage's weights summing to 1.
    assert_eq!(tracker.particle_stride(), 8);
    let cloud = tracker.particles().to_vec();
    assert_eq!(cloud.len(), 800 * 8);
    for stage in [1.0, 2.0] {
        let total: f32 = cloud
            .chunks(8)
            .filter(|p| p[0] == stage)
            .map(|p| p[7])
            .sum();
        assert!((total - 1.0).abs() < 1e-3, "stage {stage}: {total}");
    }
    // Bad options and a wrong buffer throw, and the tracker carries on.
    let bad = obj(r#"{"sigma_q": -1}"#);
    js_sys::Reflect::set(&bad, &"camera".into(), &camera).unwrap();
    let m = message(JsTracker::new("lee-cpf".into(), bad));
    assert!(m.contains("sigma_q"), "{m}");
    let m = message(tracker.step(px(&[0; 12]), Some(n(320)), Some(n(240))));
    assert!(m.contains("320x240"), "{m}");
    let rgba = scene.render(n(5)).unwrap().to_vec();
    assert!(tracker.step(px(&rgba), Some(n(320)), Some(n(240))).is_ok());
}

#[wasm_bindgen_test]
fn liu_tracker_runs_in_the_browser_with_the_native_result() {
    // Same run as the native unit test `trackers::liu::tests::same_result_as_the_browser_build`:
    // highway-curve seed 1 at 320x240, 300 particles, seed 2, five frames, also step by step.
    let (mut scene, camera, mut tracker, last, last_stepped) =
        track_five_frames_both_ways("liu-ppf", r#"{"particles": 300, "seed": 2}"#, 7);
    let config = obj(r#"{"particles": 300, "seed": 2}"#);
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let rho = |v: &JsValue| {
        let state = js_sys::Reflect::get(v, &"state".into()).unwrap();
        js_sys::Reflect::get(&state, &"liu.ego-left.rho".into())
            .unwrap()
            .as_f64()
            .unwrap()
    };
    assert_eq!(
        rho(&last).to_bits(),
        0x4046_9e3d_5573_faa5,
        "{}",
        rho(&last)
    );
    assert_eq!(rho(&last_stepped).to_bits(), rho(&last).to_bits());
    // N + N' particles of 3 boundaries x (rho, theta, d) + weight, weights summing to 1.
    assert_eq!(tracker.particle_stride(), 10);
    let cloud = tracker.particles().to_vec();
    assert_eq!(cloud.len(), 350 * 10);
    let total: f32 = cloud.chunks(10).map(|p| p[9]).sum();
    assert!((total - 1.0).abs() < 1e-3, "{total}");
    // The no-kernel baseline exists, bad options throw, and the tracker carries on.
    assert!(JsTracker::new("liu-ppf-nokernel".into(), config).is_ok());
    let bad = obj(r#"{"boundaries": 9}"#);
    js_sys::Reflect::set(&bad, &"camera".into(), &camera).unwrap();
    let m = message(JsTracker::new("liu-ppf".into(), bad));
    assert!(m.contains("boundaries"), "{m}");
    let m = message(tracker.step(px(&[0; 12]), Some(n(320)), Some(n(240))));
    assert!(m.contains("320x240"), "{m}");
    let rgba = scene.render(n(5)).unwrap().to_vec();
    assert!(tracker.step(px(&rgba), Some(n(320)), Some(n(240))).is_ok());
}

#[wasm_bindgen_test]
fn danescu_mono_runs_in_the_browser_with_the_native_result() {
    // Same run as the native unit test
    // `trackers::danescu::tests::same_result_as_the_browser_build`: highway-curve seed 1 at
    // 320x240, 300 particles, seed 2, five frames, also step by step.
    let (mut scene, camera, mut tracker, last, last_stepped) =
        track_five_frames_both_ways("danescu-mono", r#"{"particles": 300, "seed": 2}"#, 4);
    let offset = lateral_offset;
    let o = offset(&last);
    assert_eq!(o.to_bits(), 0xbfe3_d196_9700_a70e, "{o}");
    assert_eq!(offset(&last_stepped).to_bits(), o.to_bits());
    // 11 parameters, weight and cluster per particle; weights sum to 1.
    assert_eq!(tracker.particle_stride(), 13);
    let cloud = tracker.particles().to_vec();
    assert_eq!(cloud.len(), 300 * 13);
    let total: f32 = cloud.chunks(13).map(|p| p[11]).sum();
    assert!((total - 1.0).abs() < 1e-3, "{total}");
    // Ego motion: accepted when complete and finite, a thrown Error otherwise.
    assert!(tracker
        .set_ego_motion(obj(r#"{"t_s": 0.2, "speed_mps": 25, "yaw_rate": 0.01}"#))
        .is_ok());
    let m = message(tracker.set_ego_motion(obj(r#"{"t_s": 0.2, "speed_mps": 25}"#)));
    assert!(m.contains("yaw_rate"), "{m}");
    let m =
        message(tracker.set_ego_motion(obj(r#"{"t_s": 0.2, "speed_mps": 1e9, "yaw_rate": 0}"#)));
    assert!(m.contains("speed_mps"), "{m}");
    let bad = obj(r#"{"points": 0}"#);
    js_sys::Reflect::set(&bad, &"camera".into(), &camera).unwrap();
    let m = message(JsTracker::new("danescu-mono".into(), bad));
    assert!(m.contains("points"), "{m}");
    let rgba = scene.render(n(5)).unwrap().to_vec();
    assert!(tracker.step(px(&rgba), Some(n(320)), Some(n(240))).is_ok());
}

#[wasm_bindgen_test]
fn danescu_stereo_runs_in_the_browser_with_the_native_result() {
    // Same run as the native unit test
    // `trackers::danescu::tests::stereo_same_result_as_the_browser_build`: highway-curve seed
    // 1 at 320x240, 300 particles, seed 2, five stereo frames.
    let mut scene = JsScene::new(
        "highway-curve".into(),
        obj(r#"{"width": 320, "height": 240, "seed": 1}"#),
    )
    .unwrap();
    let camera = scene.camera().unwrap();
    let config = obj(r#"{"particles": 300, "seed": 2}"#);
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let mut tracker = JsTracker::new("danescu-stereo".into(), config).unwrap();
    assert!(tracker.is_stereo());
    let first = scene.render(n(0)).unwrap().to_vec();
    // Without the right image: a thrown Error that says what to do, and the tracker goes on.
    let m = message(tracker.step(px(&first), Some(n(320)), Some(n(240))));
    assert!(
        m.contains("step(left, { right })") && m.contains("danescu-mono"),
        "{m}"
    );
    let m = message(tracker.set_right(px(&[0; 12]), n(320), n(240)));
    assert!(m.contains("320x240") || m.contains("bytes"), "{m}");
    let mut last = JsValue::UNDEFINED;
    for f in 0..5 {
        let left = scene.render(n(f)).unwrap().to_vec();
        let right = scene.render_right(n(f)).unwrap().to_vec();
        tracker.set_right(px(&right), n(320), n(240)).unwrap();
        last = tracker.step(px(&left), Some(n(320)), Some(n(240))).unwrap();
    }
    let state = js_sys::Reflect::get(&last, &"state".into()).unwrap();
    let alpha = js_sys::Reflect::get(&state, &"danescu.alpha".into())
        .unwrap()
        .as_f64()
        .unwrap();
    assert_eq!(alpha.to_bits(), 0x3fb0_8834_3261_06d5, "{alpha}");
    // A one-camera tracker refuses a right image.
    let config = obj(r#"{}"#);
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let mut mono = JsTracker::new("danescu-mono".into(), config).unwrap();
    assert!(!mono.is_stereo());
    let right = scene.render_right(n(0)).unwrap().to_vec();
    let m = message(mono.set_right(px(&right), n(320), n(240)));
    assert!(m.contains("one camera"), "{m}");
}

/// A field of a JS object as a number.
fn num(value: &JsValue, key: &str) -> f64 {
    js_sys::Reflect::get(value, &key.into())
        .unwrap()
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number"))
}

/// A 320x240 camera 1.4 m above the road, 3 degrees down, 1 degree left, with the focal length
/// of a 60-degree horizontal field of view (the calibrator's default guess).
fn calibration_camera() -> JsValue {
    let f = 160.0 / libm::tan(30f64.to_radians());
    obj(&format!(
        r#"{{"width": 320, "height": 240, "fx": {f}, "fy": {f}, "cx": 159.5, "cy": 119.5,
            "height_m": 1.4, "pitch_deg": 3.0, "yaw_deg": 1.0}}"#
    ))
}

/// Feeds the 300 frames of highway-straight (a whole sway period and more: the car's heading
/// to the road, which the vanishing point also sees, averages out) to `calibrator`; returns the
/// estimate and the number of frames that said they were used.
fn calibrate_on_highway(camera: &JsValue, calibrator: &mut JsCalibrator) -> (JsValue, usize) {
    let options = obj(r#"{"seed": 1}"#);
    js_sys::Reflect::set(&options, &"camera".into(), camera).unwrap();
    let mut scene = JsScene::new("highway-straight".into(), options).unwrap();
    let mut used = 0;
    for f in 0..scene.frames() {
        let status = calibrator.feed(scene.render(n(f)).unwrap().into(), n(320.0), n(240.0));
        let status = status.unwrap();
        let flag = js_sys::Reflect::get(&status, &"used".into()).unwrap();
        used += usize::from(flag.as_bool().unwrap());
        assert_eq!(num(&status, "frames_seen"), f64::from(f + 1));
        assert_eq!(num(&status, "frames_used"), used as f64);
    }
    (calibrator.estimate().unwrap(), used)
}

/// Pitch, yaw and height errors of an estimate against the camera it should have found.
fn calibration_errors(estimate: &JsValue, truth: &JsValue) -> [f64; 3] {
    let camera = js_sys::Reflect::get(estimate, &"camera".into()).unwrap();
    [
        (num(&camera, "pitch_deg") - num(truth, "pitch_deg")).abs(),
        (num(&camera, "yaw_deg") - num(truth, "yaw_deg")).abs(),
        (num(&camera, "height_m") / num(truth, "height_m") - 1.0).abs(),
    ]
}

#[wasm_bindgen_test]
fn calibrator_recovers_the_scene_camera_from_the_field_of_view() {
    let truth = calibration_camera();
    let mut calibrator = JsCalibrator::new(obj(r#"{"width": 320, "height": 240}"#)).unwrap();
    assert_eq!((calibrator.width(), calibrator.height()), (320, 240));
    assert!(calibrator.estimate().unwrap().is_null(), "no frame yet");
    let (estimate, used) = calibrate_on_highway(&truth, &mut calibrator);
    let [pitch, yaw, height] = calibration_errors(&estimate, &truth);
    console_log!(
        "{}",
        format_args!(
            "calibrator, 60-degree guess: pitch error {pitch:.3} deg, yaw error {yaw:.3} deg, \
             height error {:.2} %, confidence {:.3}, {used} of 300 frames used",
            100.0 * height,
            num(&estimate, "confidence")
        )
    );
    assert!(
        pitch < 0.5 && yaw < 0.5 && height < 0.1,
        "{pitch} {yaw} {height}"
    );
    assert!(num(&estimate, "confidence") > 0.5);
    assert_eq!(num(&estimate, "frames_used"), used as f64);
    assert_eq!(num(&estimate, "frames_seen"), 300.0);
    let known = js_sys::Reflect::get(&estimate, &"intrinsics_known".into()).unwrap();
    assert_eq!(known.as_bool(), Some(false));
    // What the last frame showed: the two ego lines meeting at the vanishing point.
    let observation = calibrator.observation().unwrap();
    let lines: js_sys::Array = js_sys::Reflect::get(&observation, &"lines".into())
        .unwrap()
        .dyn_into()
        .unwrap();
    let ego = js_sys::Array::from(&js_sys::Reflect::get(&observation, &"ego".into()).unwrap());
    assert_eq!(ego.length(), 2);
    assert!(lines.length() >= 2);
    assert!(calibrator.marking_pixels().length() > 100);
    // The estimated camera goes straight into a tracker.
    let camera = js_sys::Reflect::get(&estimate, &"camera".into()).unwrap();
    let config = obj("{}");
    js_sys::Reflect::set(&config, &"camera".into(), &camera).unwrap();
    let mut tracker = JsTracker::new("lee-cpf".into(), config).unwrap();
    let options = obj(r#"{"seed": 1}"#);
    js_sys::Reflect::set(&options, &"camera".into(), &truth).unwrap();
    let mut scene = JsScene::new("highway-straight".into(), options).unwrap();
    let rgba = scene.render(n(0)).unwrap().to_vec();
    assert!(tracker.step(px(&rgba), Some(n(320)), Some(n(240))).is_ok());
    // Reset forgets everything.
    calibrator.reset();
    assert!(calibrator.estimate().unwrap().is_null());
}

#[wasm_bindgen_test]
fn calibrator_recovers_the_scene_camera_with_known_intrinsics() {
    // The Caltech camera (the simulator's default: fx 309, fy 344, 14 degrees down, 2.18 m)
    // at half size: its intrinsics given, so the focal lengths are not guessed.
    let truth = obj(
        r#"{"width": 320, "height": 240, "fx": 154.7181, "fy": 172.10805, "cx": 158.7017,
            "cy": 128.0176, "height_m": 2.1798, "pitch_deg": 14.0, "yaw_deg": -0.5}"#,
    );
    let options = obj(r#"{"width": 320, "height": 240, "lane_width_m": 3.6}"#);
    js_sys::Reflect::set(&options, &"intrinsics".into(), &truth).unwrap();
    let mut calibrator = JsCalibrator::new(options).unwrap();
    let (estimate, used) = calibrate_on_highway(&truth, &mut calibrator);
    let [pitch, yaw, height] = calibration_errors(&estimate, &truth);
    console_log!(
        "{}",
        format_args!(
            "calibrator, intrinsics known: pitch error {pitch:.3} deg, yaw error {yaw:.3} deg, \
             height error {:.2} %, confidence {:.3}, {used} of 300 frames used",
            100.0 * height,
            num(&estimate, "confidence")
        )
    );
    assert!(
        pitch < 0.5 && yaw < 0.5 && height < 0.1,
        "{pitch} {yaw} {height}"
    );
    let known = js_sys::Reflect::get(&estimate, &"intrinsics_known".into()).unwrap();
    assert_eq!(known.as_bool(), Some(true));
    let camera = js_sys::Reflect::get(&estimate, &"camera".into()).unwrap();
    assert_eq!(num(&camera, "fy"), 172.10805);
}

#[wasm_bindgen_test]
fn calibrator_rejects_bad_options_by_name() {
    let m = |options: JsValue| message(JsCalibrator::new(options));
    let e = m(JsValue::from_str("640x480"));
    assert!(e.contains("must be an object"), "{e}");
    let e = m(obj("[320, 240]"));
    assert!(e.contains("must be an object"), "{e}");
    let e = m(JsValue::UNDEFINED);
    assert!(e.contains("calibrator options is missing"), "{e}");
    let e = m(obj(r#"{"width": 320}"#));
    assert!(e.contains("missing field `height`"), "{e}");
    let e = m(obj(r#"{"width": 320, "height": 240, "lane_widht_m": 3.5}"#));
    assert!(e.contains("unknown field `lane_widht_m`"), "{e}");
    let e = m(obj(r#"{"width": "320", "height": 240}"#));
    assert!(e.contains("invalid type") && e.contains("320"), "{e}");
    let e = m(with(
        r#"{"width": 320, "height": 240}"#,
        "hfov_deg",
        JsValue::from_f64(f64::NAN),
    ));
    assert!(
        e.contains("invalid calibrator options: hfov_deg is NaN"),
        "{e}"
    );
    let e = m(obj(r#"{"width": 320, "height": 240, "hfov_deg": 200}"#));
    assert!(e.contains("hfov_deg") && e.contains("20 to 150"), "{e}");
    let e = m(obj(r#"{"width": 320, "height": 240, "stable_frames": 0}"#));
    assert!(e.contains("stable_frames"), "{e}");
    let e = m(obj(r#"{"width": 0, "height": 240}"#));
    assert!(e.contains("0x240"), "{e}");
    let e = m(obj(r#"{"width": 100000, "height": 240}"#));
    assert!(e.contains("at most"), "{e}");
    let e = m(obj(r#"{"width": 20, "height": 10}"#));
    assert!(e.contains("at least 32x16"), "{e}");
    let e = m(with(
        r#"{"width": 640, "height": 480}"#,
        "intrinsics",
        with(CAMERA, "fx", JsValue::from_f64(-1.0)),
    ));
    assert!(e.contains("fx"), "{e}");
    let e = m(with(
        r#"{"width": 640, "height": 480}"#,
        "intrinsics",
        calibration_camera(),
    ));
    assert!(e.contains("320x240") && e.contains("640x480"), "{e}");
}

#[wasm_bindgen_test]
fn calibrator_rejects_bad_frames_and_keeps_working() {
    let mut calibrator = JsCalibrator::new(obj(r#"{"width": 320, "height": 240}"#)).unwrap();
    let mut scene = JsScene::new(
        "highway-straight".into(),
        obj(r#"{"width": 320, "height": 240, "seed": 1}"#),
    )
    .unwrap();
    let frame = || js_sys::Uint8Array::new_with_length(320 * 240 * 4);
    let e = message(calibrator.feed(
        js_sys::Uint8Array::new_with_length(12).into(),
        n(320.0),
        n(240.0),
    ));
    assert!(e.contains("320x240"), "{e}");
    let e = message(calibrator.feed(frame().into(), n(640.0), n(480.0)));
    assert!(e.contains("640x480") && e.contains("320x240"), "{e}");
    let e = message(calibrator.feed(frame().into(), n(f64::NAN), n(240.0)));
    assert!(e.contains("width is NaN"), "{e}");
    let e = message(calibrator.feed(frame().into(), n(320.5), n(240.0)));
    assert!(e.contains("whole number"), "{e}");
    let e = message(calibrator.feed(frame().into(), n(320.0), n(0.0)));
    assert!(e.contains("height is 0"), "{e}");
    let e = message(calibrator.feed(frame().into(), n(320.0), n(1e9)));
    assert!(e.contains("16384"), "{e}");
    let e = message(calibrator.feed(JsValue::from_str("pixels"), n(320.0), n(240.0)));
    assert!(
        e.contains("Uint8Array") && e.contains("not the string"),
        "{e}"
    );
    let e = message(calibrator.feed(JsValue::NULL, n(320.0), n(240.0)));
    assert!(e.contains("Uint8Array"), "{e}");
    let e = message(calibrator.feed(
        js_sys::Float32Array::new_with_length(320 * 240 * 4).into(),
        n(320.0),
        n(240.0),
    ));
    assert!(e.contains("Uint8Array"), "{e}");
    // Nothing was counted, and frames still go in: a Uint8ClampedArray (ImageData.data) and a
    // Uint8Array view into a larger buffer.
    for f in 0..3 {
        let status = calibrator
            .feed(scene.render(n(f)).unwrap().into(), n(320.0), n(240.0))
            .unwrap();
        assert_eq!(num(&status, "frames_seen"), f64::from(f + 1));
    }
    let pixels = scene.render(n(3)).unwrap();
    let big = js_sys::Uint8Array::new_with_length(pixels.length() + 8);
    big.subarray(8, pixels.length() + 8)
        .set(&js_sys::Uint8Array::new(&pixels.buffer()), 0);
    let view = big.subarray(8, pixels.length() + 8);
    let status = calibrator.feed(view.into(), n(320.0), n(240.0)).unwrap();
    assert_eq!(num(&status, "frames_seen"), 4.0);
    let ego = js_sys::Reflect::get(&status, &"ego_found".into()).unwrap();
    assert_eq!(ego.as_bool(), Some(true), "the markings are found");
    let options = calibrator.options().unwrap();
    assert_eq!(num(&options, "lane_width_m"), 3.6);
    assert_eq!(num(&options, "stable_frames"), 5.0);
}

/// The calibrator's per-pixel pass runs four pixels per `simd128` operation in WebAssembly
/// (`lanepf::calib::marking_pixels`); over every colour it gives the bytes of the per-pixel
/// formulas.
#[wasm_bindgen_test]
fn the_simd_marking_pixels_match_the_formulas_for_every_colour() {
    use lanepf::calib::marking_pixels::{marking_pixel, marking_pixels};
    assert!(
        cfg!(target_feature = "simd128"),
        "the wasm build runs the simd128 path (.cargo/config.toml)"
    );
    let mut rgba = Vec::with_capacity(256 * 256 * 4);
    let (mut m, mut s) = (vec![0; 256 * 256], vec![0; 256 * 256]);
    for r in 0..=255u8 {
        rgba.clear();
        for g in 0..=255u8 {
            for b in 0..=255u8 {
                rgba.extend_from_slice(&[r, g, b, g ^ b]);
            }
        }
        marking_pixels(&rgba, &mut m, &mut s);
        for (i, p) in rgba.chunks_exact(4).enumerate() {
            assert_eq!(
                (m[i], s[i]),
                marking_pixel(p[0], p[1], p[2]),
                "rgb {:?}",
                &p[..3]
            );
        }
    }
}
