//! The valid range of every numeric tracker option, checked when a tracker is built.
//!
//! Each tracker lists its options as [`OptionRange`]s: a path into the options object
//! (`canny.sigma`; `process_sd[1]` for one entry of an array; `width_range_m` for every entry)
//! and an inclusive `[min, max]`. The ranges are physical (a lane is 0.5 to 10 m wide, a
//! per-frame heading noise at most 1 rad) and bound the work a step does (histogram bins,
//! clusters, grid cells), so no accepted value can hang a step or exhaust memory. Limits that
//! tie two options together (near before far, cells of a map) stay in each config's checks.

use super::liu;
use super::{Error, Result};
use crate::num_text::{Exp, Num};
use serde::Serialize;
use serde_json::Value;

/// One option's valid values: `min <= value <= max`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OptionRange {
    /// The option's path in the options object.
    pub option: &'static str,
    /// Smallest accepted value.
    pub min: f64,
    /// Largest accepted value.
    pub max: f64,
}

const fn r(option: &'static str, min: f64, max: f64) -> OptionRange {
    OptionRange { option, min, max }
}

/// The far-range and road-edge Canny detector of lee-cpf and the Danescu trackers.
macro_rules! canny {
    () => {
        [
            r("canny.sigma", 0.1, 50.0),
            r("canny.low", 0.0, 2000.0),
            r("canny.high", 0.01, 2000.0),
        ]
    };
}

pub(super) const LEE: &[&[OptionRange]] = &[
    &[
        r("stage2_particles", 0.0, 200_000.0),
        r("near_m", 0.5, 100.0),
        r("split_m", 1.0, 250.0),
        r("far_m", 2.0, 500.0),
        r("near_step_m", 0.05, 50.0),
        r("far_step_m", 0.05, 100.0),
        r("lateral_range_m", 1.0, 50.0),
        r("cell_m", 0.01, 1.0),
        r("dld.window", 1.0, 256.0),
        r("dld.gamma", 0.0, 255.0),
        r("max_marking_width_m", 0.05, 2.0),
        r("map_sigma_m", 0.01, 5.0),
    ],
    &canny!(),
    &[
        r("marking_width_m", 0.02, 1.0),
        r("alpha", 0.001, 1000.0),
        r("beta", -1000.0, 1000.0),
        r("tau_m", 0.05, 5.0),
        r("sigma_q", 0.001, 100.0),
        r("sigma_far", 0.001, 100.0),
        r("spiral_length_m", 1.0, 1000.0),
        r("process_sd[0]", 1e-9, 1.0),
        r("process_sd[1]", 1e-9, 10.0),
        r("process_sd[2]", 1e-9, 5.0),
        r("process_sd[3]", 1e-9, 1.0),
        r("process_sd[4]", 1e-9, 100.0),
        r("process_sd[5]", 1e-9, 0.1),
        r("ess_threshold", 0.0, 1.0),
        r("max_heading_rad", 0.001, 1.0),
        r("width_range_m", 0.5, 10.0),
        r("max_width_rate", 1e-6, 0.5),
        r("max_transition_m", 1.0, 1000.0),
        r("max_curvature", 1e-6, 0.5),
        r("start_iterations", 0.0, 1000.0),
        r("start_spread", 1.0, 100.0),
        r("start_fresh", 0.0, 1.0),
        r("lost_restart", 0.0, 100_000.0),
        r("relock_share", 0.0, 0.5),
        r("start_pair_share", 0.0, 1.0),
        r("side_search_share", 0.0, 0.5),
        r("curvature_prior_sd", 0.0, 1.0),
        r("kalman_process_sd[0]", 1e-9, 1.0),
        r("kalman_process_sd[1]", 1e-9, 10.0),
        r("kalman_process_sd[2]", 1e-9, 5.0),
        r("kalman_process_sd[3]", 1e-9, 1.0),
        r("kalman_process_sd[4]", 1e-9, 100.0),
        r("kalman_process_sd[5]", 1e-9, 0.1),
        r("kalman_measurement_sd[0]", 1e-9, 1.0),
        r("kalman_measurement_sd[1]", 1e-9, 10.0),
        r("kalman_measurement_sd[2]", 1e-9, 5.0),
        r("kalman_measurement_sd[3]", 1e-9, 1.0),
        r("kalman_measurement_sd[4]", 1e-9, 100.0),
        r("kalman_measurement_sd[5]", 1e-9, 0.1),
        r("valid_fraction", 0.0, 1.0),
        r("valid_support_frames", 1.0, 100.0),
        r("reacquire_near_m", 0.0, 100.0),
    ],
];

