//! The `Tracker` factory for JavaScript: `new Tracker(id, config)`.

use super::args;
use super::deprecation;
use super::error::{self, input, Kind, Thrown};
use super::estimate::{self, Keep};
use super::object;
use super::step_input;
use crate::camera::CameraFile;
use crate::filter::ResampleDecision;
use crate::trackers::{self, TrackerConfig};
use std::collections::BTreeMap;
use wasm_bindgen::prelude::*;

/// A lane tracker built by id (see `trackerIds()`).
#[wasm_bindgen(js_name = Tracker)]
pub struct JsTracker {
    inner: Box<dyn trackers::Tracker>,
    /// The last frame's pixels, copied out of the JS array (reused).
    frame: Vec<u8>,
    /// The last right frame given in `step`'s options (reused).
    right: Vec<u8>,
    /// The camera's frame size, [width, height].
    size: [usize; 2],
    /// The resampling decisions of the last `step` or `advance`, as the filters made them.
    resamplings: Vec<ResampleDecision>,
}

/// Reads a tracker config: the camera first (so that its errors name `camera.<key>`), then
/// `particles` and `seed`; every other key is the tracker's own option, read when the tracker
/// is built. The same values and messages as `TrackerConfig`'s `Deserialize` (whose flattened
/// options need serde's buffering of values, about 4 kB of the wasm; issue 21 part 5). Returns
/// the config with the camera's frame size.
fn read_config(value: &JsValue) -> Result<(TrackerConfig, [usize; 2]), Thrown> {
    const WHAT: &str = "tracker config";
    let serde_json::Value::Object(config) = object::read_value(value, WHAT, Kind::Config)? else {
        return Err(Thrown::config(format!("invalid {WHAT}: not an object")));
    };
    if !config.contains_key("camera") {
        return Err(Thrown::config(format!(
            "invalid {WHAT}: `camera` is missing"
        )));
    }
    // In key order (camera, particles and seed meet their errors in the order the derive did:
    // the other keys wait for the tracker). Taken apart and inserted, not removed or
    // collected: BTreeMap's remove and collect (which sorts) would add their code.
    let (mut camera, mut particles, mut seed) = (None, None, trackers::DEFAULT_SEED);
    let mut options = BTreeMap::new();
    for (key, value) in config {
        match key.as_str() {
            "camera" => camera = Some(object::deserialize(value, WHAT, "camera", Kind::Config)?),
            "particles" => {
                particles = object::deserialize(value, WHAT, "particles", Kind::Config)?;
            }
            "seed" => seed = object::deserialize(value, WHAT, "seed", Kind::Config)?,
            _ => {
                options.insert(key, value);
            }
        }
    }
    let Some(camera): Option<CameraFile> = camera else {
        return Err(Thrown::config(format!(
            "invalid {WHAT}: `camera` is missing"
        )));
    };
    let size = [camera.width, camera.height];
    let config = TrackerConfig {
        camera,
        particles,
        seed,
        options: trackers::Options::ByName(options),
    };
    Ok((config, size))
}

/// The ids `new Tracker(id, ...)` accepts.
#[wasm_bindgen(js_name = trackerIds, unchecked_return_type = "TrackerId[]")]
pub fn tracker_ids() -> Vec<String> {
    trackers::TRACKER_IDS
        .iter()
        .map(|s| s.to_string())
        .collect()
}

/// Every option of tracker `id` with its default value, `particles` included (pass any of them
/// in `new Tracker(id, { camera, ...options })`); throws for an unknown id.
#[wasm_bindgen(
    js_name = trackerDefaults,
    unchecked_return_type = "TrackerDefaults"
)]
pub fn tracker_defaults(
    #[wasm_bindgen(unchecked_param_type = "TrackerId")] id: JsValue,
) -> Result<JsValue, Thrown> {
    let id = args::name(&id, "tracker id")?;
    super::to_js_value(&trackers::default_options(&id).map_err(error::config)?)
}

