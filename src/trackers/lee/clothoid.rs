//! The clothoid lane model of Lee et al. (eqs. 10-17, 27-28).
//!
//! The lane centre in the vehicle frame (x forward, y left) is
//!
//! ```text
//! y_c(x) = y0 + x tan(psi) + g(x; c, delta)                       (eqs. 27-28 plus the curve)
//! y_L(x) = y_c(x) + (w + w' x) / 2,   y_R(x) = y_c(x) - (w + w' x) / 2
//! ```
//!
//! where g is the lateral deviation of a clothoid from the lane's tangent at the car. The
//! road runs straight up to the transition point at distance c, then follows a spiral whose
//! curvature grows linearly with arc length s (eqs. 10-11: d theta / ds = 2 a^2 s) from 0 to
//! delta over the spiral length s_o, then a circular arc of curvature delta. With
//! a = 1 / sqrt(2 R_c s_o) (eq. 12, R_c = 1 / |delta|) the heading is theta = (a s)^2 (eq. 13)
//! and the spiral's points are x = C(a L) / a, y = S(a L) / a (eqs. 14-17) with the Fresnel
//! integrals C and S evaluated by their power series ([`fresnel`]).
//!
//! Our choices where the paper is silent:
//! - the paper's two curve states are c and delta; the spiral length s_o is a setting
//!   (`spiral_length_m`), as a road designer would fix it;
//! - c may be negative down to -s_o: the car is already that far into the spiral (c = -s_o: in
//!   the arc). The curve is then expressed in the frame of the lane's tangent at the car, so
//!   that y0 and psi keep their meaning (offset and heading at the car) for every c;
//! - g is added laterally, as eqs. 27-28 add the half width: exact for psi = 0, with an error
//!   of order psi g(x) otherwise (under 1 cm for psi = 2 deg and g = 0.3 m).

use crate::math;

/// Fresnel integrals (C(t), S(t)) = (int_0^t cos s^2 ds, int_0^t sin s^2 ds) (eqs. 16-17) by
/// their power series
///
/// ```text
/// C(t) = sum_n (-1)^n t^(4n+1) / ((2n)! (4n+1)),  S(t) = sum_n (-1)^n t^(4n+3) / ((2n+1)! (4n+3))
/// ```
///
/// summed until the terms fall below 1e-17 of the sum. Accurate to about 1e-14 for |t| <= 2
/// (the lane model stays below t = 1.25, a heading change of 1.5 rad); the alternating terms
/// lose precision beyond |t| = 4.
pub fn fresnel(t: f64) -> (f64, f64) {
    let t4 = t * t * t * t;
    let (mut c, mut s) = (0.0, 0.0);
    // p = (-1)^n t^(4n+1) / (2n)!, q = (-1)^n t^(4n+3) / (2n+1)!.
    let (mut p, mut q) = (t, t * t * t);
    for n in 0..60 {
        let k = n as f64;
        let (dc, ds) = (p / (4.0 * k + 1.0), q / (4.0 * k + 3.0));
        c += dc;
        s += ds;
        if dc.abs() <= 1e-17 * c.abs().max(1e-300) && ds.abs() <= 1e-17 * s.abs().max(1e-300) {
            break;
        }
        p *= -t4 / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
        q *= -t4 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
    }
    (c, s)
}

/// The six states of the lane (eqs. 18-19).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LaneState {
    /// Heading psi of the lane relative to the car, radians, positive left.
    pub psi: f64,
    /// Lateral position y0 of the lane centre, metres, positive left.
    pub y0: f64,
    /// Lane width w at the car, metres.
    pub w: f64,
    /// Width variation w' per metre ahead.
    pub w1: f64,
    /// Distance c to the transition point, metres (negative: already in the curve).
    pub c: f64,
    /// Curvature delta reached after the spiral, 1/m, positive turning left.
    pub delta: f64,
}

/// The curve term g(x) of one (c, delta), with its frame precomputed.
#[derive(Debug, Clone, Copy)]
pub struct Curve {
    /// Distance before which the lane is straight (max(c, 0)).
    start: f64,
    /// Arc length of the spiral at the car (max(-c, 0)).
    l0: f64,
    /// Spiral length s_o.
    spiral: f64,
    /// Curvature rate delta / s_o.
    rate: f64,
    delta: f64,
    /// a of eq. 12 (0 for a straight road).
    a: f64,
    /// Point and heading of the spiral at l0, in the spiral's own frame.
    origin: [f64; 2],
    theta0: f64,
    /// End of the spiral in its own frame and its heading.
    end: [f64; 2],
    theta_end: f64,
}