pub(super) const LIU: &[&[OptionRange]] = &[&[
    r("top_view.x_min_m", 0.5, 200.0),
    r("top_view.x_max_m", 1.0, 500.0),
    r("top_view.y_left_m", -100.0, 100.0),
    r("top_view.y_right_m", -100.0, 100.0),
    r("top_view.m_per_px", 0.005, 1.0),
    r("boundaries", 1.0, liu::config::MAX_BOUNDARIES as f64),
    r("split", 0.1, 0.9),
    r("gradient_threshold", 0.0, 2000.0),
    r("position_variance_px2", 0.01, 100.0),
    r("intensity_mean", -100.0, 100.0),
    r("intensity_variance", 0.001, 100.0),
    r("quadrature_nodes", 1.0, 20.0),
    r("band_px", 1.0, 50.0),
    r("init_particles", 0.0, 100_000.0),
    r("sigma_rho_px", 0.001, 100.0),
    r("sigma_theta", 1e-6, 1.0),
    r("sigma_d", 1e-6, 1.0),
    r("min_spacing_m", 0.1, 10.0),
    r("max_spacing_difference_m", 0.01, 10.0),
    r("valid_fraction", 0.0, 1.0),
    r("valid_support_frames", 1.0, 100.0),
    r("valid_paint_contrast", 0.0, 255.0),
    r("default_width_m", 0.5, 10.0),
    r("default_heading_rad", 0.0, 0.9),
    r("default_jitter_m", 0.0, 2.0),
    r("relock_share", 0.0, 0.5),
    r("reacquire_near_m", 0.0, 100.0),
    r("mode_candidates", 1.0, 1000.0),
]];

pub(super) const ADACHI: &[&[OptionRange]] = &[&[
    r("near_m", 0.5, 100.0),
    r("far_m", 1.0, 200.0),
    r("rho_range_m", 1.0, 50.0),
    r("bin_m", 0.005, 1.0),
    r("edge_threshold", 0.0, 2000.0),
    r("marking_width_m", 0.02, 1.0),
    r("edge_sigma_m", 0.005, 2.0),
    r("start_iterations", 0.0, 1000.0),
    r("beta", 0.001, 1000.0),
    r("sigma_q_m", 1e-4, 5.0),
    r("sigma_w_m", 1e-4, 2.0),
    r("width_range_m", 0.5, 10.0),
    r("transitions", 0.0, 1.0),
    r("valid_support", 0.0, 1.0),
    r("valid_support_frames", 1.0, 100.0),
    r("max_heading_rad", 0.0, 0.5),
    r("max_curvature_per_m", 0.0, 0.05),
    r("shape_gain", 0.01, 1.0),
    r("relock_share", 0.0, 0.5),
    r("start_pair_share", 0.0, 1.0),
    r("vote_pair_share", 0.0, 0.5),
    r("side_search_share", 0.0, 0.5),
    r("reacquire_near_m", 0.0, 100.0),
]];

