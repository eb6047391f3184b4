//! Radial-tangential lens distortion (Brown-Conrady, the OpenCV model) and its inverse.
//!
//! On normalised image coordinates (x, y) = ((u - cx) / fx, (v - cy) / fy), with r^2 = x^2 + y^2:
//!
//! ```text
//! radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//! x_d = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//! y_d = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//! ```
//!
//! Undistortion has no closed form; it is solved by Newton's method on the 2x2 system, starting
//! from the distorted point, to 1e-12 (normalised units, about 1e-9 px), and fails cleanly when
//! the point is outside the region where the model is invertible.

use crate::error::{Error, Result};
use crate::num_text::Fixed;

/// Distortion coefficients; all zero means an ideal pinhole.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Distortion {
    /// Radial k1.
    pub k1: f64,
    /// Radial k2.
    pub k2: f64,
    /// Tangential p1.
    pub p1: f64,
    /// Tangential p2.
    pub p2: f64,
    /// Radial k3.
    pub k3: f64,
}

impl Distortion {
    /// True when every coefficient is zero.
    pub fn is_none(&self) -> bool {
        *self == Distortion::default()
    }

    /// Distorts a normalised point.
    pub fn distort(&self, x: f64, y: f64) -> [f64; 2] {
        let r2 = x * x + y * y;
        let radial = 1.0 + r2 * (self.k1 + r2 * (self.k2 + r2 * self.k3));
        [
            x * radial + 2.0 * self.p1 * x * y + self.p2 * (r2 + 2.0 * x * x),
            y * radial + self.p1 * (r2 + 2.0 * y * y) + 2.0 * self.p2 * x * y,
        ]
    }

    /// Jacobian d(x_d, y_d) / d(x, y) as [[a, b], [c, d]].
    fn jacobian(&self, x: f64, y: f64) -> [[f64; 2]; 2] {
        let r2 = x * x + y * y;
        let radial = 1.0 + r2 * (self.k1 + r2 * (self.k2 + r2 * self.k3));
        // d radial / d r^2
        let dradial = self.k1 + r2 * (2.0 * self.k2 + 3.0 * r2 * self.k3);
        let (p1, p2) = (self.p1, self.p2);
        [
            [
                radial + 2.0 * x * x * dradial + 2.0 * p1 * y + 6.0 * p2 * x,
                2.0 * x * y * dradial + 2.0 * p1 * x + 2.0 * p2 * y,
            ],
            [
                2.0 * x * y * dradial + 2.0 * p1 * x + 2.0 * p2 * y,
                radial + 2.0 * y * y * dradial + 6.0 * p1 * y + 2.0 * p2 * x,
            ],
        ]
    }

    /// The largest r^2 up to which the radial map r -> r radial(r) increases, scanned in steps
    /// of 0.0005 up to r^2 = 16 (a field of view far wider than any calibration covers);
    /// `f64::INFINITY` when it increases all the way. Beyond it the model folds over: points
    /// far outside the field of view would land back inside the image.
    pub fn monotonic_r2(&self) -> f64 {
        if self.k1 == 0.0 && self.k2 == 0.0 && self.k3 == 0.0 {
            return f64::INFINITY;
        }
        const STEP: f64 = 0.0005;
        for i in 1..=32_000 {
            let s = i as f64 * STEP;
            let radial = 1.0 + s * (self.k1 + s * (self.k2 + s * self.k3));
            let dradial = self.k1 + s * (2.0 * self.k2 + 3.0 * s * self.k3);
            if radial + 2.0 * s * dradial <= 0.0 {
                return s - STEP;
            }
        }
        f64::INFINITY
    }

    /// True when the radial map r -> r radial(r) is increasing on [0, sqrt(`r2`)], i.e. the
    /// lens model has not folded over before that radius (checked at 32 radii).
    fn radially_monotonic_to(&self, r2: f64) -> bool {
        (1..=32).all(|i| {
            let s = r2 * (i as f64 / 32.0);
            let radial = 1.0 + s * (self.k1 + s * (self.k2 + s * self.k3));
            let dradial = self.k1 + s * (2.0 * self.k2 + 3.0 * s * self.k3);
            radial + 2.0 * s * dradial > 0.0
        })
    }

