//! The [`Tracker`] trait every paper's tracker implements, and the registry that builds them by
//! id from a configuration.
//!
//! Ids (see ../shared/DESIGN.md): `liu-ppf`, `liu-ppf-nokernel`, `lee-cpf`, `adachi-mmpf`,
//! `danescu-stereo`, `danescu-mono`. An id is listed in [`TRACKER_IDS`] only once its tracker
//! is implemented; asking for any other id is an [`Error::UnknownTracker`] that lists the
//! available ones.

pub mod adachi;
pub mod danescu;
mod defaults;
mod hypothesis;
pub mod lane_change;
pub mod lee;
pub mod liu;
#[cfg(test)]
mod option_fuzz;
mod ranges;
pub mod relock;

pub use defaults::default_options;
pub use hypothesis::{spread_indices, Hypothesis};
pub use ranges::{option_ranges, OptionRange};

use crate::camera::{Camera, CameraFile};
use crate::error::{Error, Result};
use crate::lane::LaneEstimate;
use serde::Deserialize;
use std::collections::BTreeMap;

/// A lane tracker: one frame in, one estimate out.
pub trait Tracker {
    /// The tracker's id.
    fn id(&self) -> &'static str;
    /// Processes one RGBA frame of the configured camera size.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate>;
    /// Forgets the past: the next frame starts from the initial distribution.
    fn reset(&mut self);
    /// The car's motion for the next frame (Danescu's drift input). Trackers whose motion
    /// model has no ego-motion input ignore it.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a NaN or out-of-range value (see [`EgoMotion::check`]).
    fn set_ego_motion(&mut self, motion: EgoMotion) -> Result<()> {
        motion.check()
    }
    /// Whether the tracker needs a right image with every frame ([`Tracker::set_right`]).
    fn is_stereo(&self) -> bool {
        false
    }
    /// The right image of the next frame, for stereo trackers (`danescu-stereo`): call it
    /// before every [`Tracker::step`] / [`Tracker::begin_frame`].
    ///
    /// # Errors
    /// [`Error::State`] for a one-camera tracker; [`Error::BufferSize`] /
    /// [`Error::Dimensions`] as for a frame.
    fn set_right(&mut self, _rgba: &[u8], _width: usize, _height: usize) -> Result<()> {
        Err(Error::State(format!(
            "{} takes one camera; a right image is for danescu-stereo",
            self.id()
        )))
    }
    /// The particle cloud after the last step, flattened for drawing: `particle_stride()`
    /// numbers per particle, the layout documented by each tracker; empty by default.
    fn particles(&self) -> Vec<f32> {
        Vec::new()
    }
    /// Numbers per particle in [`Tracker::particles`].
    fn particle_stride(&self) -> usize {
        0
    }
    /// At most `max` particles of the cloud, spread over it ([`spread_indices`]), each drawn as
    /// the boundaries it stands for (the same roles and ranges as the estimate); empty by
    /// default.
    fn hypotheses(&self, _max: usize) -> Vec<Hypothesis> {
        Vec::new()
    }
    /// Milliseconds spent in each stage of the last [`Tracker::step`] (for `lanepf bench`).
    fn stage_times(&self) -> StageTimes {
        StageTimes::default()
    }
    /// Pictures of the tracker's cues after the last frame (empty by default).
    fn layers(&self) -> Vec<Layer> {
        Vec::new()
    }
    /// The steps one frame is cut into in per-step (teaching) mode, in order; empty when the
    /// tracker has no per-step mode.
    fn step_names(&self) -> &'static [&'static str] {
        &[]
    }
    /// Starts a frame in per-step mode: checks it and computes its image cues; the filter's
    /// steps then run one [`Tracker::advance`] at a time. `begin_frame` followed by all the
    /// steps gives exactly what [`Tracker::step`] gives.
    ///
    /// # Errors
    /// As [`Tracker::step`] for a bad frame; [`Error::State`] for a tracker without a
    /// per-step mode.
    fn begin_frame(&mut self, _rgba: &[u8], _width: usize, _height: usize) -> Result<()> {
        Err(Error::State(format!(
            "{} has no per-step mode yet; use step()",
            self.id()
        )))
    }
    /// Runs the next step of the frame started by [`Tracker::begin_frame`]; returns the
    /// estimate after the last step, `None` before it.
    ///
    /// # Errors
    /// [`Error::State`] when no frame is in progress.
    fn advance(&mut self) -> Result<Option<LaneEstimate>> {
        Err(Error::State(format!(
            "{} has no per-step mode yet; use step()",
            self.id()
        )))
    }
    /// Index into [`Tracker::step_names`] of the next step, or `None` when no frame is in
    /// progress.
    fn next_step(&self) -> Option<usize> {
        None
    }
}

