//! Inverse perspective mapping (IPM): a metric top view of the road plane.
//!
//! The top view covers longitudinal distances x in [`x_min_m`, `x_max_m`] and lateral offsets
//! y in [`y_right_m`, `y_left_m`] (road frame, ISO 8855) at `m_per_px` metres per pixel. Its
//! column c grows to the right of the car (decreasing y), its row r grows towards the car
//! (decreasing x), with pixel centres at integer coordinates:
//!
//! ```text
//! y(c) = y_left - (c + 1/2) s,     x(r) = x_max - (r + 1/2) s,     s = m_per_px
//! ```
//!
//! so the top view is W = round((y_left - y_right) / s) by H = round((x_max - x_min) / s)
//! pixels and looks like the camera image with the perspective removed (far at the top).
//! Construction projects every top-view pixel centre through the full camera model (pose and
//! lens distortion: the lookup table compensates distortion, as Liu et al. Sec. II-A suggest)
//! and stores the source pixel and its bilinear weights in 8-bit fixed point, so a frame costs
//! one table walk:
//!
//! ```text
//! I_top(c, r) = (1-a)(1-b) I(u0, v0) + a (1-b) I(u0+1, v0) + (1-a) b I(u0, v0+1) + a b I(u0+1, v0+1)
//! ```
//!
//! with (u0, v0) = floor(u, v), (a, b) = (u - u0, v - v0). Top-view pixels whose road point is
//! outside the camera image (or behind it) are invalid: they get the fill value and are
//! reported by [`Ipm::valid`], so that cues computed on the top view can ignore them.

use crate::camera::Camera;
use crate::error::{require_positive, Error, Result};
use crate::image::{check_dimensions, Image, ImageView};
use crate::num_text::{Fixed, Num};
use serde::{Deserialize, Serialize};

/// The area and resolution of the top view.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopViewConfig {
    /// Nearest road distance shown, metres (> 0).
    pub x_min_m: f64,
    /// Farthest road distance shown, metres.
    pub x_max_m: f64,
    /// Lateral extent to the left (positive y), metres.
    pub y_left_m: f64,
    /// Lateral extent to the right (negative y for the right side), metres.
    pub y_right_m: f64,
    /// Resolution, metres per top-view pixel.
    pub m_per_px: f64,
}

impl Default for TopViewConfig {
    /// 5 to 45 m ahead, 8 m to each side, 5 cm per pixel: 320 x 800 pixels covering three lanes.
    fn default() -> Self {
        Self {
            x_min_m: 5.0,
            x_max_m: 45.0,
            y_left_m: 8.0,
            y_right_m: -8.0,
            m_per_px: 0.05,
        }
    }
}

impl TopViewConfig {
    /// The top view's size in pixels (W, H).
    ///
    /// # Errors
    /// [`Error::Parameter`] for a non-finite or empty range or resolution;
    /// [`Error::Dimensions`] when the view would be too large.
    pub fn size(&self) -> Result<(usize, usize)> {
        require_positive("x_min_m", self.x_min_m)?;
        require_positive("m_per_px", self.m_per_px)?;
        let depth = self.x_max_m - self.x_min_m;
        let breadth = self.y_left_m - self.y_right_m;
        if !(depth.is_finite() && depth > 0.0) {
            return Err(Error::parameter(
                "x_max_m",
                Num(self.x_max_m),
                "must be a finite distance beyond x_min_m",
            ));
        }
        if !(breadth.is_finite() && breadth > 0.0) {
            return Err(Error::parameter(
                "y_left_m",
                Num(self.y_left_m),
                "must be a finite offset left of y_right_m",
            ));
        }
        let (w, h) = (breadth / self.m_per_px, depth / self.m_per_px);
        if w > crate::image::MAX_SIDE as f64 || h > crate::image::MAX_SIDE as f64 {
            return Err(Error::Dimensions(format!(
                "a top view of {}x{} pixels is too large: use a coarser m_per_px",
                Fixed(w, 0),
                Fixed(h, 0)
            )));
        }
        let size = ((w.round() as usize).max(1), (h.round() as usize).max(1));
        check_dimensions(size.0, size.1)?;
        Ok(size)
    }
}

