//! The demo's camera presets (`www/clips/*.camera.json`, `www/cameras/*.camera.json`, listed in
//! `www/camera-presets.js`) are cameras the library accepts, and the two Udacity 1280x720 files
//! describe one lens: they differ only in the pose each video was filmed with.

use lanepf::camera::Camera;
use std::path::Path;

fn camera_files() -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for dir in ["www/clips", "www/cameras"] {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.to_string_lossy().ends_with(".camera.json") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

fn load(path: &Path) -> Camera {
    let text = std::fs::read_to_string(path).unwrap();
    Camera::from_json_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn every_camera_file_the_demo_offers_loads_and_is_listed() {
    let presets = std::fs::read_to_string("www/camera-presets.js").unwrap();
    let files = camera_files();
    assert!(files.len() >= 6, "{files:?}");
    for path in &files {
        load(path);
        let name = path.file_name().unwrap().to_string_lossy();
        // The 640x360 clip's camera is listed through the clip's own constant (CLIP.camera).
        if name != "udacity-project-640x360.camera.json" {
            assert!(presets.contains(name.as_ref()), "{name} is not a preset");
        }
    }
}

#[test]
fn the_two_udacity_video_cameras_share_the_lens_and_differ_in_pose() {
    let project = load(Path::new("www/clips/udacity-1280x720.camera.json")).to_file();
    let challenge = load(Path::new(
        "www/clips/udacity-challenge-1280x720.camera.json",
    ))
    .to_file();
    let lens = |c: &lanepf::camera::CameraFile| {
        (
            c.width, c.height, c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.p1, c.p2, c.k3,
        )
    };
    assert_eq!(lens(&project), lens(&challenge));
    // Each pose is what `lanepf calibrate` measures over that whole video (www/clips/README.md):
    // 1.2 deg of yaw and 0.8 deg of pitch apart.
    assert!((project.yaw_deg - challenge.yaw_deg).abs() > 1.0);
    assert!((project.pitch_deg - challenge.pitch_deg).abs() > 0.5);
}
