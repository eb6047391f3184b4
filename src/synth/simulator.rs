//! [`Scene`]: a scenario built for a camera, rendering frames (mono or stereo) and their
//! exact ground truth.

use super::appearance::{box_blur, Effects};
use super::ego::Pose;
use super::kerbs;
use super::render::{self, FrameGeometry, Hit};
use super::road::Road;
use super::scene::SceneConfig;
use crate::camera::Camera;
use crate::error::{require_positive, Error, Result};
use crate::image::check_rgba;

/// Which camera of the rig to render.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Eye {
    /// The reference (left) camera.
    Left,
    /// The right camera, `baseline` metres to the right.
    Right,
}

/// A built scene.
#[derive(Debug, Clone)]
pub struct Scene {
    config: SceneConfig,
    road: Road,
    camera: Camera,
    seed: u64,
    baseline: f64,
    /// Undistorted normalised direction of every pixel (NaN where the lens cannot be inverted).
    rays: Vec<[f32; 2]>,
    /// Whether any boundary is a kerb (the per-pixel kerb geometry is skipped otherwise).
    kerbs: bool,
    table: Vec<super::render::LocalSample>,
    blur_tmp: Vec<u8>,
}

/// Stereo baseline used when the camera file gives none, metres.
pub const DEFAULT_BASELINE_M: f64 = 0.3;

/// The simulator's default camera for a `width` x `height` image: 60 degrees horizontal field
/// of view, square pixels, principal point at the centre, 1.5 m above the road, pitched 4
/// degrees down, stereo baseline [`DEFAULT_BASELINE_M`].
///
/// # Errors
/// [`Error::Dimensions`] for an unusable size.
pub fn default_camera(width: usize, height: usize) -> Result<Camera> {
    let f = width as f64 / 2.0 / crate::math::tan(crate::math::deg_to_rad(30.0));
    Camera::from_file(&crate::camera::CameraFile {
        pitch_deg: 4.0,
        baseline_m: Some(DEFAULT_BASELINE_M),
        ..crate::camera::CameraFile::pinhole(width, height, f)
    })
}

/// A 640x480 pinhole camera with a mounting drawn from `seed`, for checking what must work
/// for any camera (auto-calibration, trackers): horizontal field of view 50 to 90 degrees,
/// principal point within 5 px of the centre, height 1.1 to 2.4 m, pitch -2 to 8 degrees, yaw
/// -3 to 3 degrees, no roll, no distortion (uniform draws, in that order).
pub fn drawn_camera(seed: u64) -> crate::camera::CameraFile {
    let mut rng = crate::filter::Rng::new(seed);
    let hfov = 50.0 + 40.0 * rng.uniform();
    let f = 320.0 / crate::math::tan(crate::math::deg_to_rad(0.5 * hfov));
    // Fields are evaluated in the order written: the draws keep their order.
    crate::camera::CameraFile {
        cx: 320.0 + 10.0 * (rng.uniform() - 0.5),
        cy: 240.0 + 10.0 * (rng.uniform() - 0.5),
        height_m: 1.1 + 1.3 * rng.uniform(),
        pitch_deg: -2.0 + 10.0 * rng.uniform(),
        yaw_deg: -3.0 + 6.0 * rng.uniform(),
        ..crate::camera::CameraFile::pinhole(640, 480, f)
    }
}

