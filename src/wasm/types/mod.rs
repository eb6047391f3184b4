//! TypeScript types of the plain objects that cross the binding (configurations, options and
//! results), added to the generated `lanepf.d.ts`. The bound functions name them with
//! `unchecked_param_type` / `unchecked_return_type`; the objects themselves are still checked
//! at run time (unknown fields, wrong types, `null` and NaN throw a `LanepfError`).
//!
//! Two parts. The tracker configurations (`TrackerId`, `TrackerConfig<Id>`, each tracker's
//! options and the vision configs they nest) are generated from the Rust types into
//! `generated.d.ts` by `typegen` (a test-only generator; its tests fail when the file is stale
//! or disagrees with serde). The rest, below, is still kept by hand, in step with the Rust
//! types it describes: `camera::CameraFile`, `lane::LaneEstimate`, `trackers::{Layer,
//! EgoMotion}`, `synth::TestRoadConfig`, the truth's `state` keys (`synth::truth`) and
//! `calib::{CalibratorConfig, CalibrationEstimate, FrameObservation, LineFit}` with
//! `wasm::calibrator`'s status. The npm test (`tests/npm/`) compiles a TypeScript program
//! against both with `tsc --strict`.

use wasm_bindgen::prelude::*;

#[cfg(test)]
mod typegen;

/// The tracker configurations (`TrackerId`, `TrackerConfig<Id>`, each tracker's options and
/// the vision configs they nest), generated from the Rust types by `typegen` and checked
/// against them by its tests.
#[wasm_bindgen(typescript_custom_section)]
const GENERATED: &'static str = include_str!("generated.d.ts");

#[wasm_bindgen(typescript_custom_section)]
const TYPES: &'static str = r#"
/**
 * What kind of mistake a thrown `LanepfError` reports: `LanepfConfigError` (a constructor's id,
 * name or option object), `LanepfInputError` (a call's data: frames, sizes, indices, points,
 * ego motion), `LanepfStateError` (a call the object cannot take now: `advance()` with no frame
 * in progress, a stereo step without a right frame, a right frame for a one-camera tracker).
 */
export type LanepfErrorName = 'LanepfConfigError' | 'LanepfInputError' | 'LanepfStateError';

/** Every `Error` lanepf throws; its message names the argument or key path and the value. */
export interface LanepfError extends Error {
  name: LanepfErrorName;
}

/**
 * The scenario names `new Scene(name, ...)` accepts (see `scenarios()`); `random` only with
 * `drawn: true` (it picks a family from the seed).
 */
export type ScenarioName =
  | 'highway-straight' | 'highway-curve' | 's-curve' | 'lane-change' | 'occlusion' | 'shadows'
  | 'worn-markings' | 'night' | 'width-change' | 'pitch-bumps' | 'multi-lane' | 'urban'
  | 'random';

/** Options of `new Scene(name, options)`. */
export interface SceneOptions {
  /** Seed of texture, noise and every random choice (whole number, default 1). */
  seed?: number;
  /** Width of the default camera, pixels (default 640; ignored with `camera`). */
  width?: number;
  /** Height of the default camera, pixels (default 480; ignored with `camera`). */
  height?: number;
  /** Render through this camera instead of the default (or the drawn) one. */
  camera?: CameraConfig;
  /**
   * Draw the family member of `seed`: its road, events and camera, as `lanepf synth --seed`
   * does (default false: the family's fixed reference road through the default camera).
   */
  drawn?: boolean;
}

/** One entry of `scenarios()`. */
export interface ScenarioInfo {
  name: ScenarioName;
  description: string;
}

/** Which boundary a polyline is. */
export type Role = 'ego-left' | 'ego-right' | 'left-adjacent' | 'right-adjacent';

/** One lane boundary. */
export interface Boundary {
  role: Role;
  /** Image points [x, y], pixels, bottom of the image first, at most 10 px apart in y. */
  points: [number, number][];
  /** The same boundary on the road, [x forward, y left], metres, near first (absent when empty). */
  road_points?: [number, number][];
}

