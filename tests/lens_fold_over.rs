//! Boundaries seen through a strongly distorting lens (the bundled clip's Udacity camera, whose
//! radial model folds over at a normalised radius of about 1.15): road points a few metres
//! ahead, far outside the field of view, must not be projected back into the image, so that no
//! tracker draws a two-point stub instead of the boundary.

use lanepf::camera::Camera;
use lanepf::synth::{scenario, Eye, Scene};
use lanepf::trackers::{self, TrackerConfig, TRACKER_IDS};

#[test]
fn no_tracker_outputs_a_stub_boundary_through_the_udacity_lens() {
    let text = std::fs::read_to_string("www/clips/udacity-project-640x360.camera.json").unwrap();
    let camera = Camera::from_json_str(&text).unwrap();
    let file = camera.to_file();
    // A point 2 m ahead and 1.8 m to the side is far outside the view: not projected at all.
    assert!(camera.road_to_pixel(2.0, 1.8).is_none());
    assert!(camera.road_to_pixel(20.0, 1.8).is_some());
    let mut config = scenario("highway-straight").unwrap();
    config.frames = 30;
    let mut scene = Scene::new(config, camera.clone(), 2).unwrap();
    let (w, h) = (scene.width(), scene.height());
    let mut frames = Vec::new();
    for i in 0..30 {
        let mut rgba = vec![0u8; w * h * 4];
        scene.render(i, Eye::Left, &mut rgba, None).unwrap();
        frames.push(rgba);
    }
    for id in TRACKER_IDS.iter().filter(|id| !id.contains("stereo")) {
        let config = TrackerConfig {
            camera: file.clone(),
            particles: None,
            seed: 1,
            options: Default::default(),
        };
        let mut tracker = trackers::create(id, &config).unwrap();
        let mut valid = 0;
        for (i, f) in frames.iter().enumerate() {
            let e = tracker.step(f, w, h).unwrap();
            if !e.valid {
                continue;
            }
            valid += 1;
            for b in &e.boundaries {
                let rows = b.points.first().unwrap()[1] - b.points.last().unwrap()[1];
                assert!(
                    b.points.len() >= 3 && rows > 20.0,
                    "{id} frame {i}: {:?} boundary of {} points over {rows:.0} rows: {:?}",
                    b.role,
                    b.points.len(),
                    b.points
                );
            }
        }
        assert!(valid >= 10, "{id}: only {valid} of 30 frames valid");
    }
}
