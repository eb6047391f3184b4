//! The command-line tool, run as a user would: files in, files and exit codes out.

#![cfg(feature = "cli")]

use std::path::{Path, PathBuf};
use std::process::Command;

fn lanepf(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lanepf"))
        .args(args)
        .output()
        .expect("the lanepf binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lanepf-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn files(dir: &Path) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| d.count())
}

#[test]
fn synth_writes_frames_stereo_disparity_camera_and_truth() {
    let out = temp("synth");
    let o = out.to_str().unwrap();
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "lane-change",
        "--seed",
        "4",
        "--frames",
        "3",
        "--width",
        "160",
        "--height",
        "120",
        "--stereo",
        "--out",
        o,
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(files(&out.join("frames")), 3);
    assert_eq!(files(&out.join("right")), 3);
    assert_eq!(files(&out.join("disparity")), 3);
    let camera = lanepf::camera::Camera::load(&out.join("camera.json")).unwrap();
    assert_eq!((camera.width(), camera.height()), (160, 120));
    let gt = std::fs::read_to_string(out.join("gt.jsonl")).unwrap();
    let lines: Vec<lanepf::lane::LaneEstimate> = gt
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[2].frame, "000002.png");
    assert!(lines[0].boundaries.len() >= 2 && lines[0].state.contains_key("danescu.w0"));
    // The disparity of the bottom row (road a few metres ahead) is positive and finite.
    let (d, w, h) = lanepf::image::read_disparity_png(&out.join("disparity/000000.png")).unwrap();
    assert_eq!((w, h), (160, 120));
    assert!(d[119 * 160 + 80] > 1.0 && d[0] == 0.0, "sky has none");
    // Same seed, same frames.
    let again = temp("synth-again");
    lanepf(&[
        "synth",
        "--scenario",
        "lane-change",
        "--seed",
        "4",
        "--frames",
        "1",
        "--width",
        "160",
        "--height",
        "120",
        "--out",
        again.to_str().unwrap(),
    ]);
    let a = std::fs::read(out.join("frames/000000.png")).unwrap();
    let b = std::fs::read(again.join("frames/000000.png")).unwrap();
    assert_eq!(a, b);
    // scene.json says what the seed drew: a member of the lane-change family, its camera.
    let scene: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("scene.json")).unwrap()).unwrap();
    assert_eq!(scene["family"], "lane-change");
    assert_eq!(
        scene["scene"]["ego"]["lane_changes"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let member = lanepf::synth::draw_scenario("lane-change", 4).unwrap();
    assert!((camera.height_m() - member.mount.height_m).abs() < 1e-9);
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&again).unwrap();
}

