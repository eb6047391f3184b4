// @ts-check
// What the teaching panel says about each tracker: the paper's idea in a few sentences with its
// equations, and the parameters the paper names, as sliders. A parameter's `path` is its option
// name, with `.k` for element k of an array option; its default comes from trackerDefaults().

const PARTICLES = { path: 'particles', label: 'particles N', min: 20, max: 2000, step: 10 };
/** Options beyond the papers (ours), for real roads: each paper's filter is the default (off). */
const RELOCK = { path: 'relock_share', label: 're-lock share: particles drawn around a line detector’s ego pair (ours, beyond the paper)', min: 0, max: 0.5, step: 0.01 };
const SUPPORT_FRAMES = { path: 'valid_support_frames', label: 'frames a dashed boundary’s support is remembered (ours; 1: this frame only)', min: 1, max: 15, step: 1 };
const SNAP = { path: 'snap_to_paint', label: 'snap to paint: move each drawn boundary onto the centre of the marking it lies on (ours, beyond the paper; output only)', kind: /** @type {const} */ ('bool') };
const BENDS = { path: 'snap_follows_bends', label: 'snap follows bends: with snap to paint, follow the marking round a bend the estimate does not (ours, beyond the paper; output only)', kind: /** @type {const} */ ('bool') };
const NEEDS_PAINT = { path: 'valid_needs_paint', label: 'no lane without paint: report a frame not valid when no run of paint begins within 12 m of the nearest probe along either drawn ego boundary (ours, beyond the paper; output only)', kind: /** @type {const} */ ('bool') };
const FROM_PAINT = { path: 'valid_from_paint', label: 'a lane from paint: report as valid a frame the filter finds not valid when paint runs along both drawn ego boundaries, one from the car (ours, beyond the paper; output only)', kind: /** @type {const} */ ('bool') };
const ADJACENT = { path: 'adjacent_lanes', label: 'adjacent lanes: report the marked lanes beside the ego lane (ours, beyond the paper)', kind: /** @type {const} */ ('bool') };

/**
 * A slider (`min`, `max`, `step`) or, with `kind: 'bool'`, a checkbox for the option at `path`.
 * @typedef {{ path: string, label: string, min?: number, max?: number, step?: number, kind?: 'bool' }} Param
 */
/** @typedef {{ title: string, text: string[], params: Param[] }} TrackerText */