/// The car's motion at a frame: its timestamp, speed and yaw rate (the frame interval is the
/// difference of consecutive timestamps).
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct EgoMotion {
    /// Frame timestamp, seconds.
    pub t_s: f64,
    /// Speed, metres per second.
    pub speed_mps: f64,
    /// Yaw rate, radians per second, positive turning left.
    pub yaw_rate: f64,
}

impl EgoMotion {
    /// Largest accepted |speed|, m/s.
    pub const MAX_SPEED_MPS: f64 = 150.0;
    /// Largest accepted |yaw rate|, rad/s.
    pub const MAX_YAW_RATE: f64 = 5.0;

    /// Checks the values.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the value for a NaN or infinite one, a speed beyond
    /// [`EgoMotion::MAX_SPEED_MPS`] or a yaw rate beyond [`EgoMotion::MAX_YAW_RATE`].
    pub fn check(&self) -> Result<()> {
        crate::error::require_finite("t_s", self.t_s)?;
        for (name, v, max) in [
            ("speed_mps", self.speed_mps, Self::MAX_SPEED_MPS),
            ("yaw_rate", self.yaw_rate, Self::MAX_YAW_RATE),
        ] {
            crate::error::require_finite(name, v)?;
            if v.abs() > max {
                return Err(Error::parameter(
                    name,
                    v,
                    &format!("must be within +-{max}"),
                ));
            }
        }
        Ok(())
    }
}

/// A picture of one of a tracker's cues after the last frame, in road coordinates, for the
/// views that explain a tracker (Adachi's vote histogram, Lee's likelihood map, ...).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Layer {
    /// Values over bins of one road axis: bin k covers [start + k step, start + (k + 1) step).
    Histogram {
        /// What the values are.
        name: String,
        /// The axis, e.g. `rho (m, positive right)`.
        axis: String,
        /// Start of bin 0, metres.
        start: f64,
        /// Bin size, metres.
        step: f64,
        /// One value per bin.
        values: Vec<f32>,
    },
    /// Values on a road-plane grid of square cells: row r spans x in [x0 + r cell, x0 +
    /// (r + 1) cell), column c spans y in (y0 - (c + 1) cell, y0 - c cell] (columns run from
    /// left to right as seen from the car); `values[r * width + c]`.
    Grid {
        /// What the values are.
        name: String,
        /// Columns.
        width: usize,
        /// Rows.
        height: usize,
        /// Near edge of row 0, metres ahead.
        x0: f64,
        /// Left edge of column 0, metres (y left).
        y0: f64,
        /// Cell size, metres.
        cell: f64,
        /// One value per cell.
        values: Vec<f32>,
    },
    /// Values on a plane other than the road, row 0 at the bottom of the axes.
    Plane {
        /// What the values are.
        name: String,
        /// Columns.
        width: usize,
        /// Rows.
        height: usize,
        /// Where the rows and columns are.
        #[serde(flatten)]
        axes: PlaneAxes,
        /// One value per cell.
        values: Vec<f32>,
    },
}

/// A layer of values on a plane other than the road (e.g. Danescu's lateral density image):
/// column c is at `x0 + (c + 0.5) dx` on the x axis, row r at `y0 + (r + 0.5) dy` on the y axis;
/// `values[r * width + c]`. Part of [`Layer::Plane`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PlaneAxes {
    /// The x axis, e.g. `Z (m, ahead)`.
    pub x_axis: String,
    /// Start of column 0.
    pub x0: f64,
    /// Column size.
    pub dx: f64,
    /// The y axis, e.g. `Y (m, up)`.
    pub y_axis: String,
    /// Start of row 0.
    pub y0: f64,
    /// Row size.
    pub dy: f64,
}

