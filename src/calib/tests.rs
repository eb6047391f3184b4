//! The calibrator against the simulator's known cameras, and its input checks.

use super::*;
use crate::camera::{Camera, CameraFile};
use crate::synth::{drawn_camera, scenario, Eye, Scene};

/// Feeds `frames` frames of `name` seen through `truth` and returns the estimate and the car's
/// mean heading relative to the lane over those frames, degrees.
fn calibrate(name: &str, truth: &CameraFile, seed: u64, frames: u32) -> (CalibrationEstimate, f64) {
    let mut config = scenario(name).unwrap();
    config.frames = frames;
    let mut scene = Scene::new(config, Camera::from_file(truth).unwrap(), seed).unwrap();
    let mut cal = Calibrator::new(640, 480, Some(truth), CalibratorConfig::default()).unwrap();
    let mut rgba = vec![0u8; 640 * 480 * 4];
    let mut heading = 0.0;
    for i in 0..frames {
        scene.render(i, Eye::Left, &mut rgba, None).unwrap();
        cal.feed_rgba(&rgba, 640, 480).unwrap();
        heading += scene.truth(i).heading_rad;
    }
    let mean_heading = crate::math::rad_to_deg(heading / frames as f64);
    (cal.estimate().expect("an estimate"), mean_heading)
}

#[test]
fn pose_and_height_are_recovered_for_drawn_cameras() {
    // Scene lane width 3.6 m, the prior's default, so the height is checked without bias.
    for (seed, name) in [
        (11, "highway-straight"),
        (12, "multi-lane"),
        (13, "shadows"),
    ] {
        let truth = drawn_camera(seed);
        let (est, heading) = calibrate(name, &truth, seed, 100);
        let c = &est.camera;
        // The vanishing point shows the yaw relative to the lane: the mount's yaw minus the
        // car's mean heading over the frames (the scenes sway a few tenths of a degree).
        let (dp, dy) = (
            c.pitch_deg - truth.pitch_deg,
            c.yaw_deg - (truth.yaw_deg - heading),
        );
        let dh = (c.height_m - truth.height_m) / truth.height_m;
        let what = format!("seed {seed} {name}: {est:?} vs {truth:?}, heading {heading}");
        assert!(
            dp.abs() < 0.25 && dy.abs() < 0.25 && dh.abs() < 0.05,
            "{what}"
        );
        // 30 used frames, of which the straighter 15 count: min(1, 15 / 30) caps it at 0.5.
        assert!(est.frames_used >= 20 && est.confidence > 0.3, "{what}");
        assert!(est.intrinsics_known && c.roll_deg == 0.0);
        assert_eq!(
            (c.fx, c.cy),
            (truth.fx, truth.cy),
            "given intrinsics are kept"
        );
    }
}

#[test]
fn bad_input_is_refused_and_the_calibrator_keeps_working() {
    let truth = drawn_camera(11);
    let bad = |c: CalibratorConfig| Calibrator::new(640, 480, None, c).unwrap_err().to_string();
    let base = CalibratorConfig::default();
    assert!(bad(CalibratorConfig {
        lane_width_m: f64::NAN,
        ..base
    })
    .contains("lane_width_m"));
    assert!(bad(CalibratorConfig {
        hfov_deg: 180.0,
        ..base
    })
    .contains("hfov_deg"));
    assert!(bad(CalibratorConfig {
        stable_frames: 0,
        ..base
    })
    .contains("stable_frames"));
    assert!(bad(CalibratorConfig {
        max_bend_px: 1e300,
        ..base
    })
    .contains("max_bend_px"));
    assert!(Calibrator::new(0, 480, None, base).is_err());
    assert!(
        Calibrator::new(20, 10, None, base).is_err(),
        "too small to find lines in"
    );
    let err = Calibrator::new(320, 240, Some(&truth), base).unwrap_err();
    assert!(err.to_string().contains("640x480"), "{err}");

    let mut cal = Calibrator::new(640, 480, Some(&truth), base).unwrap();
    assert!(cal.feed_rgba(&[0; 16], 2, 2).is_err());
    assert!(cal.feed_rgba(&[0; 100], 640, 480).is_err());
    // A blank frame shows no lines and gives no estimate, and does not count as used.
    let blank = vec![90u8; 640 * 480 * 4];
    let obs = cal.feed_rgba(&blank, 640, 480).unwrap();
    assert!(obs.lines.is_empty() && !obs.used);
    assert!(cal.estimate().is_none());
}

#[test]
fn a_wrong_lane_width_prior_scales_the_height_and_nothing_else() {
    // h = W / w_1: the same frames with a prior 10 % wider give a height 10 % larger.
    let truth = drawn_camera(14);
    let mut config = scenario("highway-straight").unwrap();
    config.frames = 60;
    let mut scene = Scene::new(config, Camera::from_file(&truth).unwrap(), 14).unwrap();
    let wide = CalibratorConfig {
        lane_width_m: 3.96,
        ..CalibratorConfig::default()
    };
    let mut a = Calibrator::new(640, 480, Some(&truth), CalibratorConfig::default()).unwrap();
    let mut b = Calibrator::new(640, 480, Some(&truth), wide).unwrap();
    let mut rgba = vec![0u8; 640 * 480 * 4];
    for i in 0..60 {
        scene.render(i, Eye::Left, &mut rgba, None).unwrap();
        a.feed_rgba(&rgba, 640, 480).unwrap();
        b.feed_rgba(&rgba, 640, 480).unwrap();
    }
    let (a, b) = (a.estimate().unwrap().camera, b.estimate().unwrap().camera);
    assert!((b.height_m / a.height_m - 1.1).abs() < 1e-9, "{a:?} {b:?}");
    assert_eq!((a.pitch_deg, a.yaw_deg), (b.pitch_deg, b.yaw_deg));
}

/// A camera pitched 26 deg down (beyond [`PITCH_RANGE_DEG`]) is not a dash-cam's mount: the
/// calibrator refuses to believe a road vanishes that high and gives no estimate (a pair of
/// tree trunks or a truck's edges meets as high as that); the same road seen at 14 deg, as
/// Caltech's camera is, is measured.
#[test]
fn vanishing_points_no_mount_could_see_are_refused() {
    let feed = |pitch_deg: f64| {
        let mut truth = drawn_camera(12);
        truth.pitch_deg = pitch_deg;
        let mut config = scenario("highway-straight").unwrap();
        config.frames = 40;
        let mut scene = Scene::new(config, Camera::from_file(&truth).unwrap(), 12).unwrap();
        let mut cal = Calibrator::new(640, 480, Some(&truth), CalibratorConfig::default()).unwrap();
        let mut rgba = vec![0u8; 640 * 480 * 4];
        for i in 0..40 {
            scene.render(i, Eye::Left, &mut rgba, None).unwrap();
            cal.feed_rgba(&rgba, 640, 480).unwrap();
        }
        cal.estimate()
    };
    let steep = feed(26.0);
    assert!(steep.is_none(), "{steep:?}");
    let usual = feed(14.0).expect("an estimate at 14 deg");
    assert!((usual.camera.pitch_deg - 14.0).abs() < 0.5, "{usual:?}");
}
