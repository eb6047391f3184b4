//! The suite's Markdown table: one row per tracker and scenario.

use super::cell::CellRow;
use std::fmt::Write;

/// Column headers with their units.
const HEADER: &str = "| tracker | scenario | seeds | frames | detected | offset RMSE cm | \
heading RMSE deg | curvature RMSE 1/km | width MAE cm | points | lane config | \
recovery frames mean / max (never) | lane changes right / missed / spurious | ms |";

fn percent(x: Option<f64>) -> String {
    x.map_or_else(|| "n/a".into(), |x| format!("{:.0} %", 100.0 * x))
}

fn scaled(x: Option<f64>, scale: f64, decimals: usize) -> String {
    x.map_or_else(|| "n/a".into(), |x| format!("{:.*}", decimals, x * scale))
}

/// The table of `rows` ((tracker, scenario, row), in the order given) as Markdown.
pub fn markdown_table(rows: &[(String, String, CellRow)]) -> String {
    let mut out = String::new();
    let columns = HEADER.matches('|').count() - 1;
    let _ = writeln!(out, "{HEADER}");
    let _ = writeln!(out, "|{}", "---|".repeat(columns));
    for (tracker, scenario, r) in rows {
        let recovery = if r.blackouts == 0 {
            "-".to_string()
        } else {
            format!(
                "{} / {} ({})",
                scaled(r.recovery_mean_frames, 1.0, 1),
                r.recovery_max_frames
                    .map_or_else(|| "n/a".into(), |m| m.to_string()),
                r.not_recovered
            )
        };
        let changes = if r.lane_changes.truth == 0 && r.lane_changes.spurious == 0 {
            "-".to_string()
        } else {
            format!(
                "{} / {} / {}",
                r.lane_changes.right, r.lane_changes.missed, r.lane_changes.spurious
            )
        };
        let _ = writeln!(
            out,
            "| {tracker} | {scenario} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {recovery} | {changes} | {} |",
            r.seeds,
            r.frames,
            percent(r.detection_rate),
            scaled(r.offset_rmse_m, 100.0, 1),
            scaled(r.heading_rmse_deg, 1.0, 2),
            scaled(r.curvature_rmse_per_m, 1000.0, 2),
            scaled(r.width_mae_m, 100.0, 1),
            percent(r.point_accuracy),
            percent(r.lane_configuration_accuracy),
            scaled(r.ms, 1.0, 1),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::suite::SuiteCell;

    #[test]
    fn an_empty_cell_writes_a_row_of_n_a() {
        let row = SuiteCell::default().row();
        let t = markdown_table(&[("lee-cpf".into(), "night".into(), row)]);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0].matches('|').count(), lines[2].matches('|').count());
        assert!(
            lines[2].starts_with("| lee-cpf | night | 0 | 0 | n/a |"),
            "{t}"
        );
    }
}