/// One top-view pixel's source: the top-left source pixel (u0, v0) and the fixed-point
/// bilinear weights a, b in 0..256; `u0 == u16::MAX` marks an invalid pixel.
#[derive(Debug, Clone, Copy)]
struct Tap {
    u0: u16,
    v0: u16,
    a: u16,
    b: u16,
}

const INVALID: u16 = u16::MAX;

/// The IPM executor: a lookup table built once for a camera and a top view.
#[derive(Debug, Clone)]
pub struct Ipm {
    config: TopViewConfig,
    src_width: usize,
    src_height: usize,
    width: usize,
    height: usize,
    taps: Vec<Tap>,
    valid: Image<u8>,
    /// The source rows the taps read (see [`Ipm::source_rows`]).
    source_rows: std::ops::Range<usize>,
}

impl Ipm {
    /// Builds the lookup table for `camera`'s images and the top view `config`.
    ///
    /// # Errors
    /// As [`TopViewConfig::size`].
    pub fn new(camera: &Camera, config: TopViewConfig) -> Result<Self> {
        let (width, height) = config.size()?;
        let (sw, sh) = (camera.width(), camera.height());
        let mut taps = Vec::with_capacity(width * height);
        let mut valid = Image::new(width, height)?;
        for r in 0..height {
            for c in 0..width {
                let (x, y) = top_to_road_of(&config, c as f64, r as f64);
                let tap = camera
                    .road_to_pixel(x, y)
                    .and_then(|[u, v]| bilinear_tap(u, v, sw, sh));
                valid.set(c, r, u8::from(tap.is_some()));
                taps.push(tap.unwrap_or(Tap {
                    u0: INVALID,
                    v0: 0,
                    a: 0,
                    b: 0,
                }));
            }
        }
        // The rows `apply` reads: v0 of every valid tap, and v0 + 1 where its weight b > 0.
        let (mut first, mut end) = (usize::MAX, 0);
        for tap in taps.iter().filter(|t| t.u0 != INVALID) {
            first = first.min(tap.v0 as usize);
            end = end.max(tap.v0 as usize + 1 + usize::from(tap.b > 0));
        }
        Ok(Self {
            config,
            src_width: sw,
            src_height: sh,
            width,
            height,
            taps,
            valid,
            source_rows: first.min(end)..end,
        })
    }

    /// The rows of the source image that [`Ipm::apply`] reads (empty when the top view sees
    /// none of it): the others may hold anything.
    pub fn source_rows(&self) -> std::ops::Range<usize> {
        self.source_rows.clone()
    }

    /// Top-view width, pixels.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Top-view height, pixels.
    pub fn height(&self) -> usize {
        self.height
    }
    /// The top-view configuration.
    pub fn config(&self) -> &TopViewConfig {
        &self.config
    }
    /// 1 where the top-view pixel sees the camera image, 0 where it does not.
    pub fn valid(&self) -> &Image<u8> {
        &self.valid
    }

    /// Road point (x, y) of top-view pixel (c, r) (fractional coordinates allowed).
    pub fn top_to_road(&self, c: f64, r: f64) -> (f64, f64) {
        top_to_road_of(&self.config, c, r)
    }

    /// Top-view pixel (c, r) of road point (x, y) (may lie outside the view).
    pub fn road_to_top(&self, x: f64, y: f64) -> (f64, f64) {
        let s = self.config.m_per_px;
        (
            (self.config.y_left_m - y) / s - 0.5,
            (self.config.x_max_m - x) / s - 0.5,
        )
    }

    fn check_source<T: Copy>(&self, src: &ImageView<'_, T>) -> Result<()> {
        if (src.width(), src.height()) != (self.src_width, self.src_height) {
            return Err(Error::Dimensions(format!(
                "IPM was built for {}x{} frames but got {}x{}",
                self.src_width,
                self.src_height,
                src.width(),
                src.height()
            )));
        }
        Ok(())
    }

