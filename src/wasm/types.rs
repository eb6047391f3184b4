//! TypeScript types of the plain objects that cross the binding (configurations, options and
//! results), added to the generated `lanepf.d.ts`. The bound functions name them with
//! `unchecked_param_type` / `unchecked_return_type`; the objects themselves are still checked
//! at run time (unknown fields, wrong types, `null` and NaN throw a `LanepfError`).
//!
//! Keep these in step with the Rust types they describe: `camera::CameraFile`,
//! `trackers::TrackerConfig` and each tracker's config (`trackers::*::config`), the vision
//! configs they nest (`vision::{DldConfig, CannyConfig, TopViewConfig, HGradientConfig,
//! DensityConfig, DisparityConfig}`), `lane::LaneEstimate`, `trackers::{Layer, EgoMotion}`,
//! `synth::TestRoadConfig`, the truth's `state` keys (`synth::truth`) and `calib::{CalibratorConfig,
//! CalibrationEstimate, FrameObservation, LineFit}` with `wasm::calibrator`'s status. The npm test
//! (`tests/npm/`) compiles a TypeScript program against them with `tsc --strict`.

use wasm_bindgen::prelude::*;

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

/** The ids `new Tracker(id, ...)` accepts (see `trackerIds()`). */
export type TrackerId =
  | 'adachi-mmpf' | 'danescu-mono' | 'danescu-stereo' | 'lee-cpf' | 'liu-ppf' | 'liu-ppf-nokernel';

/**
 * The scenario names `new Scene(name, ...)` accepts (see `scenarios()`); `random` only with
 * `drawn: true` (it picks a family from the seed).
 */
export type ScenarioName =
  | 'highway-straight' | 'highway-curve' | 's-curve' | 'lane-change' | 'occlusion' | 'shadows'
  | 'worn-markings' | 'night' | 'width-change' | 'pitch-bumps' | 'multi-lane' | 'urban'
  | 'random';

/** A camera in the `camera.json` format. Unknown fields are refused. */
export interface CameraConfig {
  /** Image width, pixels (1 to 16384). */
  width: number;
  /** Image height, pixels (1 to 16384; width * height at most 2^26). */
  height: number;
  /** Focal length along x, pixels (> 0). */
  fx: number;
  /** Focal length along y, pixels (> 0). */
  fy: number;
  /** Principal point x, pixels. */
  cx: number;
  /** Principal point y, pixels. */
  cy: number;
  /** Height of the optical centre above the road, metres (> 0, at most 100). */
  height_m: number;
  /** Pitch, degrees, positive looking down at the road (|pitch| <= 80). */
  pitch_deg: number;
  /** Yaw, degrees, positive looking left of the car's axis (default 0, |yaw| <= 80). */
  yaw_deg?: number;
  /** Roll, degrees, positive when the camera's right side dips (default 0, |roll| <= 80). */
  roll_deg?: number;
  /** Radial distortion k1 (default 0). */
  k1?: number;
  /** Radial distortion k2 (default 0). */
  k2?: number;
  /** Tangential distortion p1 (default 0). */
  p1?: number;
  /** Tangential distortion p2 (default 0). */
  p2?: number;
  /** Radial distortion k3 (default 0). */
  k3?: number;
  /** Stereo baseline, metres (> 0); needed by danescu-stereo. */
  baseline_m?: number | null;
}

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

/** Options of `new TestRoad(camera, options)` (all optional). */
export interface TestRoadOptions {
  /** Lane width, metres (default 3.6). */
  lane_width_m?: number;
  /** Marking width, metres (default 0.15). */
  marking_width_m?: number;
  /** Dash length of the right marking, metres (default 3). */
  dash_length_m?: number;
  /** Dash period (dash + gap), metres (default 12). */
  dash_period_m?: number;
  /** Speed, metres per second (default 20). */
  speed_mps?: number;
  /** Frames per second (default 30). */
  fps?: number;
  /** Sway amplitude, metres (default 0.4). */
  sway_amplitude_m?: number;
  /** Sway period, seconds (default 6). */
  sway_period_s?: number;
  /** Farthest road distance drawn and reported, metres (default 80). */
  max_distance_m?: number;
}

/** Lee's dark-light-dark detector. Both fields are required when the object is given. */
export interface DldConfig {
  /** Averaging window N, pixels. */
  window: number;
  /** Threshold gamma, grey levels. */
  gamma: number;
}

