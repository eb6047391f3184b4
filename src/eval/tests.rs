//! Tests of the evaluation front end, and of every metric on the shared real data: the labels
//! themselves, written as tracker output, must score perfectly.

use super::*;
use crate::lane::{Boundary, Role};
use std::path::PathBuf;

/// A folder of `../shared/data`, or `None` (with a note) when it is absent.
fn shared(sub: &str) -> Option<PathBuf> {
    let p = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data")).join(sub);
    if p.exists() {
        Some(p)
    } else {
        println!("note: {} is absent; skipping this test", p.display());
        None
    }
}

fn fixture(sub: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/eval")).join(sub)
}

/// Roles by position at the bottom: nearest left of `centre` is ego-left, nearest right is
/// ego-right, the rest are adjacent on their side. `bottom_x[i]` is lane i's position.
fn roles_by_position(bottom_x: &[f64], centre: f64) -> Vec<Role> {
    let left = bottom_x
        .iter()
        .enumerate()
        .filter(|(_, x)| **x < centre)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i);
    let right = bottom_x
        .iter()
        .enumerate()
        .filter(|(_, x)| **x >= centre)
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i);
    bottom_x
        .iter()
        .enumerate()
        .map(|(i, x)| match (Some(i) == left, Some(i) == right) {
            (true, _) => Role::EgoLeft,
            (_, true) => Role::EgoRight,
            _ if *x < centre => Role::LeftAdjacent,
            _ => Role::RightAdjacent,
        })
        .collect()
}

/// A valid estimate for `frame` with the given image polylines (bottom-up), roles by position.
fn estimate(frame: &str, lanes: Vec<Vec<[f64; 2]>>, centre: f64) -> LaneEstimate {
    let bottom: Vec<f64> = lanes
        .iter()
        .map(|l| l.first().map_or(f64::NAN, |p| p[0]))
        .collect();
    let roles = roles_by_position(&bottom, centre);
    let boundaries = lanes
        .into_iter()
        .zip(roles)
        .map(|(points, role)| {
            let b = Boundary {
                role,
                points,
                road_points: vec![],
            };
            assert_eq!(
                b.check_polyline(),
                Ok(()),
                "{frame}: not a tracker polyline"
            );
            b
        })
        .collect();
    LaneEstimate {
        frame: frame.to_string(),
        valid: true,
        boundaries,
        ..Default::default()
    }
}

// ---- front end -------------------------------------------------------------------------

#[test]
fn formats_parse_from_their_command_line_names() {
    for f in Format::ALL {
        assert_eq!(f.as_str().parse::<Format>(), Ok(f));
        assert_eq!(serde_json::to_string(&f).unwrap(), format!("\"{f}\""));
    }
    let e = "kitti".parse::<Format>().unwrap_err().to_string();
    assert!(
        e.contains("`format` = kitti") && e.contains("culane"),
        "{e}"
    );
}

#[test]
fn a_bad_prediction_line_is_named() {
    let good = r#"{"frame": "a.png", "valid": true, "boundaries": [], "lateral_offset_m": 0, "heading_rad": 0, "curvature_per_m": 0, "lane_width_m": 3.5, "extra": 1}"#;
    let text = format!("{good}\n\n{good}\n{{\"frame\": \"b.png\"}}\n");
    let e = parse_predictions(&text, "p.jsonl").unwrap_err().to_string();
    assert!(e.contains("p.jsonl line 4"), "{e}");
    assert_eq!(
        parse_predictions(&format!("{good}\n"), "p").unwrap().len(),
        1
    );
    let e = read_predictions(Path::new("/nonexistent/p.jsonl")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }), "{e}");
}

#[test]
fn frames_match_by_file_name_or_full_name() {
    let gt = ["image/0000.png", "clips/a/20.jpg", "clips/b/20.jpg"];
    let p = |frame: &str| LaneEstimate {
        frame: frame.into(),
        ..Default::default()
    };
    let preds = vec![p("somewhere/0000.png"), p("clips/b/20.jpg"), p("9999.png")];
    let m = match_frames(&gt, &preds).unwrap();
    assert_eq!(
        m.per_gt[0].map(|e| e.frame.as_str()),
        Some("somewhere/0000.png")
    );
    assert_eq!(m.per_gt[1], None);
    assert_eq!(
        m.per_gt[2].map(|e| e.frame.as_str()),
        Some("clips/b/20.jpg")
    );
    assert_eq!(m.unknown, vec!["9999.png".to_string()]);
    let e = match_frames(&gt, &[p("20.jpg")]).unwrap_err().to_string();
    assert!(e.contains("fits 2 ground-truth frames"), "{e}");
    let e = match_frames(&gt, &[p("0000.png"), p("x/0000.png")])
        .unwrap_err()
        .to_string();
    assert!(e.contains("two predictions"), "{e}");
}