/** Which edge of a lane marking a delimiter follows. */
export type Side = 'inner' | 'outer';

/** One edge of a boundary's marking (danescu-*: eqs. 2-3 of Danescu & Nedevschi 2011). */
export interface Delimiter extends Boundary {
  /** The edge towards the ego lane ('inner') or away from it ('outer'). */
  side: Side;
}

/** A tracker's estimate (or the ground truth) of one frame. */
export interface LaneEstimate {
  /** Whether the tracker is confident in this estimate. */
  valid: boolean;
  /** The boundaries, in any order. */
  boundaries: Boundary[];
  /** Camera left of the lane centre, metres (ISO 8855 y). */
  lateral_offset_m: number;
  /** Heading of the lane relative to the camera's axis, radians, positive left. */
  heading_rad: number;
  /** Curvature of the lane at the camera, 1/m, positive turning left. */
  curvature_per_m: number;
  /** Lane width, metres. */
  lane_width_m: number;
  /** Tracker-specific parameters by name ('lee.psi', 'adachi.q', 'danescu.w0', ...);
   *  'adachi.change', 'lee.change', 'danescu.change': +1 a lane change to the left this frame,
   *  -1 to the right, 0 none. */
  state: Record<string, number>;
  /**
   * The inner and outer edges of the boundaries' markings, from trackers that model marking
   * widths (danescu-mono, danescu-stereo); absent for the others.
   */
  delimiters?: Delimiter[];
  /** The effective sample size of the particles after the frame's weighing (lee-cpf: stage 1's;
   *  `state['lee.ess2']` is stage 2's), particles; absent from a scene's truth. */
  ess?: number;
  /** adachi-mmpf only: the model probabilities P(r) of the lane configurations r = 1..4
   *  (`state['adachi.p1']` ..), summing to 1. */
  model_probabilities?: [number, number, number, number];
}

/** The named values of a scene's ground truth (`Scene.truth(f).state`). */
export interface TruthState {
  /** Time, seconds. */
  t: number;
  /** Speed, metres per second. */
  speed_mps: number;
  /** Yaw rate, radians per second, positive left. */
  yaw_rate: number;
  /** Index of the ego lane (0: leftmost). */
  ego_lane: number;
  /** 1 on a frame whose ego lane differs from the previous frame's. */
  lane_change: number;
  /** 1 on a frame of a total blackout. */
  blackout: number;
  'lee.psi': number; 'lee.y0': number; 'lee.w': number; 'lee.w1': number;
  'lee.c': number; 'lee.delta': number;
  'danescu.w0': number; 'danescu.ch': number; 'danescu.wl': number; 'danescu.cv': number;
  'danescu.y0': number; 'danescu.xcw': number; 'danescu.alpha': number;
  'danescu.gamma': number; 'danescu.psi': number; 'danescu.wl_mark': number;
  'danescu.wr_mark': number;
  'adachi.q': number; 'adachi.w': number; 'adachi.r': number;
  /** And 'liu.<role>.rho', 'liu.<role>.theta', 'liu.<role>.d' per boundary. */
  [name: string]: number;
}

/** The exact ground truth of a scene frame. */
export interface Truth extends LaneEstimate {
  /** The frame's file name as `lanepf synth` writes it: '000042.png' for frame 42. */
  frame: string;
  state: TruthState;
}

/** Values over bins of a road axis: bin k covers [start + k step, start + (k + 1) step). */
export interface HistogramLayer {
  kind: 'histogram';
  name: string;
  axis: string;
  start: number;
  step: number;
  /** One value per bin. */
  values: Float32Array;
}

/** Values on a road grid: row r at x0 + r cell metres ahead, column c at y0 - c cell (y left). */
export interface GridLayer {
  kind: 'grid';
  name: string;
  width: number;
  height: number;
  x0: number;
  y0: number;
  cell: number;
  /** values[r * width + c] */
  values: Float32Array;
}