/** A Canny edge detector. All fields are required when the object is given. */
export interface CannyConfig {
  /** Gaussian smoothing, pixels. */
  sigma: number;
  /** Lower hysteresis threshold on the gradient magnitude. */
  low: number;
  /** Upper hysteresis threshold on the gradient magnitude. */
  high: number;
}

/** The top view (inverse perspective mapping). All fields are required when given. */
export interface TopViewConfig {
  /** Nearest road distance shown, metres (> 0). */
  x_min_m: number;
  /** Farthest road distance shown, metres. */
  x_max_m: number;
  /** Lateral extent to the left (positive y), metres. */
  y_left_m: number;
  /** Lateral extent to the right (negative for the right side), metres. */
  y_right_m: number;
  /** Metres per top-view pixel. */
  m_per_px: number;
}

/** Danescu's variable-width horizontal gradient (missing fields take the defaults shown). */
export interface HGradientConfig {
  /** Width on the road the kernel half-width follows, metres (default 0.15). */
  marking_width_m?: number;
  /** Largest half-width, pixels (default 12). */
  max_half_width?: number;
  /** Gain from grey levels to HG units (default 2; the Danescu trackers' own default is 1). */
  gain?: number;
}

/** Danescu's discrete 3-D space (missing fields take the defaults shown). */
export interface DensityConfig {
  /** Cells in height (default 200). */
  rows?: number;
  /** Cells in distance (default 300). */
  cols?: number;
  /** Cell height, metres (default 0.01). */
  dy_m?: number;
  /** Cell length, metres (default 0.1). */
  dz_m?: number;
  /** Smallest density kept after the column non-maximum suppression (default 30). */
  threshold?: number;
}

/** Curbs from the elevation map (stereo; missing fields take the defaults shown). */
export interface CurbConfig {
  /** Detect curbs and add them to DT^S (default true). */
  enabled?: boolean;
  /** Elevation-map cell: ahead, lateral, metres (default [0.25, 0.1]). */
  cell_m?: [number, number];
  /** Farthest distance mapped, metres (default 15, the paper's D_3D). */
  range_m?: number;
  /** Lateral half-width mapped, metres (default 8). */
  half_width_m?: number;
  /** Fewest points that give a cell a class (default 5). */
  min_points?: number;
  /** A cell is raised between these heights, metres; above, an obstacle (default [0.06, 0.35]). */
  height_m?: [number, number];
  /** Most unknown cells between a road cell and the curb after it (default 2). */
  max_gap?: number;
  /** A foot snaps to the nearest image road edge within this many metres (default 0.2). */
  snap_m?: number;
}

/** The census stereo matcher. All fields are required when the object is given. */
export interface DisparityConfig {
  /** Largest disparity searched (replaced by the tracker with the camera's own). */
  max_disparity: number;
  /** Census window radius (at most 7). */
  census_radius: number;
  /** Cost aggregation box radius (at most 7). */
  window_radius: number;
  /** Uniqueness ratio in (0, 1]. */
  uniqueness: number;
  /** Largest left-right disagreement, pixels. */
  left_right_tolerance: number;
}

/** What every tracker is built from. */
export interface TrackerBaseConfig {
  /** The camera (the frames given to `step` must have its size). */
  camera: CameraConfig;
  /** Particles N (1 to 200000); default per tracker: 500, liu-ppf 200 (+ init_particles). */
  particles?: number;
  /** RNG seed (default 1): the same seed gives the same run natively and in the browser. */
  seed?: number;
}

