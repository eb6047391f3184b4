//! Tests every tracker of the registry passes.

use super::*;

const CAMERA: &str = r#"{"width": 640, "height": 480, "fx": 309.4, "fy": 344.2, "cx": 317.9,
    "cy": 256.5, "height_m": 2.18, "pitch_deg": 14.0, "yaw_deg": 0.0, "roll_deg": 0.0}"#;

#[test]
fn config_defaults_and_validation() {
    let c = TrackerConfig::from_json_str(&format!(r#"{{"camera": {CAMERA}}}"#)).unwrap();
    assert_eq!((c.particles, c.seed), (None, 1));
    assert_eq!(c.particles_or(500), 500);
    assert!(c.validate().is_ok());
    let c = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {CAMERA}, "particles": 0, "sigma": 2}}"#
    ))
    .unwrap();
    let Options::ByName(options) = &c.options else {
        panic!("JSON gives options by name")
    };
    assert_eq!(options["sigma"], serde_json::json!(2));
    let e = c.validate().unwrap_err().to_string();
    assert!(e.contains("`particles` = 0"), "{e}");
    let e = TrackerConfig::from_json_str(r#"{"particles": 10}"#).unwrap_err();
    assert!(e.to_string().contains("missing field `camera`"), "{e}");
}

#[test]
fn unknown_ids_list_what_exists() {
    let c = TrackerConfig::from_json_str(&format!(r#"{{"camera": {CAMERA}}}"#)).unwrap();
    let e = create("kalman-magic", &c).err().unwrap();
    assert!(matches!(e, Error::UnknownTracker { .. }));
    assert!(e
        .to_string()
        .starts_with("unknown tracker `kalman-magic`; available: "));
}

/// A 200-particle configuration for the simulator's default 320x240 camera and scenario
/// `name` (seed 1).
fn fixture(name: &str) -> (TrackerConfig, crate::synth::Scene) {
    use crate::synth::{default_camera, scenario, Scene};
    let camera = default_camera(320, 240).unwrap();
    let c = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {}, "particles": 200}}"#,
        serde_json::to_string(&camera.to_file()).unwrap()
    ))
    .unwrap();
    (c, Scene::new(scenario(name).unwrap(), camera, 1).unwrap())
}

#[test]
fn every_tracker_steps_one_step_at_a_time_to_the_same_result() {
    use crate::synth::Eye;
    let (c, mut scene) = fixture("highway-curve");
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut right = vec![0; 320 * 240 * 4];
    for id in TRACKER_IDS {
        let mut whole = create(id, &c).unwrap();
        let mut stepped = create(id, &c).unwrap();
        let n = stepped.step_names().len();
        assert!(n >= 3, "{id}: {n} steps");
        assert!(stepped.advance().is_err(), "{id}: no frame in progress");
        for f in 0..3 {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            if whole.is_stereo() {
                scene.render(f, Eye::Right, &mut right, None).unwrap();
                whole.set_right(&right, 320, 240).unwrap();
                stepped.set_right(&right, 320, 240).unwrap();
            } else {
                assert!(whole.set_right(&right, 320, 240).is_err(), "{id}");
            }
            let expected = whole.step(&rgba, 320, 240).unwrap();
            stepped.begin_frame(&rgba, 320, 240).unwrap();
            assert!(
                stepped.resamplings().is_empty(),
                "{id}: begin resamples nothing"
            );
            let mut decisions = Vec::new();
            let results: Vec<_> = (0..n)
                .map(|_| {
                    let r = stepped.advance().unwrap();
                    decisions.extend_from_slice(stepped.resamplings());
                    r
                })
                .collect();
            assert!(results[..n - 1].iter().all(Option::is_none), "{id}");
            assert_eq!(results[n - 1].as_ref(), Some(&expected), "{id} frame {f}");
            assert_eq!(stepped.particles(), whole.particles(), "{id} frame {f}");
            // The same resampling decisions, step by step as for the whole frame; after the
            // first frame every tracker resamples.
            assert_eq!(decisions, whole.resamplings(), "{id} frame {f}");
            assert!(f == 0 || !decisions.is_empty(), "{id} frame {f}");
        }
    }
}

