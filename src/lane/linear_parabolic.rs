//! Liu et al.'s linear-parabolic boundary on the top view (eqs. 1, 15-16).
//!
//! In top-view pixel coordinates (x = column to the right, y = row downwards, origin at the
//! top-left pixel centre, so the car is below the bottom row), a boundary is a line near the
//! car and a parabola far from it, joined at the row y_m:
//!
//! ```text
//! x = f(y) = a + b y               y >  y_m   (near part, eq. 15)
//!            c + d y + e y^2        y <= y_m   (far part)
//! ```
//!
//! Continuity of f and f' at y_m and the normal form of the line rho = x cos(theta) +
//! y sin(theta) (eq. 1) leave three parameters (rho, theta, d) (eq. 16):
//!
//! ```text
//! a = rho / cos(theta),  b = -tan(theta),  c = a + (y_m / 2)(b - d),  e = (b - d) / (2 y_m)
//! ```
//!
//! theta is the angle of the line's normal from the x axis (0 for a boundary running straight
//! up the top view) and the orientation of the gradient across the far part follows eq. 7,
//! theta(y) = atan(-(d + 2 e y)). For fixed y_m the model is linear in (a, b, d):
//!
//! ```text
//! far part: x = a + b (y_m/2 + y^2/(2 y_m)) + d (y - y_m/2 - y^2/(2 y_m))
//! ```
//!
//! which is how [`LinearParabolic::fit`] computes the least-squares ground truth, as the paper
//! does from marked-up lane points.

use crate::math;

/// One boundary (rho, theta, d) with its split row y_m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearParabolic {
    /// Distance of the near line from the origin along its normal, pixels.
    pub rho: f64,
    /// Angle of the near line's normal from the x axis, radians.
    pub theta: f64,
    /// Slope of the far parabola at y = 0 (dx/dy), pixels per pixel.
    pub d: f64,
    /// The split row y_m.
    pub y_m: f64,
}

impl LinearParabolic {
    /// The boundary from the near line's intercept a and slope b (x = a + b y) and d.
    pub fn from_line(a: f64, b: f64, d: f64, y_m: f64) -> Self {
        let theta = -math::atan(b);
        Self {
            rho: a * math::cos(theta),
            theta,
            d,
            y_m,
        }
    }

    /// a of eq. 16.
    pub fn a(&self) -> f64 {
        self.rho / math::cos(self.theta)
    }
    /// b of eq. 16.
    pub fn b(&self) -> f64 {
        -math::tan(self.theta)
    }
    /// c of eq. 16.
    pub fn c(&self) -> f64 {
        self.a() + self.y_m / 2.0 * (self.b() - self.d)
    }
    /// e of eq. 16.
    pub fn e(&self) -> f64 {
        (self.b() - self.d) / (2.0 * self.y_m)
    }

    /// The coefficients (a, b, c, e) at once.
    pub fn coefficients(&self) -> [f64; 4] {
        let (s, co) = (math::sin(self.theta), math::cos(self.theta));
        let a = self.rho / co;
        let b = -s / co;
        let e = (b - self.d) / (2.0 * self.y_m);
        [a, b, a + self.y_m / 2.0 * (b - self.d), e]
    }

    /// x = f(y) (eq. 15).
    pub fn x_at(&self, y: f64) -> f64 {
        let [a, b, c, e] = self.coefficients();
        if y > self.y_m {
            a + b * y
        } else {
            c + self.d * y + e * y * y
        }
    }

    /// The slope dx/dy at y.
    pub fn slope_at(&self, y: f64) -> f64 {
        let [_, b, _, e] = self.coefficients();
        if y > self.y_m {
            b
        } else {
            self.d + 2.0 * e * y
        }
    }

    /// The straight boundary of the default lane model (Sec. IV-D): d = b.
    pub fn straight(rho: f64, theta: f64, y_m: f64) -> Self {
        Self {
            rho,
            theta,
            d: -math::tan(theta),
            y_m,
        }
    }

    /// Least-squares fit of (a, b, d) to points (x, y), both parts at once; `None` when the
    /// points do not determine the three parameters (e.g. none in one of the parts).
    pub fn fit(points: &[[f64; 2]], y_m: f64) -> Option<Self> {
        // Normal equations of x = a u0 + b u1 + d u2.
        let mut ata = nalgebra::Matrix3::<f64>::zeros();
        let mut atb = nalgebra::Vector3::<f64>::zeros();
        let (mut near, mut far) = (0, 0);
        for &[x, y] in points {
            let u = if y > y_m {
                near += 1;
                nalgebra::Vector3::new(1.0, y, 0.0)
            } else {
                far += 1;
                let q = y * y / (2.0 * y_m);
                nalgebra::Vector3::new(1.0, y_m / 2.0 + q, y - y_m / 2.0 - q)
            };
            ata += u * u.transpose();
            atb += u * x;
        }
        if near < 2 || far < 1 {
            return None;
        }
        let s = ata.lu().solve(&atb)?;
        s.iter()
            .all(|v| v.is_finite())
            .then(|| Self::from_line(s[0], s[1], s[2], y_m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_parts_meet_with_the_same_slope_at_the_split() {
        // Eq. 16: f and f' are continuous at y_m.
        for &(rho, theta, d) in &[(60.0, 0.05, -0.2), (-10.0, -0.3, 0.4), (150.0, 0.0, 0.0)] {
            let m = LinearParabolic {
                rho,
                theta,
                d,
                y_m: 150.0,
            };
            let [a, b, c, e] = m.coefficients();
            let y = m.y_m;
            assert!(((a + b * y) - (c + d * y + e * y * y)).abs() < 1e-9);
            assert!((b - (d + 2.0 * e * y)).abs() < 1e-12);
            assert!((m.x_at(y + 1e-7) - m.x_at(y - 1e-7)).abs() < 1e-5);
            assert!((a - m.a()).abs() < 1e-12 && (c - m.c()).abs() < 1e-12);
            assert!((e - m.e()).abs() < 1e-15 && (b - m.b()).abs() < 1e-15);
            // The near part is the line of eq. 1.
            let yn = 250.0;
            let xn = m.x_at(yn);
            assert!((xn * math::cos(theta) + yn * math::sin(theta) - rho).abs() < 1e-9);
            // The slope follows eq. 7 in the far part.
            let h = 1e-5;
            let numeric = (m.x_at(40.0 + h) - m.x_at(40.0 - h)) / (2.0 * h);
            assert!((numeric - m.slope_at(40.0)).abs() < 1e-6);
        }
        // The default straight boundary has no bend.
        let s = LinearParabolic::straight(50.0, 0.1, 150.0);
        assert!(s.e().abs() < 1e-15);
    }

    #[test]
    fn the_fit_recovers_a_boundary_from_its_points() {
        let truth = LinearParabolic {
            rho: 80.0,
            theta: -0.08,
            d: 0.25,
            y_m: 150.0,
        };
        let points: Vec<[f64; 2]> = (0..300)
            .step_by(3)
            .map(|y| [truth.x_at(y as f64), y as f64])
            .collect();
        let f = LinearParabolic::fit(&points, 150.0).unwrap();
        assert!((f.rho - truth.rho).abs() < 1e-6, "{f:?}");
        assert!((f.theta - truth.theta).abs() < 1e-9 && (f.d - truth.d).abs() < 1e-9);
        // Too few points in a part: no fit.
        assert!(LinearParabolic::fit(&points[..40], 150.0).is_none());
    }
}
