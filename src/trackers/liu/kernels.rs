//! The kernel densities of one pixel (Liu Sec. III): the line kernel G_li (eq. 5), the
//! orientation kernel K_theta and the parabolic kernel G_pi (eqs. 12-14) by Gauss-Hermite
//! quadrature. These are the reference forms; the measurement model evaluates the same
//! expressions in its band loops (checked against these in its tests).
//!
//! Line (eq. 5): integrating the position kernels N(x_i, sigma_x^2) N(y_i, sigma_y^2) along the
//! line rho = x cos(theta) + y sin(theta) gives
//!
//! ```text
//! G_li(rho, theta) = N(rho - x_i cos(theta) - y_i sin(theta); 0, sigma_x^2 cos^2(theta) + sigma_y^2 sin^2(theta))
//! ```
//!
//! Parabola (eq. 12): with x and theta tied to y by the curve (eqs. 6-7),
//!
//! ```text
//! G_pi(c, d, e) = integral K'_x(y) K'_theta(y) N(y; y_i, sigma_y^2) dy
//!              ~= sum_k (w_k / sqrt(pi)) K'_x(y_k) K'_theta(y_k),    y_k = y_i + sqrt(2) sigma_y t_k
//! ```
//!
//! where (t_k, w_k) are the n Gauss-Hermite nodes and weights for the weight function
//! exp(-t^2), K'_x(y) = N(c + d y + e y^2 - x_i; 0, sigma_x^2) (eq. 13) and
//! K'_theta(y) = N(atan(-2 e y - d) - theta_i; 0, sigma_theta_i^2) (eq. 14), the orientation
//! difference taken modulo pi. The nodes are the roots of the Hermite polynomial H_n, found by a
//! sign scan and bisection of the orthonormal recurrence (plain arithmetic, so the nodes are
//! bit-identical natively and in wasm).

use super::descriptors::wrap_half_turn;
use crate::math;
use std::f64::consts::PI;

/// N(z; 0, var).
pub fn gaussian(z: f64, var: f64) -> f64 {
    math::exp(-z * z / (2.0 * var)) / (2.0 * PI * var).sqrt()
}

/// G_li(rho, theta) of the pixel (x_i, y_i) (eq. 5).
pub fn line_kernel(rho: f64, theta: f64, x: f64, y: f64, var_x: f64, var_y: f64) -> f64 {
    let (s, c) = (math::sin(theta), math::cos(theta));
    gaussian(rho - x * c - y * s, var_x * c * c + var_y * s * s)
}

/// K_theta: N(theta; theta_i, 1 / precision), the difference taken modulo pi.
pub fn orientation_kernel(theta: f64, theta_i: f64, precision: f64) -> f64 {
    gaussian(wrap_half_turn(theta - theta_i), 1.0 / precision)
}

/// Gauss-Hermite nodes t_k and weights w_k: sum_k w_k f(t_k) ~= integral exp(-t^2) f(t) dt,
/// exact for polynomials f of degree up to 2n - 1.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussHermite {
    /// Nodes, increasing.
    pub nodes: Vec<f64>,
    /// Weights.
    pub weights: Vec<f64>,
}

/// The orthonormal Hermite polynomials p_n(t) and p_{n-1}(t) (weight exp(-t^2)):
/// p_0 = pi^(-1/4), p_j = t sqrt(2/j) p_{j-1} - sqrt((j-1)/j) p_{j-2}.
fn hermite(n: usize, t: f64) -> (f64, f64) {
    let p0 = 1.0 / PI.sqrt().sqrt();
    let (mut prev, mut cur) = (0.0, p0);
    for j in 1..=n {
        let jf = j as f64;
        let next = t * (2.0 / jf).sqrt() * cur - ((jf - 1.0) / jf).sqrt() * prev;
        prev = cur;
        cur = next;
    }
    (cur, prev)
}