pub(super) const DANESCU: &[&[OptionRange]] = &[
    &[
        r("init_fraction", 0.0, 0.99),
        r("near_m", 0.5, 100.0),
        r("far_m", 1.0, 300.0),
        r("points", 2.0, 200.0),
        r("range_3d_m", 1.0, 100.0),
        r("diffusion[0]", 0.0, 1.0),
        r("diffusion[1]", 0.0, 0.01),
        r("diffusion[2]", 0.0, 0.1),
        r("diffusion[3]", 0.0, 0.01),
        r("diffusion[4]", 0.0, 1.0),
        r("diffusion[5]", 0.0, 2.0),
        r("diffusion[6]", 0.0, 0.2),
        r("diffusion[7]", 0.0, 0.2),
        r("diffusion[8]", 0.0, 0.2),
        r("diffusion[9]", 0.0, 0.5),
        r("diffusion[10]", 0.0, 0.5),
        r("init_width_m", 0.5, 10.0),
        r("init_offset_m", 0.0, 5.0),
        r("init_yaw_rad", 0.0, 0.5),
        r("init_curvature", 0.0, 0.1),
        r("init_width_rate", 0.0, 0.5),
        r("init_marking_m", 0.0, 1.0),
        r("init_pitch_rad", 0.0, 0.2),
        r("init_height_m", 0.0, 1.0),
        r("width_range_m", 0.0, 20.0),
        r("offset_margin_m", 0.0, 10.0),
        r("max_marking_m", 0.01, 2.0),
        r("sigma_edge_px", 0.1, 100.0),
        r("sigma_marking_px", 0.1, 100.0),
        r("sigma_gradient", 0.1, 1000.0),
        r("sigma_density", 0.01, 100.0),
        r("negative_offset_m", 0.0, 5.0),
        r("negative_reach_px", 0.0, 100.0),
        r("hgradient.marking_width_m", 0.02, 1.0),
        r("hgradient.max_half_width", 1.0, 256.0),
        r("hgradient.gain", 0.01, 100.0),
        r("marking_contrast", 0.1, 255.0),
        r("marking_width_range_m", 0.0, 2.0),
    ],
    &canny!(),
    &[
        r("density.rows", 3.0, 1000.0),
        r("density.cols", 3.0, 1000.0),
        r("density.dy_m", 0.001, 1.0),
        r("density.dz_m", 0.01, 10.0),
        r("density.threshold", 0.001, 1e6),
        r("curbs.cell_m", 0.01, 2.0),
        r("curbs.range_m", 1.0, 100.0),
        r("curbs.half_width_m", 1.0, 50.0),
        r("curbs.min_points", 1.0, 10_000.0),
        r("curbs.height_m", 0.01, 2.0),
        r("curbs.max_gap", 0.0, 1000.0),
        r("curbs.snap_m", 0.0, 1.0),
        r("disparity.max_disparity", 1.0, 256.0),
        r("disparity.census_radius", 1.0, 7.0),
        r("disparity.window_radius", 0.0, 7.0),
        r("disparity.uniqueness", 0.01, 1.0),
        r("disparity.left_right_tolerance", 0.0, 256.0),
        r("pitch_bin_rad", 1e-5, 0.1),
        r("pitch_range_rad", 1e-4, 0.5),
        r("road_tolerance_m", 0.01, 2.0),
        r("min_road_share", 0.0, 1.0),
        r("cluster_threshold_m", 0.01, 10.0),
        r("max_clusters", 1.0, 100.0),
        r("valid_distance_px", 0.1, 100.0),
        r("valid_distance_m", 0.0, 1.0),
        r("valid_support", 0.0, 1.0),
        r("valid_support_frames", 1.0, 100.0),
        r("valid_marking_factor", 0.0, 100.0),
        r("valid_marking_sides", 1.0, 2.0),
        r("valid_cluster_share", 0.0, 1.0),
        r("relock_share", 0.0, 0.5),
        r("start_iterations", 0.0, 1000.0),
    ],
];

/// The range of every numeric option of tracker `id` (`particles` excepted: 1 to
/// [`super::MAX_PARTICLES`] for all).
///
/// # Errors
/// [`Error::UnknownTracker`] for an id not in [`super::TRACKER_IDS`].
pub fn option_ranges(id: &str) -> Result<Vec<OptionRange>> {
    let groups = super::registry::entry(id)?.ranges;
    Ok(groups.iter().flat_map(|g| g.iter().copied()).collect())
}