impl Curve {
    /// The curve of a lane with transition point `c` and curvature `delta` after a spiral of
    /// `spiral` metres (c is clamped to [-spiral, inf)).
    pub fn new(c: f64, delta: f64, spiral: f64) -> Self {
        let c = c.max(-spiral);
        let rate = delta / spiral;
        let a = (rate.abs() / 2.0).sqrt();
        let mut curve = Self {
            start: c.max(0.0),
            l0: (-c).max(0.0),
            spiral,
            rate,
            delta,
            a,
            origin: [0.0; 2],
            theta0: 0.0,
            end: [0.0; 2],
            theta_end: 0.0,
        };
        curve.end = curve.spiral_point(spiral);
        curve.theta_end = curve.heading(spiral);
        curve.origin = curve.point(curve.l0);
        curve.theta0 = curve.heading(curve.l0);
        curve
    }

    /// Heading theta(L) in the spiral's frame: rate L^2 / 2 = (a L)^2 on the spiral (eq. 13),
    /// then growing by delta per metre on the arc.
    fn heading(&self, l: f64) -> f64 {
        if l <= self.spiral {
            self.rate * l * l / 2.0
        } else {
            self.rate * self.spiral * self.spiral / 2.0 + self.delta * (l - self.spiral)
        }
    }

    /// Point of the spiral at arc length L <= s_o (eqs. 14-17).
    fn spiral_point(&self, l: f64) -> [f64; 2] {
        if self.a < 1e-12 {
            // Straight (or nearly): the series limit y = rate L^3 / 6.
            return [l, self.rate * l * l * l / 6.0];
        }
        let (c, s) = fresnel(self.a * l);
        [c / self.a, self.rate.signum() * s / self.a]
    }

    /// Point at arc length L in the spiral's frame (spiral, then arc).
    fn point(&self, l: f64) -> [f64; 2] {
        if l <= self.spiral {
            return self.spiral_point(l);
        }
        let d = self.delta;
        let t1 = self.theta_end + d * (l - self.spiral);
        if d.abs() < 1e-12 {
            let (sn, cs) = (math::sin(self.theta_end), math::cos(self.theta_end));
            return [
                self.end[0] + cs * (l - self.spiral),
                self.end[1] + sn * (l - self.spiral),
            ];
        }
        [
            self.end[0] + (math::sin(t1) - math::sin(self.theta_end)) / d,
            self.end[1] + (math::cos(self.theta_end) - math::cos(t1)) / d,
        ]
    }

    /// Point at arc length L in the frame of the lane's tangent at the car.
    fn local(&self, l: f64) -> [f64; 2] {
        let p = self.point(l);
        let (sn, cs) = (math::sin(self.theta0), math::cos(self.theta0));
        let (dx, dy) = (p[0] - self.origin[0], p[1] - self.origin[1]);
        [cs * dx + sn * dy, -sn * dx + cs * dy]
    }

    /// g(x): the lateral deviation of the lane centre from its tangent at the car, x metres
    /// ahead (0 before the transition point). The arc length of x is found by Newton steps on
    /// X(L) = x (dX/dL = cos(theta(L) - theta0)), starting from L = x.
    pub fn lateral(&self, x: f64) -> f64 {
        let u = x - self.start;
        if u <= 0.0 || (self.a < 1e-12 && self.delta.abs() < 1e-12) {
            return 0.0;
        }
        let mut l = self.l0 + u;
        for _ in 0..4 {
            let p = self.local(l);
            let slope = math::cos(self.heading(l) - self.theta0).max(0.1);
            let step = (p[0] - u) / slope;
            l -= step;
            if step.abs() < 1e-9 {
                break;
            }
        }
        self.local(l)[1]
    }

    /// Curvature of the lane at the car, 1/m.
    pub fn curvature_at_car(&self) -> f64 {
        if self.l0 <= self.spiral {
            self.rate * self.l0
        } else {
            self.delta
        }
    }
}

