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
//! far parts, and where the lens bends lines that its model does not know (no distortion
//! given for a wide lens) it takes that bend for the road's.

use super::hough::LineFit;
use nalgebra::{Matrix4, Vector4};

/// Pixels per boundary the fit needs.
pub const MIN_POINTS: usize = 6;

/// The pixels' rows below the horizon must reach this many times as far as they start.
pub const MIN_ROW_SPAN: f64 = 1.2;

/// The column A (working pixels) of the lane's tangent direction at the car: the joint fit of
/// u = A + B_side t + C / t, t = v - `horizon`, to the `points` within `band` pixels of either
/// of `lines` (left, right; working pixels) in the rows `rows`. `None` with fewer than
/// [`MIN_POINTS`] pixels on a boundary, rows that do not reach [`MIN_ROW_SPAN`] times as far
/// below the horizon as they start, or a singular fit.
pub fn tangent_column(
    points: &[[f32; 2]],
    lines: [&LineFit; 2],
    horizon: f64,
    rows: (f64, f64),
    band: f64,
) -> Option<f64> {
    let mut normal = Matrix4::<f64>::zeros();
    let mut rhs = Vector4::<f64>::zeros();
    let mut counts = [0usize; 2];
    let (mut t_min, mut t_max) = (f64::INFINITY, 0.0f64);
    for p in points {
        let (x, y) = (p[0] as f64, p[1] as f64);
        let t = y - horizon;
        if y < rows.0 || y > rows.1 || t < 1.0 {
            continue;
        }
        for (side, line) in lines.iter().enumerate() {
            if (x - line.x_at(y)).abs() > band {
                continue;
            }
            let mut basis = Vector4::new(1.0, 0.0, 0.0, 1.0 / t);
            basis[1 + side] = t;
            normal += basis * basis.transpose();
            rhs += basis * x;
            counts[side] += 1;
            t_min = t_min.min(t);
            t_max = t_max.max(t);
        }
    }
    if counts.iter().any(|&n| n < MIN_POINTS) || t_max < MIN_ROW_SPAN * t_min {
        return None;
    }
    let solution = normal.try_inverse()? * rhs;
    solution[0].is_finite().then_some(solution[0])
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
            let a = tangent_column(&points, [&lines[0], &lines[1]], 100.0, (115.0, 300.0), 40.0)
                .unwrap();
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
    fn too_few_pixels_or_rows_give_no_column() {
        let (points, lines) = lane(320.0, 100.0);
        let fit = |rows: (f64, f64), band: f64| {
            tangent_column(&points, [&lines[0], &lines[1]], 100.0, rows, band)
        };
        assert!(fit((115.0, 300.0), 40.0).is_some());
        assert!(fit((115.0, 118.0), 40.0).is_none(), "4 rows");
        assert!(fit((270.0, 300.0), 40.0).is_none(), "t from 170 to 200");
        assert!(fit((250.0, 300.0), 40.0).is_some(), "t from 150 to 200");
        assert!(tangent_column(&[], [&lines[0], &lines[1]], 100.0, (0.0, 300.0), 4.0).is_none());
    }
}