impl Scene {
    /// Builds `config` for `camera` with `seed` (texture, noise and every random choice).
    ///
    /// # Errors
    /// Any invalid part of the configuration, named.
    pub fn new(config: SceneConfig, camera: Camera, seed: u64) -> Result<Self> {
        config.validate()?;
        let road = Road::new(config.road.clone(), config.road_length())?;
        let (w, h) = (camera.width(), camera.height());
        let mut rays = Vec::with_capacity(w * h);
        for v in 0..h {
            for u in 0..w {
                rays.push(match camera.pixel_to_normalised(u as f64, v as f64) {
                    Ok([x, y]) => [x as f32, y as f32],
                    Err(_) => [f32::NAN, f32::NAN],
                });
            }
        }
        let baseline = camera.baseline_m().unwrap_or(DEFAULT_BASELINE_M);
        require_positive("baseline_m", baseline)?;
        Ok(Self {
            kerbs: config.markings.has_curbs(),
            config,
            road,
            camera,
            seed,
            baseline,
            rays,
            table: Vec::new(),
            blur_tmp: Vec::new(),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &SceneConfig {
        &self.config
    }
    /// The road.
    pub fn road(&self) -> &Road {
        &self.road
    }
    /// The camera (left camera of the rig).
    pub fn camera(&self) -> &Camera {
        &self.camera
    }
    /// The stereo baseline, metres.
    pub fn baseline(&self) -> f64 {
        self.baseline
    }
    /// Image width.
    pub fn width(&self) -> usize {
        self.camera.width()
    }
    /// Image height.
    pub fn height(&self) -> usize {
        self.camera.height()
    }
    /// The car's pose at `frame`.
    pub fn pose(&self, frame: u32) -> Pose {
        self.config.ego.pose(&self.road, frame)
    }

    /// Whether `frame` falls in a blackout.
    pub fn blacked_out(&self, frame: u32) -> bool {
        let t = frame as f64 / self.config.ego.fps;
        self.config.blackouts.iter().any(|b| t >= b[0] && t < b[1])
    }

    /// Renders `frame` seen by `eye` into `rgba` (width * height * 4 bytes). When `depth` is
    /// given (width * height), it receives the depth Z (metres along the optical axis) of
    /// every pixel, 0 for the sky.
    ///
    /// # Errors
    /// [`Error::BufferSize`] for wrong buffer lengths.
    pub fn render(
        &mut self,
        frame: u32,
        eye: Eye,
        rgba: &mut [u8],
        mut depth: Option<&mut [f32]>,
    ) -> Result<Pose> {
        let (w, h) = (self.width(), self.height());
        check_rgba(rgba, w, h)?;
        if let Some(d) = depth.as_deref() {
            if d.len() != w * h {
                return Err(Error::BufferSize {
                    what: format!("a {w}x{h} depth map"),
                    expected: w * h,
                    actual: d.len(),
                });
            }
        }
        let pose = self.pose(frame);
        let baseline = if eye == Eye::Right {
            self.baseline
        } else {
            0.0
        };
        let mut table = std::mem::take(&mut self.table);
        let geo = FrameGeometry::new(
            &self.config,
            &self.road,
            &self.camera,
            pose,
            baseline,
            &mut table,
        )?;
        let effects = Effects::new(&self.config.appearance, frame, pose.t, self.seed);
        let salt = if eye == Eye::Right { 0xABCD } else { 0 };
        let night = self.config.appearance.night;
        let blackout = self.blacked_out(frame);
        let [fx, fy] = self.camera.focal();
        let cam_h = self.camera.height_m() + pose.height_offset;
        let mut s_row = pose.s;
        for v in 0..h {
            let mut s_guess = s_row;
            let mut first_in_row = true;
            for u in 0..w {
                let i = v * w + u;
                let [xn, yn] = self.rays[i];
                let hit = if blackout || xn.is_nan() {
                    Hit::Sky
                } else {
                    geo.cast(xn as f64, yn as f64)
                };
                let (rgb, z) = match hit {
                    Hit::Sky => (render::sky(v as f32 / h as f32, night), 0.0),
                    Hit::Road { x, y, depth } => {
                        let (s, d) = geo.locate(x, y, s_guess);
                        s_guess = s;
                        if first_in_row {
                            s_row = s;
                            first_in_row = false;
                        }
                        let [xn, yn] = [xn as f64, yn as f64];
                        let at = if self.kerbs {
                            kerbs::surface(
                                &geo,
                                &self.config.markings,
                                &self.road,
                                xn,
                                yn,
                                [x, y, depth],
                                s,
                                d,
                            )
                        } else {
                            kerbs::Surface::ground([x, y, depth], s, d)
                        };
                        let (x, y) = (at.x, at.y);
                        let mut c = if at.face {
                            render::shade_kerb_face(at.s, at.height, self.seed)
                        } else {
                            let fs = (x * x / (fy * (cam_h - at.height))).max(0.003);
                            let fd = (x / fx + (y / x).abs() * fs).max(0.003);
                            let raised = if self.kerbs {
                                kerbs::raised(&self.config.markings, &self.road, at.s, at.d)
                            } else {
                                kerbs::Raised::No
                            };
                            render::shade_road(
                                &self.config,
                                &self.road,
                                at.s,
                                at.d,
                                raised,
                                fd,
                                fs,
                                self.seed,
                            )
                        };
                        let light = geo.under_vehicle(x, y)
                            * if night {
                                render::night_light(x, y)
                            } else {
                                1.0
                            };
                        for k in c.iter_mut() {
                            *k *= light;
                        }
                        render::haze(&mut c, x, night);
                        (c, at.depth)
                    }
                    Hit::Vehicle {
                        index,
                        local,
                        normal,
                        depth,
                    } => {
                        let (body, half) = geo.vehicle(index);
                        let mut c = render::shade_vehicle(body, half, local, normal);
                        if night {
                            let lit = c[0] > 150.0 && c[1] < 60.0; // tail lights stay bright
                            if !lit {
                                for k in c.iter_mut() {
                                    *k *= 0.25;
                                }
                            }
                        }
                        (c, depth)
                    }
                };
                let c = if blackout {
                    [0.0; 3]
                } else {
                    effects.pixel(rgb, u, v, w, h)
                };
                let noise = effects.noise(i, salt);
                let px = &mut rgba[i * 4..i * 4 + 4];
                for k in 0..3 {
                    // Round half up (the value is clamped to be non-negative first).
                    px[k] = ((c[k] + noise).clamp(0.0, 255.0) + 0.5) as u8;
                }
                px[3] = 255;
                if let Some(d) = depth.as_deref_mut() {
                    d[i] = if blackout { 0.0 } else { z as f32 };
                }
            }
        }
        self.table = geo.into_table();
        let blur = self.config.appearance.blur;
        box_blur(rgba, &mut self.blur_tmp, w, h, blur);
        Ok(pose)
    }
}

/// FNV-1a hash of a rendered frame, for checking that the same seed gives the same pixels on
/// every target (the native and the wasm tests assert the same golden values,
/// `tests/common/goldens.rs`).
pub fn frame_fingerprint(rgba: &[u8]) -> u64 {
    rgba.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::scenario;

    pub(crate) fn small_camera() -> Camera {
        Camera::from_json_str(
            r#"{"width": 160, "height": 120, "fx": 130, "fy": 130, "cx": 80, "cy": 60,
                "height_m": 1.5, "pitch_deg": 4.0, "baseline_m": 0.4}"#,
        )
        .unwrap()
    }

    #[test]
    fn rendering_matches_the_golden_fingerprint() {
        let mut scene = Scene::new(
            crate::synth::scenario("s-curve").unwrap(),
            default_camera(160, 120).unwrap(),
            3,
        )
        .unwrap();
        let mut rgba = vec![0; 160 * 120 * 4];
        scene.render(30, Eye::Left, &mut rgba, None).unwrap();
        assert_eq!(
            frame_fingerprint(&rgba),
            crate::goldens::SCENE_FINGERPRINT,
            "{:#x}",
            frame_fingerprint(&rgba)
        );
    }

    #[test]
    fn rendering_is_deterministic_per_seed() {
        let mut a = Scene::new(scenario("shadows").unwrap(), small_camera(), 5).unwrap();
        let mut b = Scene::new(scenario("shadows").unwrap(), small_camera(), 5).unwrap();
        let mut c = Scene::new(scenario("shadows").unwrap(), small_camera(), 6).unwrap();
        let n = 160 * 120 * 4;
        let (mut x, mut y, mut z) = (vec![0; n], vec![0; n], vec![0; n]);
        a.render(40, Eye::Left, &mut x, None).unwrap();
        b.render(40, Eye::Left, &mut y, None).unwrap();
        c.render(40, Eye::Left, &mut z, None).unwrap();
        assert_eq!(x, y);
        assert_ne!(x, z);
    }

    #[test]
    fn depth_is_the_distance_along_the_optical_axis() {
        let mut config = scenario("highway-straight").unwrap();
        config.ego.sway_amplitude_m = 0.0;
        let mut scene = Scene::new(config, small_camera(), 1).unwrap();
        let mut rgba = vec![0; 160 * 120 * 4];
        let mut depth = vec![0.0; 160 * 120];
        scene
            .render(0, Eye::Left, &mut rgba, Some(&mut depth))
            .unwrap();
        // Flat road, no body motion: the pixel of road point (x, y) has depth equal to its
        // camera-frame Z.
        let cam = scene.camera().clone();
        for (x, y) in [(6.0, 0.5), (12.0, -2.0), (30.0, 1.0)] {
            let [u, v] = cam.road_to_pixel(x, y).unwrap();
            let (ui, vi) = (u.round(), v.round());
            let [xr, yr] = cam.pixel_to_road(ui, vi).unwrap();
            let want = cam.road_to_camera([xr, yr, 0.0])[2];
            let got = depth[vi as usize * 160 + ui as usize] as f64;
            assert!(
                (got - want).abs() < 1e-3 * want,
                "({x}, {y}): {got} vs {want}"
            );
        }
        // The sky has no depth.
        assert_eq!(depth[5 * 160 + 80], 0.0);
    }

    #[test]
    fn bad_buffers_and_blackouts() {
        let mut scene = Scene::new(scenario("occlusion").unwrap(), small_camera(), 1).unwrap();
        let e = scene.render(0, Eye::Left, &mut [0; 10], None).unwrap_err();
        assert!(matches!(e, Error::BufferSize { .. }));
        let mut rgba = vec![0; 160 * 120 * 4];
        let e = scene
            .render(0, Eye::Left, &mut rgba, Some(&mut [0.0; 3]))
            .unwrap_err();
        assert!(e.to_string().contains("depth"), "{e}");
        // 5.5 s at 30 fps is inside the blackout: only noise around black.
        assert!(scene.blacked_out(165));
        scene.render(165, Eye::Left, &mut rgba, None).unwrap();
        let mean = rgba.chunks(4).map(|p| p[0] as f64).sum::<f64>() / (160.0 * 120.0);
        assert!(mean < 2.0, "{mean}");
        assert!(scenario("nowhere")
            .unwrap_err()
            .to_string()
            .contains("highway-straight"));
    }
}
