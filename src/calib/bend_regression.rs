//! The yaw of straight road, from frames on gentle bends too (ours).
//!
//! On a bend the ego boundaries' straight lines cross beside the lane's tangent vanishing
//! point, towards the inside of the bend, by about as much as the boundaries bend: a curve of
//! 500 m radius that passes as straight (common bend 1.3 working pixels at most 1.5) moves
//! the yaw by nearly 2 degrees in the simulator, and a drive round a long gentle curve does
//! not average it out. One frame's bend is too noisy to correct its own vanishing point (a
//! double or worn line bends one boundary by a pixel or two on straight road), but over the
//! frames the yaw follows the signed common bend b = (b_left + b_right) / 2 while the noise
//! does not. A least-squares line
//!
//! ```text
//! yaw_i = yaw_0 + k b_i
//! ```
//!
//! over the frames that agree on the pose gives yaw_0, the yaw of a frame that does not bend.
//! The fit is used only when the frames' bends spread enough to fix k (their standard
//! deviation at least [`MIN_BEND_SPREAD_PX`]) and there are at least [`MIN_SAMPLES`] of them;
//! otherwise the estimate keeps the median yaw of its chosen frames. Noise in b flattens k (by
//! var(bend) / (var(bend) + var(noise))), so a long bend is corrected only in part, and the
//! confidence still takes the chosen frames' spread of yaws for the yaw's error.

/// Frames the fit needs.
pub const MIN_SAMPLES: usize = 10;

/// Smallest standard deviation of the frames' common bends, working pixels, for the fit.
pub const MIN_BEND_SPREAD_PX: f64 = 0.3;

/// yaw_0 of the least-squares line through `(bend, yaw)` pairs; `None` when there are too few
/// or their bends do not spread.
pub fn yaw_at_zero_bend(pairs: impl Iterator<Item = (f64, f64)> + Clone) -> Option<f64> {
    let (mut n, mut sb, mut sy) = (0.0, 0.0, 0.0);
    for (b, y) in pairs.clone() {
        n += 1.0;
        sb += b;
        sy += y;
    }
    if n < MIN_SAMPLES as f64 {
        return None;
    }
    let (mb, my) = (sb / n, sy / n);
    let (mut sbb, mut sby) = (0.0, 0.0);
    for (b, y) in pairs {
        sbb += (b - mb) * (b - mb);
        sby += (b - mb) * (y - my);
    }
    if sbb / n < MIN_BEND_SPREAD_PX * MIN_BEND_SPREAD_PX {
        return None;
    }
    let k = sby / sbb;
    Some(my - k * mb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_through_bent_frames_gives_the_straight_yaw() {
        // A long bend (b about -1.3) and a little straight road, yaw 2 degrees per pixel.
        let pairs: Vec<(f64, f64)> = (0..40)
            .map(|i| {
                let b = if i < 8 {
                    0.1 * (i % 3) as f64 - 0.1
                } else {
                    -1.3 + 0.05 * (i % 5) as f64
                };
                (b, 0.5 + 2.0 * b)
            })
            .collect();
        let y0 = yaw_at_zero_bend(pairs.iter().copied()).unwrap();
        assert!((y0 - 0.5).abs() < 1e-9, "{y0}");
        let mean = pairs.iter().map(|p| p.1).sum::<f64>() / 40.0;
        assert!(mean < -1.0, "the mean is far off: {mean}");
    }

    #[test]
    fn too_few_frames_or_no_spread_gives_none() {
        assert!(yaw_at_zero_bend((0..9).map(|i| (i as f64, 0.0))).is_none());
        assert!(yaw_at_zero_bend((0..30).map(|i| (0.1 * (i % 2) as f64, 0.3))).is_none());
    }
}