/// Time spent per stage of one frame, milliseconds.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct StageTimes {
    /// Grey conversion, top view, gradients, edges, distance maps (and stereo matching).
    pub preprocess: f64,
    /// Of `preprocess`: the stereo matching (disparity) of a stereo tracker.
    pub disparity: f64,
    /// Motion model: drift and diffusion (and injection).
    pub predict: f64,
    /// Measurement model: likelihoods of all particles.
    pub weigh: f64,
    /// Resampling.
    pub resample: f64,
    /// Estimation and conversion to boundaries.
    pub estimate: f64,
}

/// Reads a tracker's own options (all optional, unknown ones refused) from the free-form part
/// of the [`TrackerConfig`].
///
/// # Errors
/// [`Error::Config`] naming the tracker and the option's key path for an unknown option or a
/// wrong type.
pub(crate) fn parse_options<T: serde::de::DeserializeOwned>(
    id: &str,
    options: &BTreeMap<String, serde_json::Value>,
) -> Result<T> {
    let map: serde_json::Map<String, serde_json::Value> = options
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    serde_path_to_error::deserialize(serde_json::Value::Object(map)).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        if path == "." {
            Error::Config(format!("{id} options: {inner}"))
        } else {
            Error::Config(format!("{id} options: {path}: {inner}"))
        }
    })
}

/// Checks that an RGBA frame has the camera's size.
///
/// # Errors
/// [`Error::Dimensions`] for another size, [`Error::BufferSize`] for a buffer that is not
/// width * height * 4 bytes.
pub(crate) fn check_frame(camera: &Camera, rgba: &[u8], width: usize, height: usize) -> Result<()> {
    if (width, height) != (camera.width(), camera.height()) {
        return Err(Error::Dimensions(format!(
            "the tracker was built for {}x{} frames but got {width}x{height}",
            camera.width(),
            camera.height()
        )));
    }
    crate::image::check_rgba(rgba, width, height)
}

/// The error of [`Tracker::advance`] without a frame in progress.
pub(crate) fn no_frame_in_progress() -> Error {
    Error::State("no frame in progress: call beginFrame (begin_frame in Rust) first".into())
}

/// The ids of the trackers implemented so far.
pub const TRACKER_IDS: &[&str] = &[
    adachi::ID,
    danescu::ID_MONO,
    danescu::ID_STEREO,
    lee::ID,
    liu::ID,
    liu::ID_NOKERNEL,
];

/// Largest accepted particle count.
pub const MAX_PARTICLES: usize = 200_000;

/// What every tracker is built from: the camera, the particle budget, the seed, and
/// tracker-specific options (checked by the tracker itself).
#[derive(Debug, Clone, Deserialize)]
pub struct TrackerConfig {
    /// The camera (the `camera.json` format).
    pub camera: CameraFile,
    /// Number of particles N; `None`: the tracker's own default.
    #[serde(default)]
    pub particles: Option<usize>,
    /// RNG seed: the same seed gives the same run natively and in the browser.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Tracker-specific options by name.
    #[serde(flatten)]
    pub options: BTreeMap<String, serde_json::Value>,
}

fn default_seed() -> u64 {
    1
}

impl TrackerConfig {
    /// Parses a JSON configuration.
    ///
    /// # Errors
    /// [`Error::Config`] when the JSON is malformed or a field has the wrong type.
    pub fn from_json_str(text: &str) -> Result<Self> {
        serde_json::from_str(text).map_err(|e| Error::Config(format!("tracker config: {e}")))
    }

    /// Checks the configuration and returns the validated camera.
    ///
    /// # Errors
    /// Camera errors as [`Camera::from_file`] gives them; [`Error::Parameter`] for a particle
    /// count of 0 or above [`MAX_PARTICLES`].
    pub fn validate(&self) -> Result<Camera> {
        if let Some(n) = self.particles {
            if n == 0 || n > MAX_PARTICLES {
                return Err(Error::parameter(
                    "particles",
                    n,
                    &format!("must be between 1 and {MAX_PARTICLES}"),
                ));
            }
        }
        Camera::from_file(&self.camera)
    }