/// Checks every option of `config` (a tracker's options struct) against the ranges of
/// tracker `id`.
///
/// # Errors
/// [`Error::Parameter`] naming the first option outside its range (a NaN or infinite value
/// included), with the range.
pub(crate) fn check_ranges(id: &str, config: &impl Serialize) -> Result<()> {
    let value =
        serde_json::to_value(config).map_err(|e| Error::Config(format!("{id} options: {e}")))?;
    for range in option_ranges(id)? {
        let node = lookup(&value, range.option)
            .ok_or_else(|| Error::Config(format!("{id}: no option `{}`", range.option)))?;
        check_node(range, node)?;
    }
    Ok(())
}

/// The value at `path` (`a.b`, `a[2]`).
fn lookup<'a>(value: &'a Value, path: &str) -> Option<&'a Value> {
    let mut node = value;
    for part in path.split('.') {
        let (key, index) = match part.split_once('[') {
            Some((key, rest)) => (key, Some(rest.trim_end_matches(']').parse::<usize>().ok()?)),
            None => (part, None),
        };
        node = node.get(key)?;
        if let Some(k) = index {
            node = node.get(k)?;
        }
    }
    Some(node)
}

/// Checks a number, or every number of an array (nested arrays included). A NaN or infinite
/// float serialises as `null`.
fn check_node(range: OptionRange, node: &Value) -> Result<()> {
    match node {
        Value::Array(items) => items.iter().try_for_each(|v| check_node(range, v)),
        Value::Number(n) => {
            let v = n.as_f64().unwrap_or(f64::NAN);
            if (range.min..=range.max).contains(&v) {
                Ok(())
            } else if n.is_f64() {
                Err(out_of_range(range, short(v)))
            } else {
                Err(out_of_range(range, n))
            }
        }
        _ => Err(out_of_range(range, "a non-finite number")),
    }
}

fn out_of_range(range: OptionRange, value: impl std::fmt::Display) -> Error {
    Error::parameter(
        range.option,
        value,
        &format!(
            "must be between {} and {}",
            short(range.min),
            short(range.max)
        ),
    )
}