/** Options of `adachi-mmpf` (all optional; defaults shown). */
export interface AdachiOptions {
  /** Nearest road distance of the voting region, metres (6). */
  near_m?: number;
  /** Farthest road distance of the voting region, metres (22). */
  far_m?: number;
  /** Half-range of the rho axis, metres (8). */
  rho_range_m?: number;
  /** Histogram bin size, metres (0.05). */
  bin_m?: number;
  /** Which edge of a marking votes ('left-edge'). */
  polarity?: 'left-edge' | 'right-edge' | 'both';
  /** Horizontal Sobel response an edge point needs (80). */
  edge_threshold?: number;
  /** Marking width of the template, metres (0.15). */
  marking_width_m?: number;
  /** Spread of edge positions around the template's edge, metres (0.1). */
  edge_sigma_m?: number;
  /** Filter iterations on the first frame and after a reset (20, at most 1000). */
  start_iterations?: number;
  /** Weight of the noise histogram (1). */
  beta?: number;
  /** Random walk of the lane position per frame, metres (0.08). */
  sigma_q_m?: number;
  /** Random walk of the lane width per frame, metres (0.04). */
  sigma_w_m?: number;
  /** Accepted lane widths [min, max], metres ([2.5, 4.8]). */
  width_range_m?: [number, number];
  /** Model transition matrix, 4 rows of 4 (the paper's Table 1). */
  transitions?: number[][];
  /** A frame is valid when each ego boundary's edge voted in at least this share of the
   *  voting region's rows (0.08; 0 to 1). */
  valid_support?: number;
  /** 'straight': the paper's lanes parallel to the car; 'curved' (not in the paper): the edge
   *  points are straightened by the road's bend and heading before they vote, and the
   *  boundaries are drawn bent ('straight'). */
  lane_shape?: 'straight' | 'curved';
  /** 'curved' only: largest heading of the lane to the car searched, radians (0.1; 0 to 0.5). */
  max_heading_rad?: number;
  /** 'curved' only: largest curvature searched, 1/m (0.012; 0 to 0.05). */
  max_curvature_per_m?: number;
  /** 'curved' only: how far the followed road shape moves to each frame's best (0.5; 0.01 to 1). */
  shape_gain?: number;
  /** Share of the particles replaced each frame by draws around the ego pair a bottom-up
   *  line detector finds (not in the paper; 0, off; 0 to 0.5). */
  /** Share of the stage-1 particles replaced each frame by draws around the ego pair a
   *  bottom-up line detector finds (not in the paper; 0, off; 0 to 0.5). */
  relock_share?: number;
}

/** Options of `lee-cpf` (all optional; defaults shown). */
export interface LeeOptions {
  /** The cascade or one of the paper's single-stage baselines ('cascade'). */
  variant?: 'cascade' | 'first-order' | 'full-model';
  /** Particles of stage 2; 0: as stage 1 (0). */
  stage2_particles?: number;
  /** Nearest road distance measured, metres (5). */
  near_m?: number;
  /** End of the near range and start of the far range, metres (20). */
  split_m?: number;
  /** End of the far range, metres (50, at most 500). */
  far_m?: number;
  /** Spacing of the near evaluation points, metres (1). */
  near_step_m?: number;
  /** Spacing of the far evaluation points, metres (2). */
  far_step_m?: number;
  /** Lateral half-range of the likelihood map, metres (8). */
  lateral_range_m?: number;
  /** Cell size of the likelihood map, metres (0.1). */
  cell_m?: number;
  /** The DLD detector ({ window: 3, gamma: 20 }). */
  dld?: DldConfig;
  /** Largest marking candidate width, metres (0.45). */
  max_marking_width_m?: number;
  /** sigma_D of the likelihood map, metres (0.2). */
  map_sigma_m?: number;
  /** Canny of the far range ({ sigma: 1, low: 40, high: 100 }). */
  canny?: CannyConfig;
  /** Marking width when matching far points to edges, metres (0.15). */
  marking_width_m?: number;
  /** Weight alpha of the boundary points (1). */
  alpha?: number;
  /** Weight beta of the points inside the lane (-0.5). */
  beta?: number;
  /** Distance tau of the inside points from the boundaries, metres (0.6). */
  tau_m?: number;
  /** sigma of the Gaussian on q (0.25). */
  sigma_q?: number;
  /** sigma of the stage-2 Gaussian (0.25). */
  sigma_far?: number;
  /** Spiral length of the clothoid, metres (60). */
  spiral_length_m?: number;
  /** Process noise per frame: psi, y0, w, w', c, delta ([0.004, 0.06, 0.01, 0.0005, 1.5, 0.0002]). */
  process_sd?: [number, number, number, number, number, number];
  /** Resample a stage when N_eff falls below this fraction of N (0.5). */
  ess_threshold?: number;
  /** Largest |psi|, radians (0.1, below 1.2). */
  max_heading_rad?: number;
  /** Accepted lane widths [min, max], metres ([2.5, 4.5]). */
  width_range_m?: [number, number];
  /** Largest |w'| (0.02). */
  max_width_rate?: number;
  /** Largest c, metres (60). */
  max_transition_m?: number;
  /** Largest |delta|, 1/m (0.02). */
  max_curvature?: number;
  /** Filter iterations on the first frame and after a reset (20, at most 1000). */
  start_iterations?: number;
  /** Process noise of the first start iteration, times Q, narrowing to Q (10, 1 to 100). */
  start_spread?: number;
  /** Share of particles drawn anew in the first half of the start iterations (0.2, 0 to 1). */
  start_fresh?: number;
  /** Restart after this many frames with no marking near either boundary (2; 0: never). */
  lost_restart?: number;
  relock_share?: number;
  /** Report the lanes beside the ego lane (left-adjacent, right-adjacent) where markings run
   *  beside an ego boundary at a lane's width (not in the paper; false, off). */
  adjacent_lanes?: boolean;
  /** Kalman smoothing of the output (true). */
  kalman?: boolean;
  /** Kalman process noise, same order as process_sd ([0.003, 0.03, 0.01, 0.0005, 2, 0.0002]). */
  kalman_process_sd?: [number, number, number, number, number, number];
  /** Kalman measurement noise, same order ([0.006, 0.05, 0.05, 0.002, 6, 0.0005]). */
  kalman_measurement_sd?: [number, number, number, number, number, number];
  /** Share of near points with marking support that makes a frame valid (0.15). */
  valid_fraction?: number;
}