/// The typed result fields read from `state`: every tracker's ESS (at most its particle count),
/// adachi-mmpf's model probabilities (summing to 1) and nobody else's; the truth has neither.
#[test]
fn every_tracker_reports_its_ess_and_adachi_its_model_probabilities() {
    use crate::synth::Eye;
    let (c, mut scene) = fixture("highway-curve");
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut right = vec![0; 320 * 240 * 4];
    for id in TRACKER_IDS {
        let mut tracker = create(id, &c).unwrap();
        for f in 0..2 {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            if tracker.is_stereo() {
                scene.render(f, Eye::Right, &mut right, None).unwrap();
                tracker.set_right(&right, 320, 240).unwrap();
            }
            let e = tracker.step(&rgba, 320, 240).unwrap();
            let n = (tracker.particles().len() / tracker.particle_stride()) as f64;
            let ess = e.ess().unwrap_or_else(|| panic!("{id}: no ESS"));
            assert!(ess > 0.0 && ess <= n + 1e-6, "{id}: ESS {ess} of {n}");
            match e.model_probabilities() {
                Some(p) => {
                    assert_eq!(*id, "adachi-mmpf");
                    assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{p:?}");
                }
                None => assert_ne!(*id, "adachi-mmpf"),
            }
            let truth = crate::trackers::scene_truth(&scene, f);
            assert_eq!((truth.ess(), truth.model_probabilities()), (None, None));
        }
    }
}

#[test]
fn every_tracker_draws_its_particles_around_its_estimate() {
    use crate::lane::{Boundary, Role};
    use crate::synth::Eye;
    let (c, mut scene) = fixture("highway-straight");
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut right = vec![0; 320 * 240 * 4];
    for id in TRACKER_IDS {
        let mut t = create(id, &c).unwrap();
        let mut estimate = None;
        for f in 0..10 {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            if t.is_stereo() {
                scene.render(f, Eye::Right, &mut right, None).unwrap();
                t.set_right(&right, 320, 240).unwrap();
            }
            estimate = Some(t.step(&rgba, 320, 240).unwrap());
        }
        let estimate = estimate.unwrap();
        let cloud = t.particles().len() / t.particle_stride();
        let drawn = t.hypotheses(60);
        assert_eq!(drawn.len(), cloud.min(60), "{id}");
        assert!(t.hypotheses(0).is_empty(), "{id}");
        let at_10m = |b: &[Boundary]| {
            b.iter()
                .find(|b| b.role == Role::EgoLeft)
                .and_then(|b| b.y_at(10.0))
        };
        let expected = at_10m(&estimate.boundaries).unwrap();
        let (mut sum, mut total, mut lo, mut hi) = (0.0, 0.0, f64::MAX, f64::MIN);
        for h in &drawn {
            assert!(
                h.weight.is_finite() && (0.0..=1.0).contains(&h.weight),
                "{id}"
            );
            for b in &h.boundaries {
                assert!(b
                    .points
                    .iter()
                    .all(|p| (0.0..=319.0).contains(&p[0]) && (0.0..=239.0).contains(&p[1])));
            }
            if let Some(y) = at_10m(&h.boundaries) {
                sum += h.weight * y;
                total += h.weight;
                (lo, hi) = (lo.min(y), hi.max(y));
            }
        }
        // The weighted cloud sits on the estimate, and it is a cloud, not one line.
        // (Not for liu-ppf-nokernel, the paper's weak baseline: its cloud holds several
        // boundaries at once, 0.7-3.6 m left, so the roles differ between its particles.)
        let mean = sum / total;
        assert!(
            *id == liu::ID_NOKERNEL || (mean - expected).abs() < 0.25,
            "{id}: cloud {mean} vs estimate {expected}"
        );
        assert!(hi - lo > 0.005, "{id}: every drawn particle at {lo}");
    }
}

/// On the first frame of drawn `highway-straight` members, scene seeds 1-3 (each its own road
/// and camera, 320x240), every tracker's main cue peaks on the true boundaries.
#[test]
fn every_tracker_shows_its_main_cue_on_the_true_boundaries() {
    for seed in 1..=3 {
        main_cue_on_the_true_boundaries(seed);
    }
}

