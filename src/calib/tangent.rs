//! The column of the lane's tangent at the car, from the ego boundaries' marking pixels
//! (`tangent_yaw`; ours).
//!
//! A boundary y(X) = y0 + psi X + kappa X^2 / 2 on a flat road (X ahead, y left; psi the lane's
//! heading relative to the camera, kappa its curvature), seen by a pinhole camera pitched down
//! by theta at height h, lies at depth Z = X cos(theta) + h sin(theta) and row
//! t = v - v_h = fy h / (Z cos(theta)) below the horizon v_h, at column u = cx - fx y / Z. With
//! X = fy h / (t cos^2(theta)) - h tan(theta) this is
//!
//! ```text
//! u(t) = A + B t + C / t,   A = cx - fx psi / cos(theta),   B ~ y0,   C ~ kappa
//! ```
//!
//! up to a constant kappa h tan(theta) in the heading (under 0.02 degrees for a 500 m curve,
//! 1.5 m and 6 degrees). The two ego boundaries share A and C (one lane, one
//! heading, one curvature) and have their own B; least squares over both boundaries' pixels
//! gives the four. A is the vanishing point's column of the lane's direction at the car. The
//! crossing of two straight lines through the same pixels is the direction of a chord some
//! 5-40 m long instead, which on a 500 m curve lies nearly 2 degrees towards the bend's inside.
//! The 1 / t term is fixed by the pixels near the horizon, so the fit needs the boundaries'
//! far parts, takes one pixel a row and side (anything more near the horizon, such as a
//! double line's second stripe, reads as a bend), and where the lens bends lines that its
//! model does not know (no distortion given for a wide lens) takes that bend for the road's.
//!
//! For the same reason t must be counted from the true horizon: a horizon a pixel or two off
//! also reads as a bend. The straight lines' crossing, which gives the row, rises by 1-3
//! working pixels on a bend (in the simulator at 1/500 m) when the two boundaries' pixels
//! cover different rows, so on a bent frame the horizon row v_h is fitted too: the row within
//! [`HORIZON_SEARCH_PX`] of the crossing's whose least-squares fit leaves the smallest sum of
//! squared residuals (the tangent lines of both boundaries meet on it; a grid, then a
//! golden-section search). On a straight frame the crossing's row is the horizon, and the
//! calibrator holds it there ([`super::calibrator::BENT_SHARE`]): a free row there only adds
//! noise to a fit whose yaw already scatters by about half a degree from frame to frame.

use super::hough::LineFit;
use nalgebra::{Matrix4, Vector4};

/// Rows per boundary the fit needs.
pub const MIN_POINTS: usize = 6;

/// The pixels' rows below the horizon must reach this many times as far as they start.
pub const MIN_ROW_SPAN: f64 = 1.2;

/// How far (working pixels) the fitted horizon row may lie from the straight lines' crossing
/// on a bent frame (the calibrator holds it there on a straight one).
pub const HORIZON_SEARCH_PX: f64 = 3.0;

/// One row's pixel nearest a boundary's straight line: its distance from the line, its column
/// and its row (working pixels).
pub type NearestPixel = Option<(f64, f64, f64)>;

