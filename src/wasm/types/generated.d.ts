// Generated from the Rust types by src/wasm/types/typegen (`LANEPF_BLESS=1 cargo test --lib typegen`,
// or `make types`): do not edit. Each option's docs are its Rust docs; the defaults and ranges
// are the running code's.

/**
 * The ids `new Tracker(id, ...)` accepts (see `trackerIds()`).
 */
export type TrackerId =
  | 'adachi-mmpf' | 'danescu-mono' | 'danescu-stereo' | 'lee-cpf' | 'liu-ppf' | 'liu-ppf-nokernel';

/**
 * The named option sets `trackerPreset(id, preset)` accepts: `paper` (each paper's filter, the defaults) and `real-roads` (our options beyond the papers for real footage).
 */
export type TrackerPreset =
  | 'paper' | 'real-roads';

/**
 * What every tracker is built from: the camera, the particle budget, the seed, and the
 * tracker's own options (checked by the tracker itself). In JSON the options are keys beside
 * these; in Rust they may instead be typed, naming the tracker (`TrackerConfig::new`).
 */
export interface TrackerBaseConfig {
  /**
   * The camera (the `camera.json` format); the frames given to `step` must have its size.
   */
  camera: CameraConfig;
  /**
   * Number of particles N (1 to 200000); left out: the tracker's own default.
   */
  particles?: number;
  /**
   * Seed of the random generator: the same seed gives the same run natively and in the
   * browser.
   *
   * @defaultValue `1`
   */
  seed?: number;
}

/**
 * A camera as written in a `camera.json` file: plain numbers, checked when a camera, scene
 * or tracker is built from them (`from_file`). Unknown fields are refused.
 *
 * A field marked optional takes its default when left out.
 */
export interface CameraConfig {
  /**
   * Image width, pixels (1 to 16384; width x height at most 2^26).
   */
  width: number;
  /**
   * Image height, pixels (1 to 16384).
   */
  height: number;
  /**
   * Focal length along x, pixels (> 0).
   */
  fx: number;
  /**
   * Focal length along y, pixels (> 0).
   */
  fy: number;
  /**
   * Principal point x, pixels.
   */
  cx: number;
  /**
   * Principal point y, pixels.
   */
  cy: number;
  /**
   * Height of the optical centre above the road, metres (> 0, at most 100).
   */
  height_m: number;
  /**
   * Pitch, degrees, positive when the camera looks down at the road (|pitch| <= 80).
   */
  pitch_deg: number;
  /**
   * Yaw, degrees, positive when the camera looks left of the car's forward axis (|yaw| <=
   * 80; 0 when left out).
   */
  yaw_deg?: number;
  /**
   * Roll, degrees, positive when the camera's right side dips (ISO 8855; |roll| <= 80; 0
   * when left out).
   */
  roll_deg?: number;
  /**
   * Radial distortion k1 (0 when left out).
   */
  k1?: number;
  /**
   * Radial distortion k2 (0 when left out).
   */
  k2?: number;
  /**
   * Tangential distortion p1 (0 when left out).
   */
  p1?: number;
  /**
   * Tangential distortion p2 (0 when left out).
   */
  p2?: number;
  /**
   * Radial distortion k3 (0 when left out).
   */
  k3?: number;
  /**
   * Stereo baseline (distance from the left to the right camera), metres (> 0); needed by
   * danescu-stereo.
   */
  baseline_m?: number;
}

/**
 * The car's motion at a frame: its timestamp, speed and yaw rate (the frame interval is the
 * difference of consecutive timestamps). All three fields are required.
 *
 * Every field is required when the object is given.
 */
export interface EgoMotion {
  /**
   * Frame timestamp, seconds.
   */
  t_s: number;
  /**
   * Speed, metres per second (|speed| <= 150).
   */
  speed_mps: number;
  /**
   * Yaw rate, radians per second, positive turning left (|yaw rate| <= 5).
   */
  yaw_rate: number;
}

/**
 * Options of the straight test road (all optional; a field left out takes its default).
 *
 * A field left out takes its default.
 */
export interface TestRoadOptions {
  /**
   * Lane width W, metres.
   *
   * @defaultValue `3.6`
   */
  lane_width_m?: number;
  /**
   * Marking width m, metres.
   *
   * @defaultValue `0.15`
   */
  marking_width_m?: number;
  /**
   * Dash length L of the right marking, metres.
   *
   * @defaultValue `3`
   */
  dash_length_m?: number;
  /**
   * Dash period P (dash + gap), metres.
   *
   * @defaultValue `12`
   */
  dash_period_m?: number;
  /**
   * Speed v, metres per second.
   *
   * @defaultValue `20`
   */
  speed_mps?: number;
  /**
   * Frames per second.
   *
   * @defaultValue `30`
   */
  fps?: number;
  /**
   * Sway amplitude A, metres.
   *
   * @defaultValue `0.4`
   */
  sway_amplitude_m?: number;
  /**
   * Sway period T, seconds.
   *
   * @defaultValue `6`
   */
  sway_period_s?: number;
  /**
   * Farthest road distance drawn and reported, metres.
   *
   * @defaultValue `80`
   */
  max_distance_m?: number;
}

/**
 * Lee's dark-light-dark (DLD) marking detector (eqs. 21-24): averaging window and threshold.
 *
 * Every field is required when the object is given.
 */
export interface DldConfig {
  /**
   * Averaging window N, pixels.
   */
  window: number;
  /**
   * Threshold gamma on I_d, grey levels.
   */
  gamma: number;
}

/**
 * A Canny edge detector: smoothing and the two hysteresis thresholds.
 *
 * Every field is required when the object is given.
 */
export interface CannyConfig {
  /**
   * Gaussian smoothing, pixels.
   */
  sigma: number;
  /**
   * Lower hysteresis threshold on |grad I|.
   */
  low: number;
  /**
   * Upper hysteresis threshold on |grad I|.
   */
  high: number;
}

/**
 * The area and resolution of the top view.
 *
 * Every field is required when the object is given.
 */
export interface TopViewConfig {
  /**
   * Nearest road distance shown, metres (> 0).
   */
  x_min_m: number;
  /**
   * Farthest road distance shown, metres.
   */
  x_max_m: number;
  /**
   * Lateral extent to the left (positive y), metres.
   */
  y_left_m: number;
  /**
   * Lateral extent to the right (negative y for the right side), metres.
   */
  y_right_m: number;
  /**
   * Resolution, metres per top-view pixel.
   */
  m_per_px: number;
}

/**
 * Danescu's variable-width horizontal gradient: the kernel follows a marking's width.
 *
 * A field left out takes its default.
 */
export interface HGradientConfig {
  /**
   * Width on the road the kernel half-width follows, metres.
   *
   * @defaultValue `0.15`
   */
  marking_width_m?: number;
  /**
   * Largest half-width k, pixels.
   *
   * @defaultValue `12`
   */
  max_half_width?: number;
  /**
   * Gain from grey levels to HG units (a step of 128 / gain grey levels saturates).
   *
   * @defaultValue `2`
   */
  gain?: number;
}

/**
 * Danescu's discrete lateral space (the 3-D density image) and its density threshold.
 *
 * A field left out takes its default.
 */
export interface DensityConfig {
  /**
   * Cells in height (h).
   *
   * @defaultValue `200`
   */
  rows?: number;
  /**
   * Cells in distance (w).
   *
   * @defaultValue `300`
   */
  cols?: number;
  /**
   * Cell height dY, metres.
   *
   * @defaultValue `0.01`
   */
  dy_m?: number;
  /**
   * Cell length dZ, metres.
   *
   * @defaultValue `0.1`
   */
  dz_m?: number;
  /**
   * Smallest density kept after the column non-maximum suppression.
   *
   * @defaultValue `30`
   */
  threshold?: number;
}

/**
 * Options of the curb detection (stereo only).
 *
 * A field left out takes its default.
 */