/** Options of `liu-ppf` and `liu-ppf-nokernel` (all optional; defaults shown). */
export interface LiuOptions {
  /** The top view ({ x_min_m: 6, x_max_m: 36, y_left_m: 6, y_right_m: -6, m_per_px: 0.1 }). */
  top_view?: TopViewConfig;
  /** Boundaries tracked, 1 to 6 (3). */
  boundaries?: number;
  /** Split row y_m as a fraction of the top-view height, 0.1 to 0.9 (0.5). */
  split?: number;
  /** Gradient threshold of the measurement mask (10). */
  gradient_threshold?: number;
  /** Variance of the position kernels, pixels^2 (1). */
  position_variance_px2?: number;
  /** Mean of the intensity kernel (1). */
  intensity_mean?: number;
  /** Variance of the intensity kernel (0.5). */
  intensity_variance?: number;
  /** Gauss-Hermite nodes of the parabolic kernel, 1 to 20 (3). */
  quadrature_nodes?: number;
  /** Half-width of the band near a boundary, pixels, 1 to 50 (3). */
  band_px?: number;
  /** Initialisation particles added every frame, at most 100000 (50). */
  init_particles?: number;
  /** Random walk of rho, pixels (1). */
  sigma_rho_px?: number;
  /** Random walk of theta, radians (0.004). */
  sigma_theta?: number;
  /** Random walk of d (0.01). */
  sigma_d?: number;
  /** Smallest spacing of neighbouring boundaries, metres (2.4). */
  min_spacing_m?: number;
  /** Largest difference of neighbouring spacings, metres (0.5). */
  max_spacing_difference_m?: number;
  /** Share of near rows with edge support that makes a frame valid (0.15). */
  valid_fraction?: number;
  /** Default lane model: lane widths [min, max], metres ([3, 4]). */
  default_width_m?: [number, number];
  /** Default lane model: largest heading, radians (0.05). */
  default_heading_rad?: number;
  /** Default lane model: spread of each boundary, metres (0.1). */
  default_jitter_m?: number;
  /** Share of the particles replaced each frame by default-model lanes on the ego pair a
   *  bottom-up line detector finds (not in the paper; 0, off; 0 to 0.5). */
  relock_share?: number;
}