#[test]
fn synthetic_fixture_end_to_end() {
    // Three ground-truth frames; predictions: one exact, one invalid, one for an unknown frame;
    // frame 000002 has no prediction.
    let gt_dir = fixture("synthetic");
    let preds = read_predictions(&fixture("synthetic/pred.jsonl")).unwrap();
    let r = evaluate(Format::Synthetic, &preds, &gt_dir).unwrap();
    assert_eq!(
        (
            r.frames,
            r.predicted_frames,
            r.invalid_predictions,
            r.missing_frames
        ),
        (3, 2, 1, 1)
    );
    assert_eq!(r.unknown_frames, vec!["000009.png".to_string()]);
    let Metrics::Synthetic(s) = &r.metrics else {
        panic!("wrong metrics: {r:?}")
    };
    assert_eq!(s.params.detection_rate, Some(1.0 / 3.0));
    let off = s.params.lateral_offset_m.unwrap();
    assert_eq!(off.n, 1);
    assert!((off.mae - 0.05).abs() < 1e-12, "{off:?}");
    assert!((s.params.state["lee.psi"].mae - 0.002).abs() < 1e-12);
    // 2 boundaries per frame, only frame 0's two are predicted (5 px off): 2 of 6.
    assert_eq!((s.boundaries.gt, s.boundaries.correct), (6, 2));
    assert_eq!(s.boundaries.mean_abs_dx_px, Some(5.0));
    let table = r.to_string();
    assert!(
        table.contains("synthetic evaluation: 3 ground-truth frames"),
        "{table}"
    );
    assert!(table.contains("lee.psi"), "{table}");
    let json = serde_json::to_string(&r).unwrap();
    assert!(
        json.contains(r#""format":"synthetic""#) && json.contains(r#""rmse""#),
        "{json}"
    );
}

// ---- TuSimple on the shared frames -----------------------------------------------------

/// The labels of each frame as tracker output: lane k's present points, bottom-up.
fn tusimple_as_predictions(
    labels: &[tusimple::TusimpleFrame],
    shift: impl Fn(usize, usize) -> Option<f64>,
) -> Vec<LaneEstimate> {
    labels
        .iter()
        .enumerate()
        .map(|(f, l)| {
            let lanes = l
                .lanes
                .iter()
                .enumerate()
                .filter_map(|(k, xs)| {
                    let dx = shift(f, k)?;
                    let pts: Vec<[f64; 2]> = xs
                        .iter()
                        .zip(&l.h_samples)
                        .rev()
                        .filter(|(x, _)| **x >= 0.0)
                        .map(|(x, y)| [x + dx, *y])
                        .collect();
                    Some(pts)
                })
                .collect();
            estimate(file_name(&l.frame), lanes, 639.5)
        })
        .collect()
}

#[test]
fn tusimple_labels_as_predictions_score_perfectly_and_perturbed_lower() {
    let Some(dir) = shared("tusimple") else {
        return;
    };
    let labels = tusimple::read_labels(&dir.join("labels.json")).unwrap();
    assert_eq!(labels.len(), 6);
    let preds = tusimple_as_predictions(&labels, |_, _| Some(0.0));
    let r = evaluate(Format::Tusimple, &preds, &dir).unwrap();
    println!("TuSimple, labels as predictions:\n{r}");
    assert_eq!((r.frames, r.predicted_frames, r.missing_frames), (6, 6, 0));
    let Metrics::Tusimple(t) = &r.metrics else {
        panic!("{r:?}")
    };
    assert_eq!((t.accuracy, t.fp, t.fn_rate), (1.0, 0.0, 0.0), "{t:?}");
    // One frame has 5 labelled lanes: the special case is exercised and still perfect.
    assert!(t.frames.iter().any(|f| f.gt_lanes == 5));

    // Perturbed: lane 1 (steep, threshold about 32 px) moved 60 px and the last lane dropped,
    // in every frame.
    let preds = tusimple_as_predictions(&labels, |f, k| {
        if k + 1 == labels[f].lanes.len() {
            None
        } else if k == 1 {
            Some(60.0)
        } else {
            Some(0.0)
        }
    });
    let r = evaluate(Format::Tusimple, &preds, &dir).unwrap();
    println!("TuSimple, perturbed:\n{r}");
    let Metrics::Tusimple(t) = &r.metrics else {
        panic!("{r:?}")
    };
    assert!(t.accuracy < 0.9, "{t:?}");
    assert!(t.fn_rate > 0.2 && t.fp > 0.0, "{t:?}");
}

// ---- Caltech on the shared frames ------------------------------------------------------

#[test]
fn caltech_labels_as_predictions_score_perfectly_in_both_modes() {
    let Some(dir) = shared("caltech-cordova1") else {
        return;
    };
    let labels = caltech::read_labels(&dir.join("labels.json")).unwrap();
    assert_eq!(labels.frames.len(), 77);
    let size = labels.image_size;
    let preds: Vec<LaneEstimate> = labels
        .frames
        .iter()
        .map(|f| {
            let [left, right] = caltech::ego_lanes(&f.lanes, size);
            let lanes: Vec<Vec<[f64; 2]>> = f
                .lanes
                .iter()
                .map(|l| {
                    let mut pts = caltech::bezier_polyline(&l.bezier_xy, 100);
                    if pts[0][1] < pts[pts.len() - 1][1] {
                        pts.reverse();
                    }
                    pts
                })
                .collect();
            let mut e = estimate(&format!("frames/{}", f.frame), lanes, 319.5);
            // Roles as the ego-lane rule of the labels says (the bottom points may differ).
            for (i, b) in e.boundaries.iter_mut().enumerate() {
                b.role = if Some(i) == left {
                    Role::EgoLeft
                } else if Some(i) == right {
                    Role::EgoRight
                } else if b.points[0][0] < 319.5 {
                    Role::LeftAdjacent
                } else {
                    Role::RightAdjacent
                };
            }
            e
        })
        .collect();
    let r = evaluate(Format::Caltech, &preds, &dir).unwrap();
    println!("Caltech, labels as predictions:\n{r}");
    let Metrics::Caltech(c) = &r.metrics else {
        panic!("{r:?}")
    };
    for m in [&c.all_lanes, &c.ego_lanes] {
        assert_eq!(m.correct_rate, Some(1.0), "{c:?}");
        assert_eq!(m.false_positive_rate, Some(0.0), "{c:?}");
    }
    assert_eq!(c.all_lanes.gt_lanes, 4 * 28 + 3 * 25 + 5 * 20);
    assert!(c.ego_lanes.gt_lanes >= 2 * 70, "{c:?}");
}

// ---- CULane on the shared frames -------------------------------------------------------

#[test]
fn culane_labels_as_predictions_give_f1_1() {
    let Some(dir) = shared("culane/06030819_0755.MP4") else {
        return;
    };
    let labels = culane::read_labels(&dir).unwrap();
    assert_eq!(labels.len(), 60);
    assert!(labels
        .iter()
        .all(|f| f.image_size == Some(culane::CULANE_SIZE)));
    let preds: Vec<LaneEstimate> = labels
        .iter()
        .map(|f| {
            let lanes = f
                .lanes
                .iter()
                .map(|l| {
                    let mut pts = l.clone();
                    if pts[0][1] < pts[pts.len() - 1][1] {
                        pts.reverse();
                    }
                    pts
                })
                .collect();
            estimate(&f.frame, lanes, 819.5)
        })
        .collect();
    let r = evaluate(Format::Culane, &preds, &dir).unwrap();
    println!("CULane, labels as predictions:\n{r}");
    let Metrics::Culane(c) = &r.metrics else {
        panic!("{r:?}")
    };
    assert_eq!(c.f1, Some(1.0), "{c:?}");
    assert_eq!(c.counts.fp + c.counts.fn_, 0);
    assert!(c.counts.tp > 200, "{c:?}");
}

// ---- Per-frame figures (`lanepf eval --per-frame`) -------------------------------------

#[test]
fn synthetic_per_frame_figures_follow_the_ground_truth_and_sum_to_the_totals() {
    let preds = read_predictions(&fixture("synthetic/pred.jsonl")).unwrap();
    let r = evaluate(Format::Synthetic, &preds, &fixture("synthetic")).unwrap();
    let Metrics::Synthetic(s) = &r.metrics else {
        panic!("{r:?}")
    };
    // Frame 0 exact (2 of 2), frame 1 invalid, frame 2 without a prediction.
    let got: Vec<(&str, usize, usize, bool)> = s
        .boundaries
        .frames
        .iter()
        .map(|f| (f.frame.as_str(), f.correct, f.gt, f.valid))
        .collect();
    assert_eq!(
        got,
        vec![
            ("000000.png", 2, 2, true),
            ("000001.png", 0, 2, false),
            ("000002.png", 0, 2, false)
        ]
    );
    let table = r.frames_table();
    assert_eq!(table.lines().count(), 4, "{table}");
    assert_eq!(table.matches("<- missed").count(), 2, "{table}");
}

/// The labels as predictions with frame `broken` left out: only it is short in the per-frame
/// figures, and they sum to the totals.
#[test]
fn caltech_and_culane_per_frame_figures_name_the_frame_that_fails() {
    if let Some(dir) = shared("caltech-cordova1") {
        let labels = caltech::read_labels(&dir.join("labels.json")).unwrap();
        let size = labels.image_size;
        let broken = "f00123.png";
        let preds: Vec<LaneEstimate> = labels
            .frames
            .iter()
            .filter(|f| f.frame != broken)
            .map(|f| {
                let [left, right] = caltech::ego_lanes(&f.lanes, size);
                let ego = [(left, Role::EgoLeft), (right, Role::EgoRight)];
                let mut e = estimate(&f.frame, Vec::new(), 319.5);
                // The roles of the labels' ego-lane rule (the bottom points may differ).
                for (i, role) in ego.into_iter().filter_map(|(i, r)| Some((i?, r))) {
                    let mut points = caltech::bezier_polyline(&f.lanes[i].bezier_xy, 100);
                    if points[0][1] < points[points.len() - 1][1] {
                        points.reverse();
                    }
                    e.boundaries.push(Boundary {
                        role,
                        points,
                        road_points: Vec::new(),
                    });
                }
                e
            })
            .collect();
        let r = evaluate(Format::Caltech, &preds, &dir).unwrap();
        let Metrics::Caltech(c) = &r.metrics else {
            panic!("{r:?}")
        };
        assert_eq!(c.frames.len(), labels.frames.len());
        let sum = |f: fn(&caltech::CaltechFrameScore) -> caltech::FrameCounts| {
            c.frames.iter().map(f).fold([0; 3], |s, n| {
                [s[0] + n.gt_lanes, s[1] + n.predicted, s[2] + n.matched]
            })
        };
        let e = &c.ego_lanes;
        assert_eq!(sum(|f| f.ego_lanes), [e.gt_lanes, e.predicted, e.matched]);
        let a = &c.all_lanes;
        assert_eq!(sum(|f| f.all_lanes), [a.gt_lanes, a.predicted, a.matched]);
        let short: Vec<&str> = c
            .frames
            .iter()
            .filter(|f| f.ego_lanes.matched < f.ego_lanes.gt_lanes)
            .map(|f| f.frame.as_str())
            .collect();
        assert_eq!(short, vec![broken]);
        let table = r.frames_table();
        assert_eq!(table.matches("<- ego").count(), 1, "{table}");
        let line = table.lines().find(|l| l.contains(broken)).unwrap();
        assert!(
            line.contains(" 0/0/2 ") && line.ends_with("<- ego"),
            "{line}"
        );
    }
    if let Some(dir) = shared("culane/06030819_0755.MP4") {
        let labels = culane::read_labels(&dir).unwrap();
        let broken = labels[7].frame.clone();
        let preds: Vec<LaneEstimate> = labels
            .iter()
            .filter(|f| f.frame != broken)
            .map(|f| estimate(&f.frame, f.lanes.clone(), 819.5))
            .collect();
        let r = evaluate(Format::Culane, &preds, &dir).unwrap();
        let Metrics::Culane(c) = &r.metrics else {
            panic!("{r:?}")
        };
        assert_eq!(c.frames.len(), 60);
        let fns: Vec<(&str, usize)> = c
            .frames
            .iter()
            .filter(|f| f.counts.fn_ > 0 || f.counts.fp > 0)
            .map(|f| (f.frame.as_str(), f.counts.fn_))
            .collect();
        assert_eq!(fns, vec![(broken.as_str(), labels[7].lanes.len())]);
        let tp: usize = c.frames.iter().map(|f| f.counts.tp).sum();
        assert_eq!(tp, c.counts.tp);
        assert_eq!(r.frames_table().lines().count(), 61);
        // The labels as predictions: each predicted lane's best IoU is 1, and the frame left
        // out has none.
        for f in &c.frames {
            let expected = if f.frame == broken { 0 } else { f.counts.tp };
            assert_eq!(f.best_iou.len(), expected, "{}", f.frame);
            assert!(
                f.best_iou.iter().all(|&v| v == 1.0),
                "{}: {:?}",
                f.frame,
                f.best_iou
            );
        }
    }
}
