//! The Kalman filter on the CPF output (Lee et al. Fig. 4: "to increase the smoothness and
//! the robustness of the state estimation").
//!
//! The paper does not give its design. Ours: one scalar filter per state with the same
//! identity process model as the particle filter (eq. 20), x_k = x_{k-1} + v (var q^2), and the
//! CPF estimate as the measurement z_k = x_k + e (var r^2):
//!
//! ```text
//! P- = P + q^2,  K = P- / (P- + r^2),  x = x + K (z - x),  P = (1 - K) P-
//! ```
//!
//! At a lane change the CPF's y0 jumps by one lane width; the filter's y0 is moved by the same
//! whole number of widths first, so the jump passes through unsmoothed and the smoothing goes on.

/// Six scalar Kalman filters: psi, y0, w, w', c, delta.
#[derive(Debug, Clone)]
pub struct Smoother {
    q2: [f64; 6],
    r2: [f64; 6],
    x: [f64; 6],
    p: [f64; 6],
    started: bool,
}

impl Smoother {
    /// Process and measurement standard deviations per state.
    pub fn new(process_sd: [f64; 6], measurement_sd: [f64; 6]) -> Self {
        Self {
            q2: process_sd.map(|v| v * v),
            r2: measurement_sd.map(|v| v * v),
            x: [0.0; 6],
            p: [0.0; 6],
            started: false,
        }
    }

    /// Forgets the past.
    pub fn reset(&mut self) {
        self.started = false;
    }

    /// One update with the raw estimate `z`; returns the smoothed state.
    pub fn update(&mut self, z: [f64; 6]) -> [f64; 6] {
        if !self.started {
            self.x = z;
            self.p = self.r2;
            self.started = true;
            return z;
        }
        // Follow a lane change: shift y0 by whole lane widths towards the measurement.
        let w = z[2];
        if w > 0.0 {
            self.x[1] += ((z[1] - self.x[1]) / w).round() * w;
        }
        for (i, &zi) in z.iter().enumerate() {
            let p = self.p[i] + self.q2[i];
            let k = p / (p + self.r2[i]);
            self.x[i] += k * (zi - self.x[i]);
            self.p[i] = (1.0 - k) * p;
        }
        self.x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::Rng;

    #[test]
    fn smoothing_reduces_noise_and_passes_lane_changes() {
        let mut k = Smoother::new([0.001; 6], [0.05; 6]);
        let mut rng = Rng::new(9);
        let (mut raw, mut smooth) = (0.0, 0.0);
        for i in 0..400 {
            let z = [0.0, 0.2, 3.6, 0.0, 10.0, 0.0].map(|v| v + rng.gaussian(0.0, 0.05));
            let x = k.update(z);
            if i >= 100 {
                raw += (z[1] - 0.2f64).powi(2);
                smooth += (x[1] - 0.2f64).powi(2);
            }
        }
        assert!(smooth < raw / 4.0, "smoothed {smooth} raw {raw}");
        // A lane change: y0 jumps from +1.7 to -1.9; the output follows at once.
        let mut k = Smoother::new([0.001; 6], [0.05; 6]);
        for _ in 0..50 {
            k.update([0.0, 1.7, 3.6, 0.0, 10.0, 0.0]);
        }
        let x = k.update([0.0, -1.9, 3.6, 0.0, 10.0, 0.0]);
        assert!((x[1] + 1.9).abs() < 0.05, "{}", x[1]);
    }
}