/** Options of `danescu-mono` and `danescu-stereo` (all optional; defaults shown). */
export interface DanescuOptions {
  /** Share of particles drawn from the initialisation distribution each frame, [0, 1) (0.1). */
  init_fraction?: number;
  /** Nearest distance of the image mapping, metres (5). */
  near_m?: number;
  /** Farthest distance of the image mapping, metres (35). */
  far_m?: number;
  /** Points per edge, 2 to 200 (20). */
  points?: number;
  /** Range of the 3-D mapping D_3D, metres (15). */
  range_3d_m?: number;
  /** Diffusion per frame of w0, ch, wl, cv, y0, xcw, alpha, gamma, psi, wl_mark, wr_mark. */
  diffusion?: [number, number, number, number, number, number, number, number, number, number, number];
  /** Initial lane widths (inner edges), metres ([2.6, 4.2]). */
  init_width_m?: [number, number];
  /** Initial |X_CW| up to, metres (1.2). */
  init_offset_m?: number;
  /** Initial |psi| up to, radians (0.06). */
  init_yaw_rad?: number;
  /** Initial |C_H| up to, 1/m (0.003). */
  init_curvature?: number;
  /** Initial |W_l| up to (0.01). */
  init_width_rate?: number;
  /** Initial marking widths, metres ([0, 0.3]). */
  init_marking_m?: [number, number];
  /** Initial |pitch change| up to, radians (0.01; stereo). */
  init_pitch_rad?: number;
  /** Initial |Y_0| up to, metres (0.05; stereo). */
  init_height_m?: number;
  /** Validation: accepted lane widths, metres ([2.2, 5]). */
  width_range_m?: [number, number];
  /** Validation: how far outside the lane the car may be, metres (0.5). */
  offset_margin_m?: number;
  /** Validation: largest marking width, metres (0.5). */
  max_marking_m?: number;
  /** sigma of the road-edge likelihood, pixels (3). */
  sigma_edge_px?: number;
  /** sigma of the marking likelihood, pixels (3). */
  sigma_marking_px?: number;
  /** sigma_G of the gradient likelihood (30). */
  sigma_gradient?: number;
  /** sigma_D of the density likelihood, cells (1). */
  sigma_density?: number;
  /** Negative points lie this far inside the lane, metres (0.3). */
  negative_offset_m?: number;
  /** Reach of a negative point, pixels (3). */
  negative_reach_px?: number;
  /** The marking-width model and gradient cue; false: the authors' previous approach (true). */
  marking_widths?: boolean;
  /** The variable-width gradient ({ marking_width_m: 0.15, max_half_width: 12, gain: 1 }). */
  hgradient?: HGradientConfig;
  /** Smallest |gradient| of a marking edge (40). */
  marking_contrast?: number;
  /** Accepted marking widths on the road, metres ([0.05, 0.5]). */
  marking_width_range_m?: [number, number];
  /** Road edges ({ sigma: 1, low: 40, high: 100 }). */
  canny?: CannyConfig;
  /** The discrete 3-D space (stereo). */
  density?: DensityConfig;
  /** Curbs from the elevation map (stereo). */
  curbs?: CurbConfig;
  /** The stereo matcher (stereo; { max_disparity: 64, census_radius: 2, window_radius: 3,
   * uniqueness: 0.9, left_right_tolerance: 1 }). */
  disparity?: DisparityConfig;
  /** Preliminary pitch histogram bin, radians (0.0005). */
  pitch_bin_rad?: number;
  /** Preliminary pitch search range, +- radians (0.05). */
  pitch_range_rad?: number;
  /** Road points lie within this height of the road line, metres (0.1). */
  road_tolerance_m?: number;
  /** The 3-D data (density cue, curbs) counts only in a frame whose road points are at least
   *  this share of the road region's pixels (0.02; 0: every frame). Ours, not the paper's. */
  min_road_share?: number;
  /** MBSAS distance threshold on X_CW, metres (0.4). */
  cluster_threshold_m?: number;
  /** MBSAS: at most this many clusters (5). */
  max_clusters?: number;
  /** Validity: edge distance, pixels (2). */
  valid_distance_px?: number;
  /** Validity: share of points with edge support (0.15). */
  valid_support?: number;
  /** Validity: share of particles in the estimate's cluster (0.3). */
  valid_cluster_share?: number;
  /** Share of the particles replaced each frame by draws around the ego pair a bottom-up
   *  line detector finds (not in the paper; 0, off; 0 to 0.5). */
  relock_share?: number;
  /** Report the lanes beside the ego lane (left-adjacent, right-adjacent) where markings run
   *  beside an ego boundary at a lane's width (not in the paper; false, off). */
  adjacent_lanes?: boolean;
}

/**
 * `new Tracker(id, config)`: the camera, particles and seed, plus the options of the chosen
 * tracker. The type allows every tracker's options; at run time a tracker refuses an option
 * that is not its own with a `LanepfConfigError` naming it.
 */
export interface TrackerConfig
  extends TrackerBaseConfig, AdachiOptions, LeeOptions, LiuOptions, DanescuOptions {}

/** The car's motion at a frame (`setEgoMotion`); all three fields are required. */
export interface EgoMotion {
  /** Frame timestamp, seconds. */
  t_s: number;
  /** Speed, metres per second (|speed| <= 150). */
  speed_mps: number;
  /** Yaw rate, radians per second, positive turning left (|yaw rate| <= 5). */
  yaw_rate: number;
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
  values: number[];
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
  values: number[];
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
  values: number[];
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

/** The older form of `step` and `beginFrame`: the bytes and the size (declaration merging adds
 *  these overloads to the class). */
export interface Tracker {
  /** Processes one frame of RGBA bytes (`ImageData.data`) of `width` x `height` pixels. */
  step(rgba: Rgba, width: number, height: number): LaneEstimate;
  /** Starts a frame of RGBA bytes of `width` x `height` pixels in per-step mode. */
  beginFrame(rgba: Rgba, width: number, height: number): void;
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
