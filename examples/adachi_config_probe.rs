//! Diagnostic: why adachi-mmpf's model r (which neighbouring lanes exist, Adachi eq. 5) is
//! right or wrong on drawn family members (issue 20). For each member (320x240, tracker seed 1,
//! default options unless OPTIONS is given, as `lanepf eval-suite` runs it) and each frame:
//! the truth's model and the estimate's, and for each neighbour the truth has, the share of
//! the voting region's rows that its outer boundary crosses (where the paper's straight
//! boundary at the truth's rho would lie inside the region: visible) and its vote support
//! (Likelihood::support at the truth's rho); and the log-likelihood (eq. 6) of each model at
//! its best (q, w) near the truth's, so that the evidence for a neighbour shows apart from
//! the filter. One summary line per member and one for all.
//!
//! `cargo run --release --example adachi_config_probe -- SCENARIOS SEEDS [FRAMES] [OPTIONS]
//! [-v]`, e.g. `-- highway-straight,multi-lane 1000..1005 150`.
use lanepf::synth::{draw_scenario, Eye};
use lanepf::trackers::adachi::config::AdachiConfig;
use lanepf::trackers::adachi::likelihood::{Likelihood, OFFSETS};
use lanepf::trackers::adachi::votes::Votes;
use lanepf::trackers::adachi::AdachiTracker;
use lanepf::trackers::{Options, TrackerConfig};

#[derive(Default, Clone)]
struct Tally {
    frames: usize,
    valid: usize,
    right: usize,
    // per side (left, right): frames the truth has the neighbour, of those the estimate says
    // so, the truth says none and the estimate says one.
    has: [usize; 2],
    said: [usize; 2],
    none_said: [usize; 2],
    none: [usize; 2],
    // of the frames with the neighbour: its outer boundary visible in < 50 % of the rows
    half_hidden: [usize; 2],
    // frames with the neighbour where the likelihood at the truth favours the truth model over
    // the same without that neighbour
    ll_favours: [usize; 2],
    vis_sum: [f64; 2],
    // frames with the neighbour whose outer boundary (the truth's) has no image point 6-22 m
    // ahead / none at all
    unseen_region: [usize; 2],
    unseen: [usize; 2],
    support_sum: [f64; 2],
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let verbose = a.iter().any(|s| s == "-v");
    let grad = a.iter().any(|s| s == "-g");
    let a: Vec<String> = a.into_iter().filter(|s| s != "-v" && s != "-g").collect();
    let scenarios: Vec<&str> = a[1].split(',').collect();
    let (lo, hi) = a[2].split_once("..").expect("SEEDS as A..B");
    let seeds = lo.parse::<u64>().unwrap()..=hi.parse::<u64>().unwrap();
    let max_frames: u32 = a.get(3).map_or(u32::MAX, |s| s.parse().unwrap());
    let options = a.get(4).cloned().unwrap_or_else(|| "{}".into());
    if grad {
        for name in &scenarios {
            for seed in seeds.clone() {
                gradients(name, seed, max_frames.min(300));
            }
        }
        return;
    }
    let mut all = Tally::default();
    for name in &scenarios {
        let mut family = Tally::default();
        for seed in seeds.clone() {
            let t = member(name, seed, max_frames, &options, verbose);
            add(&mut family, &t);
            print_tally(&format!("{name} {seed}"), &t);
        }
        print_tally(&format!("{name} all"), &family);
        add(&mut all, &family);
    }
    print_tally("all", &all);
}

fn add(a: &mut Tally, b: &Tally) {
    a.frames += b.frames;
    a.valid += b.valid;
    a.right += b.right;
    for s in 0..2 {
        a.has[s] += b.has[s];
        a.said[s] += b.said[s];
        a.none_said[s] += b.none_said[s];
        a.none[s] += b.none[s];
        a.half_hidden[s] += b.half_hidden[s];
        a.ll_favours[s] += b.ll_favours[s];
        a.vis_sum[s] += b.vis_sum[s];
        a.unseen_region[s] += b.unseen_region[s];
        a.unseen[s] += b.unseen[s];
        a.support_sum[s] += b.support_sum[s];
    }
}

fn print_tally(label: &str, t: &Tally) {
    let pc = |a: usize, b: usize| {
        if b == 0 {
            "-".to_string()
        } else {
            format!("{:.0}%", 100.0 * a as f64 / b as f64)
        }
    };
    let mean = |a: f64, b: usize| if b == 0 { f64::NAN } else { a / b as f64 };
    let mut line = format!(
        "{label}: valid {}/{} model right {} |",
        t.valid,
        t.frames,
        pc(t.right, t.valid)
    );
    for (s, side) in ["left", "right"].iter().enumerate() {
        line += &format!(
            " {side}: truth yes {} (no image point 6-22 m {}, none at all {}) said {} (outer line visible in <50% rows {}, mean vis {:.2}, \
             support {:.2}, eq.6 favours it {}); truth no {} said yes {} |",
            t.has[s],
            pc(t.unseen_region[s], t.has[s]),
            pc(t.unseen[s], t.has[s]),
            pc(t.said[s], t.has[s]),
            pc(t.half_hidden[s], t.has[s]),
            mean(t.vis_sum[s], t.has[s]),
            mean(t.support_sum[s], t.has[s]),
            pc(t.ll_favours[s], t.has[s]),
            t.none[s],
            pc(t.none_said[s], t.none[s]),
        );
    }
    println!("{line}");
}

