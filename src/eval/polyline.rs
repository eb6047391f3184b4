//! Small geometric helpers on image polylines shared by the metrics.
//!
//! A polyline is a list of image points [x, y]. Trackers write them bottom-up with at most
//! 10 px between consecutive rows, but nothing here relies on that: a row is looked up in the
//! first segment (in point order) whose closed y interval contains it, and distances are taken
//! to the nearest segment.

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
}