    /// The particle count: the configured one, or the tracker's `default`.
    pub fn particles_or(&self, default: usize) -> usize {
        self.particles.unwrap_or(default)
    }
}

/// Builds the tracker `id` from `config`.
///
/// # Errors
/// [`Error::UnknownTracker`] for an id not in [`TRACKER_IDS`]; configuration errors as
/// [`TrackerConfig::validate`] gives them.
pub fn create(id: &str, config: &TrackerConfig) -> Result<Box<dyn Tracker>> {
    let _camera = config.validate()?;
    if id == adachi::ID {
        return Ok(Box::new(adachi::AdachiTracker::new(config)?));
    }
    if id == danescu::ID_MONO || id == danescu::ID_STEREO {
        let id = if id == danescu::ID_MONO {
            danescu::ID_MONO
        } else {
            danescu::ID_STEREO
        };
        return Ok(Box::new(danescu::DanescuTracker::new(config, id)?));
    }
    if id == lee::ID {
        return Ok(Box::new(lee::LeeTracker::new(config)?));
    }
    if id == liu::ID || id == liu::ID_NOKERNEL {
        return Ok(Box::new(liu::LiuTracker::new(config, id == liu::ID)?));
    }
    Err(Error::UnknownTracker {
        id: id.to_string(),
        available: if TRACKER_IDS.is_empty() {
            "none yet (the trackers of the four papers are being built)".to_string()
        } else {
            TRACKER_IDS.join(", ")
        },
    })
}

