//! The straight test road: a flat, straight, two-boundary road seen by any camera, with exact
//! ground truth. It stands in for the full scene simulator in the demo skeleton and the
//! end-to-end tests.
//!
//! Geometry (road frame, ISO 8855): the lane centre is the line y = -o(t), where the camera's
//! lateral offset o(t) = A sin(2 pi t / T) sways it inside the lane (positive = camera left of
//! the centre). The camera translates sideways without turning, so the heading is exactly 0.
//! The left boundary (solid yellow) is centred at y = -o + W/2, the right one (dashed white,
//! dash length L of period P, moving towards the camera at speed v) at y = -o - W/2; markings are
//! m metres wide.
//!
//! Rendering: every pixel's road point (x, y) is computed once at construction by
//! back-projection; a frame then only shades. A marking covers the fraction of the pixel's
//! lateral footprint (the road distance between horizontally neighbouring pixels) that lies
//! inside the marking (box-filter anti-aliasing), asphalt has a fixed texture tied to the road
//! (it moves with the car) and fades into haze with distance; above the horizon is sky.

use crate::camera::Camera;
use crate::error::{require_finite, require_positive, Error, Result};
use crate::image::check_dimensions;
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use crate::math;
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// Options of the straight test road (all optional; a field left out takes its default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TestRoadConfig {
    /// Lane width W, metres.
    pub lane_width_m: f64,
    /// Marking width m, metres.
    pub marking_width_m: f64,
    /// Dash length L of the right marking, metres.
    pub dash_length_m: f64,
    /// Dash period P (dash + gap), metres.
    pub dash_period_m: f64,
    /// Speed v, metres per second.
    pub speed_mps: f64,
    /// Frames per second.
    pub fps: f64,
    /// Sway amplitude A, metres.
    pub sway_amplitude_m: f64,
    /// Sway period T, seconds.
    pub sway_period_s: f64,
    /// Farthest road distance drawn and reported, metres.
    pub max_distance_m: f64,
}

impl Default for TestRoadConfig {
    fn default() -> Self {
        Self {
            lane_width_m: 3.6,
            marking_width_m: 0.15,
            dash_length_m: 3.0,
            dash_period_m: 12.0,
            speed_mps: 20.0,
            fps: 30.0,
            sway_amplitude_m: 0.4,
            sway_period_s: 6.0,
            max_distance_m: 80.0,
        }
    }
}

impl TestRoadConfig {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        require_positive("lane_width_m", self.lane_width_m)?;
        require_positive("marking_width_m", self.marking_width_m)?;
        require_positive("dash_length_m", self.dash_length_m)?;
        require_positive("dash_period_m", self.dash_period_m)?;
        require_finite("speed_mps", self.speed_mps)?;
        require_positive("fps", self.fps)?;
        require_finite("sway_amplitude_m", self.sway_amplitude_m)?;
        require_positive("sway_period_s", self.sway_period_s)?;
        require_positive("max_distance_m", self.max_distance_m)?;
        if self.marking_width_m >= self.lane_width_m / 2.0 {
            return Err(Error::parameter(
                "marking_width_m",
                Num(self.marking_width_m),
                "must be less than half the lane width",
            ));
        }
        if self.dash_length_m > self.dash_period_m {
            return Err(Error::parameter(
                "dash_length_m",
                Num(self.dash_length_m),
                "must not exceed dash_period_m",
            ));
        }
        if self.sway_amplitude_m.abs() >= self.lane_width_m / 2.0 {
            return Err(Error::parameter(
                "sway_amplitude_m",
                Num(self.sway_amplitude_m),
                "must keep the camera inside the lane (|A| < W/2)",
            ));
        }
        Ok(())
    }
}

/// Road point of a pixel, or `None` above the horizon.
#[derive(Debug, Clone, Copy)]
struct PixelRoad {
    x: f32,
    y: f32,
    /// Lateral road distance covered by the pixel (metres).
    footprint: f32,
}

/// The renderer, with its per-pixel road lookup table.
#[derive(Debug, Clone)]
pub struct TestRoad {
    camera: Camera,
    config: TestRoadConfig,
    pixels: Vec<Option<PixelRoad>>,
}