    /// Maps a grey frame to the top view; invalid pixels get `fill`.
    ///
    /// # Errors
    /// [`Error::Dimensions`] when `src` is not the camera's size. `dst` is resized to the top
    /// view (no reallocation after the first call).
    pub fn apply(&self, src: &ImageView<'_, u8>, fill: u8, dst: &mut Image<u8>) -> Result<()> {
        self.check_source(src)?;
        dst.resize(self.width, self.height)?;
        let stride = src.stride();
        let data = src.as_slice();
        for (out, tap) in dst.data_mut().iter_mut().zip(&self.taps) {
            if tap.u0 == INVALID {
                *out = fill;
                continue;
            }
            let i = tap.v0 as usize * stride + tap.u0 as usize;
            let (a, b) = (tap.a as u32, tap.b as u32);
            let (p00, p10) = (data[i] as u32, data[i + step_x(tap)] as u32);
            let row = i + step_y(tap, stride);
            let (p01, p11) = (data[row] as u32, data[row + step_x(tap)] as u32);
            let top = p00 * (256 - a) + p10 * a;
            let bottom = p01 * (256 - a) + p11 * a;
            *out = ((top * (256 - b) + bottom * b + (1 << 15)) >> 16) as u8;
        }
        Ok(())
    }

    /// Maps a float image (e.g. a cue map) to the top view; invalid pixels get `fill`.
    ///
    /// # Errors
    /// As [`Ipm::apply`].
    pub fn apply_f32(
        &self,
        src: &ImageView<'_, f32>,
        fill: f32,
        dst: &mut Image<f32>,
    ) -> Result<()> {
        self.check_source(src)?;
        dst.resize(self.width, self.height)?;
        let stride = src.stride();
        let data = src.as_slice();
        for (out, tap) in dst.data_mut().iter_mut().zip(&self.taps) {
            if tap.u0 == INVALID {
                *out = fill;
                continue;
            }
            let i = tap.v0 as usize * stride + tap.u0 as usize;
            let (a, b) = (tap.a as f32 / 256.0, tap.b as f32 / 256.0);
            let row = i + step_y(tap, stride);
            let top = data[i] * (1.0 - a) + data[i + step_x(tap)] * a;
            let bottom = data[row] * (1.0 - a) + data[row + step_x(tap)] * a;
            *out = top * (1.0 - b) + bottom * b;
        }
        Ok(())
    }
}

#[inline]
fn step_x(tap: &Tap) -> usize {
    // Weight a = 0 needs no right neighbour (it may not exist on the last column).
    usize::from(tap.a > 0)
}

#[inline]
fn step_y(tap: &Tap, stride: usize) -> usize {
    if tap.b > 0 {
        stride
    } else {
        0
    }
}

fn top_to_road_of(config: &TopViewConfig, c: f64, r: f64) -> (f64, f64) {
    let s = config.m_per_px;
    (
        config.x_max_m - (r + 0.5) * s,
        config.y_left_m - (c + 0.5) * s,
    )
}