/// Milliseconds from a monotonic clock (0 where none is available, e.g. plain wasm).
pub(crate) fn now() -> f64 {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use std::sync::OnceLock;
        static START: OnceLock<std::time::Instant> = OnceLock::new();
        START
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_secs_f64()
            * 1e3
    }
    #[cfg(target_arch = "wasm32")]
    {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CAMERA: &str = r#"{"width": 640, "height": 480, "fx": 309.4, "fy": 344.2, "cx": 317.9,
        "cy": 256.5, "height_m": 2.18, "pitch_deg": 14.0, "yaw_deg": 0.0, "roll_deg": 0.0}"#;

    #[test]
    fn config_defaults_and_validation() {
        let c = TrackerConfig::from_json_str(&format!(r#"{{"camera": {CAMERA}}}"#)).unwrap();
        assert_eq!((c.particles, c.seed), (None, 1));
        assert_eq!(c.particles_or(500), 500);
        assert!(c.validate().is_ok());
        let c = TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {CAMERA}, "particles": 0, "sigma": 2}}"#
        ))
        .unwrap();
        assert_eq!(c.options["sigma"], serde_json::json!(2));
        let e = c.validate().unwrap_err().to_string();
        assert!(e.contains("`particles` = 0"), "{e}");
        let e = TrackerConfig::from_json_str(r#"{"particles": 10}"#).unwrap_err();
        assert!(e.to_string().contains("missing field `camera`"), "{e}");
    }

    #[test]
    fn unknown_ids_list_what_exists() {
        let c = TrackerConfig::from_json_str(&format!(r#"{{"camera": {CAMERA}}}"#)).unwrap();
        let e = create("kalman-magic", &c).err().unwrap();
        assert!(matches!(e, Error::UnknownTracker { .. }));
        assert!(e
            .to_string()
            .starts_with("unknown tracker `kalman-magic`; available: "));
    }

    /// A 200-particle configuration for the simulator's default 320x240 camera and scenario
    /// `name` (seed 1).
    fn fixture(name: &str) -> (TrackerConfig, crate::synth::Scene) {
        use crate::synth::{default_camera, scenario, Scene};
        let camera = default_camera(320, 240).unwrap();
        let c = TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {}, "particles": 200}}"#,
            serde_json::to_string(&camera.to_file()).unwrap()
        ))
        .unwrap();
        (c, Scene::new(scenario(name).unwrap(), camera, 1).unwrap())
    }

    #[test]
    fn every_tracker_steps_one_step_at_a_time_to_the_same_result() {
        use crate::synth::Eye;
        let (c, mut scene) = fixture("highway-curve");
        let mut rgba = vec![0; 320 * 240 * 4];
        let mut right = vec![0; 320 * 240 * 4];
        for id in TRACKER_IDS {
            let mut whole = create(id, &c).unwrap();
            let mut stepped = create(id, &c).unwrap();
            let n = stepped.step_names().len();
            assert!(n >= 3, "{id}: {n} steps");
            assert!(stepped.advance().is_err(), "{id}: no frame in progress");
            for f in 0..3 {
                scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                if whole.is_stereo() {
                    scene.render(f, Eye::Right, &mut right, None).unwrap();
                    whole.set_right(&right, 320, 240).unwrap();
                    stepped.set_right(&right, 320, 240).unwrap();
                } else {
                    assert!(whole.set_right(&right, 320, 240).is_err(), "{id}");
                }
                let expected = whole.step(&rgba, 320, 240).unwrap();
                stepped.begin_frame(&rgba, 320, 240).unwrap();
                let results: Vec<_> = (0..n).map(|_| stepped.advance().unwrap()).collect();
                assert!(results[..n - 1].iter().all(Option::is_none), "{id}");
                assert_eq!(results[n - 1].as_ref(), Some(&expected), "{id} frame {f}");
                assert_eq!(stepped.particles(), whole.particles(), "{id} frame {f}");
            }
        }
    }

    #[test]
    fn every_tracker_draws_its_particles_around_its_estimate() {
        use crate::lane::{Boundary, Role};
        use crate::synth::Eye;
        let (c, mut scene) = fixture("highway-straight");
        let mut rgba = vec![0; 320 * 240 * 4];
        let mut right = vec![0; 320 * 240 * 4];
        for id in TRACKER_IDS {
            let mut t = create(id, &c).unwrap();
            let mut estimate = None;
            for f in 0..10 {
                scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                if t.is_stereo() {
                    scene.render(f, Eye::Right, &mut right, None).unwrap();
                    t.set_right(&right, 320, 240).unwrap();
                }
                estimate = Some(t.step(&rgba, 320, 240).unwrap());
            }
            let estimate = estimate.unwrap();
            let cloud = t.particles().len() / t.particle_stride();
            let drawn = t.hypotheses(60);
            assert_eq!(drawn.len(), cloud.min(60), "{id}");
            assert!(t.hypotheses(0).is_empty(), "{id}");
            let at_10m = |b: &[Boundary]| {
                b.iter()
                    .find(|b| b.role == Role::EgoLeft)
                    .and_then(|b| b.y_at(10.0))
            };
            let expected = at_10m(&estimate.boundaries).unwrap();
            let (mut sum, mut total, mut lo, mut hi) = (0.0, 0.0, f64::MAX, f64::MIN);
            for h in &drawn {
                assert!(
                    h.weight.is_finite() && (0.0..=1.0).contains(&h.weight),
                    "{id}"
                );
                for b in &h.boundaries {
                    assert!(b
                        .points
                        .iter()
                        .all(|p| (0.0..=319.0).contains(&p[0]) && (0.0..=239.0).contains(&p[1])));
                }
                if let Some(y) = at_10m(&h.boundaries) {
                    sum += h.weight * y;
                    total += h.weight;
                    (lo, hi) = (lo.min(y), hi.max(y));
                }
            }
            // The weighted cloud sits on the estimate, and it is a cloud, not one line.
            // (Not for liu-ppf-nokernel, the paper's weak baseline: its cloud holds several
            // boundaries at once, 0.7-3.6 m left, so the roles differ between its particles.)
            let mean = sum / total;
            assert!(
                *id == liu::ID_NOKERNEL || (mean - expected).abs() < 0.25,
                "{id}: cloud {mean} vs estimate {expected}"
            );
            assert!(hi - lo > 0.005, "{id}: every drawn particle at {lo}");
        }
    }

    #[test]
    fn every_tracker_shows_its_main_cue_on_the_true_boundaries() {
        use crate::lane::Role;
        use crate::synth::Eye;
        let (c, mut scene) = fixture("highway-straight");
        let mut rgba = vec![0; 320 * 240 * 4];
        let mut right = vec![0; 320 * 240 * 4];
        scene.render(0, Eye::Left, &mut rgba, None).unwrap();
        scene.render(0, Eye::Right, &mut right, None).unwrap();
        let truth = scene.truth(0);
        // Lateral positions y of the true boundaries (`ego`: only the ego lane's) x metres
        // ahead.
        let true_y = |x: f64, ego: bool| -> Vec<f64> {
            truth
                .boundaries
                .iter()
                .filter(|b| !ego || matches!(b.role, Role::EgoLeft | Role::EgoRight))
                .filter_map(|b| b.y_at(x))
                .collect()
        };
        let near = |y: f64, x: f64| true_y(x, false).iter().any(|t| (t - y).abs() < 0.3);
        // liu-ppf-nokernel is the paper's deliberately weak baseline: its cue, the brightness
        // of edge pixels, peaks on bright asphalt as well (liu-ppf shows the same pixels with
        // their orientation kernels).
        for id in TRACKER_IDS.iter().filter(|&&id| id != liu::ID_NOKERNEL) {
            let mut t = create(id, &c).unwrap();
            if t.is_stereo() {
                t.set_right(&right, 320, 240).unwrap();
            }
            t.step(&rgba, 320, 240).unwrap();
            let layers = t.layers();
            assert!(!layers.is_empty(), "{id}");
            match &layers[0] {
                Layer::Histogram {
                    start,
                    step,
                    values,
                    ..
                } => {
                    // The strongest bin (rho = -y) lies on a boundary.
                    let k = (0..values.len())
                        .max_by(|&a, &b| values[a].total_cmp(&values[b]))
                        .unwrap();
                    let rho = start + (k as f64 + 0.5) * step;
                    assert!(near(-rho, 14.0), "{id}: peak at rho {rho}");
                }
                Layer::Grid {
                    width,
                    height,
                    x0,
                    y0,
                    cell,
                    values,
                    ..
                } => {
                    assert_eq!(values.len(), width * height, "{id}");
                    // Every true boundary (dashed ones somewhere along the range) reaches the
                    // top of the map, and every cell at the top lies on a boundary.
                    let (mut found, mut boundaries) = (vec![false; 4], 0);
                    for r in 0..*height {
                        let x = x0 + (r as f64 + 0.5) * cell;
                        let ys = true_y(x, false);
                        boundaries = boundaries.max(ys.len());
                        let row = &values[r * width..(r + 1) * width];
                        for (k, y) in ys.iter().enumerate().take(4) {
                            let c = ((y0 - y) / cell) as usize;
                            if c < *width
                                && row[c.saturating_sub(2)..(c + 3).min(*width)]
                                    .iter()
                                    .any(|&v| v > 0.99)
                            {
                                found[k] = true;
                            }
                        }
                        for (c, _) in row.iter().enumerate().filter(|(_, &v)| v > 0.99) {
                            // One cell of slack for the grid's quantisation and the 3 x 3
                            // operators that fill it.
                            // operators that fill it; against every boundary of the road,
                            // including the parts of markings at the image border that the
                            // truth polylines (marking centres in the image) leave out.
                            let y = y0 - (c as f64 + 0.5) * cell;
                            let pose = scene.pose(0);
                            let on = (0..=scene.road().lanes())
                                .filter_map(|k| scene.boundary_y(&pose, k, x))
                                .any(|t| (t - y).abs() < 0.3 + cell);
                            assert!(on, "{id}: maximum at x {x} y {y}");
                        }
                    }
                    assert!(boundaries >= 2, "{id}");
                    assert!(
                        found[..boundaries.min(4)].iter().all(|&f| f),
                        "{id}: {found:?}"
                    );
                }
                Layer::Plane { .. } => panic!("{id}: the main layer must be on the road"),
            }
        }
    }
}
