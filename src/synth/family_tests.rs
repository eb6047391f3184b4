//! Every family member, over a range of seeds, is valid, within its ranges and what its name
//! says.

use super::*;
use crate::synth::markings::Pattern;
use crate::synth::road::Road;
use crate::synth::{frame_fingerprint, Eye, Scene};

/// Seeds the properties are checked on.
const SEEDS: std::ops::Range<u64> = 0..40;

fn built(m: &FamilyMember) -> Road {
    m.config.validate().unwrap();
    Road::new(m.config.road.clone(), m.config.road_length()).unwrap()
}

/// Arc lengths of the car over the run, every `step` frames.
fn driven(m: &FamilyMember, road: &Road, step: usize) -> Vec<crate::synth::Pose> {
    (0..m.config.frames)
        .step_by(step)
        .map(|f| m.config.ego.pose(road, f))
        .collect()
}

#[test]
fn every_member_is_valid_and_within_the_shared_ranges() {
    for name in family_names() {
        for seed in SEEDS {
            let m = draw_scenario(name, seed).unwrap();
            let road = built(&m);
            let c = &m.config;
            let widths = std::iter::once(c.road.lane_width_m)
                .chain(c.road.width_changes.iter().map(|w| w.width_m));
            for w in widths {
                assert!((2.8..4.2).contains(&w), "{name} {seed}: width {w}");
            }
            assert!((1..=4).contains(&road.lanes()));
            let styles = [c.markings.outer, c.markings.inner]
                .into_iter()
                .chain(c.markings.overrides.iter().map(|o| o.style));
            for st in styles.filter(|st| st.pattern != Pattern::Curb) {
                assert!((0.10..0.25).contains(&st.width_m), "{name} {seed}: {st:?}");
            }
            assert!(
                c.frames >= 300 && c.frames <= 660,
                "{name} {seed}: {}",
                c.frames
            );
            assert_eq!(draw_scenario(name, seed).unwrap(), m, "{name} {seed}");
        }
        assert_ne!(
            draw_scenario(name, 1).unwrap(),
            draw_scenario(name, 2).unwrap()
        );
    }
}

/// The largest and smallest curvature of the road at the car.
fn curvature_span(m: &FamilyMember, road: &Road) -> (f64, f64) {
    driven(m, road, 5)
        .iter()
        .map(|p| road.at(p.s).curvature)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
            (lo.min(k), hi.max(k))
        })
}

#[test]
fn every_member_is_what_its_name_says() {
    for seed in SEEDS {
        let member = |name: &str| {
            let m = draw_scenario(name, seed).unwrap();
            let road = built(&m);
            (m, road)
        };
        let (m, road) = member("highway-straight");
        let (lo, hi) = curvature_span(&m, &road);
        assert!(lo >= -1e-4 && hi <= 1e-4, "straight {seed}: {lo} {hi}");

        let (m, road) = member("highway-curve");
        let last = m.config.ego.pose(&road, m.config.frames - 1);
        assert!(
            road.at(last.s).curvature.abs() >= 1e-3 - 1e-12,
            "curve {seed}"
        );

        let (m, road) = member("s-curve");
        let (lo, hi) = curvature_span(&m, &road);
        assert!(
            lo <= -1.0 / 520.0 && hi >= 1.0 / 520.0,
            "s-curve {seed}: {lo} {hi}"
        );

        let (m, road) = member("lane-change");
        let lanes: Vec<usize> = driven(&m, &road, 1).iter().map(|p| p.lane).collect();
        let changes: Vec<usize> = (1..lanes.len())
            .filter(|&i| lanes[i] != lanes[i - 1])
            .collect();
        assert_eq!(changes.len(), 2, "lane-change {seed}: {changes:?}");
        assert!(
            changes[1] + 30 < lanes.len(),
            "lane-change {seed}: {changes:?}"
        );

        let (m, _) = member("occlusion");
        let scene = Scene::new(m.config.clone(), m.mount.camera(8, 6).unwrap(), seed).unwrap();
        let dark: Vec<u32> = (0..m.config.frames)
            .filter(|&f| scene.blacked_out(f))
            .collect();
        assert!(dark.len() >= 15, "occlusion {seed}: {}", dark.len());
        assert!(
            dark[dark.len() - 1] + 30 < m.config.frames,
            "occlusion {seed}"
        );
        assert!(m.config.vehicles.len() >= 2);

        let (m, road) = member("shadows");
        let end = driven(&m, &road, 1).last().unwrap().s;
        let shaded = m.config.shadows.iter().any(|s| match *s {
            Shadow::Trees { from_s, .. } | Shadow::Band { from_s, .. } => from_s < end,
        });
        assert!(shaded, "shadows {seed}");

        let (m, road) = member("worn-markings");
        let end = driven(&m, &road, 1).last().unwrap().s + 120.0;
        assert!(
            m.config.markings.wear.iter().any(|w| w.from_s < end),
            "worn {seed}"
        );

        let (m, _) = member("night");
        assert!(m.config.appearance.night && m.config.appearance.noise >= 3.0);

        let (m, road) = member("width-change");
        let poses = driven(&m, &road, 5);
        let widths: Vec<f64> = poses.iter().map(|p| road.lane_width(p.s + 60.0)).collect();
        let span = widths.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
            - widths.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(span >= 0.4, "width-change {seed}: {span}");

        let (m, road) = member("pitch-bumps");
        let pitch = driven(&m, &road, 1)
            .iter()
            .map(|p| p.pitch_offset.abs())
            .fold(0.0, f64::max);
        assert!(pitch >= 0.5f64.to_radians(), "pitch-bumps {seed}: {pitch}");
        assert!(m.config.vertical.curvature.abs() >= 2e-4);

        let (m, road) = member("multi-lane");
        let configs: Vec<(bool, bool)> = driven(&m, &road, 1)
            .iter()
            .map(|p| {
                (
                    p.lane > 0 && road.lane_exists(p.lane - 1, p.s),
                    road.lane_exists(p.lane + 1, p.s),
                )
            })
            .collect();
        assert!(
            configs.windows(2).any(|w| w[0] != w[1]),
            "multi-lane {seed}: the lane configuration never changes"
        );

        let (m, road) = member("urban");
        let (lo, hi) = curvature_span(&m, &road);
        assert!(lo.abs().max(hi.abs()) >= 1.0 / 250.0 - 1e-9, "urban {seed}");
        assert!(m.config.markings.has_curbs());

        let r = draw_scenario(RANDOM_SCENARIO, seed).unwrap();
        assert_eq!(r, draw_scenario(r.scenario, seed).unwrap());
    }
    // The random family mixes all of them.
    let picked: std::collections::BTreeSet<&str> = (0..200)
        .map(|s| draw_scenario(RANDOM_SCENARIO, s).unwrap().scenario)
        .collect();
    assert_eq!(picked.len(), SCENARIOS.len());
}