#[test]
fn errors_are_one_clear_line_and_a_failure_status() {
    let (code, _, err) = lanepf(&["synth", "--scenario", "moon", "--out", "/tmp/never"]);
    assert_eq!(code, 1);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("unknown scenario `moon`") && err.contains("urban"),
        "{err}"
    );

    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "nope",
        "--camera",
        "/no/camera.json",
        "--frames",
        "/tmp",
        "--out",
        "/tmp/x.jsonl",
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("/no/camera.json"), "{err}");

    // A real camera but an unknown tracker: the message lists what exists.
    let dir = temp("track");
    std::fs::create_dir_all(&dir).unwrap();
    let cam = dir.join("camera.json");
    std::fs::write(
        &cam,
        r#"{"width": 64, "height": 48, "fx": 50, "fy": 50, "cx": 32, "cy": 24, "height_m": 1.5, "pitch_deg": 3}"#,
    )
    .unwrap();
    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "nope",
        "--camera",
        cam.to_str().unwrap(),
        "--frames",
        dir.to_str().unwrap(),
        "--out",
        dir.join("o.jsonl").to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("unknown tracker `nope`; available:"), "{err}");
    assert!(!err.contains("panicked"));

    let (code, _, err) = lanepf(&["bench", "--tracker", "nope", "--frames", "1"]);
    assert_eq!(code, 1);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("adachi-mmpf"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bench_leaves_warmup_frames_untimed_and_takes_the_motion() {
    let (code, out, err) = lanepf(&[
        "bench",
        "--tracker",
        "danescu-mono",
        "--frames",
        "3",
        "--warmup",
        "2",
        "--motion",
        "--width",
        "160",
        "--height",
        "120",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(rows.as_array().unwrap().len(), 1, "{out}");
    assert_eq!(rows[0]["tracker"], "danescu-mono");
    assert_eq!(
        (rows[0]["frames"].as_u64(), rows[0]["warmup"].as_u64()),
        (Some(3), Some(2))
    );
    assert!(rows[0]["median_ms"].as_f64().unwrap() > 0.0, "{out}");

    let (code, _, err) = lanepf(&["bench", "--frames", "3", "--warmup", "3"]);
    assert_eq!(code, 1);
    assert!(err.contains("--warmup"), "{err}");
}

#[test]
fn bench_runs_the_named_preset() {
    let run = |preset: &str| {
        let (code, out, err) = lanepf(&[
            "bench",
            "--tracker",
            "lee-cpf",
            "--frames",
            "2",
            "--width",
            "160",
            "--height",
            "120",
            "--preset",
            preset,
            "--json",
        ]);
        assert_eq!(code, 0, "{err}");
        let rows: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(rows[0]["preset"], preset, "{out}");
        rows[0]["options"].clone()
    };
    // lee-cpf's real-roads preset turns the re-lock proposal on; the paper's filter has it off.
    assert_eq!(run("paper")["relock_share"], 0.0);
    assert_eq!(run("real-roads")["relock_share"], 0.05);
    let (code, _, err) = lanepf(&["bench", "--frames", "2", "--preset", "fast"]);
    assert_eq!(code, 1);
    assert!(err.contains("unknown preset `fast`"), "{err}");
}

#[test]
fn eval_scores_ground_truth_as_perfect_and_a_shifted_copy_lower() {
    let out = temp("eval");
    let o = out.to_str().unwrap();
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "highway-curve",
        "--frames",
        "4",
        "--width",
        "160",
        "--height",
        "120",
        "--out",
        o,
    ]);
    assert_eq!(code, 0, "{err}");
    let gt = out.join("gt.jsonl");
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        gt.to_str().unwrap(),
        "--gt",
        gt.to_str().unwrap(),
        "--format",
        "synthetic",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["frames"], 4);
    let synthetic = &report["metrics"]["synthetic"];
    assert_eq!(synthetic["boundaries"]["accuracy"], 1.0);
    assert_eq!(synthetic["params"]["lateral_offset_m"]["rmse"], 0.0);
    // A copy 30 px to the right is no longer correct.
    let shifted: String = std::fs::read_to_string(&gt)
        .unwrap()
        .lines()
        .map(|l| {
            let mut e: lanepf::lane::LaneEstimate = serde_json::from_str(l).unwrap();
            for b in &mut e.boundaries {
                for p in &mut b.points {
                    p[0] += 30.0;
                }
            }
            e.lateral_offset_m += 0.5;
            serde_json::to_string(&e).unwrap() + "\n"
        })
        .collect();
    let pred = out.join("shifted.jsonl");
    std::fs::write(&pred, shifted).unwrap();
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        pred.to_str().unwrap(),
        "--gt",
        gt.to_str().unwrap(),
        "--format",
        "synthetic",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let synthetic = &report["metrics"]["synthetic"];
    assert_eq!(
        synthetic["boundaries"]["accuracy"], 0.0,
        "30 px off is past the 20 px rule"
    );
    let rmse = synthetic["params"]["lateral_offset_m"]["rmse"]
        .as_f64()
        .unwrap();
    assert!((rmse - 0.5).abs() < 1e-9, "{rmse}");
    // --per-frame: after the report, one line a ground-truth frame, each marked missed.
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        pred.to_str().unwrap(),
        "--gt",
        gt.to_str().unwrap(),
        "--format",
        "synthetic",
        "--per-frame",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = stdout.lines().filter(|l| l.contains("<- missed")).collect();
    assert_eq!(rows.len(), 4, "{stdout}");
    assert!(rows[0].trim_start().starts_with("000000.png"), "{stdout}");
    let (code, _, err) = lanepf(&["eval", "--pred", o, "--gt", o, "--format", "kitti"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("synthetic, caltech, tusimple, culane or kitti-road"),
        "{err}"
    );
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn track_runs_a_tracker_over_synthetic_frames_and_eval_scores_it() {
    let out = temp("track-adachi");
    let o = out.to_str().unwrap();
    // The plumbing on the fixed reference road; the same accuracy over a range of drawn roads
    // is asserted through eval-suite below.
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "highway-straight",
        "--reference",
        "--frames",
        "20",
        "--width",
        "320",
        "--height",
        "240",
        "--out",
        o,
    ]);
    assert_eq!(code, 0, "{err}");
    let pred = out.join("pred.jsonl");
    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "adachi-mmpf",
        "--camera",
        out.join("camera.json").to_str().unwrap(),
        "--frames",
        out.join("frames").to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<lanepf::lane::LaneEstimate> = std::fs::read_to_string(&pred)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 20);
    assert_eq!(lines[3].frame, "000003.png");
    assert!(lines.iter().all(|l| l.valid && l.ms > 0.0));
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        pred.to_str().unwrap(),
        "--gt",
        out.join("gt.jsonl").to_str().unwrap(),
        "--format",
        "synthetic",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let accuracy = report["metrics"]["synthetic"]["boundaries"]["accuracy"]
        .as_f64()
        .unwrap();
    assert!(accuracy > 0.9, "boundary accuracy {accuracy}");
    // A frame of the wrong size is one clear error.
    let small = temp("track-small");
    std::fs::create_dir_all(&small).unwrap();
    lanepf::image::write_rgba_png(&small.join("a.png"), &[0; 64], 4, 4).unwrap();
    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "adachi-mmpf",
        "--camera",
        out.join("camera.json").to_str().unwrap(),
        "--frames",
        small.to_str().unwrap(),
        "--out",
        small.join("p.jsonl").to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("is 4x4 but the camera is 320x240"), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&small).unwrap();
}

