//! Diagnostic: one tracker on one drawn family member (320x240, tracker seed 1, as
//! `lanepf eval-suite` runs it), a line per frame: the truth's lane change, blackout, ego lane, offset,
//! width and curvature against the estimate's validity, offset, width and curvature, then the
//! estimate's state keys given; on stderr, the truth's and the output's lane-change events.
//!
//! `cargo run --release --example trace_member -- TRACKER SCENARIO SEED [KEY...]`, e.g.
//! `-- danescu-mono lane-change 1000 danescu.change danescu.xcw`.
use lanepf::eval::suite::run_member;
use lanepf::synth::draw_scenario;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let member = draw_scenario(&a[2], a[3].parse().unwrap()).unwrap();
    let run = run_member(
        &member,
        &[a[1].clone()],
        320,
        240,
        None,
        1,
        &Default::default(),
    )
    .unwrap();
    let keys: Vec<&String> = a[4..].iter().collect();
    for (i, (t, e)) in run.truth.iter().zip(&run.outputs[0].1).enumerate() {
        let mut line = format!(
            "{i:4} tlc={} bo={} tlane={} toff={:6.2} tw={:5.2} tc={:8.5} | v={} off={:6.2} w={:5.2} c={:8.5}",
            t.state.get("lane_change").copied().unwrap_or(0.0),
            t.state.get("blackout").copied().unwrap_or(0.0),
            t.state.get("ego_lane").copied().unwrap_or(f64::NAN),
            t.lateral_offset_m, t.lane_width_m, t.curvature_per_m,
            u8::from(e.valid), e.lateral_offset_m, e.lane_width_m, e.curvature_per_m
        );
        for k in &keys {
            line += &format!(
                " {k}={:.3}",
                e.state.get(k.as_str()).copied().unwrap_or(f64::NAN)
            );
        }
        println!("{line}");
    }
    use lanepf::eval::lane_changes::{predicted_lane_changes, truth_lane_changes};
    let preds: Vec<_> = run.outputs[0].1.iter().map(Some).collect();
    eprintln!("truth {:?}", truth_lane_changes(&run.truth));
    eprintln!("pred  {:?}", predicted_lane_changes(&preds));
}