export interface CurbConfig {
  /**
   * Detect curbs and add them to DT^S (`false`: markings only).
   *
   * @defaultValue `true`
   */
  enabled?: boolean;
  /**
   * Cell size of the elevation map: ahead, lateral, metres.
   *
   * @defaultValue `[0.25, 0.1]`
   */
  cell_m?: [number, number];
  /**
   * Farthest distance mapped, metres (the paper's D_3D by default: the road is taken as
   * the plane z = m x, which a vertical curve bends away from further out).
   *
   * @defaultValue `15`
   */
  range_m?: number;
  /**
   * Lateral half-width mapped, metres.
   *
   * @defaultValue `8`
   */
  half_width_m?: number;
  /**
   * Fewest votes for a cell's class (fewer: unknown).
   *
   * @defaultValue `5`
   */
  min_points?: number;
  /**
   * A cell is raised (a curb) between these elevations, metres; above, an obstacle.
   *
   * @defaultValue `[0.06, 0.35]`
   */
  height_m?: [number, number];
  /**
   * Most unknown cells between a road cell and the curb after it.
   *
   * @defaultValue `2`
   */
  max_gap?: number;
  /**
   * In the image, a foot moves to the nearest road edge within this many metres.
   *
   * @defaultValue `0.2`
   */
  snap_m?: number;
}

/**
 * The census stereo matcher.
 *
 * Every field is required when the object is given.
 */
export interface DisparityConfig {
  /**
   * Largest disparity searched D, pixels (disparities 0..=D are tried); 1..=256 and below
   * the image width.
   */
  max_disparity: number;
  /**
   * Census window radius c: a (2c+1)^2 window, (2c+1)^2 - 1 bits; at most 7.
   */
  census_radius: number;
  /**
   * Cost aggregation box radius r: a (2r+1)^2 box; at most 7.
   */
  window_radius: number;
  /**
   * Uniqueness ratio k in (0, 1]: the best cost must be below k times the best cost at a
   * non-neighbouring disparity.
   */
  uniqueness: number;
  /**
   * Largest accepted difference between the left and right winners, pixels.
   */
  left_right_tolerance: number;
}

/**
 * Settings of `adachi-mmpf`.
 *
 * The options of `adachi-mmpf` in `new Tracker(id, { camera, ...options })`:
 * all optional (a key left out takes its default); an option of another tracker is
 * a type error, and refused at run time.
 */