/** @type {Record<string, TrackerText>} */
export const TRACKERS = {
  'liu-ppf': {
    title: 'Liu, Wörgötter & Markelić 2013: partitioned particle filter, kernel-density measurements',
    text: [
      'The frame is warped to a top view. Each boundary is a linear-parabolic curve: a line (ρ, θ) near the car and a parabola of curvature d beyond it.',
      'The state space is partitioned: first the linear parts random-walk (eqs. 18-19) and are weighed, then the cloud is resampled, then the parabolic parts random-walk (eqs. 22-23) and are weighed. Each partition searches a few dimensions instead of all of them.',
      'The measurement is a kernel density over edge pixels: each pixel near a boundary counts with an orientation kernel (its gradient direction against the curve’s) and an intensity kernel (eqs. 20-21, 24-25). N′ initialisation particles from a straight-lane prior are added every frame.',
    ],
    params: [
      PARTICLES,
      { path: 'init_particles', label: "initialisation particles N'", min: 0, max: 200, step: 5 },
      { path: 'sigma_rho_px', label: 'σ_ρ: random walk of ρ (px)', min: 0.1, max: 5, step: 0.1 },
      { path: 'sigma_theta', label: 'σ_θ: random walk of θ (rad)', min: 0.0005, max: 0.03, step: 0.0005 },
      { path: 'sigma_d', label: 'σ_d: random walk of d', min: 0.001, max: 0.05, step: 0.001 },
      { path: 'gradient_threshold', label: 'gradient threshold of the mask', min: 1, max: 60, step: 1 },
      RELOCK,
      { path: 'top_view_resolved', label: 'top view only as far as the camera resolves it (ours, beyond the paper)', kind: /** @type {const} */ ('bool') },
      { path: 'reacquire_near_m', label: 'after a loss, valid again only with a marking this near (m beyond the top view’s near end; 0: off; ours, beyond the paper)', min: 0, max: 15, step: 0.5 },
      SUPPORT_FRAMES,
      { path: 'mode_candidates', label: 'estimate: the heaviest mode around this many heaviest particles (1: the heaviest particle’s; ours)', min: 1, max: 64, step: 1 },
      { path: 'valid_paint_contrast', label: 'valid only with paint on one ego boundary: a stripe this many grey levels brighter than the road beside it (0: off; ours)', min: 0, max: 40, step: 1 },
      ADJACENT,
      SNAP,
      BENDS,
      NEEDS_PAINT,
      FROM_PAINT,
    ],
  },
  'lee-cpf': {
    title: 'Lee, Jang & Sunwoo 2015: cascade particle filter on a clothoid lane',
    text: [
      'The lane is a clothoid: heading ψ, offset y₀, width w and its rate w′ at the car; straight up to a transition point at distance c, then a spiral into a curve of curvature δ (eqs. 10-19).',
      'Stage 1 tracks [ψ, y₀, w, w′] on a likelihood map built from dark-light-dark marking candidates near the car (eqs. 21-33). Stage 2 tracks [c, δ] on Canny edges far away, each particle completed with the stage-1 estimate. Each stage resamples when its effective sample size falls below N_thr.',
      'A Kalman filter smooths the six states. The cascade splits a 6-D search into a 4-D and a 2-D one.',
    ],
    params: [
      PARTICLES,
      { path: 'process_sd.0', label: 'σ of ψ per frame (rad)', min: 0.0005, max: 0.02, step: 0.0005 },
      { path: 'process_sd.1', label: 'σ of y₀ per frame (m)', min: 0.005, max: 0.3, step: 0.005 },
      { path: 'process_sd.2', label: 'σ of w per frame (m)', min: 0.001, max: 0.05, step: 0.001 },
      { path: 'process_sd.4', label: 'σ of c, the transition point, per frame (m)', min: 0.1, max: 5, step: 0.1 },
      { path: 'ess_threshold', label: 'N_thr / N: resample below', min: 0, max: 1, step: 0.05 },
      { path: 'kalman', label: 'Kalman smoothing', kind: 'bool' },
      { path: 'start_pair_share', label: 'start: share drawn around a line detector’s ego pair (ours; 0: uniform)', min: 0, max: 1, step: 0.05 },
      RELOCK,
      { path: 'curvature_prior_sd', label: 'curvature prior σ of δ (1/m; 0: off): far-stage bends need evidence (ours, beyond the paper)', min: 0, max: 0.02, step: 0.0005 },
      { path: 'side_search_share', label: 'side search: share drawn at new widths beside the one supported boundary (ours, beyond the paper)', min: 0, max: 0.5, step: 0.05 },
      SUPPORT_FRAMES,
      { path: 'reacquire_near_m', label: 'after a loss, valid again only with a marking this near (m beyond the nearest measured; 0: off; ours, beyond the paper)', min: 0, max: 15, step: 0.5 },
      ADJACENT,
      SNAP,
      BENDS,
      NEEDS_PAINT,
      FROM_PAINT,
    ],
  },
  'adachi-mmpf': {
    title: 'Adachi, Inayoshi & Kurita: multiple-model particle filter on edge votes',
    text: [
      'Edge points in a box ahead vote onto one lateral axis ρ: the histogram H_j. A particle is (r, q, w): a model r (which of four boundaries exist), the lane position q and width w.',
      'Each frame the model switches by the Markov chain of Table 1 and q, w random-walk (eqs. 7-8), with q wrapping by a lane at ±w/2 (eq. 9), which is how a lane change shows.',
      'The weight compares the histogram with an edge distribution: the template of each boundary model r has, plus β times the noise histogram N_j of all the box’s pixels, normalised (eq. 4); each vote multiplies in its bin’s probability (eq. 6). The estimate is the most probable model and its particles’ mean.',
    ],
    params: [
      PARTICLES,
      { path: 'sigma_q_m', label: 'σ_q: random walk of q (m)', min: 0.005, max: 0.3, step: 0.005 },
      { path: 'sigma_w_m', label: 'σ_w: random walk of w (m)', min: 0.002, max: 0.15, step: 0.002 },
      { path: 'beta', label: 'β: weight of the noise histogram', min: 0.05, max: 3, step: 0.05 },
      { path: 'edge_threshold', label: 'edge threshold', min: 10, max: 300, step: 5 },
      { path: 'start_pair_share', label: 'start: share drawn around the vote histogram’s lane pairs (ours; 0: uniform)', min: 0, max: 1, step: 0.05 },
      RELOCK,
      { path: 'side_search_share', label: 'side search: share drawn at new widths beside the one supported boundary (ours, beyond the paper)', min: 0, max: 0.5, step: 0.05 },
      { path: 'reacquire_near_m', label: 'after a loss, valid again only with a vote this near (m beyond the voting region’s nearest row; 0: off; ours, beyond the paper)', min: 0, max: 15, step: 0.5 },
      { path: 'vote_pair_share', label: 'vote-pair share: particles redrawn each frame around those pairs (ours, beyond the paper)', min: 0, max: 0.5, step: 0.01 },
      { path: 'paired_edges', label: 'paired edges: only a bright stripe’s two edges vote, not a seam, kerb or shadow (ours, beyond the paper)', kind: /** @type {const} */ ('bool') },
      SUPPORT_FRAMES,
      ADJACENT,
      SNAP,
      BENDS,
      NEEDS_PAINT,
      FROM_PAINT,
    ],
  },
  'danescu-stereo': {
    title: 'Danescu & Nedevschi 2011: particle filter on an 11-parameter 3-D lane',
    text: [
      'A particle is a whole 3-D lane: width W₀ and its rate, horizontal and vertical curvature, height Y₀, offset X_CW, pitch α, roll γ, yaw ψ and the two marking widths (eqs. 1-4).',
      'Each frame: resample keeping N − R particles and draw R from a generic distribution; drift every particle by the car’s speed and yaw rate, then diffuse; weigh each by projecting it into the image and comparing with distance transforms of marking and road edges (eqs. 9-14) and, with stereo, with a 3-D density image of road points. With stereo, curbs found as steps in an elevation map of the 3-D points join the markings (the “elevation map” layer).',
      'The estimate clusters the particles by X_CW (MBSAS) and averages the biggest cluster’s heavy particles (eq. 15). danescu-mono is our one-camera variant: a flat road, no density cue.',
    ],
    params: [
      PARTICLES,
      { path: 'init_fraction', label: 'R / N: initialisation share', min: 0, max: 0.5, step: 0.01 },
      { path: 'diffusion.5', label: 'diffusion of X_CW (m)', min: 0.005, max: 0.2, step: 0.005 },
      { path: 'diffusion.8', label: 'diffusion of ψ (rad)', min: 0.0005, max: 0.02, step: 0.0005 },
      { path: 'diffusion.0', label: 'diffusion of W₀ (m)', min: 0.005, max: 0.15, step: 0.005 },
      { path: 'sigma_edge_px', label: 'σ of the edge distance (px)', min: 0.5, max: 10, step: 0.5 },
      { path: 'sigma_density', label: 'σ_D of the density distance (cells; stereo only)', min: 0.25, max: 8, step: 0.25 },
      { path: 'marking_widths', label: 'marking widths and gradient cue (off: the previous approach)', kind: 'bool' },
      { path: 'start_iterations', label: 'start rounds on the first frame (ours; 0: the paper’s start)', min: 0, max: 30, step: 1 },
      { path: 'valid_distance_m', label: 'validity tolerance on the road (m; ours; 0: pixels only)', min: 0, max: 0.1, step: 0.005 },
      SUPPORT_FRAMES,
      { path: 'valid_marking_factor', label: 'support only with a marking edge within this many tolerances too (ours; 0: any road edge)', min: 0, max: 6, step: 0.5 },
      { path: 'valid_marking_sides', label: 'sides that need that marking support: 2 both, 1 at least one (ours)', min: 1, max: 2, step: 1 },
      RELOCK,
      ADJACENT,
      SNAP,
      BENDS,
      NEEDS_PAINT,
      FROM_PAINT,
    ],
  },
};
TRACKERS['danescu-mono'] = TRACKERS['danescu-stereo'];
TRACKERS['liu-ppf-nokernel'] = {
  ...TRACKERS['liu-ppf'],
  title: 'Liu et al. 2013, PPF-NoKernel: the paper’s baseline without the kernels',
  text: [
    'The same partitioned particle filter, but each edge pixel near a boundary counts only by the intensity kernel K_c of its grey level (eqs. 26-27, Sec. V-A): no position kernel, no orientation kernel, no gradient term. Compare it with liu-ppf on the same scene to see what the kernels buy.',
  ],
};

/** Value at `path` of an options object. */
/**
 * @param {Record<string, unknown>} options
 * @param {string} path
 */
export function getPath(options, path) {
  const [key, index] = path.split('.');
  const value = options[key];
  if (index === undefined) return value;
  return Array.isArray(value) ? value[Number(index)] : undefined;
}

/** `options` with `path` set to `value` (arrays copied, not shared). */
/**
 * @param {Record<string, unknown>} options
 * @param {string} path
 * @param {unknown} value
 * @returns {Record<string, unknown>}
 */
export function setPath(options, path, value) {
  const [key, index] = path.split('.');
  if (index === undefined) return { ...options, [key]: value };
  const array = [.../** @type {unknown[]} */ (options[key])];
  array[Number(index)] = value;
  return { ...options, [key]: array };
}
