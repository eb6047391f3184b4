//! Small geometric helpers on image polylines shared by the metrics.
//!
//! A polyline is a list of image points [x, y]. Trackers write them bottom-up with at most
//! 10 px between consecutive rows, but nothing here relies on that: a row is looked up in the
//! first segment (in point order) whose closed y interval contains it, and distances are taken
//! to the nearest segment.

use super::limits::MAX_RESAMPLED;
use crate::error::{Error, Result};

/// The smallest and largest y of `points`, or `None` for an empty polyline.
pub fn y_range(points: &[[f64; 2]]) -> Option<(f64, f64)> {
    let mut it = points.iter();
    let first = it.next()?;
    Some(it.fold((first[1], first[1]), |(lo, hi), p| {
        (lo.min(p[1]), hi.max(p[1]))
    }))
}

/// x of the polyline at row `y` by linear interpolation in the first segment whose closed y
/// interval contains `y` (a horizontal segment at that row gives its first point's x); `None`
/// when no segment (or, for a single point, the point itself) is at that row.
pub fn x_at_y(points: &[[f64; 2]], y: f64) -> Option<f64> {
    if let [p] = points {
        return (p[1] == y).then_some(p[0]);
    }
    for s in points.windows(2) {
        let ([x0, y0], [x1, y1]) = (s[0], s[1]);
        if y < y0.min(y1) || y > y0.max(y1) {
            continue;
        }
        if y1 == y0 {
            return Some(x0);
        }
        let t = (y - y0) / (y1 - y0);
        return Some(x0 + t * (x1 - x0));
    }
    None
}

/// Points along the polyline at arc-length steps of at most `spacing` (> 0), both ends
/// included, written into `out` (cleared first). Each segment is split into the fewest equal
/// steps no longer than `spacing`.
///
/// # Errors
/// [`Error::Config`] when that takes more than [`MAX_RESAMPLED`] points (or a coordinate is
/// not finite), counted before anything is written.
pub fn resample_into(points: &[[f64; 2]], spacing: f64, out: &mut Vec<[f64; 2]>) -> Result<()> {
    out.clear();
    let Some(first) = points.first() else {
        return Ok(());
    };
    let spacing = if spacing > 0.0 { spacing } else { 1.0 };
    let steps = |s: &[[f64; 2]]| {
        let (dx, dy) = (s[1][0] - s[0][0], s[1][1] - s[0][1]);
        ((dx * dx + dy * dy).sqrt() / spacing).ceil().max(1.0)
    };
    let total: f64 = 1.0 + points.windows(2).map(steps).sum::<f64>();
    if total.is_nan() || total > MAX_RESAMPLED as f64 {
        let length: f64 = points.windows(2).map(|s| steps(s) * spacing).sum();
        return Err(Error::Config(format!(
            "a polyline of {} points and {length:.0} px would be resampled to {total:.0} points \
             every {spacing} px, more than {MAX_RESAMPLED}",
            points.len()
        )));
    }
    out.push(*first);
    for s in points.windows(2) {
        let (a, b) = (s[0], s[1]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let n = steps(s) as usize;
        for k in 1..=n {
            let t = k as f64 / n as f64;
            out.push([a[0] + t * dx, a[1] + t * dy]);
        }
    }
    Ok(())
}

/// Squared distance from `p` to the segment `a`-`b`.
pub fn segment_distance_sq(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (px, py) = (p[0] - a[0], p[1] - a[1]);
    let len_sq = dx * dx + dy * dy;
    let t = if len_sq > 0.0 {
        ((px * dx + py * dy) / len_sq).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (px - t * dx, py - t * dy);
    ex * ex + ey * ey
}

/// Distance from `p` to the nearest point of the polyline (to its only point if it has one;
/// infinity if it is empty).
pub fn distance_to_polyline(p: [f64; 2], points: &[[f64; 2]]) -> f64 {
    match points {
        [] => f64::INFINITY,
        [q] => ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt(),
        _ => points
            .windows(2)
            .map(|s| segment_distance_sq(p, s[0], s[1]))
            .fold(f64::INFINITY, f64::min)
            .sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_interpolated_in_the_first_covering_segment() {
        let pts = [[100.0, 400.0], [110.0, 390.0], [130.0, 380.0]];
        assert_eq!(x_at_y(&pts, 400.0), Some(100.0));
        assert_eq!(x_at_y(&pts, 395.0), Some(105.0));
        assert_eq!(x_at_y(&pts, 385.0), Some(120.0));
        assert_eq!(x_at_y(&pts, 380.0), Some(130.0));
        assert_eq!(x_at_y(&pts, 379.9), None);
        assert_eq!(x_at_y(&pts, 400.1), None);
        assert_eq!(x_at_y(&[[5.0, 7.0]], 7.0), Some(5.0));
        assert_eq!(x_at_y(&[], 7.0), None);
        assert_eq!(y_range(&pts), Some((380.0, 400.0)));
    }

    #[test]
    fn resampling_keeps_ends_and_spacing() {
        let pts = [[0.0, 0.0], [0.0, 10.0], [3.0, 14.0]];
        let mut out = Vec::new();
        resample_into(&pts, 1.0, &mut out).unwrap();
        assert_eq!(out.first(), Some(&[0.0, 0.0]));
        assert_eq!(out.last(), Some(&[3.0, 14.0]));
        assert_eq!(out.len(), 1 + 10 + 5);
    }

    #[test]
    fn resampling_a_zigzag_far_outside_the_image_is_refused_before_allocating() {
        // Issue 19: 300 points alternating x = 0 and x = 1e7 took 13 s and 700 MB.
        let pts: Vec<[f64; 2]> = (0..300)
            .map(|k| [if k % 2 == 0 { 0.0 } else { 1e7 }, k as f64])
            .collect();
        let mut out = Vec::new();
        let e = resample_into(&pts, 1.0, &mut out).unwrap_err().to_string();
        assert!(
            e.contains("300 points") && e.contains("more than 50000"),
            "{e}"
        );
        assert!(out.capacity() == 0 && out.is_empty());
        let e = resample_into(&[[0.0, 0.0], [f64::INFINITY, 0.0]], 1.0, &mut out);
        assert!(e.is_err());
    }

    #[test]
    fn distances_to_segments_and_points() {
        let line = [[0.0, 0.0], [10.0, 0.0]];
        assert!((distance_to_polyline([5.0, 3.0], &line) - 3.0).abs() < 1e-12);
        assert!((distance_to_polyline([13.0, 4.0], &line) - 5.0).abs() < 1e-12);
        assert!((distance_to_polyline([3.0, 4.0], &[[0.0, 0.0]]) - 5.0).abs() < 1e-12);
        assert_eq!(distance_to_polyline([0.0, 0.0], &[]), f64::INFINITY);
    }
}