/// The best ln-likelihood of `model` over (q, w) within 0.3 m / 0.2 m of the truth's.
fn best_ll(lik: &Likelihood, votes: &Votes, model: usize, q: f64, w: f64) -> f64 {
    let mut best = f64::NEG_INFINITY;
    for i in -15..=15 {
        for k in -10..=10 {
            let ll = lik.log_likelihood(votes, model, q + i as f64 * 0.02, w + k as f64 * 0.02);
            best = best.max(ll);
        }
    }
    best
}

fn member(name: &str, seed: u64, max_frames: u32, options: &str, verbose: bool) -> Tally {
    let member = draw_scenario(name, seed).unwrap();
    let (w, h) = (320, 240);
    let mut scene = member.scene(w, h).unwrap();
    let options: serde_json::Value = serde_json::from_str(options).unwrap();
    let opts: std::collections::BTreeMap<String, serde_json::Value> =
        serde_json::from_value(options.clone()).unwrap();
    let config = TrackerConfig {
        camera: scene.camera().to_file(),
        particles: None,
        seed: 1,
        options: Options::ByName(opts),
    };
    let mut tracker = AdachiTracker::new(&config).unwrap();
    let mut aconfig: AdachiConfig = serde_json::from_value(options).unwrap();
    aconfig.lane_shape = lanepf::trackers::adachi::config::LaneShape::Straight;
    let mut votes = Votes::new(scene.camera(), &aconfig).unwrap();
    let mut lik = Likelihood::new(&aconfig);
    let rows_total = votes.rows_crossing(0, votes.bins() - 1).max(1);
    let m = aconfig.marking_width_m;
    let mut rgba = vec![0u8; w * h * 4];
    let frames = member.config.frames.min(max_frames);
    let mut t = Tally::default();
    {
        let mk = &member.mount;
        let pose = scene.pose(0);
        let road = scene.road();
        let style = |k: usize| {
            scene
                .config()
                .markings
                .style(road, k, pose.s)
                .map_or("-".to_string(), |st| format!("{:?}", st.pattern))
        };
        let lane = pose.lane;
        println!(
            "{name} {seed}: {} lanes of {:.2} m, lane {lane}, hfov {:.0} deg, height {:.2} m, \
             pitch {:.1} deg, yaw {:.1} deg; lines k-1 {} | k {} | k+1 {} | k+2 {}",
            member.config.road.lanes,
            member.config.road.lane_width_m,
            mk.hfov_deg,
            mk.height_m,
            mk.pitch_deg,
            mk.yaw_deg,
            if lane > 0 {
                style(lane - 1)
            } else {
                "-".into()
            },
            style(lane),
            style(lane + 1),
            style(lane + 2),
        );
    }
    for f in 0..frames {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        let truth = lanepf::trackers::scene_truth(&scene, f);
        let e = tracker.track(&rgba, w, h).unwrap();
        votes.vote(&rgba);
        lik.prepare(&votes);
        t.frames += 1;
        if !e.valid {
            continue;
        }
        t.valid += 1;
        let tr = truth.state["adachi.r"] as usize;
        let (tq, tw) = (truth.state["adachi.q"], truth.state["adachi.w"]);
        t.right += usize::from(tr == e.r);
        let truth_side = [tr == 2 || tr == 4, tr == 3 || tr == 4];
        let est_side = [e.r == 2 || e.r == 4, e.r == 3 || e.r == 4];
        let mut vis = [f64::NAN; 2];
        let mut sup = [f64::NAN; 2];
        let mut dll = [f64::NAN; 2];
        for s in 0..2 {
            // rho of the neighbour's outer boundary: l = 2 (left, -3w/2) or 3 (right, +3w/2)
            let rho = tq + OFFSETS[2 + s] * tw / 2.0;
            let edge = rho - m / 2.0;
            let j = votes.bin_of(edge);
            vis[s] = votes.rows_crossing(j, j) as f64 / rows_total as f64;
            sup[s] = lik.support(&votes, rho);
            // eq. 6 with and without this neighbour, the other side as the truth has it
            let other = truth_side[1 - s];
            let model_of = |left: bool, right: bool| usize::from(left) + 2 * usize::from(right);
            let (with, without) = if s == 0 {
                (model_of(true, other), model_of(false, other))
            } else {
                (model_of(other, true), model_of(other, false))
            };
            dll[s] = best_ll(&lik, &votes, with, tq, tw) - best_ll(&lik, &votes, without, tq, tw);
            if truth_side[s] {
                let role = [
                    lanepf::lane::Role::LeftAdjacent,
                    lanepf::lane::Role::RightAdjacent,
                ][s];
                let b = truth.boundaries.iter().find(|b| b.role == role).unwrap();
                t.unseen[s] += usize::from(b.road_points.is_empty());
                t.unseen_region[s] +=
                    usize::from(!b.road_points.iter().any(|p| (6.0..=22.0).contains(&p[0])));
                t.has[s] += 1;
                t.said[s] += usize::from(est_side[s]);
                t.half_hidden[s] += usize::from(vis[s] < 0.5);
                t.vis_sum[s] += vis[s];
                t.support_sum[s] += sup[s];
                t.ll_favours[s] += usize::from(dll[s] > 0.0);
            } else {
                t.none[s] += 1;
                t.none_said[s] += usize::from(est_side[s]);
            }
        }
        if verbose {
            println!(
                "{f:4} r {tr}->{} p [{:.2} {:.2} {:.2} {:.2}] q {tq:.2}/{:.2} w {tw:.2}/{:.2} \
                 vis L {:.2} R {:.2} sup L {:.2} R {:.2} dll L {:.0} R {:.0}",
                e.r,
                e.probabilities[0],
                e.probabilities[1],
                e.probabilities[2],
                e.probabilities[3],
                e.q,
                e.w,
                vis[0],
                vis[1],
                sup[0],
                sup[1],
                dll[0],
                dll[1]
            );
        }
    }
    t
}