/** Values on another plane: column c at x0 + (c + 0.5) dx, row r at y0 + (r + 0.5) dy. */
export interface PlaneLayer {
  kind: 'plane';
  name: string;
  width: number;
  height: number;
  x_axis: string;
  x0: number;
  dx: number;
  y_axis: string;
  y0: number;
  dy: number;
  /** values[r * width + c] */
  values: Float32Array;
}

/** A picture of one of a tracker's cues (`Tracker.layers()`). */
export type Layer = HistogramLayer | GridLayer | PlaneLayer;

/** One particle drawn as the boundaries it stands for (`Tracker.hypotheses(max)`). */
export interface Hypothesis {
  /** The particle's normalised weight (the cloud's weights sum to 1). */
  weight: number;
  /** adachi-mmpf: the model r (1..4); lee-cpf: the stage (1 or 2; 0 single-stage);
   * danescu-*: the MBSAS cluster (-1 for none); liu-ppf: 0. */
  group: number;
  boundaries: Boundary[];
}

/**
 * One resampling decision of a tracker's filter, as the filter made it
 * (`Tracker.resamplings()`): e.g. lee-cpf's stage 1 with `{ rule: 'ess-below', ess: 394.2,
 * particles: 500, threshold: 250, resampled: false }`.
 */
export interface ResampleDecision {
  /** `'ess-below'`: resampled when `ess < threshold` (Lee, Algorithm 1); `'always'`: every
   *  time; `'injection'`: every frame, keeping N - k particles for k fresh ones (liu-ppf,
   *  danescu-*); `'between-stages'`: between the partitions of partitioned sampling (liu-ppf);
   *  `'never'`. */
  rule: 'ess-below' | 'always' | 'injection' | 'between-stages' | 'never';
  /** The effective sample size of the weights the filter decided on (particles). */
  ess: number;
  /** The filter's particle count N. */
  particles: number;
  /** The ESS below which it resamples (particles); null unless `rule` is `'ess-below'`. */
  threshold: number | null;
  /** Whether it resampled. */
  resampled: boolean;
}

/** Options of `new Calibrator(options)`. Unknown fields are refused. */
export interface CalibratorOptions {
  /** Frame width, pixels (at least 32). */
  width: number;
  /** Frame height, pixels (at least 16). */
  height: number;
  /** A camera of the same size whose fx, fy, cx, cy and distortion are known (its pose is
   *  ignored); without it the focal length comes from `hfov_deg` and the principal point is
   *  the image centre. */
  intrinsics?: CameraConfig | null;
  /** Lane-width prior, metres (2.5 to 5; default 3.6): the height is only as right as this. */
  lane_width_m?: number;
  /** Horizontal field of view used without intrinsics, degrees (20 to 150; default 60). */
  hfov_deg?: number;
  /** Frames whose vanishing points must agree for a frame to count (1 to 120; default 5; 1
   *  for independent still images). */
  stable_frames?: number;
  /** Largest common bend of the ego boundaries on straight road, working pixels (0.1 to 10;
   *  default 1.5). */
  max_bend_px?: number;
  /** The yaw from the lane's tangent at the car (a fit with a curvature term) from the first
   *  frame, instead of the boundaries' straight crossing until `tangent_yaw_after` frames
   *  agree (default false): better on long gentle bends; on the one real clip with a
   *  reference yaw (Caltech) 0.1 degrees off it; off by default because on short clips the
   *  trackers, adachi-mmpf most, do worse with its cameras. */
  tangent_yaw?: boolean;
  /** The yaw switches from the crossing's to the tangent's once this many frames that agree
   *  on the pose have a tangent (0 to 2000; default 100; 0: never), and stays the tangent's
   *  until `reset()`. */
  tangent_yaw_after?: number;
}

/** What `Calibrator.feed` says about one frame. */
export interface CalibrationStatus {
  /** The frame measured the camera (straight road, stable vanishing point). */
  used: boolean;
  /** Both ego boundaries were found. */
  ego_found: boolean;
  /** The ego boundaries are straight. */
  straight: boolean;
  /** The vanishing points of the last `stable_frames` frames agree. */
  stable: boolean;
  /** Where the ego boundaries meet, undistorted pixels. */
  vanishing_point: [number, number] | null;
  /** Frames used so far (at most 2000, the newest). */
  frames_used: number;
  /** Frames fed so far. */
  frames_seen: number;
}