/// The column A (working pixels) of the lane's tangent direction at the car, and the horizon
/// row v_h it used: the joint fit of u = A + B_side t + C / t, t = v - v_h, over the rows
/// `rows`, to one pixel a row and side, the one of `points` nearest that side's line of
/// `lines` (left, right; working pixels) and within `band` pixels of it. v_h is `horizon`
/// when `search` is 0, else the best row within `search` pixels of it (and at most halfway
/// down to the highest pixel). One pixel a row: the second stripe of a double line, which
/// leaves the band where the stripes diverge towards the car, would otherwise weigh the far
/// rows twice and read as a bend (on Caltech's double yellow line a median 6 full-resolution
/// pixels, 1.1 degrees, of the column). `nearest` is scratch space kept between calls: it
/// grows only when the rows do. `None` with fewer than [`MIN_POINTS`] rows on a boundary,
/// rows that do not reach [`MIN_ROW_SPAN`] times as far below the horizon as they start, or a
/// singular fit.
pub fn tangent_column(
    points: &[[f32; 2]],
    lines: [&LineFit; 2],
    horizon: f64,
    rows: (f64, f64),
    band: f64,
    search: f64,
    nearest: &mut Vec<[NearestPixel; 2]>,
) -> Option<(f64, f64)> {
    let first = rows.0.max(horizon + 1.0).floor();
    let n_rows = (rows.1 - first).max(0.0) as usize + 1;
    nearest.clear();
    nearest.resize(n_rows, [None; 2]);
    for p in points {
        let (x, y) = (p[0] as f64, p[1] as f64);
        if y < rows.0 || y > rows.1 || y - horizon < 1.0 {
            continue;
        }
        let Some(row) = nearest.get_mut((y - first) as usize) else {
            continue;
        };
        for (side, line) in lines.iter().enumerate() {
            let d = (x - line.x_at(y)).abs();
            if d <= band && row[side].is_none_or(|(best, _, _)| d < best) {
                row[side] = Some((d, x, y));
            }
        }
    }
    let mut counts = [0usize; 2];
    let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for row in nearest.iter() {
        for (side, pixel) in row.iter().enumerate() {
            if let Some((_, _, y)) = *pixel {
                counts[side] += 1;
                y_min = y_min.min(y);
                y_max = y_max.max(y);
            }
        }
    }
    if counts.iter().any(|&n| n < MIN_POINTS) || y_max - horizon < MIN_ROW_SPAN * (y_min - horizon)
    {
        return None;
    }
    let pixels = || {
        nearest.iter().flat_map(|row| {
            row.iter()
                .enumerate()
                .filter_map(|(side, p)| p.map(|(_, x, y)| (side, x, y)))
        })
    };
    // The least-squares (A, B_left, B_right, C) for the horizon row `v_h`, and its sum of
    // squared residuals.
    let fit = |v_h: f64| -> Option<(Vector4<f64>, f64)> {
        let basis = |side: usize, y: f64| {
            let t = y - v_h;
            let mut b = Vector4::new(1.0, 0.0, 0.0, 1.0 / t);
            b[1 + side] = t;
            b
        };
        let mut normal = Matrix4::<f64>::zeros();
        let mut rhs = Vector4::<f64>::zeros();
        for (side, x, y) in pixels() {
            let b = basis(side, y);
            normal += b * b.transpose();
            rhs += b * x;
        }
        let solution = normal.try_inverse()? * rhs;
        let rss = pixels()
            .map(|(side, x, y)| (x - basis(side, y).dot(&solution)).powi(2))
            .sum::<f64>();
        (solution.iter().all(|v| v.is_finite()) && rss.is_finite()).then_some((solution, rss))
    };
    let rss = |v_h: f64| fit(v_h).map_or(f64::INFINITY, |f| f.1);
    let (lo, hi) = (
        horizon - search,
        (horizon + search).min(horizon + 0.5 * (y_min - horizon)),
    );
    let mut v_h = horizon;
    if search > 0.0 {
        const GRID: usize = 24;
        let step = (hi - lo) / GRID as f64;
        let mut best = (rss(horizon), horizon);
        for k in 0..=GRID {
            let v = lo + step * k as f64;
            let r = rss(v);
            if r < best.0 {
                best = (r, v);
            }
        }
        // Golden-section search in the grid cells either side of the best row: one new fit an
        // iteration, the other inner point carried over.
        let (mut a, mut b) = ((best.1 - step).max(lo), (best.1 + step).min(hi));
        const INV_PHI: f64 = 0.618_033_988_749_895;
        let (mut m1, mut m2) = (b - INV_PHI * (b - a), a + INV_PHI * (b - a));
        let (mut r1, mut r2) = (rss(m1), rss(m2));
        for _ in 0..30 {
            if r1 < r2 {
                (b, m2, r2) = (m2, m1, r1);
                m1 = b - INV_PHI * (b - a);
                r1 = rss(m1);
            } else {
                (a, m1, r1) = (m1, m2, r2);
                m2 = a + INV_PHI * (b - a);
                r2 = rss(m2);
            }
        }
        v_h = 0.5 * (a + b);
    }
    fit(v_h).map(|(solution, _)| (solution[0], v_h))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lane's two boundaries u = a + b_side t + c / t below the horizon row 100, and the
    /// straight lines through their ends.
    fn lane(a: f64, c: f64) -> (Vec<[f32; 2]>, [LineFit; 2]) {
        let horizon = 100.0;
        let u = |b: f64, y: f64| {
            let t = y - horizon;
            a + b * t + c / t
        };
        let mut points = Vec::new();
        for b in [-1.2, 1.5] {
            for y in 115..=300 {
                points.push([u(b, y as f64) as f32, y as f32]);
            }
        }
        let chord = |b: f64| {
            let (x0, x1) = (u(b, 115.0), u(b, 300.0));
            LineFit {
                x_ref: x0,
                y_ref: 115.0,
                slope: (x1 - x0) / 185.0,
                support: 186,
                y_top: 115.0,
                y_bottom: 300.0,
                bend: 0.0,
            }
        };
        (points, [chord(-1.2), chord(1.5)])
    }

    #[test]
    fn the_tangent_column_is_recovered_where_the_chords_miss_it() {
        for c in [0.0, 300.0, -300.0] {
            let (points, lines) = lane(320.0, c);
            let a = tangent_column(
                &points,
                [&lines[0], &lines[1]],
                100.0,
                (115.0, 300.0),
                40.0,
                0.0,
                &mut Vec::new(),
            )
            .unwrap()
            .0;
            assert!((a - 320.0).abs() < 0.05, "c {c}: {a}");
            // The chords cross off the tangent's column on a bend, on it on a straight road.
            let [l, r] = lines;
            let y = l.y_ref + (r.x_ref - l.x_ref) / (l.slope - r.slope);
            let chord_u = l.x_at(y);
            if c == 0.0 {
                assert!((chord_u - 320.0).abs() < 0.05, "{chord_u}");
            } else {
                assert!((chord_u - 320.0).abs() > 5.0, "c {c}: {chord_u}");
                assert!((chord_u - 320.0).signum() == c.signum(), "c {c}: {chord_u}");
            }
        }
    }

    #[test]
    fn the_horizon_row_is_fitted_not_taken_from_the_crossing() {
        // The chords' crossing two rows off the horizon (row 100), as on a bend: held there,
        // the fit reads the error as a bend and moves the column; fitted, it finds the row.
        let (points, lines) = lane(320.0, 300.0);
        for given in [98.0, 102.0] {
            let fit = |search: f64| {
                tangent_column(
                    &points,
                    [&lines[0], &lines[1]],
                    given,
                    (115.0, 300.0),
                    40.0,
                    search,
                    &mut Vec::new(),
                )
                .unwrap()
            };
            let (held, _) = fit(0.0);
            assert!((held - 320.0).abs() > 0.5, "given {given}: {held}");
            let (column, row) = fit(HORIZON_SEARCH_PX);
            assert!((column - 320.0).abs() < 0.05, "given {given}: {column}");
            assert!((row - 100.0).abs() < 0.01, "given {given}: {row}");
        }
    }

    #[test]
    fn too_few_pixels_or_rows_give_no_column() {
        let (points, lines) = lane(320.0, 100.0);
        let fit = |rows: (f64, f64), band: f64| {
            tangent_column(
                &points,
                [&lines[0], &lines[1]],
                100.0,
                rows,
                band,
                HORIZON_SEARCH_PX,
                &mut Vec::new(),
            )
        };
        assert!(fit((115.0, 300.0), 40.0).is_some());
        assert!(fit((115.0, 118.0), 40.0).is_none(), "4 rows");
        assert!(fit((270.0, 300.0), 40.0).is_none(), "t from 170 to 200");
        assert!(fit((250.0, 300.0), 40.0).is_some(), "t from 150 to 200");
        let none = tangent_column(
            &[],
            [&lines[0], &lines[1]],
            100.0,
            (0.0, 300.0),
            4.0,
            0.0,
            &mut Vec::new(),
        );
        assert!(none.is_none());
    }

    #[test]
    fn a_double_lines_second_stripe_does_not_read_as_a_bend() {
        // A straight lane whose left boundary has a second stripe outside it, 0.45 pixels off
        // at the top and leaving the 4-pixel band 133 rows below the horizon, as a double
        // yellow line does: counted with the first it weighs the far rows to the left.
        let (mut points, lines) = lane(320.0, 0.0);
        for y in 115..=300 {
            let t = (y - 100) as f64;
            points.push([(320.0 - 1.23 * t) as f32, y as f32]);
        }
        let mut scratch = Vec::new();
        let fit = |points: &[[f32; 2]], scratch: &mut Vec<_>| {
            tangent_column(
                points,
                [&lines[0], &lines[1]],
                100.0,
                (115.0, 300.0),
                4.0,
                0.0,
                scratch,
            )
            .unwrap()
            .0
        };
        let a = fit(&points, &mut scratch);
        assert!((a - 320.0).abs() < 0.05, "{a}");
        // The scratch is reused: a second frame gives the same column.
        assert_eq!(fit(&points, &mut scratch), a);
    }
}