impl GaussHermite {
    /// The n-point rule (n >= 1).
    pub fn new(n: usize) -> Self {
        let n = n.max(1);
        // All roots of H_n lie in (-sqrt(2n + 1), sqrt(2n + 1)) and are at least
        // pi / sqrt(2n + 1) apart; a scan finer than that brackets each one.
        let bound = ((2 * n + 1) as f64).sqrt();
        let steps = 64 * n * n + 64;
        let h = 2.0 * bound / steps as f64;
        let mut nodes = Vec::with_capacity(n);
        let mut left = -bound;
        let mut f_left = hermite(n, left).0;
        for s in 1..=steps {
            let right = -bound + s as f64 * h;
            let f_right = hermite(n, right).0;
            if f_left == 0.0 {
                nodes.push(left);
            } else if f_left * f_right < 0.0 {
                let (mut a, mut b, mut fa) = (left, right, f_left);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m == a || m == b {
                        break;
                    }
                    let fm = hermite(n, m).0;
                    if fm == 0.0 {
                        a = m;
                        b = m;
                        break;
                    }
                    if fa * fm < 0.0 {
                        b = m;
                    } else {
                        a = m;
                        fa = fm;
                    }
                }
                nodes.push(0.5 * (a + b));
            }
            left = right;
            f_left = f_right;
        }
        // Odd n: 0 is a root; symmetrise the rule (the scan's rounding is not).
        let mut nodes: Vec<f64> = nodes.into_iter().take(n).collect();
        for k in 0..n / 2 {
            let t = 0.5 * (nodes[n - 1 - k] - nodes[k]);
            nodes[k] = -t;
            nodes[n - 1 - k] = t;
        }
        if n % 2 == 1 {
            nodes[n / 2] = 0.0;
        }
        // w_k = 2 / p_n'(t_k)^2, p_n' = sqrt(2n) p_{n-1}.
        let weights = nodes
            .iter()
            .map(|&t| {
                let (_, p_prev) = hermite(n, t);
                1.0 / (n as f64 * p_prev * p_prev)
            })
            .collect();
        Self { nodes, weights }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }
    /// Never true.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// The curve x = c + d y + e y^2 of a far part (eq. 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parabola {
    /// c.
    pub c: f64,
    /// d.
    pub d: f64,
    /// e.
    pub e: f64,
}

/// The pixel whose kernels are integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pixel {
    /// Column x_i.
    pub x: f64,
    /// Row y_i.
    pub y: f64,
    /// Gradient orientation theta_i (modulo pi).
    pub theta: f64,
    /// 1 / sigma_theta_i^2 = |grad I|.
    pub precision: f64,
}

/// The integrand of eq. 12 without K_y: K'_x(y) K'_theta(y) (eqs. 13-14).
pub fn parabolic_integrand(p: &Parabola, px: &Pixel, y: f64, var_x: f64) -> f64 {
    let x = p.c + p.d * y + p.e * y * y;
    let theta = math::atan(-2.0 * p.e * y - p.d);
    gaussian(x - px.x, var_x) * orientation_kernel(theta, px.theta, px.precision)
}