#[test]
fn a_closed_output_pipe_ends_quietly() {
    // `lanepf synth --list | head -0`: the reader is gone before lanepf writes; it must not
    // panic (println! would) and it exits successfully.
    let writer = {
        let (_reader, writer) = std::io::pipe().unwrap();
        writer // the reader is closed at the end of this block
    };
    let out = Command::new(env!("CARGO_BIN_EXE_lanepf"))
        .args(["synth", "--list"])
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.status.success(), "{stderr}");
}

#[test]
fn calibrate_recovers_the_synthetic_camera_and_track_runs_with_camera_auto() {
    let out = temp("calibrate");
    std::fs::create_dir_all(&out).unwrap();
    let truth = lanepf::camera::CameraFile {
        cx: 322.0,
        cy: 236.0,
        height_m: 1.6,
        pitch_deg: 3.0,
        yaw_deg: 1.0,
        ..lanepf::camera::CameraFile::pinhole(640, 480, 480.0)
    };
    let cam = out.join("truth.json");
    truth.write(&cam).unwrap();
    let d = out.join("scene");
    // The reference road: its lanes are 3.6 m wide, the prior the height comes from (a drawn
    // road's 2.8-4.2 m lanes would scale the height by as much).
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "highway-straight",
        "--reference",
        "--seed",
        "3",
        "--frames",
        "40",
        "--camera",
        cam.to_str().unwrap(),
        "--out",
        d.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let frames = d.join("frames");
    let estimate = out.join("estimate.json");
    let (code, stdout, err) = lanepf(&[
        "calibrate",
        "--frames",
        frames.to_str().unwrap(),
        "--intrinsics",
        cam.to_str().unwrap(),
        "--json",
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert!(report["confidence"].as_f64().unwrap() > 0.0, "{stdout}");
    assert_eq!(report["frames_seen"], 40);
    assert_eq!(
        report["yaw_from_tangent"], false,
        "40 frames: under the 100 that switch to the tangent"
    );
    let est = lanepf::camera::CameraFile::read(&estimate).unwrap();
    assert!((est.pitch_deg - 3.0).abs() < 0.5, "{est:?}");
    // The vanishing point shows the camera's yaw relative to the lane: the mount's 1 degree
    // minus the car's mean heading over these frames (the scene's sway).
    let gt = std::fs::read_to_string(d.join("gt.jsonl")).unwrap();
    let headings: Vec<f64> = gt
        .lines()
        .map(|l| {
            serde_json::from_str::<serde_json::Value>(l).unwrap()["heading_rad"]
                .as_f64()
                .unwrap()
        })
        .collect();
    let heading_deg =
        headings.iter().sum::<f64>() / headings.len() as f64 * 180.0 / std::f64::consts::PI;
    assert!(
        (est.yaw_deg - (1.0 - heading_deg)).abs() < 0.2,
        "{est:?}, heading {heading_deg}"
    );
    assert!((est.height_m / 1.6 - 1.0).abs() < 0.1, "{est:?}");
    // The same with each frame's yaw from the lane's tangent (on a straight road, the same
    // vanishing point).
    let (code, _, err) = lanepf(&[
        "calibrate",
        "--frames",
        frames.to_str().unwrap(),
        "--intrinsics",
        cam.to_str().unwrap(),
        "--tangent-yaw",
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let by_tangent = lanepf::camera::CameraFile::read(&estimate).unwrap();
    assert!(
        (by_tangent.pitch_deg - est.pitch_deg).abs() < 0.02,
        "{by_tangent:?}"
    );
    assert!(
        (by_tangent.yaw_deg - (1.0 - heading_deg)).abs() < 0.2,
        "{by_tangent:?}, heading {heading_deg}"
    );
    // The switch from a given number of agreeing frames: the summary says which yaw it holds,
    // and that yaw is the tangent's above.
    let (code, stdout, err) = lanepf(&[
        "calibrate",
        "--frames",
        frames.to_str().unwrap(),
        "--intrinsics",
        cam.to_str().unwrap(),
        "--tangent-yaw-after",
        "10",
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("the lane's tangent"), "{stdout}");
    let switched = lanepf::camera::CameraFile::read(&estimate).unwrap();
    assert_eq!(switched.yaw_deg, by_tangent.yaw_deg);
    // The help's default is the library's; the two yaw options exclude each other.
    let (_, help, _) = lanepf(&["calibrate", "--help"]);
    let default = lanepf::calib::CalibratorConfig::default().tangent_yaw_after;
    assert!(help.contains(&format!("[default: {default}]")), "{help}");
    let (code, _, err) = lanepf(&[
        "calibrate",
        "--frames",
        frames.to_str().unwrap(),
        "--tangent-yaw",
        "--tangent-yaw-after",
        "10",
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("cannot be used with"), "{err}");

    let pred = out.join("p.jsonl");
    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "adachi-mmpf",
        "--camera",
        "auto",
        "--intrinsics",
        cam.to_str().unwrap(),
        "--frames",
        frames.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("camera auto: pitch"),
        "the estimate is reported: {err}"
    );
    let lines = std::fs::read_to_string(&pred).unwrap();
    assert_eq!(lines.lines().count(), 40);

    // --intrinsics without --camera auto, and frames with no markings, are clear errors.
    let (code, _, err) = lanepf(&[
        "track",
        "--tracker",
        "adachi-mmpf",
        "--camera",
        cam.to_str().unwrap(),
        "--intrinsics",
        cam.to_str().unwrap(),
        "--frames",
        frames.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("--intrinsics is for --camera auto"), "{err}");
    // The calibration's options without --camera auto are errors too.
    for calibration in [&["--tangent-yaw"][..], &["--tangent-yaw-after", "50"]] {
        let mut args = vec!["track", "--tracker", "adachi-mmpf", "--camera"];
        args.push(cam.to_str().unwrap());
        args.extend(calibration);
        args.extend(["--frames", frames.to_str().unwrap()]);
        args.extend(["--out", pred.to_str().unwrap()]);
        let (code, _, err) = lanepf(&args);
        assert_eq!(code, 1);
        let want = format!("{} is for --camera auto", calibration[0]);
        assert!(err.contains(&want), "{err}");
    }
    let blank = out.join("blank");
    std::fs::create_dir_all(&blank).unwrap();
    let grey = vec![100u8; 320 * 240 * 4];
    for i in 0..3 {
        let path = blank.join(format!("{i}.png"));
        lanepf::image::write_rgba_png(&path, &grey, 320, 240).unwrap();
    }
    let (code, _, err) = lanepf(&[
        "calibrate",
        "--frames",
        blank.to_str().unwrap(),
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("no straight lane markings found in the 3 frames"),
        "{err}"
    );
    let (code, _, err) = lanepf(&[
        "calibrate",
        "--frames",
        frames.to_str().unwrap(),
        "--lane-width",
        "NaN",
        "--out",
        estimate.to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("lane_width_m"), "{err}");
}

/// `lanepf track --tracker lee-cpf` on the scene `lanepf synth` wrote to `scene`, with `args`
/// and, when given, a config file of that text (written to `out/<name>.json`): the exit code,
/// stderr and the output lines with `ms` zeroed.
fn track_lee(
    out: &Path,
    scene: &Path,
    name: &str,
    config: Option<&str>,
    args: &[&str],
) -> (i32, String, Vec<serde_json::Value>) {
    let pred = out.join(format!("{name}.jsonl"));
    let mut all: Vec<String> = [
        "track",
        "--tracker",
        "lee-cpf",
        "--camera",
        scene.join("camera.json").to_str().unwrap(),
        "--frames",
        scene.join("frames").to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec();
    all.extend(args.iter().map(|a| a.to_string()));
    if let Some(text) = config {
        let path = out.join(format!("{name}.json"));
        std::fs::write(&path, text).unwrap();
        all.extend(["--config".into(), path.display().to_string()]);
    }
    let refs: Vec<&str> = all.iter().map(String::as_str).collect();
    let (code, _, err) = lanepf(&refs);
    let lines = std::fs::read_to_string(&pred)
        .unwrap_or_default()
        .lines()
        .map(|l| {
            let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
            v["ms"] = 0.into();
            v
        })
        .collect();
    (code, err, lines)
}

#[test]
fn track_takes_the_seed_once_and_the_camera_only_from_camera() {
    let out = temp("seed-once");
    let d = out.join("scene");
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "highway-straight",
        "--frames",
        "3",
        "--width",
        "160",
        "--height",
        "120",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let run = |config: Option<&str>, seed: Option<&str>, name: &str| {
        let seed: Vec<&str> = seed.map_or(vec![], |s| vec!["--seed", s]);
        track_lee(&out, &d, name, config, &seed)
    };
    let (code, err, _) = run(Some(r#"{"seed": 7}"#), Some("7"), "twice");
    assert_eq!(code, 1);
    assert!(err.contains("the seed is given twice: --seed 7"), "{err}");
    let (code, err, _) = run(Some(r#"{"camera": {}}"#), None, "camera");
    assert_eq!(code, 1);
    assert!(err.contains("`camera` comes from --camera"), "{err}");
    // The seed from the file and the same seed from the flag give the same run; another seed
    // does not.
    let (code, err, from_file) = run(Some(r#"{"seed": 7}"#), None, "file");
    assert_eq!(code, 0, "{err}");
    let (_, _, from_flag) = run(None, Some("7"), "flag");
    let (_, _, other) = run(None, Some("8"), "other");
    assert_eq!(from_file.len(), 3);
    assert_eq!(from_file, from_flag);
    assert_ne!(from_file, other);
}

/// `--preset real-roads` is the paper's defaults with our options for real roads, and the
/// options of --config replace a preset's values.
#[test]
fn track_starts_from_a_preset_and_the_config_replaces_its_values() {
    let out = temp("preset");
    let d = out.join("scene");
    let (code, _, err) = lanepf(&[
        "synth",
        "--scenario",
        "multi-lane",
        "--frames",
        "4",
        "--width",
        "320",
        "--height",
        "240",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let run = |preset: Option<&str>, config: Option<&str>, name: &str| {
        let preset: Vec<&str> = preset.map_or(vec![], |p| vec!["--preset", p]);
        track_lee(&out, &d, name, config, &preset)
    };
    let (code, err, _) = run(Some("real"), None, "unknown");
    assert_eq!(code, 1);
    assert!(
        err.contains("unknown preset `real`: use one of paper, real-roads"),
        "{err}"
    );
    let (code, err, paper) = run(None, None, "paper");
    assert_eq!(code, 0, "{err}");
    let (_, _, named_paper) = run(Some("paper"), None, "named-paper");
    let (_, _, roads) = run(Some("real-roads"), None, "roads");
    let ours = r#"{"relock_share": 0.05, "curvature_prior_sd": 0.004, "adjacent_lanes": true,
        "valid_support_frames": 5, "side_search_share": 0.2, "reacquire_near_m": 4,
        "kalman_process_sd": [0.009, 0.09, 0.1, 0.0015, 6.0, 0.0006], "snap_to_paint": true,
        "snap_follows_bends": true, "valid_needs_paint": true, "valid_from_paint": true}"#;
    let (_, _, by_hand) = run(None, Some(ours), "by-hand");
    let off = r#"{"relock_share": 0, "curvature_prior_sd": 0, "adjacent_lanes": false,
        "valid_support_frames": 1, "side_search_share": 0, "reacquire_near_m": 0,
        "kalman_process_sd": [0.003, 0.03, 0.01, 0.0005, 2.0, 0.0002], "snap_to_paint": false,
        "snap_follows_bends": false, "valid_needs_paint": false, "valid_from_paint": false}"#;
    let (_, _, replaced) = run(Some("real-roads"), Some(off), "replaced");
    assert_eq!(paper.len(), 4);
    assert_eq!(named_paper, paper);
    assert_ne!(roads, paper);
    assert_eq!(roads, by_hand);
    assert_eq!(replaced, paper);
}

/// Issue 19: `eval` reads at most 256 MiB a file, 1 MiB a line and 5000 points a polyline, and
/// resamples a polyline to at most 50 000 points, each with a clear error; ground truth in
/// another format than `--format` says which format it looks like.
#[test]
fn eval_caps_its_inputs_and_names_the_format_it_sees() {
    let out = temp("eval-caps");
    std::fs::create_dir_all(&out).unwrap();
    let labels = out.join("labels.json");
    std::fs::write(
        &labels,
        r#"{"image_size": [640, 480], "frames": [{"frame": "f0.png", "lanes": [
            {"bezier_xy": [[300, 479], [310, 400], [320, 330], [330, 260]]}]}]}"#,
    )
    .unwrap();
    let prediction = |points: &[[f64; 2]]| {
        serde_json::json!({"frame": "f0.png", "valid": true, "lateral_offset_m": 0.0,
            "heading_rad": 0.0, "curvature_per_m": 0.0, "lane_width_m": 3.5,
            "boundaries": [{"role": "ego-left", "points": points}]})
        .to_string()
            + "\n"
    };
    let eval = |pred: &Path, format: &str| {
        lanepf(&[
            "eval",
            "--pred",
            pred.to_str().unwrap(),
            "--gt",
            labels.to_str().unwrap(),
            "--format",
            format,
        ])
    };
    let write = |name: &str, text: &str| {
        let path = out.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let good = write("good.jsonl", &prediction(&[[300.0, 479.0], [330.0, 260.0]]));
    let (code, _, err) = eval(&good, "caltech");
    assert_eq!(code, 0, "{err}");

    // A Caltech labels.json read as TuSimple names the format it looks like.
    let (code, _, err) = eval(&good, "tusimple");
    assert_eq!(code, 1);
    assert!(
        err.contains("looks like Caltech Lanes labels") && err.contains("try --format caltech"),
        "{err}"
    );
    // 300 points alternating x = 0 and x = 1e7: refused before 13 s and 700 MB of samples.
    let zigzag: Vec<[f64; 2]> = (0..300)
        .map(|k| [if k % 2 == 0 { 0.0 } else { 1e7 }, 479.0 - k as f64])
        .collect();
    let (code, _, err) = eval(&write("zigzag.jsonl", &prediction(&zigzag)), "caltech");
    assert_eq!(code, 1);
    assert!(
        err.contains("frame f0.png") && err.contains("more than 50000"),
        "{err}"
    );
    let many: Vec<[f64; 2]> = (0..6000).map(|k| [300.0, k as f64 * 0.05]).collect();
    let (code, _, err) = eval(&write("many.jsonl", &prediction(&many)), "caltech");
    assert_eq!(code, 1);
    assert!(
        err.contains("line 1: boundary 0 has 6000 points, more than the 5000"),
        "{err}"
    );
    let long = format!("{{\"frame\": \"{}\"}}\n", "x".repeat(2 << 20));
    let (code, _, err) = eval(&write("long.jsonl", &long), "caltech");
    assert_eq!(code, 1);
    assert!(
        err.contains("line 1: 2097165 bytes long, more than the 1024 KiB"),
        "{err}"
    );
    // An endless file is refused after 256 MiB, not read until memory runs out.
    if Path::new("/dev/zero").exists() {
        let (code, _, err) = eval(Path::new("/dev/zero"), "caltech");
        assert_eq!(code, 1);
        assert!(err.contains("/dev/zero: larger than 256 MiB"), "{err}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn eval_suite_rejects_bad_arguments_with_one_clear_line() {
    let out = temp("suite-bad");
    let o = out.to_str().unwrap();
    for (args, want) in [
        (
            vec!["--tracker", "lee-cpf", "--seeds", "5..2"],
            "--seeds 5..2: the range is empty",
        ),
        (
            vec!["--tracker", "lee-cpf", "--seeds", "one..2"],
            "`one` is not a seed",
        ),
        (vec!["--tracker", "nope", "--seeds", "1..2"], "adachi-mmpf"),
        (
            vec![
                "--tracker",
                "all",
                "--seeds",
                "1",
                "--scenarios",
                "s-curve,moon",
            ],
            "unknown scenario `moon`",
        ),
        (
            vec!["--tracker", "all", "--seeds", "1", "--frames", "0"],
            "--frames",
        ),
        (
            vec!["--tracker", "lee-cpf", "--seeds", "1", "--options", "[1]"],
            "--options must be a JSON object",
        ),
        (
            vec![
                "--tracker",
                "adachi-mmpf",
                "--seeds",
                "1",
                "--options",
                r#"{"curvature_prior_sd": 0.004}"#,
            ],
            "curvature_prior_sd",
        ),
    ] {
        let mut full = vec!["eval-suite"];
        full.extend(&args);
        full.extend(["--out", o]);
        let (code, _, err) = lanepf(&full);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    assert!(!out.exists(), "nothing is written on bad arguments");
}

#[test]
fn eval_suite_writes_one_table_as_markdown_and_json() {
    let out = temp("suite");
    let o = out.to_str().unwrap();
    let (code, stdout, err) = lanepf(&[
        "eval-suite",
        "--tracker",
        "lee-cpf",
        "--seeds",
        "3..4",
        "--scenarios",
        "occlusion,random",
        "--frames",
        "3",
        "--width",
        "160",
        "--height",
        "120",
        "--out",
        o,
    ]);
    assert_eq!(code, 0, "{err}");
    let md = std::fs::read_to_string(out.join("suite.md")).unwrap();
    assert_eq!(md, stdout);
    // Header, rule, two scenarios and the row pooling both.
    assert_eq!(md.lines().count(), 5, "{md}");
    assert!(md.contains("| lee-cpf | random | 2 | 6 |"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("suite.json")).unwrap()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[2]["scenario"], "all");
    assert_eq!(rows[2]["scores"]["frames"], 12);
    assert_eq!(json["seeds"], serde_json::json!([3, 4]));
    for key in [
        "detection_rate",
        "offset_rmse_m",
        "heading_rmse_deg",
        "curvature_rmse_per_m",
        "width_mae_m",
        "point_accuracy",
        "lane_configuration_accuracy",
        "recovery_mean_frames",
        "lane_changes",
        "ms",
    ] {
        assert!(rows[0]["scores"].get(key).is_some(), "{key}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `--options` builds every tracker of the run with them, and suite.json says so: lee-cpf
/// with `adjacent_lanes` on `multi-lane` (a lane each side) reports the neighbouring lanes, so
/// its lane configuration is scored and more boundaries are right than with the paper's
/// ego lane alone (measured 2026-11-25, seeds 1-2, 30 frames: 78 % against 62 %).
#[test]
fn eval_suite_runs_the_trackers_with_the_options_given() {
    let run = |options: Option<&str>| {
        let out = temp(if options.is_some() {
            "suite-opt"
        } else {
            "suite-noopt"
        });
        let mut args = vec![
            "eval-suite",
            "--tracker",
            "lee-cpf",
            "--seeds",
            "1..2",
            "--scenarios",
            "multi-lane",
            "--frames",
            "30",
            "--out",
            out.to_str().unwrap(),
        ];
        if let Some(o) = options {
            args.extend(["--options", o]);
        }
        let (code, _, err) = lanepf(&args);
        assert_eq!(code, 0, "{err}");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("suite.json")).unwrap())
                .unwrap();
        std::fs::remove_dir_all(&out).unwrap();
        json
    };
    let paper = run(None);
    let with = run(Some(r#"{"adjacent_lanes": true}"#));
    assert_eq!(with["options"], serde_json::json!({"adjacent_lanes": true}));
    assert_eq!(paper["options"], serde_json::json!({}));
    let scores = |j: &serde_json::Value| j["rows"][0]["scores"].clone();
    assert!(scores(&paper)["lane_configuration_accuracy"].is_null());
    assert!(scores(&with)["lane_configuration_accuracy"].is_f64());
    let points = |j: &serde_json::Value| scores(j)["point_accuracy"].as_f64().unwrap();
    assert!(
        points(&with) >= points(&paper) + 0.1,
        "{} against {}",
        points(&with),
        points(&paper)
    );
}

/// Adachi's boundary accuracy on the first 20 frames of straight highways, pooled over eight
/// drawn roads and cameras (scene seeds 1-8; measured 92 % on 2026-11-25, single roads
/// 67-100 %: the 67 % is a two-lane road where it reports no neighbour lane).
#[test]
fn eval_suite_adachi_finds_the_boundaries_of_drawn_straight_highways() {
    let out = temp("suite-adachi");
    let (code, _, err) = lanepf(&[
        "eval-suite",
        "--tracker",
        "adachi-mmpf",
        "--seeds",
        "1..8",
        "--scenarios",
        "highway-straight",
        "--frames",
        "20",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("suite.json")).unwrap()).unwrap();
    let scores = &json["rows"][0]["scores"];
    assert_eq!(scores["detection_rate"], 1.0, "{scores}");
    let accuracy = scores["point_accuracy"].as_f64().unwrap();
    assert!(accuracy > 0.9, "boundary accuracy {accuracy}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// `eval --format kitti-road`: a folder of KITTI lane masks, each frame's ego lane scored pixel
/// by pixel; a mask named otherwise is an error that says how KITTI names them.
#[test]
fn eval_scores_the_ego_lane_against_kitti_road_masks() {
    let out = temp("kitti-road");
    let gt = out.join("gt_image_2");
    std::fs::create_dir_all(&gt).unwrap();
    // 20 x 10: rows 0-3 not evaluated (black), rows 4-9 the lane in columns 8-11 (magenta).
    let mut rgba = Vec::new();
    for y in 0..10 {
        for x in 0..20 {
            let c = match (y, x) {
                (0..=3, _) => [0, 0, 0],
                (_, 8..=11) => [255, 0, 255],
                _ => [255, 0, 0],
            };
            rgba.extend_from_slice(&[c[0], c[1], c[2], 255]);
        }
    }
    lanepf::image::write_rgba_png(&gt.join("um_lane_000000.png"), &rgba, 20, 10).unwrap();
    lanepf::image::write_rgba_png(&gt.join("umm_lane_000001.png"), &rgba, 20, 10).unwrap();
    // um_000000: the lane exactly; umm_000001: two columns to the right (columns 10-13).
    let line = |frame: &str, left: f64, right: f64| {
        format!(
            r#"{{"frame": "{frame}", "valid": true, "ms": 1, "lateral_offset_m": 0, "heading_rad": 0, "curvature_per_m": 0, "lane_width_m": 3.6, "boundaries": [{{"role": "ego-left", "points": [[{left}, 9], [{left}, 0]]}}, {{"role": "ego-right", "points": [[{right}, 9], [{right}, 0]]}}]}}"#
        )
    };
    let pred = out.join("pred.jsonl");
    std::fs::write(
        &pred,
        [
            line("image_2/um_000000.png", 8.0, 11.0),
            line("image_2/umm_000001.png", 10.0, 13.0),
        ]
        .join("\n"),
    )
    .unwrap();
    let (p, g) = (pred.to_str().unwrap(), gt.to_str().unwrap());
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        p,
        "--gt",
        g,
        "--format",
        "kitti-road",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let kitti = &report["metrics"]["kitti-road"];
    // 24 lane pixels a frame: the first all found; the second 12 found, 12 false, 12 missed.
    assert_eq!(kitti["total"]["true_positives"], 36, "{stdout}");
    assert_eq!(kitti["total"]["false_positives"], 12, "{stdout}");
    assert_eq!(kitti["total"]["false_negatives"], 12, "{stdout}");
    assert_eq!(kitti["frames"][0]["frame"], "um_000000.png", "{stdout}");
    let (code, stdout, err) = lanepf(&[
        "eval",
        "--pred",
        p,
        "--gt",
        g,
        "--format",
        "kitti-road",
        "--per-frame",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("F1                                   75.0 %"),
        "{stdout}"
    );
    assert!(stdout.contains("umm_000001.png"), "{stdout}");
    std::fs::copy(gt.join("um_lane_000000.png"), gt.join("_lane_000002.png")).unwrap();
    let (code, _, err) = lanepf(&["eval", "--pred", p, "--gt", g, "--format", "kitti-road"]);
    assert_eq!(code, 1);
    assert!(err.contains("<category>_lane_<number>.png"), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}
