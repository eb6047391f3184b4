//! `curvature_prior_sd` (ours, beyond the paper) against the paper's uniform curvature, on
//! drawn members of the scenario families (320x240, tracker seed 1).

use crate::trackers::fresh_roads::member_scores;

/// The curvature RMSE (1/km) of lee-cpf's valid frames on each member (NaN: none valid).
fn curvature_rmse_per_km(
    scenario: &str,
    seeds: std::ops::RangeInclusive<u64>,
    frames: u32,
    prior_sd: f64,
) -> Vec<f64> {
    let option = ("curvature_prior_sd", serde_json::json!(prior_sd));
    member_scores("lee-cpf", scenario, seeds, frames, option)
        .iter()
        .map(|score| {
            score
                .report
                .params
                .curvature_per_m
                .map_or(f64::NAN, |s| s.rmse * 1e3)
        })
        .collect()
}

fn mean(values: &[f64]) -> f64 {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    finite.iter().sum::<f64>() / finite.len() as f64
}

/// On `shadows` the far band holds shadow edges and roadside texture as much as markings, and
/// the paper's far stage locks onto a false bend on some roads (measured 2026-11-26, seeds
/// 1-12, 100 frames: 5-16 /km on seeds 2, 4, 9, 10, 11, the others under 0.2); the prior
/// keeps the mean error under half the paper's and every road under 7.5 /km (6.8 at worst). On `s-curve`,
/// whose bends are real (radii down to about 250 m), it costs no accuracy.
#[test]
fn the_curvature_prior_stops_false_bends_and_keeps_real_ones() {
    let paper = curvature_rmse_per_km("shadows", 1..=12, 100, 0.0);
    let prior = curvature_rmse_per_km("shadows", 1..=12, 100, 0.004);
    println!("shadows curvature RMSE 1/km\n paper {paper:.2?}\n prior {prior:.2?}");
    assert!(
        paper.iter().any(|&e| e > 5.0),
        "the paper's false bend is gone: {paper:.2?}"
    );
    assert!(
        mean(&prior) < 0.5 * mean(&paper),
        "{prior:.2?} against {paper:.2?}"
    );
    // NaN: no valid frame on the road (seed 6, with or without the prior).
    let finite = prior.iter().filter(|e| e.is_finite());
    assert!(finite.clone().count() >= 10, "{prior:.2?}");
    assert!(finite.into_iter().all(|&e| e <= 7.5), "{prior:.2?}");

    let paper = curvature_rmse_per_km("s-curve", 1..=4, 100, 0.0);
    let prior = curvature_rmse_per_km("s-curve", 1..=4, 100, 0.004);
    println!("s-curve curvature RMSE 1/km\n paper {paper:.2?}\n prior {prior:.2?}");
    assert!(
        mean(&prior) <= mean(&paper) + 0.1,
        "{prior:.2?} against {paper:.2?}"
    );
}