export interface AdachiOptions {
  /**
   * Nearest road distance of the voting region (the box of Fig. 3a), metres.
   *
   * Range: 0.5 to 100.
   * @defaultValue `6`
   */
  near_m?: number;
  /**
   * Farthest road distance of the voting region, metres.
   *
   * Range: 1 to 200.
   * @defaultValue `22`
   */
  far_m?: number;
  /**
   * Half-range of the rho axis, metres (bins cover [-rho_range, rho_range)).
   *
   * Range: 1 to 50.
   * @defaultValue `8`
   */
  rho_range_m?: number;
  /**
   * Histogram bin size, metres.
   *
   * Range: 0.005 to 1.
   * @defaultValue `0.05`
   */
  bin_m?: number;
  /**
   * Edge polarity.
   *
   * - `'left-edge'`: Dark to light going right: the left edge of a bright marking (the paper's choice).
   * - `'right-edge'`: Light to dark going right: the right edge.
   * - `'both'`: Both edges.
   *
   * @defaultValue `'left-edge'`
   */
  polarity?: 'left-edge' | 'right-edge' | 'both';
  /**
   * Sobel response an edge point needs (grey levels x 4): g_x, or the gradient magnitude
   * with `edge_response: "gradient"`.
   *
   * Range: 0 to 2000.
   * @defaultValue `80`
   */
  edge_threshold?: number;
  /**
   * `horizontal` (g_x of the polarity, the default) or `gradient` (ours: the gradient
   * magnitude, the polarity from the sign of g_x), see `EdgeResponse`.
   *
   * - `'horizontal'`: The horizontal Sobel response g_x of the polarity (our reading since the first increment). A boundary at lateral distance Y seen from a camera h metres high crosses the image at an angle whose tangent is h / |Y|, and g_x falls with it: the neighbours' outer lines (|Y| about 1.5 w, 5-6 m) give a fifth to a third of an ego line's g_x.
   * - `'gradient'`: Ours: the Sobel gradient magnitude sqrt(g_x^2 + g_y^2), with the polarity still from the sign of g_x (a left edge is dark to light going right). The same threshold then passes a line at any angle (see `votes`).
   *
   * @defaultValue `'horizontal'`
   */
  edge_response?: 'horizontal' | 'gradient';
  /**
   * Marking width assumed by the template H_bar, metres.
   *
   * Range: 0.02 to 1.
   * @defaultValue `0.15`
   */
  marking_width_m?: number;
  /**
   * Spread of edge positions around the template's edge, metres (added to the bin width in
   * quadrature).
   *
   * Range: 0.005 to 2.
   * @defaultValue `0.1`
   */
  edge_sigma_m?: number;
  /**
   * Filter iterations on the first frame (and after a reset) before the first estimate:
   * the paper does not say how the filter starts; a uniform start needs a few predict /
   * weigh / resample rounds on the same votes to find the lane.
   *
   * Range: 0 to 1000.
   * @defaultValue `20`
   */
  start_iterations?: number;
  /**
   * Weight beta of the noise histogram N_j (eq. 4).
   *
   * Range: 0.001 to 1000.
   * @defaultValue `1`
   */
  beta?: number;
  /**
   * Random-walk standard deviation sigma_q of the lane position per frame, metres (eq. 8).
   *
   * Range: 0.0001 to 5.
   * @defaultValue `0.08`
   */
  sigma_q_m?: number;
  /**
   * Random-walk standard deviation sigma_w of the lane width per frame, metres (eq. 7).
   *
   * Range: 0.0001 to 2.
   * @defaultValue `0.04`
   */
  sigma_w_m?: number;
  /**
   * Lane widths accepted, metres ([min, max]); particles outside are clamped.
   *
   * Range: 0.5 to 10 (each entry).
   * @defaultValue `[2.5, 4.8]`
   */
  width_range_m?: [number, number];
  /**
   * Model transition matrix pi (rows: from model 1..4), Table 1 by default.
   *
   * Range: 0 to 1 (each entry).
   * @defaultValue `[[0.75, 0.125, 0.125, 0], [0.08333333333333333, 0.75, 0.08333333333333333, 0.08333333333333333], [0.08333333333333333, 0.08333333333333333, 0.75, 0.08333333333333333], [0, 0.125, 0.125, 0.75]]`
   */
  transitions?: number[][];
  /**
   * A frame is valid when each ego boundary of the estimate has at least this vote support:
   * the share of the voting region's rows in which its edge voted (see
   * `support`). Not in the paper, which does not define a
   * valid frame.
   *
   * Range: 0 to 1.
   * @defaultValue `0.08`
   */
  valid_support?: number;
  /**
   * Validity: a side under `valid_support` this frame still counts when its mean support
   * over the last this many frames (this one included; fewer since a reset) reaches
   * `valid_support` and the other side this frame holds at least twice it
   * (`support_memory`; ours; 1: this frame's alone, the default).
   *
   * Range: 1 to 100.
   * @defaultValue `1`
   */
  valid_support_frames?: number;
  /**
   * `straight` (the paper) or `curved` (ours: see `road_shape`).
   *
   * - `'straight'`: Straight lines parallel to the car: the paper's model (Sec. 3.2).
   * - `'curved'`: Not in the paper: the edge points are straightened by the road's bend and heading before they vote (`road_shape`), and the boundaries are drawn bent.
   *
   * @defaultValue `'straight'`
   */
  lane_shape?: 'straight' | 'curved';
  /**
   * `curved` only: the largest heading of the lane to the car searched, radians (0 to 0.5).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0.1`
   */
  max_heading_rad?: number;
  /**
   * `curved` only: the largest curvature searched, 1/m (0 to 0.05, a 20 m radius).
   *
   * Range: 0 to 0.05.
   * @defaultValue `0.012`
   */
  max_curvature_per_m?: number;
  /**
   * `curved` only: how far the followed shape moves to each frame's best (0.01 to 1).
   *
   * Range: 0.01 to 1.
   * @defaultValue `0.5`
   */
  shape_gain?: number;
  /**
   * Share of the particles replaced, each frame the auto-calibration's line detector finds
   * an ego pair, by draws around that pair on the road (its centre where the votes measure
   * q, its width, with sigma_q and sigma_w; the model r kept): a data-driven proposal that
   * lets a cloud stuck on a wrong lane re-lock (ours, beyond the paper; 0: off, the
   * paper's filter; see `relock`).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  relock_share?: number;
  /**
   * Share of the initial particles (first frame, and after a reset) drawn around the ego
   * pairs the first frame's vote histogram forms (`pairs`), the rest uniform; their
   * model r uniform. The paper leaves the start open; 0 gives the uniform start we had until
   * 2026-11-26, which locks in on false modes (see `pairs`).
   *
   * Range: 0 to 1.
   * @defaultValue `0.5`
   */
  start_pair_share?: number;
  /**
   * Share of the particles redrawn each frame around the ego pairs of the frame's vote
   * histogram (`pairs`), model r uniform: a data-driven proposal from the paper's
   * own cue that lets a locked or lost cloud find the lane again (ours, beyond the paper;
   * 0: off, the paper's filter). It also finds a false lane where that is the likelihood's
   * maximum (a guard rail's foot beside a line: RESULTS, *Accuracy on real data*).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  vote_pair_share?: number;
  /**
   * Share of the particles replaced, each frame after one whose estimate had one ego
   * boundary with vote support (at least `valid_support`) and the other none (under 0.05),
   * by lanes that keep the supported boundary where it is and take the width w anew,
   * uniform over `width_range_m`, their model r kept (ours, beyond the paper; 0: off, the
   * paper's filter; see `side_search`).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  side_search_share?: number;
  /**
   * Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
   * is not held back): the lane counts again only when an edge voted for one of its
   * boundaries within this many metres beyond the voting region's nearest row, or within
   * the longest such reach of the last 30 valid frames that saw both boundaries
   * (`reacquire`; ours, beyond the paper; 0: off, the default). Markings
   * that begin only further ahead, past an unmarked crossing, are not yet the car's lane.
   *
   * Range: 0 to 100.
   * @defaultValue `0`
   */
  reacquire_near_m?: number;
  /**
   * Only marking edges vote: an edge point votes when the opposite edge of a bright stripe
   * lies beside it, at most `PAIRED_EDGE_MAX_M` away on the road, on the marking's side
   * (ours, beyond the paper; false: every edge point votes, the paper's Sec. 3.2). A seam
   * between asphalt and concrete, a barrier's foot or a shadow's edge is one edge with no
   * partner and does not vote; a dark stripe (crack sealant) has its edges in the wrong order.
   *
   * @defaultValue `false`
   */
  paired_edges?: boolean;
  /**
   * `edge_threshold` holds up to `THRESHOLD_WIDTH_PX` pixels of image width; a wider image
   * scales it by 640 / width (ours, beyond the paper; false: grey levels per pixel at any
   * size). A lens and a codec blur an edge over a share of the image, so at twice the width
   * the same edge's gradient per pixel is about half: the markings of 1280x720 dash-cam
   * video fall under the threshold that suits 640x480.
   *
   * @defaultValue `false`
   */
  width_scaled_threshold?: boolean;
  /**
   * Report the lanes beside the ego lane that the estimate's model r leaves out, where the
   * bottom-up detector's markings run beside an ego boundary at a lane's width
   * (`adjacent_lanes`; ours, beyond the paper, whose neighbours come
   * from r alone; off by default).
   *
   * @defaultValue `false`
   */
  adjacent_lanes?: boolean;
  /**
   * Move each reported boundary onto the centre of the paint it lies on: a straight
   * sideways correction fitted to the marking centres the bottom-up detector's marking
   * image shows within 0.3 m of it, or 0.6 m where no run of paint lies within 0.3 m
   * (`paint_snap`; ours, beyond the
   * paper; output only: the filter and the validity are unchanged; off by default).
   *
   * @defaultValue `false`
   */
  snap_to_paint?: boolean;
  /**
   * With `snap_to_paint`: the snap follows the paint round a bend: each probe's search is
   * centred on the line through the last run of paint centres, and the correction gets a
   * quadratic term (`paint_snap`; ours; off by default).
   *
   * @defaultValue `false`
   */
  snap_follows_bends?: boolean;
  /**
   * Report a valid frame not valid when no run of paint begins along either drawn ego
   * boundary within 12 m of its nearest probe (4 m ahead, or where the boundary comes
   * into view; 12 m: a dashed line's longest common gap, so the paint beyond a crossing
   * does not keep its near side valid): a run of at least four paint centres 0.5 m apart
   * (1.5 m) and in four rows of the image, each within 10 cm of the last, found within
   * 0.3 m of the boundary from 4 to 40 m ahead in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_needs_paint?: boolean;
  /**
   * Report as valid a frame the filter finds not valid when paint runs along both drawn ego
   * boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
   * counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
   * dashed line's gap), in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_from_paint?: boolean;
}

/**
 * Every option of the Danescu trackers.
 *
 * The options of `danescu-mono` and `danescu-stereo` in `new Tracker(id, { camera, ...options })`:
 * all optional (a key left out takes its default); an option of another tracker is
 * a type error, and refused at run time.
 */
export interface DanescuOptions {
  /**
   * Share of each frame's particles drawn from the generic initialisation distribution
   * (Sec. III), in [0, 1).
   *
   * Range: 0 to 0.99.
   * @defaultValue `0.1`
   */
  init_fraction?: number;
  /**
   * Nearest distance of the image-space mapping, metres (raised to the first visible row).
   *
   * Range: 0.5 to 100.
   * @defaultValue `5`
   */
  near_m?: number;
  /**
   * Farthest distance of the image-space mapping, metres.
   *
   * Range: 1 to 300.
   * @defaultValue `35`
   */
  far_m?: number;
  /**
   * Points P per delimiter edge in image space and in the 3-D space (eq. 5).
   *
   * Range: 2 to 200.
   * @defaultValue `20`
   */
  points?: number;
  /**
   * D_3D: range of the 3-D mapping (eq. 5), metres.
   *
   * Range: 1 to 100.
   * @defaultValue `15`
   */
  range_3d_m?: number;
  /**
   * Diffusion: standard deviation per frame of each parameter, in the order of
   * `Lane3d::NAMES` (w0, ch, wl, cv, y0, xcw, alpha, gamma, psi, wl_mark, wr_mark).
   *
   * Ranges: `diffusion[0]` 0 to 1, `diffusion[1]` 0 to 0.01, `diffusion[2]` 0 to 0.1, `diffusion[3]` 0 to 0.01, `diffusion[4]` 0 to 1, `diffusion[5]` 0 to 2, `diffusion[6]` 0 to 0.2, `diffusion[7]` 0 to 0.2, `diffusion[8]` 0 to 0.2, `diffusion[9]` 0 to 0.5, `diffusion[10]` 0 to 0.5.
   * @defaultValue `[0.03, 0.0003, 0.001, 5e-5, 0.015, 0.04, 0.004, 0.0003, 0.004, 0.01, 0.01]`
   */
  diffusion?: [number, number, number, number, number, number, number, number, number, number, number];
  /**
   * The generic initialisation distribution: uniform lane width (inner edges), metres.
   *
   * Range: 0.5 to 10 (each entry).
   * @defaultValue `[2.6, 4.2]`
   */
  init_width_m?: [number, number];
  /**
   * The generic initialisation distribution: uniform |X_CW| up to this, metres.
   *
   * Range: 0 to 5.
   * @defaultValue `1.2`
   */
  init_offset_m?: number;
  /**
   * The generic initialisation distribution: uniform |psi| up to this, radians.
   *
   * Range: 0 to 0.5.
   * @defaultValue `0.06`
   */
  init_yaw_rad?: number;
  /**
   * The generic initialisation distribution: uniform |C_H| up to this, 1/m.
   *
   * Range: 0 to 0.1.
   * @defaultValue `0.003`
   */
  init_curvature?: number;
  /**
   * The generic initialisation distribution: uniform |W_l| up to this.
   *
   * Range: 0 to 0.5.
   * @defaultValue `0.01`
   */
  init_width_rate?: number;
  /**
   * The generic initialisation distribution: uniform marking widths W_L, W_R, metres.
   *
   * Range: 0 to 1 (each entry).
   * @defaultValue `[0, 0.3]`
   */
  init_marking_m?: [number, number];
  /**
   * The generic initialisation distribution: uniform |alpha - calibrated pitch| up to this,
   * radians (stereo only).
   *
   * Range: 0 to 0.2.
   * @defaultValue `0.01`
   */
  init_pitch_rad?: number;
  /**
   * The generic initialisation distribution: uniform |Y_0| up to this, metres (stereo only).
   *
   * Range: 0 to 1.
   * @defaultValue `0.05`
   */
  init_height_m?: number;
  /**
   * Validation (Sec. VII-D): the lane width W(Z) must stay in this range over the mapped
   * distances, metres (the paper rejects a lane "too narrow, too wide" and gives no
   * limits; [2.2, 4.5] in `real-roads` for danescu-mono).
   *
   * Range: 0 to 20 (each entry).
   * @defaultValue `[2.2, 5]`
   */
  width_range_m?: [number, number];
  /**
   * Validation: the car may be at most this far outside the lane, |X_CW| <= W_0/2 + margin.
   *
   * Range: 0 to 10.
   * @defaultValue `0.5`
   */
  offset_margin_m?: number;
  /**
   * Validation: largest marking width, metres.
   *
   * Range: 0.01 to 2.
   * @defaultValue `0.5`
   */
  max_marking_m?: number;
  /**
   * sigma of the road-edge likelihood (DT^E), pixels.
   *
   * Range: 0.1 to 100.
   * @defaultValue `3`
   */
  sigma_edge_px?: number;
  /**
   * sigma of the marking likelihood (DT^S), pixels.
   *
   * Range: 0.1 to 100.
   * @defaultValue `3`
   */
  sigma_marking_px?: number;
  /**
   * sigma_G of eq. 12, HG units.
   *
   * Range: 0.1 to 1000.
   * @defaultValue `30`
   */
  sigma_gradient?: number;
  /**
   * sigma_D of eq. 14, cells (the paper gives no value). 1 cell: with 0.5 the density
   * cue alone left a median effective sample size of 19 of 500 particles, and the
   * parameters it does not see (the marking widths above all) wandered.
   *
   * Range: 0.01 to 100.
   * @defaultValue `1`
   */
  sigma_density?: number;
  /**
   * Negative points lie this far inside the lane from the inner edges, metres.
   *
   * Range: 0 to 5.
   * @defaultValue `0.3`
   */
  negative_offset_m?: number;
  /**
   * A negative point costs c - DT when an edge is closer than c pixels.
   *
   * Range: 0 to 100.
   * @defaultValue `3`
   */
  negative_reach_px?: number;
  /**
   * The marking-width model and the gradient cue (Sec. II, VI-A c, VII-B). `false` runs
   * the authors' previous approach the paper compares with (Fig. 10): W_L = W_R = 0 and no
   * gradient likelihood.
   *
   * @defaultValue `true`
   */
  marking_widths?: boolean;
  /**
   * The variable-width gradient.
   *
   * Ranges: `hgradient.marking_width_m` 0.02 to 1, `hgradient.max_half_width` 1 to 256, `hgradient.gain` 0.01 to 100.
   * @defaultValue `{ gain: 1, marking_width_m: 0.15, max_half_width: 12 }`
   */
  hgradient?: HGradientConfig;
  /**
   * Marking detection on HG: smallest |g| of a marking edge, grey levels.
   *
   * Range: 0.1 to 255.
   * @defaultValue `40`
   */
  marking_contrast?: number;
  /**
   * Marking detection: accepted marking widths on the road, metres.
   *
   * Range: 0 to 2 (each entry).
   * @defaultValue `[0.05, 0.5]`
   */
  marking_width_range_m?: [number, number];
  /**
   * Road edges (Canny).
   *
   * Ranges: `canny.sigma` 0.1 to 50, `canny.low` 0 to 2000, `canny.high` 0.01 to 2000.
   * @defaultValue `{ high: 100, low: 40, sigma: 1 }`
   */
  canny?: CannyConfig;
  /**
   * The discrete 3-D space and its density threshold (stereo only).
   *
   * Ranges: `density.rows` 3 to 1000, `density.cols` 3 to 1000, `density.dy_m` 0.001 to 1, `density.dz_m` 0.01 to 10, `density.threshold` 0.001 to 1000000.
   * @defaultValue `{ cols: 300, dy_m: 0.01, dz_m: 0.1, rows: 200, threshold: 30 }`
   */
  density?: DensityConfig;
  /**
   * Curbs from the elevation map, added to DT^S (stereo only).
   *
   * Ranges: `curbs.cell_m` 0.01 to 2, `curbs.range_m` 1 to 100, `curbs.half_width_m` 1 to 50, `curbs.min_points` 1 to 10000, `curbs.height_m` 0.01 to 2, `curbs.max_gap` 0 to 1000, `curbs.snap_m` 0 to 1.
   * @defaultValue `{ cell_m: [0.25, 0.1], enabled: true, half_width_m: 8, height_m: [0.06, 0.35], max_gap: 2, min_points: 5, range_m: 15, snap_m: 0.2 }`
   */
  curbs?: CurbConfig;
  /**
   * The stereo matcher (stereo only; `max_disparity` is set from the camera: the
   * disparity of the nearest visible road point).
   *
   * Ranges: `disparity.max_disparity` 1 to 256, `disparity.census_radius` 1 to 7, `disparity.window_radius` 0 to 7, `disparity.uniqueness` 0.01 to 1, `disparity.left_right_tolerance` 0 to 256.
   * @defaultValue `{ census_radius: 2, left_right_tolerance: 1, max_disparity: 64, uniqueness: 0.9, window_radius: 3 }`
   */
  disparity?: DisparityConfig;
  /**
   * Preliminary pitch detection: histogram bin, radians.
   *
   * Range: 1e-5 to 0.1.
   * @defaultValue `0.0005`
   */
  pitch_bin_rad?: number;
  /**
   * Preliminary pitch detection: searched pitch changes, +- radians.
   *
   * Range: 0.0001 to 0.5.
   * @defaultValue `0.05`
   */
  pitch_range_rad?: number;
  /**
   * Road points lie within this height of the detected road line, metres.
   *
   * Range: 0.01 to 2.
   * @defaultValue `0.1`
   */
  road_tolerance_m?: number;
  /**
   * The 3-D data counts (the density cue of eqs. 13-14 and the curbs) only in a frame
   * whose road points are at least this share of the road region's pixels (ours; the
   * paper does not say what a frame without usable stereo data does). Measured at 320x240
   * on drawn roads: 20-30 % by day, 4.7-8 % at night, 0.5-1.2 % in a blacked-out frame
   * (matches of sensor noise). With those noise points weighing the particles while the
   * image cues were empty, the cloud drifted in width and offset through a blackout and
   * re-locked 9 frames after it on average, 24 at worst (`occlusion`, seeds 1000-1002).
   * 0.02 by default, between the blackout and the night; 0 uses the 3-D data of every
   * frame, as before (a share of 0.05 cut the night's density cue too: width MAE 5 -> 28
   * cm).
   *
   * Range: 0 to 1.
   * @defaultValue `0.02`
   */
  min_road_share?: number;
  /**
   * MBSAS: distance threshold on X_CW, metres.
   *
   * Range: 0.01 to 10.
   * @defaultValue `0.4`
   */
  cluster_threshold_m?: number;
  /**
   * MBSAS: at most this many clusters S.
   *
   * Range: 1 to 100.
   * @defaultValue `5`
   */
  max_clusters?: number;
  /**
   * Validity: a frame is valid when, on each side, at least `valid_support` of the
   * estimate's inner-edge points are within this many pixels of a road edge (and its
   * cluster holds `valid_cluster_share` of the particles).
   *
   * Range: 0.1 to 100.
   * @defaultValue `2`
   */
  valid_distance_px?: number;
  /**
   * Validity: the tolerance as a distance on the road, metres, where that is more pixels
   * than `valid_distance_px` (ours; 0: pixels only). The tolerance at distance Z is
   * max(`valid_distance_px`, f_x `valid_distance_m` / Z): a pixel tolerance alone is
   * physically four times tighter through a 1280-pixel camera of 1156 px focal length than
   * through a 640-pixel one of 309 px, and a blurred marking's Canny edge on a video frame
   * falls a few pixels off the model's edge.
   *
   * Range: 0 to 1.
   * @defaultValue `0`
   */
  valid_distance_m?: number;
  /**
   * Validity: the share of the estimate's inner-edge points on each side that must be
   * within `valid_distance_px` of a road edge (a dashed line of 3 m dashes every 12 m gives
   * about 0.25).
   *
   * Range: 0 to 1.
   * @defaultValue `0.15`
   */
  valid_support?: number;
  /**
   * Validity: a side under `valid_support` this frame still counts when its mean support
   * over the last this many frames (this one included; fewer since a reset) reaches
   * `valid_support` and the other side this frame holds at least twice it: a dashed line's
   * support swings with the dashes' phase (`support_memory`; ours,
   * beyond the paper; 1: this frame's alone, the default).
   *
   * Range: 1 to 100.
   * @defaultValue `1`
   */
  valid_support_frames?: number;
  /**
   * Validity: an inner-edge point supports its side only when a marking edge (the marking
   * image of DT^S) also lies within this many times its tolerance (`valid_distance_px`,
   * `valid_distance_m`), besides the road edge (ours, beyond the paper; 0: off, any road
   * edge supports, the default). A tree shadow's edge or a seam is a road edge with no
   * marking beside it, and would otherwise keep a lane through an unmarked crossing; so is
   * a kerb to danescu-mono, whose lane bounded by a kerb without paint is then never valid
   * (danescu-stereo puts the kerbs' feet into the marking image).
   *
   * Range: 0 to 100.
   * @defaultValue `0`
   */
  valid_marking_factor?: number;
  /**
   * Validity with a positive `valid_marking_factor`: on how many sides (1 or 2) the support
   * must come from points with a marking edge beside the road edge. 2 (the default): on
   * both, each side's support counts only such points. 1 (ours): on at least one side (its
   * share of such points, averaged over the last `valid_support_frames` frames, reaches
   * `valid_support`), while each side's support counts any road edge as without the factor;
   * so a lane between a painted line and a kerb without paint stays valid, and a crossing
   * without paint on either side, where only shadow edges or kerbs remain, is not.
   *
   * Range: 1 to 2.
   * @defaultValue `2`
   */
  valid_marking_sides?: number;
  /**
   * Validity: the estimate's MBSAS cluster holds at least this share of the resampled
   * particles.
   *
   * Range: 0 to 1.
   * @defaultValue `0.3`
   */
  valid_cluster_share?: number;
  /**
   * Share of the particles replaced, after the drift, each frame the auto-calibration's
   * line detector finds an ego pair, by draws around that pair on the road (X_CW, psi and
   * W_0 from it with the diffusion's spreads, the rest kept): a data-driven proposal beside
   * the generic one of `init_fraction` (ours, beyond the paper; 0: off, the paper's
   * filter; see `relock`).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  relock_share?: number;
  /**
   * Filter rounds on the first frame (and after a reset), each: resample, inject, diffuse
   * (no ego motion), weigh on the same frame (ours; 0: the paper's start, whose first frame
   * is weighed once from the initial distribution: its most populous cluster then holds
   * about a quarter of the cloud, under `valid_cluster_share`, and the first estimate is
   * not valid).
   *
   * Range: 0 to 1000.
   * @defaultValue `0`
   */
  start_iterations?: number;
  /**
   * Report the lanes beside the ego lane (`left-adjacent`, `right-adjacent`) where the
   * bottom-up detector's markings run beside an ego boundary at a lane's width
   * (`adjacent_lanes`; ours, beyond the paper, which follows the ego lane
   * only; off by default).
   *
   * @defaultValue `false`
   */
  adjacent_lanes?: boolean;
  /**
   * Move each reported boundary onto the centre of the paint it lies on: a straight
   * sideways correction fitted to the marking centres the bottom-up detector's marking
   * image shows within 0.3 m of it, or 0.6 m where no run of paint lies within 0.3 m
   * (`paint_snap`; ours, beyond the
   * paper; output only: the filter and the validity are unchanged; off by default).
   *
   * @defaultValue `false`
   */
  snap_to_paint?: boolean;
  /**
   * With `snap_to_paint`: the snap follows the paint round a bend: each probe's search is
   * centred on the line through the last run of paint centres, and the correction gets a
   * quadratic term (`paint_snap`; ours; off by default).
   *
   * @defaultValue `false`
   */
  snap_follows_bends?: boolean;
  /**
   * Report a valid frame not valid when no run of paint begins along either drawn ego
   * boundary within 12 m of its nearest probe (4 m ahead, or where the boundary comes
   * into view; 12 m: a dashed line's longest common gap, so the paint beyond a crossing
   * does not keep its near side valid): a run of at least four paint centres 0.5 m apart
   * (1.5 m) and in four rows of the image, each within 10 cm of the last, found within
   * 0.3 m of the boundary from 4 to 40 m ahead in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_needs_paint?: boolean;
  /**
   * Report as valid a frame the filter finds not valid when paint runs along both drawn ego
   * boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
   * counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
   * dashed line's gap), in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_from_paint?: boolean;
}

/**
 * Settings of `lee-cpf`.
 *
 * The options of `lee-cpf` in `new Tracker(id, { camera, ...options })`:
 * all optional (a key left out takes its default); an option of another tracker is
 * a type error, and refused at run time.
 */
export interface LeeOptions {
  /**
   * Filter structure.
   *
   * - `'cascade'`: The cascade particle filter: stage 1 [psi, y0, w, w'], stage 2 [c, delta] (Algorithm 1).
   * - `'first-order'`: PF1: one filter over the first-order model [psi, y0, w, w'] (no curve).
   * - `'full-model'`: PF2/PF3: one filter over all six states, weighed by both measurement models.
   *
   * @defaultValue `'cascade'`
   */
  variant?: 'cascade' | 'first-order' | 'full-model';
  /**
   * Particles of stage 2 (stage 1 and the single-stage filters use `particles`); 0: the
   * same as stage 1.
   *
   * Range: 0 to 200000.
   * @defaultValue `0`
   */
  stage2_particles?: number;
  /**
   * Nearest road distance measured, metres (raised to the first visible distance).
   *
   * Range: 0.5 to 100.
   * @defaultValue `5`
   */
  near_m?: number;
  /**
   * End of the near range (DLD, stage 1) and start of the far range (Canny, stage 2), m.
   *
   * Range: 1 to 250.
   * @defaultValue `20`
   */
  split_m?: number;
  /**
   * End of the far range, metres.
   *
   * Range: 2 to 500.
   * @defaultValue `50`
   */
  far_m?: number;
  /**
   * Spacing of the evaluation points x = 1..M of eqs. 31-32 in the near range, metres.
   *
   * Range: 0.05 to 50.
   * @defaultValue `1`
   */
  near_step_m?: number;
  /**
   * Spacing of the far-range evaluation points, metres.
   *
   * Range: 0.05 to 100.
   * @defaultValue `2`
   */
  far_step_m?: number;
  /**
   * Lateral half-range of the likelihood map, metres.
   *
   * Range: 1 to 50.
   * @defaultValue `8`
   */
  lateral_range_m?: number;
  /**
   * Cell size of the likelihood map (square cells), metres.
   *
   * Range: 0.01 to 1.
   * @defaultValue `0.1`
   */
  cell_m?: number;
  /**
   * DLD detector (eqs. 21-24): averaging window N (pixels) and threshold gamma.
   *
   * Ranges: `dld.window` 1 to 256, `dld.gamma` 0 to 255.
   * @defaultValue `{ gamma: 20, window: 3 }`
   */
  dld?: DldConfig;
  /**
   * Largest pattern length of a marking candidate (eq. 26), metres.
   *
   * Range: 0.05 to 2.
   * @defaultValue `0.45`
   */
  max_marking_width_m?: number;
  /**
   * Spread sigma_D that turns a distance d (m) into the likelihood exp(-d^2 / 2 sigma_D^2)
   * of the map D (eq. 31).
   *
   * Range: 0.01 to 5.
   * @defaultValue `0.2`
   */
  map_sigma_m?: number;
  /**
   * Canny detector of the far range.
   *
   * Ranges: `canny.sigma` 0.1 to 50, `canny.low` 0 to 2000, `canny.high` 0.01 to 2000.
   * @defaultValue `{ high: 100, low: 40, sigma: 1 }`
   */
  canny?: CannyConfig;
  /**
   * Marking width assumed when matching far points to Canny edges, metres.
   *
   * Range: 0.02 to 1.
   * @defaultValue `0.15`
   */
  marking_width_m?: number;
  /**
   * Weight alpha of the boundary points (eq. 32).
   *
   * Range: 0.001 to 1000.
   * @defaultValue `1`
   */
  alpha?: number;
  /**
   * Weight beta of the points inside the lane (eq. 32; negative: a marking there counts
   * against the particle).
   *
   * Range: -1000 to 1000.
   * @defaultValue `-0.5`
   */
  beta?: number;
  /**
   * Distance tau of the inside points from the boundaries (eqs. 29-30), metres.
   *
   * Range: 0.05 to 5.
   * @defaultValue `0.6`
   */
  tau_m?: number;
  /**
   * Standard deviation sigma of the Gaussian on q (eq. 33), in units of q (whose ideal
   * value mu = 2 alpha).
   *
   * Range: 0.001 to 100.
   * @defaultValue `0.25`
   */
  sigma_q?: number;
  /**
   * Standard deviation of the stage-2 Gaussian on the fraction of far points on an edge.
   *
   * Range: 0.001 to 100.
   * @defaultValue `0.25`
   */
  sigma_far?: number;
  /**
   * Spiral length s_o of the clothoid (eq. 12), metres.
   *
   * Range: 1 to 1000.
   * @defaultValue `60`
   */
  spiral_length_m?: number;
  /**
   * Diagonal of the process noise Q per frame (eq. 20): psi (rad), y0 (m), w (m), w' (m/m),
   * c (m), delta (1/m). Calibrated, as the paper calibrates Q on ground-truth markings, on
   * the simulator's truth (`examples/lee_calibrate_q.rs`): the largest frame-to-frame change
   * at 30 fps of psi, y0 (a lane change) and w; for w', whose largest change is a step at
   * the start of a width change, 0.0005 (the cloud follows the step in about 20 frames; a
   * looser w' trades off against w, which the near range alone cannot separate); c moves by
   * up to the distance driven per frame, about 1 m.
   *
   * Ranges: `process_sd[0]` 1e-9 to 1, `process_sd[1]` 1e-9 to 10, `process_sd[2]` 1e-9 to 5, `process_sd[3]` 1e-9 to 1, `process_sd[4]` 1e-9 to 100, `process_sd[5]` 1e-9 to 0.1.
   * @defaultValue `[0.004, 0.06, 0.01, 0.0005, 1.5, 0.0002]`
   */
  process_sd?: [number, number, number, number, number, number];
  /**
   * Resample a stage when its effective sample size falls below this fraction of N
   * (N_thr of Algorithm 1).
   *
   * Range: 0 to 1.
   * @defaultValue `0.5`
   */
  ess_threshold?: number;
  /**
   * Limits of the initial distribution and of the states: |psi| (rad).
   *
   * Range: 0.001 to 1.
   * @defaultValue `0.1`
   */
  max_heading_rad?: number;
  /**
   * Accepted lane widths [min, max], metres.
   *
   * Range: 0.5 to 10 (each entry).
   * @defaultValue `[2.5, 4.5]`
   */
  width_range_m?: [number, number];
  /**
   * Largest |w'|.
   *
   * Range: 1e-6 to 0.5.
   * @defaultValue `0.02`
   */
  max_width_rate?: number;
  /**
   * Largest c, metres (c ranges over [-spiral_length_m, max_transition_m]).
   *
   * Range: 1 to 1000.
   * @defaultValue `60`
   */
  max_transition_m?: number;
  /**
   * Largest |delta|, 1/m.
   *
   * Range: 1e-6 to 0.5.
   * @defaultValue `0.02`
   */
  max_curvature?: number;
  /**
   * Filter iterations on the first frame (and after a reset): the paper does not say how
   * the filter starts; a uniform start needs a few rounds on the same frame to find the lane.
   *
   * Range: 0 to 1000.
   * @defaultValue `20`
   */
  start_iterations?: number;
  /**
   * How much wider than Q the process noise of the first start iteration is; it narrows
   * linearly to Q by the last (ours, like the start iterations: a cloud diffusing by Q
   * alone stays where the uniform start's luckiest particles were, often on one marking
   * at a wrong width).
   *
   * Range: 1 to 100.
   * @defaultValue `10`
   */
  start_spread?: number;
  /**
   * Share of the stage-1 particles drawn anew from the initial distribution in each of the
   * first half of the start iterations (ours; 0 turns it off).
   *
   * Range: 0 to 1.
   * @defaultValue `0.2`
   */
  start_fresh?: number;
  /**
   * Restart from the initial distribution after this many consecutive frames in which no
   * marking supports either boundary of the estimate (ours; 0: never).
   *
   * Range: 0 to 100000.
   * @defaultValue `2`
   */
  lost_restart?: number;
  /**
   * Share of the stage-1 particles replaced, each frame the auto-calibration's line
   * detector finds an ego pair, by draws around that pair on the road (its centre, width
   * and heading with the process noise Q; w', c and delta kept): a data-driven proposal
   * that lets a cloud stuck on a wrong lane re-lock (ours, beyond the paper; 0: off, the
   * paper's filter).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  relock_share?: number;
  /**
   * Share of the stage-1 particles of a first frame (the start, and after a restart) drawn
   * around the ego pair the same bottom-up line detector finds in that frame, the rest
   * from the initial distribution (ours: the paper does not say how the filter starts;
   * 0.5 by default; 0: the uniform start alone, as before 2026-11-26). The detector then
   * runs on first frames only, unless `relock_share` or an output option (`adjacent_lanes`,
   * `snap_to_paint`, `valid_needs_paint`) needs it on every frame.
   *
   * Range: 0 to 1.
   * @defaultValue `0.5`
   */
  start_pair_share?: number;
  /**
   * Share of the stage-1 particles replaced, each frame after one on which one boundary of
   * the estimate had near support (at least `valid_fraction`) and the other had none (under
   * 0.05), by draws that keep the supported boundary where it is and take the width anew,
   * uniform over `width_range_m`: a search for the lost side where the lane widens or
   * narrows faster than the process noise lets the width follow (a turn pocket, a merge;
   * ours, beyond the paper; 0: off, the paper's filter).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  side_search_share?: number;
  /**
   * Standard deviation, 1/m, of a zero-mean Gaussian prior on the curvature delta,
   * multiplied into stage 2's weights: p(c, delta | z) ~ N(f; 1, sigma_far^2) N(delta; 0,
   * sd^2) (ours, beyond the paper, whose curvature is uniform within `max_curvature`; 0: off,
   * the paper's filter). Where the far band holds little of the markings (a low camera
   * looking level, low contrast near the horizon), a uniform prior lets the curve follow
   * whatever edges are there: a barrier's top, a seam, roadside texture. Highway design
   * keeps radii above a few hundred metres (delta under about 0.003 /m); 0.004 makes a 250 m
   * radius cost half a nat and a 67 m one seven.
   *
   * Range: 0 to 1.
   * @defaultValue `0`
   */
  curvature_prior_sd?: number;
  /**
   * Report the lanes beside the ego lane (`left-adjacent`, `right-adjacent`) where the
   * bottom-up detector's markings run beside an ego boundary at a lane's width
   * (`adjacent_lanes`; ours, beyond the paper, which follows the ego lane
   * only; off by default).
   *
   * @defaultValue `false`
   */
  adjacent_lanes?: boolean;
  /**
   * Kalman smoothing of the CPF output (Fig. 4).
   *
   * @defaultValue `true`
   */
  kalman?: boolean;
  /**
   * Kalman process noise per frame, same order as `process_sd`.
   *
   * Ranges: `kalman_process_sd[0]` 1e-9 to 1, `kalman_process_sd[1]` 1e-9 to 10, `kalman_process_sd[2]` 1e-9 to 5, `kalman_process_sd[3]` 1e-9 to 1, `kalman_process_sd[4]` 1e-9 to 100, `kalman_process_sd[5]` 1e-9 to 0.1.
   * @defaultValue `[0.003, 0.03, 0.01, 0.0005, 2, 0.0002]`
   */
  kalman_process_sd?: [number, number, number, number, number, number];
  /**
   * Kalman measurement noise (spread of the raw CPF estimate), same order.
   *
   * Ranges: `kalman_measurement_sd[0]` 1e-9 to 1, `kalman_measurement_sd[1]` 1e-9 to 10, `kalman_measurement_sd[2]` 1e-9 to 5, `kalman_measurement_sd[3]` 1e-9 to 1, `kalman_measurement_sd[4]` 1e-9 to 100, `kalman_measurement_sd[5]` 1e-9 to 0.1.
   * @defaultValue `[0.006, 0.05, 0.05, 0.002, 6, 0.0005]`
   */
  kalman_measurement_sd?: [number, number, number, number, number, number];
  /**
   * A frame is valid when, on each boundary, at least this fraction of the estimate's near
   * points lie within sigma_D of a marking candidate (D >= exp(-1/2)).
   *
   * Range: 0 to 1.
   * @defaultValue `0.15`
   */
  valid_fraction?: number;
  /**
   * Validity: a side under `valid_fraction` this frame still counts when its mean support
   * over the last this many frames (this one included; fewer since a reset) reaches
   * `valid_fraction` and the other side this frame holds at least twice it
   * (`support_memory`; ours, beyond the paper; 1: this frame's alone,
   * the default).
   *
   * Range: 1 to 100.
   * @defaultValue `1`
   */
  valid_support_frames?: number;
  /**
   * Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
   * is not held back): the lane counts again only when a marking
   * supports one of its boundaries within this many metres beyond the nearest measured
   * distance, or within the longest such reach of the last 30 valid frames that saw both
   * boundaries (a lane tracked between dashed lines accepts their gaps; see
   * `reacquire`; ours, beyond the paper; 0: off, the default; 4 in `real-roads`).
   * Markings that begin only further ahead, past an unmarked crossing, are not yet the
   * car's lane.
   *
   * Range: 0 to 100.
   * @defaultValue `0`
   */
  reacquire_near_m?: number;
  /**
   * Move each reported boundary onto the centre of the paint it lies on: a straight
   * sideways correction fitted to the marking centres the bottom-up detector's marking
   * image shows within 0.3 m of it, or 0.6 m where no run of paint lies within 0.3 m
   * (`paint_snap`; ours, beyond the
   * paper; output only: the filter and the validity are unchanged; off by default).
   *
   * @defaultValue `false`
   */
  snap_to_paint?: boolean;
  /**
   * With `snap_to_paint`: the snap follows the paint round a bend: each probe's search is
   * centred on the line through the last run of paint centres, and the correction gets a
   * quadratic term (`paint_snap`; ours; off by default).
   *
   * @defaultValue `false`
   */
  snap_follows_bends?: boolean;
  /**
   * Report a valid frame not valid when no run of paint begins along either drawn ego
   * boundary within 12 m of its nearest probe (4 m ahead, or where the boundary comes
   * into view; 12 m: a dashed line's longest common gap, so the paint beyond a crossing
   * does not keep its near side valid): a run of at least four paint centres 0.5 m apart
   * (1.5 m) and in four rows of the image, each within 10 cm of the last, found within
   * 0.3 m of the boundary from 4 to 40 m ahead in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_needs_paint?: boolean;
  /**
   * Report as valid a frame the filter finds not valid when paint runs along both drawn ego
   * boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
   * counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
   * dashed line's gap), in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_from_paint?: boolean;
}

/**
 * Settings of `liu-ppf` and `liu-ppf-nokernel`.
 *
 * The options of `liu-ppf` and `liu-ppf-nokernel` in `new Tracker(id, { camera, ...options })`:
 * all optional (a key left out takes its default); an option of another tracker is
 * a type error, and refused at run time.
 */
export interface LiuOptions {
  /**
   * The top view (IPM) the model lives on. Ours: 6 to 36 m ahead, 6 m to each side, 10 cm
   * per pixel (120 x 300 pixels): three boundaries of 3.5 m lanes fit with room to move,
   * and a 15 cm marking is 1.5 pixels wide, so sigma_x = 1 pixel is 10 cm.
   *
   * Ranges: `top_view.x_min_m` 0.5 to 200, `top_view.x_max_m` 1 to 500, `top_view.y_left_m` -100 to 100, `top_view.y_right_m` -100 to 100, `top_view.m_per_px` 0.005 to 1.
   * @defaultValue `{ m_per_px: 0.1, x_max_m: 36, x_min_m: 6, y_left_m: 6, y_right_m: -6 }`
   */
  top_view?: TopViewConfig;
  /**
   * Number of boundaries n_l tracked (Fig. 3: 3).
   *
   * Range: 1 to 6.
   * @defaultValue `3`
   */
  boundaries?: number;
  /**
   * The split row y_m as a fraction of the top-view height (the paper: 0.5).
   *
   * Range: 0.1 to 0.9.
   * @defaultValue `0.5`
   */
  split?: number;
  /**
   * Gradient-magnitude threshold of the measurement mask (Sobel on 0-255 grey levels).
   *
   * Range: 0 to 2000.
   * @defaultValue `10`
   */
  gradient_threshold?: number;
  /**
   * Variances sigma_x^2 and sigma_y^2 of the position kernels, pixels^2.
   *
   * Range: 0.01 to 100.
   * @defaultValue `1`
   */
  position_variance_px2?: number;
  /**
   * Mean mu_c of the intensity kernel K_c on the normalised image.
   *
   * Range: -100 to 100.
   * @defaultValue `1`
   */
  intensity_mean?: number;
  /**
   * Variance sigma_c^2 of the intensity kernel (the paper gives it for PPF-NoKernel only;
   * we use the same for PPF-Kernel). 0.5 makes K_c nearly flat (a grey-40 pixel weighs 0.49
   * of a white one); 0.05 (ours) discounts the noise the gradient mask passes on dark
   * asphalt and halves the offset error on `night` (RESULTS, liu-ppf on curves, at night).
   *
   * Range: 0.001 to 100.
   * @defaultValue `0.5`
   */
  intensity_variance?: number;
  /**
   * Gauss-Hermite nodes of the parabolic kernel integral (eq. 12; the paper does not say how
   * many). Three reproduce a fine numerical integral to 2.5e-4 relative on the slopes and
   * bends a top view has (five: 5e-7), far below the kernels' own modelling error.
   *
   * Range: 1 to 20.
   * @defaultValue `3`
   */
  quadrature_nodes?: number;
  /**
   * Half-width, in pixels across the boundary, of the band whose mask pixels are "near the
   * predicted lane" (the paper does not say; 3 = 3 sigma_x).
   *
   * Range: 1 to 50.
   * @defaultValue `3`
   */
  band_px?: number;
  /**
   * Initialisation particles N' added every frame (Sec. IV-D).
   *
   * Range: 0 to 100000.
   * @defaultValue `50`
   */
  init_particles?: number;
  /**
   * Random walk of the linear part (eq. 19): sigma_rho (pixels) and sigma_theta (rad).
   *
   * Range: 0.001 to 100.
   * @defaultValue `1`
   */
  sigma_rho_px?: number;
  /**
   * See `sigma_rho_px`.
   *
   * Range: 1e-6 to 1.
   * @defaultValue `0.004`
   */
  sigma_theta?: number;
  /**
   * Random walk of the parabolic part (eq. 23): sigma_d (pixels per pixel).
   *
   * Range: 1e-6 to 1.
   * @defaultValue `0.01`
   */
  sigma_d?: number;
  /**
   * Smallest spacing between neighbouring boundaries, metres (the paper: 12 px).
   *
   * Range: 0.1 to 10.
   * @defaultValue `2.4`
   */
  min_spacing_m?: number;
  /**
   * Largest difference between neighbouring spacings, metres (the paper: 5 px).
   *
   * Range: 0.01 to 10.
   * @defaultValue `0.5`
   */
  max_spacing_difference_m?: number;
  /**
   * A frame is valid when both ego boundaries of the estimate have a strong edge pixel of
   * their orientation (within 0.1 rad, gradient at least twice the threshold) within 1 pixel
   * (sigma_x) in at least this fraction of the near rows (the paper does not define valid
   * frames; this is ours, as for lee-cpf; a dashed line gives about 0.25).
   *
   * Range: 0 to 1.
   * @defaultValue `0.15`
   */
  valid_fraction?: number;
  /**
   * Validity: a side under `valid_fraction` this frame still counts when its mean support
   * over the last this many frames (this one included; fewer since a reset) reaches
   * `valid_fraction` and the other side this frame holds at least twice it
   * (`support_memory`; ours; 1: this frame's alone, the default).
   *
   * Range: 1 to 100.
   * @defaultValue `1`
   */
  valid_support_frames?: number;
  /**
   * Validity (ours, beyond the paper; 0: off, the default): besides the edge support, one
   * ego boundary at least must show paint in `valid_fraction` of the near rows: a top-view
   * pixel within 2 columns of its line brighter by this many grey levels than the road
   * 0.3 m to either side (`PAINT_REACH_M`). A tree shadow's edge along the road is
   * an edge of the boundary's orientation with no bright stripe, and would otherwise keep
   * a lane through an unmarked crossing; one side is enough, so a kerb may bound the other.
   *
   * Range: 0 to 255.
   * @defaultValue `0`
   */
  valid_paint_contrast?: number;
  /**
   * Default lane model (Sec. IV-D): range of lane widths, metres.
   *
   * Range: 0.5 to 10 (each entry).
   * @defaultValue `[3, 4]`
   */
  default_width_m?: [number, number];
  /**
   * Default lane model: largest heading of the straight boundaries, radians.
   *
   * Range: 0 to 0.9.
   * @defaultValue `0.05`
   */
  default_heading_rad?: number;
  /**
   * Default lane model: spread of each boundary about the parallel set, metres.
   *
   * Range: 0 to 2.
   * @defaultValue `0.1`
   */
  default_jitter_m?: number;
  /**
   * Share of the particles replaced, after the linear part's random walk, each frame the
   * auto-calibration's line detector finds an ego pair, by default-model lanes placed on
   * that pair (its width and heading, boundaries jittered by `default_jitter_m`): a
   * data-driven proposal beside the paper's N' default-model particles (ours, beyond the
   * paper; 0: off; see `relock`).
   *
   * Range: 0 to 0.5.
   * @defaultValue `0`
   */
  relock_share?: number;
  /**
   * Move each reported boundary onto the centre of the paint it lies on: a straight
   * sideways correction fitted to the marking centres the bottom-up detector's marking
   * image shows within 0.3 m of it, or 0.6 m where no run of paint lies within 0.3 m
   * (`paint_snap`; ours, beyond the
   * paper; output only: the filter and the validity are unchanged; off by default).
   *
   * @defaultValue `false`
   */
  snap_to_paint?: boolean;
  /**
   * With `snap_to_paint`: the snap follows the paint round a bend: each probe's search is
   * centred on the line through the last run of paint centres, and the correction gets a
   * quadratic term (`paint_snap`; ours; off by default).
   *
   * @defaultValue `false`
   */
  snap_follows_bends?: boolean;
  /**
   * Report a valid frame not valid when no run of paint begins along either drawn ego
   * boundary within 12 m of its nearest probe (4 m ahead, or where the boundary comes
   * into view; 12 m: a dashed line's longest common gap, so the paint beyond a crossing
   * does not keep its near side valid): a run of at least four paint centres 0.5 m apart
   * (1.5 m) and in four rows of the image, each within 10 cm of the last, found within
   * 0.3 m of the boundary from 4 to 40 m ahead in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged, and it stands on frames under
   * 32x16, where the detector cannot run; off by default).
   *
   * @defaultValue `false`
   */
  valid_needs_paint?: boolean;
  /**
   * Report as valid a frame the filter finds not valid when paint runs along both drawn ego
   * boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
   * counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
   * dashed line's gap), in the bottom-up detector's marking image
   * (`paint_output`; ours, beyond the paper; output only: the filter's
   * own validity, which its other rules read, is unchanged; off by default).
   *
   * @defaultValue `false`
   */
  valid_from_paint?: boolean;
  /**
   * Also report the lanes beside the ego lane on the sides the partitions leave out
   * (`left-adjacent`, `right-adjacent`), where markings run beside an ego boundary at a
   * lane's width in the bottom-up detector's marking image
   * (`adjacent_lanes`; ours, beyond the paper, whose boundaries are the
   * partitions' alone; off by default).
   *
   * @defaultValue `false`
   */
  adjacent_lanes?: boolean;
  /**
   * Ends the top view where the camera still resolves it (ours, beyond the paper, which
   * names no range): its far end at most `resolved_distance_m`, where one
   * top-view pixel spans `MIN_COLUMNS_PER_TOP_VIEW_PIXEL` image columns, but at least
   * `MIN_TOP_VIEW_LENGTH_M` beyond its start; and a valid frame's support is counted over
   * the view's nearest `VALID_WINDOW_M` (the default view's near part) rather than its
   * near part, which a shorter view halves. Off: `top_view` and the near part as given.
   *
   * @defaultValue `false`
   */
  top_view_resolved?: boolean;
  /**
   * Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
   * is not held back): the lane counts again only when a strong edge supports one of its
   * ego boundaries within this many metres beyond the top view's near end, or within the
   * longest such reach of the last 30 valid frames that saw both boundaries (see
   * `reacquire`; ours, beyond the paper; 0: off, the default; 4 in
   * `real-roads`). Markings that begin only further ahead, past an unmarked crossing, are
   * not yet the car's lane.
   *
   * Range: 0 to 100.
   * @defaultValue `0`
   */
  reacquire_near_m?: number;
  /**
   * How the estimate picks its mode (the paper does not say how it reads its estimate off
   * the particles): among the particles within half the minimum lane spacing of each of the
   * `mode_candidates` heaviest particles, the set of the largest total weight, whose weighted
   * mean is the estimate. 1 (the default): the heaviest particle's mode. More (ours, 32 in
   * `real-roads`): a mode that many particles share wins over one heavy particle's, which on
   * real footage is often a lane tilted about a far point.
   *
   * Range: 1 to 1000.
   * @defaultValue `1`
   */
  mode_candidates?: number;
}

/**
 * Each tracker's own options, by id.
 */
export interface TrackerOptionsById {
  'adachi-mmpf': AdachiOptions;
  'danescu-mono': DanescuOptions;
  'danescu-stereo': DanescuOptions;
  'lee-cpf': LeeOptions;
  'liu-ppf': LiuOptions;
  'liu-ppf-nokernel': LiuOptions;
}

/**
 * `new Tracker(id, config)`: the camera, particles and seed, and the options of tracker `Id`
 * (`TrackerOptionsById`). With a literal id (`new Tracker('lee-cpf', { ... })`) an option of
 * another tracker is a type error; `TrackerConfig` without `Id` is any one tracker's config.
 */
export type TrackerConfig<Id extends TrackerId = TrackerId> =
  Id extends TrackerId ? TrackerBaseConfig & TrackerOptionsById[Id] : never;

/**
 * `trackerDefaults(id)`: every option of tracker `Id` with its default, `particles` included.
 */
export type TrackerDefaults<Id extends TrackerId = TrackerId> =
  Id extends TrackerId ? Required<TrackerOptionsById[Id]> & { particles: number } : never;