/// A limit as a person writes it: 1e-9 and 1e6 rather than 0.000000001 and 1000000.
fn short(v: f64) -> String {
    if v != 0.0 && !(1e-3..1e6).contains(&v.abs()) {
        Exp(v).to_string()
    } else {
        Num(v).to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trackers::{adachi, danescu, lee, TRACKER_IDS};

    /// Every numeric leaf of a tracker's defaults, as a path.
    fn numeric_paths(value: &Value, prefix: &str, out: &mut Vec<String>) {
        match value {
            Value::Object(map) => {
                for (k, v) in map {
                    let path = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    numeric_paths(v, &path, out);
                }
            }
            Value::Array(items) => {
                for (k, v) in items.iter().enumerate() {
                    numeric_paths(v, &format!("{prefix}[{k}]"), out);
                }
            }
            Value::Number(_) => out.push(prefix.to_string()),
            _ => {}
        }
    }

    #[test]
    fn every_numeric_option_has_a_range_that_holds_its_default() {
        for id in TRACKER_IDS {
            let ranges = option_ranges(id).unwrap();
            let defaults = super::super::default_options(id).unwrap();
            let mut paths = Vec::new();
            numeric_paths(&defaults, "", &mut paths);
            for path in paths.iter().filter(|p| *p != "particles") {
                let covered = ranges.iter().any(|r| {
                    let base = path.split('[').next().unwrap_or(path);
                    r.option == path
                        || r.option == base
                        || path.starts_with(&format!("{}[", r.option))
                });
                assert!(covered, "{id}: `{path}` has no range");
            }
            for r in &ranges {
                assert!(r.min <= r.max, "{id}: {r:?}");
                check_node(*r, lookup(&defaults, r.option).unwrap())
                    .unwrap_or_else(|e| panic!("{id}: default out of range: {e}"));
            }
        }
        assert!(option_ranges("nope").is_err());
    }

    #[test]
    fn a_value_outside_its_range_is_named_with_the_range() {
        let mut c = lee::config::LeeConfig::default();
        c.process_sd[1] = 1e308;
        let e = check_ranges(lee::ID, &c).unwrap_err().to_string();
        assert!(
            e.contains("`process_sd[1]`") && e.contains("between 1e-9 and 10"),
            "{e}"
        );
        c.process_sd[1] = f64::NAN;
        let e = check_ranges(lee::ID, &c).unwrap_err().to_string();
        assert!(e.contains("`process_sd[1]` = a non-finite number"), "{e}");
    }

    /// Issue 19's examples: each passed the old checks and then panicked, hung or allocated
    /// gigabytes in the first step; now the tracker is refused, naming the option and range.
    #[test]
    fn the_values_that_crashed_or_hung_a_step_are_refused_by_name() {
        use crate::synth::default_camera;
        let camera = serde_json::to_value(default_camera(96, 72).unwrap().to_file()).unwrap();
        for (id, option, expected) in [
            (
                lee::ID,
                r#""width_range_m": [2.5, 1e200]"#,
                "`width_range_m` = 1e200: must be between 0.5 and 10",
            ),
            (
                lee::ID,
                r#""max_width_rate": 1e200"#,
                "`max_width_rate` = 1e200: must be between 1e-6 and 0.5",
            ),
            (
                lee::ID,
                r#""process_sd": [0.004, 1e308, 0.01, 0.0005, 1.5, 0.0002]"#,
                "`process_sd[1]` = 1e308: must be between 1e-9 and 10",
            ),
            (
                lee::ID,
                r#""spiral_length_m": 5e-324"#,
                "`spiral_length_m` = 4.94066e-324: must be between 1 and 1000",
            ),
            (
                liu::ID,
                r#""sigma_theta": 1e8"#,
                "`sigma_theta` = 1e8: must be between 1e-6 and 1",
            ),
            (
                adachi::ID,
                r#""near_m": 5e-324"#,
                "`near_m` = 4.94066e-324: must be between 0.5 and 100",
            ),
            (
                danescu::ID_MONO,
                r#""max_clusters": 2147483648"#,
                "`max_clusters` = 2147483648: must be between 1 and 100",
            ),
            (
                danescu::ID_STEREO,
                r#""max_clusters": 10000000"#,
                "`max_clusters` = 10000000: must be between 1 and 100",
            ),
        ] {
            let text = format!(r#"{{"camera": {camera}, {option}}}"#);
            let config = super::super::TrackerConfig::from_json_str(&text).unwrap();
            let e = super::super::create(id, &config)
                .err()
                .map(|e| e.to_string());
            assert!(
                e.as_deref().is_some_and(|e| e.contains(expected)),
                "{id} {option}: {e:?}"
            );
        }
    }

    /// The ranges as pkg/README.md lists them: one bullet per tracker.
    fn documented(ids: &[&str]) -> String {
        let ranges = option_ranges(ids[0]).unwrap();
        let list: Vec<String> = ranges
            .iter()
            .map(|r| format!("`{}` {} to {}", r.option, short(r.min), short(r.max)))
            .collect();
        let names: Vec<String> = ids.iter().map(|id| format!("`{id}`")).collect();
        format!("- {}: {}.", names.join(", "), list.join(", "))
    }

    #[test]
    fn the_package_readme_lists_every_range() {
        let readme = include_str!("../../pkg/README.md");
        let missing: Vec<String> = [
            &[adachi::ID][..],
            &[lee::ID],
            &[liu::ID, liu::ID_NOKERNEL],
            &[danescu::ID_MONO, danescu::ID_STEREO],
        ]
        .iter()
        .map(|ids| documented(ids))
        .filter(|line| !readme.contains(line.as_str()))
        .collect();
        assert!(
            missing.is_empty(),
            "pkg/README.md lacks:\n{}",
            missing.join("\n")
        );
    }
}
