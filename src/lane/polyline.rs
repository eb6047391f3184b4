//! Sampling a road-plane curve y = f(x) into an image polyline.
//!
//! Every tracker describes a boundary as a lateral position y(x) on the road (ISO 8855: x
//! forward, y left); the output contract wants image points ordered from the bottom of the image
//! upward, no more than [`MAX_POINT_SPACING_PX`] apart in y. The curve is sampled at
//! geometrically growing distances (x_{k+1} = 1.03 x_k, dense near the car where the image
//! changes fastest), projected, and wherever two consecutive visible points are too far apart in
//! y the interval is bisected (up to 12 times). Points outside the image are dropped; the
//! polyline is the first visible run, so a boundary hidden behind the hood or off the side of
//! the image starts where it becomes visible.

use super::estimate::MAX_POINT_SPACING_PX;

/// Samples y = `curve(x)` for x in [`x_min`, `x_max`] (metres, `x_min > 0`) into image points,
/// bottom first. `project` maps a road point (x, y) to a pixel, or `None` when it cannot be seen
/// (behind the camera); `width` x `height` is the image size. Also returns the road points kept.
pub fn sample_road_curve(
    curve: impl Fn(f64) -> f64,
    project: impl Fn(f64, f64) -> Option<[f64; 2]>,
    x_min: f64,
    x_max: f64,
    width: usize,
    height: usize,
) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let (w, h) = (width as f64, height as f64);
    let visible = |x: f64| -> Option<[f64; 2]> {
        let p = project(x, curve(x))?;
        (p[0] >= 0.0 && p[0] <= w - 1.0 && p[1] >= 0.0 && p[1] <= h - 1.0).then_some(p)
    };
    let mut image = Vec::new();
    let mut road = Vec::new();
    if !(x_min > 0.0 && x_max > x_min && x_min.is_finite() && x_max.is_finite()) {
        return (image, road);
    }
    let push = |x: f64, p: [f64; 2], image: &mut Vec<[f64; 2]>, road: &mut Vec<[f64; 2]>| {
        image.push(p);
        road.push([x, curve(x)]);
    };
    let mut prev: Option<(f64, [f64; 2])> = None;
    let mut x = x_min;
    loop {
        match (prev, visible(x)) {
            (None, Some(p)) => {
                push(x, p, &mut image, &mut road);
                prev = Some((x, p));
            }
            (Some((x0, p0)), Some(p1)) => {
                refine(&visible, (x0, p0), (x, p1), 12, &mut |xm, pm| {
                    push(xm, pm, &mut image, &mut road)
                });
                // Keep the polyline going up the image: a point that goes back down (a curve
                // bending past the horizon) ends it.
                if p1[1] > p0[1] {
                    break;
                }
                push(x, p1, &mut image, &mut road);
                prev = Some((x, p1));
            }
            (Some(_), None) => break,
            (None, None) => {}
        }
        if x >= x_max {
            break;
        }
        x = (x * 1.03).min(x_max);
    }
    (image, road)
}

/// Inserts points between `a` and `b` (exclusive) until consecutive points are at most
/// [`MAX_POINT_SPACING_PX`] apart in y, calling `emit` in order of increasing x.
fn refine(
    visible: &impl Fn(f64) -> Option<[f64; 2]>,
    a: (f64, [f64; 2]),
    b: (f64, [f64; 2]),
    depth: u32,
    emit: &mut impl FnMut(f64, [f64; 2]),
) {
    if (a.1[1] - b.1[1]).abs() <= MAX_POINT_SPACING_PX || depth == 0 {
        return;
    }
    let xm = 0.5 * (a.0 + b.0);
    let Some(pm) = visible(xm) else { return };
    refine(visible, a, (xm, pm), depth - 1, emit);
    emit(xm, pm);
    refine(visible, (xm, pm), b, depth - 1, emit);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::{Boundary, Role};

    /// A level pinhole camera 2 m above the road: u = cx - f y / x, v = cy + f h / x.
    fn level(x: f64, y: f64) -> Option<[f64; 2]> {
        (x > 0.1).then(|| [320.0 - 400.0 * y / x, 200.0 + 400.0 * 2.0 / x])
    }

    #[test]
    fn polyline_is_bottom_up_dense_and_on_the_curve() {
        let (img, road) = sample_road_curve(|_| 1.8, level, 1.0, 80.0, 640, 480);
        assert!(img.len() > 20);
        assert_eq!(img.len(), road.len());
        let b = Boundary {
            role: Role::EgoLeft,
            points: img.clone(),
            road_points: vec![],
        };
        assert_eq!(b.check_polyline(), Ok(()));
        // The first point is where the line enters the image bottom (v <= 479 => x >= 2.8 m).
        assert!(img[0][1] <= 479.0 && img[0][1] > 440.0, "{:?}", img[0]);
        for (p, r) in img.iter().zip(&road) {
            let q = level(r[0], r[1]).unwrap();
            assert!((p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
            assert_eq!(r[1], 1.8);
        }
        // It reaches 80 m: v = 200 + 800 / 80 = 210.
        assert!((img.last().unwrap()[1] - 210.0).abs() < 1e-9);
    }

    #[test]
    fn invisible_or_invalid_ranges_give_empty_polylines() {
        // A boundary 100 m to the left never enters a 640 px wide image beyond 1 m... except far
        // away; keep it off-image by stopping at 50 m (u = 320 - 400*100/50 = -480).
        let (img, _) = sample_road_curve(|_| 100.0, level, 1.0, 50.0, 640, 480);
        assert!(img.is_empty());
        assert!(sample_road_curve(|_| 0.0, level, 0.0, 50.0, 640, 480)
            .0
            .is_empty());
        assert!(sample_road_curve(|_| 0.0, level, 10.0, f64::NAN, 640, 480)
            .0
            .is_empty());
    }
}