/// Every option of tracker `id` with its value in the named `preset`, `particles` included:
/// `paper` gives each paper's filter (the same as `trackerDefaults(id)`), `real-roads` our
/// options beyond the papers that measured better on real footage (the re-lock proposal, the
/// neighbouring lanes, lee-cpf's curvature prior). Pass them on to `new Tracker(id, { camera,
/// ...options })`; throws for an unknown id or preset.
#[wasm_bindgen(js_name = trackerPreset, unchecked_return_type = "TrackerDefaults")]
pub fn tracker_preset(
    #[wasm_bindgen(unchecked_param_type = "TrackerId")] id: JsValue,
    #[wasm_bindgen(unchecked_param_type = "TrackerPreset")] preset: JsValue,
) -> Result<JsValue, Thrown> {
    let id = args::name(&id, "tracker id")?;
    let preset: trackers::Preset = args::name(&preset, "preset")?
        .parse()
        .map_err(error::config)?;
    super::to_js_value(&trackers::preset_options(&id, preset).map_err(error::config)?)
}

#[wasm_bindgen(js_class = Tracker)]
impl JsTracker {
    /// `new Tracker(id, { camera, particles?, seed?, ...options })`; throws an `Error` for an
    /// unknown id (listing the available ones) or a bad configuration. The options are tracker
    /// `id`'s (`TrackerOptionsById[id]`): with a literal id, another tracker's option is a type
    /// error.
    #[wasm_bindgen(constructor)]
    pub fn new(
        // `Id` is the class's type parameter, declared by scripts/build-pkg.sh.
        #[wasm_bindgen(unchecked_param_type = "Id")] id: JsValue,
        #[wasm_bindgen(unchecked_param_type = "TrackerConfig<Id>")] config: JsValue,
    ) -> Result<JsTracker, Thrown> {
        let id = args::name(&id, "tracker id")?;
        let (options, size) = read_config(&config)?;
        let inner = trackers::create(&id, &options).map_err(error::config)?;
        Ok(JsTracker {
            inner,
            size,
            frame: Vec::new(),
            right: Vec::new(),
            resamplings: Vec::new(),
        })
    }

    /// Checks a frame's size and copies its pixels into `self.frame`.
    fn take_frame(
        &mut self,
        rgba: &JsValue,
        width: &JsValue,
        height: &JsValue,
    ) -> Result<[usize; 2], Thrown> {
        let size = [args::side(width, "width")?, args::side(height, "height")?];
        args::rgba(rgba, "rgba", size, &mut self.frame)?;
        Ok(size)
    }

    /// The tracker's id.
    #[wasm_bindgen(getter, unchecked_return_type = "Id")]
    pub fn id(&self) -> String {
        self.inner.id().to_string()
    }