/** `Calibrator.estimate()`: the camera and how sure the calibrator is of it. */
export interface CalibrationEstimate {
  /** The estimated camera (roll 0); goes straight into `new Tracker(id, { camera })`. */
  camera: CameraConfig;
  /** 0 (nothing known) to 1 (pitch and yaw well within 0.5 degrees, height within 10 %). */
  confidence: number;
  /** Frames that measured the camera. */
  frames_used: number;
  /** Frames fed. */
  frames_seen: number;
  /** Spread of the per-frame pitch, degrees. */
  pitch_sd_deg: number;
  /** Spread of the per-frame yaw, degrees. */
  yaw_sd_deg: number;
  /** Spread of the per-frame height, metres. */
  height_sd_m: number;
  /** Vanishing point of the estimate, undistorted pixels. */
  vanishing_point: [number, number];
  /** Whether intrinsics were given (false: focal length from `hfov_deg`). */
  intrinsics_known: boolean;
  /** Whether the yaw is the lane's tangent at the car (`tangent_yaw`, or `tangent_yaw_after`
   *  frames agree) rather than the boundaries' straight crossing. */
  yaw_from_tangent: boolean;
}

/** A straight line through marking pixels: x = x_ref + slope (y - y_ref), undistorted pixels. */
export interface CalibrationLine {
  x_ref: number;
  y_ref: number;
  /** dx / dy. */
  slope: number;
  /** Marking pixels on the line. */
  support: number;
  /** Topmost row of those pixels. */
  y_top: number;
  /** Bottom row of those pixels. */
  y_bottom: number;
  /** Signed bend, pixels (0 unless the line is an ego boundary). */
  bend: number;
}

/** `Calibrator.observation()`: what the last frame showed. */
export interface CalibrationObservation {
  /** Lines, strongest first. */
  lines: CalibrationLine[];
  /** Indices in `lines` of the ego boundaries (left, right). */
  ego: [number, number] | null;
  /** Where the ego boundaries meet. */
  vanishing_point: [number, number] | null;
  straight: boolean;
  stable: boolean;
  used: boolean;
}

/** An RGBA frame: `ImageData.data`, `Scene.render(f)` or any width*height*4 bytes. */
export type Rgba = Uint8Array | Uint8ClampedArray;

/**
 * A frame with its size: an `ImageData`, or any object with RGBA bytes in `data`
 * (`width * height * 4` of them) and the size in pixels.
 */
export interface RgbaFrame {
  data: Rgba;
  width: number;
  height: number;
}

/**
 * What `step(frame, options)` and `beginFrame(frame, options)` take besides the frame, for this
 * frame only. Unknown keys and `null` are refused.
 */
export interface StepOptions {
  /** The right camera's frame, same size (`danescu-stereo` only; a one-camera tracker throws a
   *  `LanepfStateError`). */
  right?: RgbaFrame;
  /** The car's motion at this frame (the Danescu trackers drift by it; the others ignore it). */
  motion?: EgoMotion;
}
"#;

/// The older form of `Tracker.step` and `beginFrame`, as overloads merged into the class: only
/// in the main module's `.d.ts`, which declares the class.
#[cfg(feature = "wasm-track")]
#[wasm_bindgen(typescript_custom_section)]
const TRACKER_OVERLOADS: &'static str = r#"
/** The older form of `step` and `beginFrame`: the bytes and the size (declaration merging adds
 *  these overloads to the class, whose type parameter `scripts/build-pkg.sh` declares). */
export interface Tracker<Id extends TrackerId = TrackerId> {
  /** Processes one frame of RGBA bytes (`ImageData.data`) of `width` x `height` pixels. */
  step(rgba: Rgba, width: number, height: number): LaneEstimate;
  /** Starts a frame of RGBA bytes of `width` x `height` pixels in per-step mode. */
  beginFrame(rgba: Rgba, width: number, height: number): void;
}
"#;