/// The tap for source pixel position (u, v), or `None` outside the image.
fn bilinear_tap(u: f64, v: f64, width: usize, height: usize) -> Option<Tap> {
    let (maxu, maxv) = ((width - 1) as f64, (height - 1) as f64);
    if !(u >= 0.0 && v >= 0.0 && u <= maxu && v <= maxv) {
        return None;
    }
    let (u0, v0) = (u.floor(), v.floor());
    let mut a = ((u - u0) * 256.0).round() as u16;
    let mut b = ((v - v0) * 256.0).round() as u16;
    let (mut u0, mut v0) = (u0 as usize, v0 as usize);
    // A weight rounded up to 256 means the next pixel entirely.
    if a == 256 {
        u0 += 1;
        a = 0;
    }
    if b == 256 {
        v0 += 1;
        b = 0;
    }
    Some(Tap {
        u0: u0 as u16,
        v0: v0 as u16,
        a,
        b,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::caltech;
    use crate::image::rgba_to_gray;
    use crate::synth::{TestRoad, TestRoadConfig};

    /// Reference: exact floating-point bilinear sampling through the camera, no table.
    fn reference(camera: &Camera, ipm: &Ipm, src: &Image<u8>, c: usize, r: usize) -> Option<f64> {
        let (x, y) = ipm.top_to_road(c as f64, r as f64);
        let [u, v] = camera.road_to_pixel(x, y)?;
        let (w, h) = (src.width() as f64, src.height() as f64);
        if !(u >= 0.0 && v >= 0.0 && u <= w - 1.0 && v <= h - 1.0) {
            return None;
        }
        let (u0, v0) = (u.floor(), v.floor());
        let (a, b) = (u - u0, v - v0);
        let px = |du: f64, dv: f64| {
            let (x, y) = ((u0 + du).min(w - 1.0), (v0 + dv).min(h - 1.0));
            src.get(x as usize, y as usize) as f64
        };
        Some(
            (1.0 - a) * (1.0 - b) * px(0.0, 0.0)
                + a * (1.0 - b) * px(1.0, 0.0)
                + (1.0 - a) * b * px(0.0, 1.0)
                + a * b * px(1.0, 1.0),
        )
    }

    fn noise_image(w: usize, h: usize) -> Image<u8> {
        let mut state = 12345u32;
        let data = (0..w * h)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                (state >> 24) as u8
            })
            .collect();
        Image::from_vec(w, h, data).unwrap()
    }

    #[test]
    fn table_matches_exact_bilinear_sampling_within_one_grey_level() {
        let camera = caltech();
        let ipm = Ipm::new(&camera, TopViewConfig::default()).unwrap();
        assert_eq!((ipm.width(), ipm.height()), (320, 800));
        let src = noise_image(640, 480);
        let mut top = Image::new(1, 1).unwrap();
        ipm.apply(&src.view(), 7, &mut top).unwrap();
        let mut checked = 0;
        for r in (0..ipm.height()).step_by(7) {
            for c in (0..ipm.width()).step_by(5) {
                match reference(&camera, &ipm, &src, c, r) {
                    Some(want) => {
                        assert_eq!(ipm.valid().get(c, r), 1);
                        let got = top.get(c, r) as f64;
                        assert!((got - want).abs() <= 1.0, "({c}, {r}): {got} vs {want:.2}");
                        checked += 1;
                    }
                    None => {
                        assert_eq!(ipm.valid().get(c, r), 0);
                        assert_eq!(top.get(c, r), 7);
                    }
                }
            }
        }
        assert!(checked > 3000, "{checked}");
    }

    #[test]
    fn straight_markings_become_vertical_lines_at_their_metric_offset() {
        let camera = caltech();
        let config = TestRoadConfig {
            sway_amplitude_m: 0.0,
            ..Default::default()
        };
        let road = TestRoad::new(camera.clone(), config).unwrap();
        let mut rgba = vec![0; 640 * 480 * 4];
        road.render(0, &mut rgba).unwrap();
        let mut gray = Image::new(640, 480).unwrap();
        rgba_to_gray(&rgba, 640, 480, &mut gray).unwrap();
        let ipm = Ipm::new(&camera, TopViewConfig::default()).unwrap();
        let mut top = Image::new(1, 1).unwrap();
        ipm.apply(&gray.view(), 0, &mut top).unwrap();
        // The solid left marking is centred at y = +1.8 m: column (8 - 1.8) / 0.05 - 0.5.
        let (want, _) = ipm.road_to_top(10.0, 1.8);
        for r in (ipm.height() / 2..ipm.height()).step_by(20) {
            let row = top.row(r);
            let window = (want as usize - 10)..(want as usize + 10);
            let brightest = window.clone().max_by_key(|&c| row[c]).unwrap();
            assert!(
                (brightest as f64 - want).abs() <= 1.5,
                "row {r}: {brightest} vs {want}"
            );
            assert!(row[brightest] > 120);
        }
    }

    #[test]
    fn coordinates_round_trip_and_bad_input_is_an_error() {
        let ipm = Ipm::new(&caltech(), TopViewConfig::default()).unwrap();
        let (c, r) = ipm.road_to_top(17.3, -2.2);
        let (x, y) = ipm.top_to_road(c, r);
        assert!((x - 17.3).abs() < 1e-12 && (y + 2.2).abs() < 1e-12);
        let small = Image::<u8>::new(320, 240).unwrap();
        let e = ipm
            .apply(&small.view(), 0, &mut Image::new(1, 1).unwrap())
            .unwrap_err();
        assert!(e.to_string().contains("built for 640x480"), "{e}");
        let bad = TopViewConfig {
            m_per_px: f64::NAN,
            ..Default::default()
        };
        assert!(Ipm::new(&caltech(), bad).is_err());
        let huge = TopViewConfig {
            m_per_px: 1e-5,
            ..Default::default()
        };
        assert!(matches!(
            Ipm::new(&caltech(), huge),
            Err(Error::Dimensions(_))
        ));
        let inverted = TopViewConfig {
            x_max_m: 1.0,
            ..Default::default()
        };
        assert!(Ipm::new(&caltech(), inverted)
            .unwrap_err()
            .to_string()
            .contains("x_max_m"));
    }
}