#[test]
fn reference_members_are_the_fixed_roads_and_names_are_checked() {
    for (name, _) in SCENARIOS {
        let r = reference_member(name, 1).unwrap();
        assert_eq!(r.config, scenario(name).unwrap());
        assert_eq!(r.mount, CameraMount::REFERENCE);
    }
    assert!(reference_member(RANDOM_SCENARIO, 1).is_err());
    let e = draw_scenario("moon", 1).unwrap_err().to_string();
    assert!(
        e.contains("unknown scenario `moon`") && e.contains("random"),
        "{e}"
    );
}

#[test]
fn a_member_renders_the_golden_fingerprint() {
    use crate::goldens::{FAMILY_FINGERPRINT, FINGERPRINT_MEMBER};
    let m = draw_scenario(FINGERPRINT_MEMBER.0, FINGERPRINT_MEMBER.1).unwrap();
    let mut scene = m.scene(160, 120).unwrap();
    let mut rgba = vec![0; 160 * 120 * 4];
    scene
        .render(FINGERPRINT_MEMBER.2, Eye::Left, &mut rgba, None)
        .unwrap();
    let got = frame_fingerprint(&rgba);
    assert_eq!(got, FAMILY_FINGERPRINT, "{got:#x}");
}

/// Half the ego car's width, and how far its body reaches ahead of and behind the camera,
/// metres (a 4.5 m car with the camera 1 m behind its front).
const EGO_HALF_WIDTH_M: f64 = 0.9;
const EGO_AHEAD_M: f64 = 1.0;
const EGO_BEHIND_M: f64 = 3.5;

/// The first frame at which a vehicle of `config` overlaps the ego car on the road (in arc
/// length and lateral position; every 2nd frame), if any.
fn first_collision(config: &SceneConfig) -> Option<(u32, usize)> {
    let road = Road::new(config.road.clone(), config.road_length()).unwrap();
    (0..config.frames).step_by(2).find_map(|f| {
        let p = config.ego.pose(&road, f);
        let t = f as f64 / config.ego.fps;
        config.vehicles.iter().enumerate().find_map(|(k, v)| {
            let rear = v.start_s + v.speed_mps * t;
            let mid = rear + v.size_m[0] / 2.0;
            let d = road.lane_centre(v.lane, mid) + v.offset_m;
            let along = rear < p.s + EGO_AHEAD_M && rear + v.size_m[0] > p.s - EGO_BEHIND_M;
            let across = (d - p.d).abs() < v.size_m[1] / 2.0 + EGO_HALF_WIDTH_M;
            (along && across).then_some((f, k))
        })
    })
}

#[test]
fn no_vehicle_drives_or_parks_through_the_ego_car() {
    let mut collisions = Vec::new();
    for name in family_names() {
        for seed in SEEDS {
            let m = draw_scenario(name, seed).unwrap();
            if let Some(c) = first_collision(&m.config) {
                collisions.push(format!(
                    "{name} seed {seed}: frame {}, vehicle {}",
                    c.0, c.1
                ));
            }
        }
        if let Some(c) = scenario(name).ok().and_then(|r| first_collision(&r)) {
            collisions.push(format!("{name} reference: frame {}, vehicle {}", c.0, c.1));
        }
    }
    assert!(collisions.is_empty(), "{collisions:#?}");
}