impl TestRoad {
    /// Builds the renderer for `camera`'s image size.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a bad configuration, [`Error::Dimensions`] for a bad camera size.
    pub fn new(camera: Camera, config: TestRoadConfig) -> Result<Self> {
        config.validate()?;
        let (w, h) = (camera.width(), camera.height());
        check_dimensions(w, h)?;
        let road = |u: usize, v: usize| -> Option<[f64; 2]> {
            let p = camera.pixel_to_road(u as f64, v as f64).ok()?;
            (p[0] > 0.0 && p[0] <= config.max_distance_m * 1.5).then_some(p)
        };
        let mut pixels = Vec::with_capacity(w * h);
        for v in 0..h {
            for u in 0..w {
                pixels.push(road(u, v).map(|p| {
                    let q = road(u + 1, v).or_else(|| road(u.saturating_sub(1), v));
                    let footprint = q.map_or(0.01, |q| (q[1] - p[1]).abs().max(1e-4));
                    PixelRoad {
                        x: p[0] as f32,
                        y: p[1] as f32,
                        footprint: footprint as f32,
                    }
                }));
            }
        }
        Ok(Self {
            camera,
            config,
            pixels,
        })
    }

    /// Image width.
    pub fn width(&self) -> usize {
        self.camera.width()
    }
    /// Image height.
    pub fn height(&self) -> usize {
        self.camera.height()
    }
    /// The configuration.
    pub fn config(&self) -> &TestRoadConfig {
        &self.config
    }

    /// Lateral offset o(t) of frame `frame` (metres, camera left of the lane centre > 0).
    pub fn lateral_offset(&self, frame: u32) -> f64 {
        let t = frame as f64 / self.config.fps;
        self.config.sway_amplitude_m
            * math::sin(2.0 * std::f64::consts::PI * t / self.config.sway_period_s)
    }

    /// Distance travelled at frame `frame`.
    fn travelled(&self, frame: u32) -> f64 {
        self.config.speed_mps * frame as f64 / self.config.fps
    }

    /// Renders frame `frame` as RGBA into `out` (width * height * 4 bytes).
    ///
    /// # Errors
    /// [`Error::BufferSize`] when `out` has the wrong length.
    pub fn render(&self, frame: u32, out: &mut [u8]) -> Result<()> {
        crate::image::check_rgba(out, self.width(), self.height())?;
        let c = &self.config;
        let o = self.lateral_offset(frame) as f32;
        let s = self.travelled(frame);
        let half_lane = (c.lane_width_m / 2.0) as f32;
        let half_mark = (c.marking_width_m / 2.0) as f32;
        let (dash, period) = (c.dash_length_m, c.dash_period_m);
        let far = c.max_distance_m as f32;
        let h = self.height() as f32;
        for (i, (px, rgba)) in self.pixels.iter().zip(out.chunks_exact_mut(4)).enumerate() {
            let Some(p) = px else {
                // Sky: lighter towards the horizon.
                let v = (i / self.width()) as f32 / h;
                let shade = 150.0 + 80.0 * v;
                rgba.copy_from_slice(&[
                    (shade * 0.75) as u8,
                    (shade * 0.85) as u8,
                    shade as u8,
                    255,
                ]);
                continue;
            };
            let world_x = p.x as f64 + s;
            // Asphalt with a texture fixed to the road (10 cm cells).
            let cell = hash2((world_x * 10.0).floor() as i64, (p.y * 10.0).floor() as i64);
            let mut col = [
                78.0 + (cell % 17) as f32,
                80.0 + (cell % 17) as f32,
                84.0 + (cell % 17) as f32,
            ];
            let left = coverage(p.y - (-o + half_lane), half_mark, p.footprint);
            let in_dash = (world_x.rem_euclid(period)) < dash;
            let right = if in_dash {
                coverage(p.y - (-o - half_lane), half_mark, p.footprint)
            } else {
                0.0
            };
            blend(&mut col, [235.0, 190.0, 40.0], left);
            blend(&mut col, [240.0, 240.0, 240.0], right);
            // Haze towards the far end.
            let haze = (p.x / far).clamp(0.0, 1.0);
            blend(&mut col, [170.0, 180.0, 190.0], haze * haze);
            rgba.copy_from_slice(&[col[0] as u8, col[1] as u8, col[2] as u8, 255]);
        }
        Ok(())
    }