    /// Processes one frame and returns the estimate: `step(frame, { right?, motion? })` with
    /// an `ImageData` or `{ data, width, height }` (the right camera's frame of a stereo
    /// tracker and the car's motion in the options), or `step(rgba, width, height)`.
    #[wasm_bindgen(unchecked_return_type = "LaneEstimate")]
    pub fn step(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "RgbaFrame")] frame: JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "StepOptions")] options: Option<JsValue>,
        // Only in the older form, `(rgba, width, height)`, declared in `types.rs`.
        #[wasm_bindgen(unchecked_optional_param_type = "undefined")] height: Option<JsValue>,
    ) -> Result<JsValue, Thrown> {
        let [w, h] = self.take_step_input(&frame, options.as_ref(), height.as_ref())?;
        self.resamplings.clear();
        let estimate = self.inner.step(&self.frame, w, h).map_err(input)?;
        self.resamplings = self.inner.resamplings().to_vec();
        estimate::to_js(&estimate, Keep::Neither)
    }

    /// Reads a `step` / `beginFrame` call's arguments ([`step_input::read`]) and, once all of
    /// them are checked, hands the motion and the right frame to the tracker; returns the
    /// left frame's size (its pixels are in `self.frame`).
    fn take_step_input(
        &mut self,
        frame: &JsValue,
        options: Option<&JsValue>,
        height: Option<&JsValue>,
    ) -> Result<[usize; 2], Thrown> {
        let (size, extras) =
            step_input::read(frame, options, height, &mut self.frame, &mut self.right)?;
        if extras.right.is_some() && !self.inner.is_stereo() {
            // The tracker's own refusal (a one-camera tracker), before anything is applied.
            return self.inner.set_right(&[], 0, 0).map(|_| size).map_err(input);
        }
        if (extras.right.is_some() || extras.motion.is_some()) && size != self.size {
            // Refused here rather than by the step, after the motion and the right frame had
            // been handed over.
            let ([w, h], [cw, ch]) = (size, self.size);
            return Err(Thrown::input(format!(
                "frame is {w}x{h} but the tracker's camera is {cw}x{ch}: frames must have the \
                 camera's size"
            )));
        }
        // Neither can fail now: the motion is checked and the right frame has the camera's size.
        if let Some([w, h]) = extras.right {
            self.inner.set_right(&self.right, w, h).map_err(input)?;
        }
        if let Some(motion) = extras.motion {
            self.inner.set_ego_motion(motion).map_err(input)?;
        }
        Ok(size)
    }

    /// The particle cloud after the last step as a `Float32Array` of `particleStride` numbers
    /// per particle (adachi-mmpf: model r 1..4, q in metres, w in metres, weight; lee-cpf:
    /// stage 1 or 2 (0 for a single-stage variant), psi, y0, w, w', c, delta, weight;
    /// liu-ppf: 3 numbers (rho, theta, d) per boundary and the weight; danescu-mono: the 11
    /// lane parameters w0, ch, wl, cv, y0, xcw, alpha, gamma, psi, wl_mark, wr_mark, the
    /// weight and the MBSAS cluster, -1 for an initialisation particle; danescu-stereo: the same).
    pub fn particles(&self) -> js_sys::Float32Array {
        js_sys::Float32Array::from(&self.inner.particles()[..])
    }

    /// Pictures of the tracker's cues after the last frame: `[{ kind: 'histogram', name, axis,
    /// start, step, values } | { kind: 'grid', name, width, height, x0, y0, cell, values }]`
    /// (adachi-mmpf: the vote and noise histograms; lee-cpf: the likelihood map D and the DLD
    /// candidates; liu-ppf: the measurement pixels and the top view; danescu-mono: the marking
    /// and road edges; danescu-stereo: those and `{ kind: 'plane', name, width, height, x_axis,
    /// x0, dx, y_axis, y0, dy, values }` for the 3-D density image and its column maxima;
    /// grid row r is x0 + r cell metres ahead, column c is y0 - c cell metres left).
    /// Each layer's `values` is a `Float32Array`.
    #[wasm_bindgen(unchecked_return_type = "Layer[]")]
    pub fn layers(&self) -> Result<JsValue, Thrown> {
        super::layers::to_js(&self.inner.layers())
    }

    /// At most `max` particles spread over the cloud, each drawn as the boundaries it stands
    /// for: `[{ weight, group, boundaries: [{ role, points, road_points }] }]` (weight: the
    /// normalised weight; group: adachi-mmpf the model r, lee-cpf the stage, danescu-* the
    /// MBSAS cluster or -1, liu-ppf 0). For drawing the cloud without knowing each model.
    /// `max` is a whole number; above the particle count it means every particle.
    #[wasm_bindgen(unchecked_return_type = "Hypothesis[]")]
    pub fn hypotheses(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] max: JsValue,
    ) -> Result<JsValue, Thrown> {
        let max = args::whole(&max, "max", 0.0, 9_007_199_254_740_991.0)?;
        let max = max as usize; // saturates: 2^32 and above mean every particle on wasm32
        super::to_js_value(&self.inner.hypotheses(max))
    }

    /// Numbers per particle in `particles()`.
    #[wasm_bindgen(getter, js_name = particleStride)]
    pub fn particle_stride(&self) -> usize {
        self.inner.particle_stride()
    }

    /// The car's motion for the next frame: `{ t_s, speed_mps, yaw_rate }` (timestamp in
    /// seconds, speed in m/s, yaw rate in rad/s positive turning left). danescu-mono and
    /// danescu-stereo drift their particles by it; the other trackers ignore it. Throws for a
    /// missing or unknown field or a NaN or out-of-range value.
    ///
    /// @deprecated Pass the motion with the frame instead: `step(frame, { motion })`.
    #[wasm_bindgen(js_name = setEgoMotion)]
    pub fn set_ego_motion(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "EgoMotion")] motion: JsValue,
    ) -> Result<(), Thrown> {
        deprecation::warn_once(
            &deprecation::SET_EGO_MOTION,
            "lanepf: Tracker.setEgoMotion is deprecated; pass the motion with the frame: \
             tracker.step(frame, { motion })",
        );
        let motion: trackers::EgoMotion = object::read(&motion, "ego motion", Kind::Input)?;
        self.inner.set_ego_motion(motion).map_err(input)
    }

    /// Whether the tracker needs the right image of every frame (`setRight`): danescu-stereo.
    #[wasm_bindgen(getter, js_name = isStereo)]
    pub fn is_stereo(&self) -> bool {
        self.inner.is_stereo()
    }

    /// The right camera's RGBA frame for the next `step` / `beginFrame` of a stereo tracker
    /// (used once). Throws for a one-camera tracker or a frame of the wrong size.
    ///
    /// @deprecated Pass the right frame with the left one instead: `step(left, { right })`.
    #[wasm_bindgen(js_name = setRight)]
    pub fn set_right(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Rgba")] rgba: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] width: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] height: JsValue,
    ) -> Result<(), Thrown> {
        deprecation::warn_once(
            &deprecation::SET_RIGHT,
            "lanepf: Tracker.setRight is deprecated; pass the right frame with the left one: \
             tracker.step(left, { right })",
        );
        if !self.inner.is_stereo() {
            // The tracker's own refusal, before the frame is even looked at.
            return self.inner.set_right(&[], 0, 0).map_err(input);
        }
        let [w, h] = self.take_frame(&rgba, &width, &height)?;
        self.inner.set_right(&self.frame, w, h).map_err(input)
    }

    /// Forgets the past.
    pub fn reset(&mut self) {
        self.resamplings.clear();
        self.inner.reset();
    }

    /// The resampling decisions of the last `step()` or `advance()`, in the order the filters
    /// made them (empty after `beginFrame`, `reset`, a call that threw, or a step that did not
    /// resample or test): `[{ rule, ess, particles, threshold, resampled }]`. `rule` is
    /// `'ess-below'` (resample when `ess < threshold`: lee-cpf's N_thr), `'always'`,
    /// `'injection'` (every frame, the set rebuilt with fresh particles: liu-ppf,
    /// danescu-*), `'between-stages'` (liu-ppf's partitions) or `'never'`; `ess` is the
    /// effective sample size the filter tested, `threshold` (particles) is null unless the rule
    /// is `'ess-below'`. Each filter of a tracker reports its own (lee-cpf's two stages one
    /// after the other; on a first frame the start-up rounds too).
    #[wasm_bindgen(unchecked_return_type = "ResampleDecision[]")]
    pub fn resamplings(&self) -> Result<JsValue, Thrown> {
        super::to_js_value(&self.resamplings)
    }

    /// The steps of one frame in per-step (teaching) mode, in order; empty for a tracker
    /// without one.
    #[wasm_bindgen(js_name = stepNames)]
    pub fn step_names(&self) -> Vec<String> {
        self.inner
            .step_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    /// Starts a frame in per-step mode (computes its image cues); then call `advance()` once
    /// per step. Takes the same arguments as `step`. Throws for a bad frame or a tracker
    /// without a per-step mode.
    #[wasm_bindgen(js_name = beginFrame)]
    pub fn begin_frame(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "RgbaFrame")] frame: JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "StepOptions")] options: Option<JsValue>,
        // Only in the older form, `(rgba, width, height)`, declared in `types.rs`.
        #[wasm_bindgen(unchecked_optional_param_type = "undefined")] height: Option<JsValue>,
    ) -> Result<(), Thrown> {
        let [w, h] = self.take_step_input(&frame, options.as_ref(), height.as_ref())?;
        self.resamplings.clear();
        self.inner.begin_frame(&self.frame, w, h).map_err(input)
    }

    /// Runs the next step; returns the estimate after the last step and `null` before it (read
    /// `particles()` in between to watch the cloud move). Throws when no frame is in progress.
    #[wasm_bindgen(unchecked_return_type = "LaneEstimate | null")]
    pub fn advance(&mut self) -> Result<JsValue, Thrown> {
        self.resamplings.clear();
        let estimate = self.inner.advance().map_err(input)?;
        self.resamplings = self.inner.resamplings().to_vec();
        match estimate {
            Some(estimate) => estimate::to_js(&estimate, Keep::Neither),
            None => Ok(JsValue::NULL),
        }
    }

    /// Index into `stepNames()` of the next step, or `undefined` when no frame is in progress.
    #[wasm_bindgen(getter, js_name = nextStep)]
    pub fn next_step(&self) -> Option<usize> {
        self.inner.next_step()
    }
}
