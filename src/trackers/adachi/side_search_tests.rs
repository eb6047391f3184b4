//! `side_search_share` (ours, beyond the paper; [`crate::trackers::side_search`]) against the
//! paper's filter on drawn members of the scenario families (320x240, tracker seed 1).

use crate::trackers::fresh_roads::member_scores;

/// adachi-mmpf's boundary accuracy and detection rate on each member of `scenario`.
fn scores(scenario: &str, seeds: std::ops::RangeInclusive<u64>, share: f64) -> Vec<(f64, f64)> {
    let option = ("side_search_share", serde_json::json!(share));
    member_scores("adachi-mmpf", scenario, seeds, 150, option)
        .iter()
        .map(|s| {
            (
                s.report.boundaries.accuracy.unwrap_or(0.0),
                s.report.params.detection_rate.unwrap_or(0.0),
            )
        })
        .collect()
}

#[test]
fn probe() {
    for family in ["pitch-bumps", "lane-change", "width-change"] {
        let paper = scores(family, 1..=12, 0.0);
        let search = scores(family, 1..=12, 0.2);
        println!("{family}\n paper  {paper:.2?}\n search {search:.2?}");
    }
}