/// G_pi(c, d, e) of one pixel by Gauss-Hermite quadrature over y (eq. 12).
pub fn parabolic_kernel(
    p: &Parabola,
    px: &Pixel,
    var_x: f64,
    var_y: f64,
    rule: &GaussHermite,
) -> f64 {
    let scale = (2.0 * var_y).sqrt();
    let sum: f64 = rule
        .nodes
        .iter()
        .zip(&rule.weights)
        .map(|(&t, &w)| w * parabolic_integrand(p, px, px.y + scale * t, var_x))
        .sum();
    sum / PI.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_hermite_rules_integrate_polynomials_exactly() {
        for n in 1..=20 {
            let rule = GaussHermite::new(n);
            assert_eq!(rule.len(), n);
            // Moments of exp(-t^2): integral t^(2m) = Gamma(m + 1/2).
            let mut gamma = PI.sqrt();
            for m in 0..n {
                let q: f64 = rule
                    .nodes
                    .iter()
                    .zip(&rule.weights)
                    .map(|(&t, &w)| w * t.powi(2 * m as i32))
                    .sum();
                assert!(
                    (q - gamma).abs() < 1e-10 * gamma,
                    "n {n} m {m}: {q} vs {gamma}"
                );
                let odd: f64 = rule
                    .nodes
                    .iter()
                    .zip(&rule.weights)
                    .map(|(&t, &w)| w * t.powi(2 * m as i32 + 1))
                    .sum();
                assert!(
                    odd.abs() < 1e-10 * gamma * (m as f64 + 1.0),
                    "n {n} m {m}: {odd}"
                );
                gamma *= m as f64 + 0.5;
            }
        }
        // Known 3-point rule: nodes 0, +-sqrt(3/2); weights 2 sqrt(pi)/3, sqrt(pi)/6.
        let r = GaussHermite::new(3);
        assert!((r.nodes[2] - 1.5f64.sqrt()).abs() < 1e-14);
        assert!((r.weights[1] - 2.0 * PI.sqrt() / 3.0).abs() < 1e-14);
    }

    #[test]
    fn the_line_kernel_is_eq_3_integrated_along_the_line() {
        // Eq. 4-5: integrating delta(rho - x cos - y sin) N(x_i, sx^2) N(y_i, sy^2) over (x, y)
        // is the integral of the position kernels along the line: parametrise the line by
        // arc length s from its foot point.
        let (rho, theta) = (5.0, 0.4);
        let (xi, yi, vx, vy) = (3.0, 2.5, 1.0, 2.0);
        let (s, c) = (math::sin(theta), math::cos(theta));
        let along = |t: f64| {
            let (x, y) = (rho * c - t * s, rho * s + t * c);
            gaussian(x - xi, vx) * gaussian(y - yi, vy)
        };
        let numeric = math::simpson(along, -40.0, 40.0, 20_000);
        let g = line_kernel(rho, theta, xi, yi, vx, vy);
        assert!(
            (numeric - g).abs() < 1e-9 * g.max(1e-12),
            "{numeric} vs {g}"
        );
    }

    #[test]
    fn three_and_five_node_quadratures_match_a_fine_integral_of_the_parabolic_kernel() {
        // Eq. 12 by Simpson on a fine grid against the rule, over curves with the slopes and
        // bends a top view has (|dx/dy| < 0.6) and pixels on and beside them. (Measured: 2
        // nodes 5e-3, 3 nodes 2.5e-4, 4 nodes 1e-5, 5 nodes 5e-7.)
        for (n, bound) in [(3, 1e-3), (5, 1e-5)] {
            let rule = GaussHermite::new(n);
            let mut worst: f64 = 0.0;
            for &(d, e) in &[(0.0, 0.0), (0.3, -0.002), (-0.5, 0.001), (0.1, 0.0005)] {
                for &dx in &[0.0, 0.7, -1.5] {
                    for &dtheta in &[0.0, 0.1] {
                        let p = Parabola { c: 40.0, d, e };
                        let y = 80.0;
                        let x = p.c + d * y + e * y * y + dx;
                        let theta = math::atan(-2.0 * e * y - d) + dtheta;
                        let px = Pixel {
                            x,
                            y,
                            theta,
                            precision: 60.0,
                        };
                        let numeric = math::simpson(
                            |t| parabolic_integrand(&p, &px, t, 1.0) * gaussian(t - y, 1.0),
                            y - 12.0,
                            y + 12.0,
                            24_000,
                        );
                        let q = parabolic_kernel(&p, &px, 1.0, 1.0, &rule);
                        worst = worst.max((q - numeric).abs() / numeric);
                    }
                }
            }
            assert!(worst < bound, "{n} nodes: relative error {worst}");
        }
    }
}