    /// Exact ground truth of frame `frame`.
    pub fn truth(&self, frame: u32) -> LaneEstimate {
        let o = self.lateral_offset(frame);
        let half = self.config.lane_width_m / 2.0;
        let boundary = |role: Role, y: f64| {
            let (points, road_points) = sample_road_curve(
                |_| y,
                |x, y| self.camera.road_to_pixel(x, y),
                0.5,
                self.config.max_distance_m,
                self.width(),
                self.height(),
            );
            Boundary {
                role,
                points,
                road_points,
            }
        };
        LaneEstimate {
            frame: frame.to_string(),
            valid: true,
            ms: 0.0,
            boundaries: vec![
                boundary(Role::EgoLeft, -o + half),
                boundary(Role::EgoRight, -o - half),
            ],
            lateral_offset_m: o,
            heading_rad: 0.0,
            curvature_per_m: 0.0,
            lane_width_m: self.config.lane_width_m,
            delimiters: Vec::new(),
            state: Default::default(),
        }
    }
}

/// Fraction of a pixel of lateral footprint `fp` centred `d` metres from a marking's centre line
/// that the marking (half width `half`) covers.
fn coverage(d: f32, half: f32, fp: f32) -> f32 {
    let lo = (d - fp / 2.0).max(-half);
    let hi = (d + fp / 2.0).min(half);
    ((hi - lo) / fp).clamp(0.0, 1.0)
}

fn blend(col: &mut [f32; 3], with: [f32; 3], a: f32) {
    for k in 0..3 {
        col[k] += (with[k] - col[k]) * a;
    }
}

/// A small integer hash for the asphalt texture (deterministic on every target).
fn hash2(a: i64, b: i64) -> u32 {
    let mut h = (a as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (b as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h ^= h >> 29;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    (h >> 32) as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::caltech;

    fn pixel(rgba: &[u8], w: usize, p: [f64; 2]) -> [u8; 3] {
        let i = (p[1].round() as usize * w + p[0].round() as usize) * 4;
        [rgba[i], rgba[i + 1], rgba[i + 2]]
    }

    #[test]
    fn markings_are_drawn_where_the_truth_says() {
        let road = TestRoad::new(caltech(), TestRoadConfig::default()).unwrap();
        let (w, h) = (road.width(), road.height());
        let mut rgba = vec![0; w * h * 4];
        for frame in [0, 17, 45] {
            road.render(frame, &mut rgba).unwrap();
            let truth = road.truth(frame);
            assert_eq!(truth.boundaries.len(), 2);
            let left = &truth.boundaries[0];
            assert_eq!(left.role, Role::EgoLeft);
            left.check_polyline().unwrap();
            // The solid yellow marking: red and green high, blue low, near the car.
            let near: Vec<_> = left.points.iter().filter(|p| p[1] > 320.0).collect();
            assert!(near.len() > 5);
            for p in near {
                let [r, g, b] = pixel(&rgba, w, *p);
                assert!(
                    r > 150 && g > 120 && b < 110,
                    "frame {frame} at {p:?}: {r} {g} {b}"
                );
            }
            // The lane centre, half-way between the boundaries, is asphalt.
            let (l, r) = (left.points[3], truth.boundaries[1].points[3]);
            let [gray, _, _] = pixel(&rgba, w, [(l[0] + r[0]) / 2.0, (l[1] + r[1]) / 2.0]);
            assert!(gray < 110, "frame {frame}: centre {gray}");
        }
    }

    #[test]
    fn truth_moves_with_the_sway() {
        let road = TestRoad::new(caltech(), TestRoadConfig::default()).unwrap();
        // A quarter of the 6 s period at 30 fps: o = A.
        assert!((road.lateral_offset(45) - 0.4).abs() < 1e-12);
        let t = road.truth(45);
        assert!((t.boundaries[0].road_points[0][1] - (1.8 - 0.4)).abs() < 1e-12);
        assert!((t.boundaries[1].road_points[0][1] - (-1.8 - 0.4)).abs() < 1e-12);
    }

    #[test]
    fn bad_configs_and_buffers_are_errors() {
        let bad = TestRoadConfig {
            sway_amplitude_m: 2.0,
            ..Default::default()
        };
        let e = TestRoad::new(caltech(), bad).unwrap_err().to_string();
        assert!(e.contains("sway_amplitude_m"), "{e}");
        let nan = TestRoadConfig {
            fps: f64::NAN,
            ..Default::default()
        };
        assert!(TestRoad::new(caltech(), nan).is_err());
        let road = TestRoad::new(caltech(), TestRoadConfig::default()).unwrap();
        let e = road.render(0, &mut [0; 16]).unwrap_err();
        assert!(matches!(e, Error::BufferSize { .. }), "{e}");
    }
}