impl LaneState {
    /// Lane-centre lateral position at distance x (first-order part plus `curve`).
    pub fn centre(&self, x: f64, curve: Option<&Curve>) -> f64 {
        self.centre_with(x, math::tan(self.psi), curve)
    }

    /// [`LaneState::centre`] with tan(psi) computed once by the caller.
    #[inline]
    pub fn centre_with(&self, x: f64, tan_psi: f64, curve: Option<&Curve>) -> f64 {
        self.y0 + x * tan_psi + curve.map_or(0.0, |c| c.lateral(x))
    }

    /// Half the lane width at distance x: (w + w' x) / 2.
    pub fn half_width(&self, x: f64) -> f64 {
        (self.w + self.w1 * x) / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_series_matches_numerical_integration() {
        for &t in &[0.0, 0.1, 0.5, 1.0, 1.25, 1.7, 2.0, -0.8] {
            let (c, s) = fresnel(t);
            let cn = math::simpson(|u| math::cos(u * u), 0.0, t, 20_000);
            let sn = math::simpson(|u| math::sin(u * u), 0.0, t, 20_000);
            assert!(
                (c - cn).abs() < 1e-12 && (s - sn).abs() < 1e-12,
                "t {t}: {c} {s} vs {cn} {sn}"
            );
        }
        // The limits at infinity are sqrt(pi/8); at t = 2 the series is still exact enough to
        // match the known values C(2) = 0.461461..., S(2) = 0.804776...
        let (c, s) = fresnel(2.0);
        assert!((c - 0.461_461_2).abs() < 1e-6 && (s - 0.804_776_6).abs() < 1e-6);
    }

    /// The curve integrated numerically from its curvature: y'' ~ kappa(s) along the arc.
    fn integrate(c: f64, delta: f64, spiral: f64, x_max: f64) -> Vec<(f64, f64)> {
        // March along the arc length from the car with small steps in the car's frame.
        let kappa = |s_from_start: f64| {
            if s_from_start <= 0.0 {
                0.0
            } else if s_from_start <= spiral {
                delta * s_from_start / spiral
            } else {
                delta
            }
        };
        let (mut x, mut y, mut th) = (0.0f64, 0.0f64, 0.0f64);
        let ds = 1e-3;
        let mut out = Vec::new();
        let mut s = 0.0;
        let mut next = 1.0;
        while x < x_max {
            let k = kappa(s - c);
            th += k * ds / 2.0;
            x += math::cos(th) * ds;
            y += math::sin(th) * ds;
            th += k * ds / 2.0;
            s += ds;
            if x >= next {
                out.push((x, y));
                next += 1.0;
            }
        }
        out
    }

    #[test]
    fn curve_matches_the_integrated_curvature_profile() {
        for &(c, delta) in &[
            (20.0, 0.004),
            (0.0, -0.01),
            (-30.0, 1.0 / 300.0),
            (-80.0, 0.02),
        ] {
            let curve = Curve::new(c, delta, 60.0);
            for (x, y) in integrate(c.max(-60.0), delta, 60.0, 40.0) {
                let g = curve.lateral(x);
                assert!(
                    (g - y).abs() < 2e-3,
                    "c {c} delta {delta} x {x}: {g} vs {y}"
                );
            }
        }
        // Curvature at the car: 0 before the curve, half-way up the spiral, then delta.
        assert_eq!(Curve::new(10.0, 0.01, 60.0).curvature_at_car(), 0.0);
        assert!((Curve::new(-30.0, 0.01, 60.0).curvature_at_car() - 0.005).abs() < 1e-12);
        assert_eq!(Curve::new(-100.0, 0.01, 60.0).curvature_at_car(), 0.01);
        // A straight road has no deviation.
        assert_eq!(Curve::new(5.0, 0.0, 60.0).lateral(50.0), 0.0);
    }

    #[test]
    fn boundaries_follow_eqs_27_and_28() {
        let s = LaneState {
            psi: 0.02,
            y0: 0.3,
            w: 3.6,
            w1: 0.01,
            c: 0.0,
            delta: 0.0,
        };
        let x = 10.0;
        let left = s.centre(x, None) + s.half_width(x);
        let right = s.centre(x, None) - s.half_width(x);
        assert!((left - (0.3 + 10.0 * math::tan(0.02) + 3.7 / 2.0)).abs() < 1e-12);
        assert!((left - right - 3.7).abs() < 1e-12);
    }
}