/// `-g`: for each truth boundary role, over the voting region's rows of `frames` frames, the
/// share of rows whose largest horizontal Sobel response gx (left-edge polarity) within 4 px
/// of the boundary's image position passes 80 (the default `edge_threshold`), 40 and 20, and
/// the share whose Sobel magnitude sqrt(gx^2 + gy^2) (with gx > 0) passes 80.
fn gradients(name: &str, seed: u64, frames: u32) {
    use lanepf::lane::Role;
    let member = draw_scenario(name, seed).unwrap();
    let (w, h) = (320usize, 240usize);
    let mut scene = member.scene(w, h).unwrap();
    let cam = scene.camera().clone();
    let rows: Vec<usize> = (0..h)
        .filter(|&v| {
            cam.pixel_to_road(w as f64 / 2.0, v as f64)
                .is_ok_and(|[x, _]| (6.0..=22.0).contains(&x))
        })
        .collect();
    let mut rgba = vec![0u8; w * h * 4];
    let roles = [
        Role::EgoLeft,
        Role::EgoRight,
        Role::LeftAdjacent,
        Role::RightAdjacent,
    ];
    // per role: rows seen, gx > 80, > 40, > 20, magnitude > 80
    let mut n = [[0usize; 5]; 4];
    for f in 0..frames {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        let truth = lanepf::trackers::scene_truth(&scene, f);
        let g = |u: usize, v: usize| {
            let p = &rgba[(v * w + u) * 4..];
            lanepf::image::luma(p[0], p[1], p[2]) as f64
        };
        for (ri, role) in roles.iter().enumerate() {
            let Some(b) = truth.boundaries.iter().find(|b| b.role == *role) else {
                continue;
            };
            for &v in &rows {
                // u of the boundary at row v, by linear interpolation of its points
                let vv = v as f64;
                let Some(u) = b.points.windows(2).find_map(|s| {
                    let ([u0, v0], [u1, v1]) = (s[0], s[1]);
                    ((v0 - vv) * (v1 - vv) <= 0.0 && v0 != v1)
                        .then(|| u0 + (u1 - u0) * (vv - v0) / (v1 - v0))
                }) else {
                    continue;
                };
                if u < 6.0 || u > (w - 7) as f64 || v < 1 || v + 1 >= h {
                    continue;
                }
                let (mut gx_max, mut mag_max) = (0.0f64, 0.0f64);
                for du in -4i64..=4 {
                    let uu = (u.round() as i64 + du) as usize;
                    let gx = (g(uu + 1, v - 1) + 2.0 * g(uu + 1, v) + g(uu + 1, v + 1))
                        - (g(uu - 1, v - 1) + 2.0 * g(uu - 1, v) + g(uu - 1, v + 1));
                    let gy = (g(uu - 1, v + 1) + 2.0 * g(uu, v + 1) + g(uu + 1, v + 1))
                        - (g(uu - 1, v - 1) + 2.0 * g(uu, v - 1) + g(uu + 1, v - 1));
                    gx_max = gx_max.max(gx);
                    if gx > 0.0 {
                        mag_max = mag_max.max((gx * gx + gy * gy).sqrt());
                    }
                }
                n[ri][0] += 1;
                n[ri][1] += usize::from(gx_max > 80.0);
                n[ri][2] += usize::from(gx_max > 40.0);
                n[ri][3] += usize::from(gx_max > 20.0);
                n[ri][4] += usize::from(mag_max > 80.0);
            }
        }
    }
    for (ri, role) in roles.iter().enumerate() {
        let c = n[ri];
        if c[0] == 0 {
            continue;
        }
        let pc = |k: usize| 100.0 * c[k] as f64 / c[0] as f64;
        println!(
            "{name} {seed} {:?}: {} rows in the image; gx > 80 {:.0} %, > 40 {:.0} %, > 20 {:.0} %; \
             |grad| > 80 {:.0} %",
            role,
            c[0],
            pc(1),
            pc(2),
            pc(3),
            pc(4)
        );
    }
}