fn main_cue_on_the_true_boundaries(seed: u64) {
    use crate::lane::Role;
    use crate::synth::Eye;
    let (member, mut scene) = fresh_roads::member_scene("highway-straight", seed, 320, 240, 1);
    let c = fresh_roads::config_for(&scene, r#", "particles": 200"#);
    let about = fresh_roads::describe(&member);
    // Half the span of a double left edge beside the car (0 for other lines).
    let double = fresh_roads::inner_line_m("highway-straight", seed);
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut right = vec![0; 320 * 240 * 4];
    scene.render(0, Eye::Left, &mut rgba, None).unwrap();
    scene.render(0, Eye::Right, &mut right, None).unwrap();
    let truth = crate::trackers::scene_truth(&scene, 0);
    // Lateral positions y of the true boundaries (`ego`: only the ego lane's) x metres
    // ahead.
    let true_y = |x: f64, ego: bool| -> Vec<f64> {
        truth
            .boundaries
            .iter()
            .filter(|b| !ego || matches!(b.role, Role::EgoLeft | Role::EgoRight))
            .filter_map(|b| b.y_at(x))
            .collect()
    };
    let near = |y: f64, x: f64| true_y(x, false).iter().any(|t| (t - y).abs() < 0.3);
    // liu-ppf-nokernel is the paper's deliberately weak baseline: its cue, the brightness
    // of edge pixels, peaks on bright asphalt as well (liu-ppf shows the same pixels with
    // their orientation kernels).
    for id in TRACKER_IDS.iter().filter(|&&id| id != liu::ID_NOKERNEL) {
        let mut t = create(id, &c).unwrap();
        if t.is_stereo() {
            t.set_right(&right, 320, 240).unwrap();
        }
        t.step(&rgba, 320, 240).unwrap();
        let layers = t.layers();
        assert!(!layers.is_empty(), "{id}");
        match &layers[0] {
            Layer::Histogram {
                start,
                step,
                values,
                ..
            } => {
                // The strongest bin (rho = -y) lies on a boundary.
                let k = (0..values.len())
                    .max_by(|&a, &b| values[a].total_cmp(&values[b]))
                    .unwrap();
                let rho = start + (k as f64 + 0.5) * step;
                assert!(near(-rho, 14.0), "{about}: {id}: peak at rho {rho}");
            }
            Layer::Grid {
                width,
                height,
                x0,
                y0,
                cell,
                values,
                ..
            } => {
                assert_eq!(values.len(), width * height, "{about}: {id}");
                // Every true boundary inside the map's lateral extent (dashed ones somewhere
                // along the range) reaches the top of the map, and every cell at the top lies
                // on a boundary.
                let (mut found, mut inside, mut boundaries) = (vec![false; 4], vec![false; 4], 0);
                for r in 0..*height {
                    let x = x0 + (r as f64 + 0.5) * cell;
                    let ys = true_y(x, false);
                    boundaries = boundaries.max(ys.len());
                    let row = &values[r * width..(r + 1) * width];
                    for (k, y) in ys.iter().enumerate().take(4) {
                        let c = ((y0 - y) / cell) as usize;
                        inside[k] |= y0 - y >= 0.0 && c < *width;
                        if c < *width
                            && row[c.saturating_sub(2)..(c + 3).min(*width)]
                                .iter()
                                .any(|&v| v > 0.99)
                        {
                            found[k] = true;
                        }
                    }
                    for (c, _) in row.iter().enumerate().filter(|(_, &v)| v > 0.99) {
                        // One cell of slack for the grid's quantisation and the 3 x 3
                        // operators that fill it.
                        // operators that fill it; against every boundary of the road,
                        // including the parts of markings at the image border that the
                        // truth polylines (marking centres in the image) leave out.
                        let y = y0 - (c as f64 + 0.5) * cell;
                        let pose = scene.pose(0);
                        // A double line's paint reaches further from its centre.
                        let on = (0..=scene.road().lanes())
                            .filter_map(|k| Some((k, scene.boundary_y(&pose, k, x)?)))
                            .any(|(k, t)| {
                                (t - y).abs() < 0.3 + cell + if k == 0 { double } else { 0.0 }
                            });
                        assert!(on, "{about}: {id}: maximum at x {x} y {y}");
                    }
                }
                assert!(boundaries >= 2, "{about}: {id}");
                assert!(
                    (0..boundaries.min(4)).all(|k| found[k] || !inside[k]),
                    "{about}: {id}: found {found:?} inside {inside:?}"
                );
            }
            Layer::Plane { .. } => panic!("{id}: the main layer must be on the road"),
        }
    }
}