    /// The normalised point whose distortion is (`xd`, `yd`).
    ///
    /// # Errors
    /// [`Error::Geometry`] when Newton's method does not converge (the point lies where the
    /// distortion model folds over, far outside a calibrated field of view), or converges to
    /// a solution beyond that fold.
    pub fn undistort(&self, xd: f64, yd: f64) -> Result<[f64; 2]> {
        if self.is_none() {
            return Ok([xd, yd]);
        }
        let (mut x, mut y) = (xd, yd);
        for _ in 0..50 {
            let [fx, fy] = self.distort(x, y);
            let (ex, ey) = (fx - xd, fy - yd);
            if ex.abs() < 1e-12 && ey.abs() < 1e-12 {
                if self.radially_monotonic_to(x * x + y * y) {
                    return Ok([x, y]);
                }
                break;
            }
            let [[a, b], [c, d]] = self.jacobian(x, y);
            let det = a * d - b * c;
            if !det.is_finite() || det.abs() < 1e-12 {
                break;
            }
            x -= (d * ex - b * ey) / det;
            y -= (a * ey - c * ex) / det;
            if !(x.is_finite() && y.is_finite()) {
                break;
            }
        }
        Err(Error::Geometry(format!(
            "cannot undistort normalised point ({}, {}): outside the region where \
             the lens distortion model is invertible",
            Fixed(xd, 4),
            Fixed(yd, 4)
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Udacity camera's calibration (../shared/data/README.md).
    const UDACITY: Distortion = Distortion {
        k1: -0.24667,
        k2: -0.02544,
        p1: -0.00067,
        p2: 0.00013,
        k3: 0.01067,
    };

    #[test]
    fn the_udacity_lens_folds_over_near_radius_1_15() {
        let r2 = UDACITY.monotonic_r2();
        assert!((r2.sqrt() - 1.15).abs() < 0.02, "fold at r = {}", r2.sqrt());
        // Just inside, the map still grows; beyond, it shrinks.
        let r_d = |r: f64| UDACITY.distort(r, 0.0)[0];
        let r = r2.sqrt();
        assert!(r_d(r) > r_d(r - 0.01));
        assert!(r_d(r + 0.05) < r_d(r));
        assert_eq!(Distortion::default().monotonic_r2(), f64::INFINITY);
        let pincushion = Distortion {
            k1: 0.1,
            ..Distortion::default()
        };
        assert_eq!(pincushion.monotonic_r2(), f64::INFINITY);
    }

    #[test]
    fn undistort_inverts_distort_over_the_field_of_view() {
        // 1280x720 with fx = 1156: the corners are at about (0.58, 0.34) normalised.
        for i in -6..=6 {
            for j in -4..=4 {
                let (x, y) = (i as f64 * 0.1, j as f64 * 0.09);
                let [xd, yd] = UDACITY.distort(x, y);
                let [xu, yu] = UDACITY.undistort(xd, yd).unwrap();
                assert!(
                    (xu - x).abs() < 1e-10 && (yu - y).abs() < 1e-10,
                    "({x}, {y})"
                );
            }
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let (x, y, h) = (0.31, -0.22, 1e-6);
        let j = UDACITY.jacobian(x, y);
        let dx = |f: [f64; 2], g: [f64; 2]| [(f[0] - g[0]) / (2.0 * h), (f[1] - g[1]) / (2.0 * h)];
        let col0 = dx(UDACITY.distort(x + h, y), UDACITY.distort(x - h, y));
        let col1 = dx(UDACITY.distort(x, y + h), UDACITY.distort(x, y - h));
        for (got, want) in [
            (j[0][0], col0[0]),
            (j[1][0], col0[1]),
            (j[0][1], col1[0]),
            (j[1][1], col1[1]),
        ] {
            assert!((got - want).abs() < 1e-6, "{got} vs {want}");
        }
    }

    #[test]
    fn barrel_distortion_pulls_points_inwards_and_far_points_fail_cleanly() {
        let [xd, _] = UDACITY.distort(0.5, 0.0);
        assert!(xd < 0.5);
        assert!(UDACITY.undistort(50.0, 40.0).is_err());
        assert_eq!(
            Distortion::default().undistort(0.3, 0.2).unwrap(),
            [0.3, 0.2]
        );
    }
}
