//! Each output boundary moved onto the centre of the paint it was drawn on (option
//! `snap_to_paint`, ours, beyond the papers).
//!
//! A particle filter's estimate is a weighted mean (or mode) of particles spread by process
//! noise: on a still, or right after a jump, it lies some centimetres off the marking's centre:
//! on CULane's 1640-pixel stills a median 7-14 pixels from the labels near the car, up to half
//! of the 30-pixel line the benchmark scores.
//! After the estimate, each boundary y_b(x) (on the flat road of the camera,
//! `super::flat_boundary`) is moved by a straight correction fitted to the paint across it,
//!
//!   y(x) = y_b(x) + a + b (x - x̄),
//!
//! which keeps the estimate's curvature (with `snap_follows_bends`, below, a quadratic one):
//!
//! 1. At distances x every [`PROBE_STEP_M`] from [`NEAR_M`] to [`FAR_M`] (within the
//!    boundary's range) the marking intensity of the auto-calibration's working image
//!    ([`crate::calib`]; bilinear between its blocks) is sampled across the boundary, at road
//!    points y_b(x) + δ every [`STEP_M`].
//! 2. The brightest sample δ* within [`SEARCH_M`] is paint when it exceeds by
//!    [`MIN_CONTRAST`] the road [`BESIDE_M`] to either side of it, one of the two grey (the
//!    test of [`super::adjacent_lanes`]). The paint's centre c(x) is the middle of the span,
//!    within [`PAIR_M`] of δ*, where the intensity stays above half way from the brighter
//!    side's road to the peak (its ends interpolated between samples): the two strokes of a
//!    double line up to about 0.3 m across are one marking (a strip wider than about 2
//!    [`BESIDE_M`], a gutter or a car's side, fails the test against the road beside it).
//!    Known limit: the span reaches [`PAIR_M`] from the peak only, and the road is tested
//!    [`BESIDE_M`] from the peak, so a wider marking's centre is biased towards the stroke
//!    holding the peak (a 30 cm line by about 2 cm; a 15 / 15 / 15 cm double line by 6-12 cm,
//!    found at few distances).
//! 3. a and b by least squares over the centres, then again without those more than
//!    [`OUTLIER_M`] off the last fit, three times with a tighter tolerance each time; b = 0
//!    when the centres span less than [`MIN_SPAN_M`]; nothing moves with fewer than
//!    [`MIN_CENTRES`] centres, and |b| is at most [`MAX_SLOPE`].
//!
//! 4. Paint runs along the boundary (for `valid_needs_paint` and `valid_from_paint`,
//!    [`super::paint_output`]) when at least [`MIN_PAINT_RUN`] centres lie on neighbouring
//!    probes, each within [`RUN_STEP_M`] of the last, in as many rows of the working image:
//!    1.5 m of one marking near the car, where a crossing's transverse bars, a car's edges or
//!    a patch of glare give scattered centres. (Far off, one row spans several probes: a blob
//!    there counts once.) Known limit: a zebra crossing's stripes run along the road, 0.5 m
//!    wide and metres long, and one within 0.3 m of a boundary is a run like a line's.
//!    Where the first run begins, from the nearest probe, is [`Snapped::painted_from_m`] (for
//!    `valid_needs_paint` and `valid_from_paint`).
//! 5. Where steps 1-4 find no run of paint along the boundary, they run again with the peak
//!    looked for within [`WIDE_SEARCH_M`] (since 2026-12-01, session 37): an estimate more than
//!    0.3 m off its marking, as liu-ppf's right boundary after a gap in Caltech's sequence
//!    (0.3-0.56 m off the dashes) or a still's boundary on CULane, is moved onto it; where the
//!    first search found a run, nothing changes. Each probe samples only the span its search
//!    reads (a wider one near the image's edge would lose the probe).
//!
//! With `snap_follows_bends` (ours) the snap goes round a bend the estimate does not follow
//! (adachi-mmpf's straight model, a curvature the filter has not caught up with), where the
//! paint leaves the 0.3 m search some metres ahead:
//!
//! - each probe's search is centred on y_b(x) + g(x), g the least-squares line through the
//!   last [`GUIDE_CENTRES`] centres of the latest run of at least [`MIN_PAINT_RUN`] (step 4),
//!   extrapolated, its slope at most [`MAX_FOLLOW_SLOPE`] and its value at most
//!   [`MAX_FOLLOW_M`] from the boundary (with the search's [`SEARCH_M`], under half of a 3 m
//!   lane: it does not walk onto a neighbour's line); g = 0 until the first such run, so
//!   isolated centres (a crossing's bar, an arrow) do not steer it; it carries over a dashed
//!   line's gaps and is dropped after [`MAX_GUIDE_GAP_M`] without a centre;
//! - the correction is y(x) = y_b(x) + a + b t + q t^2, t = x - x̄, by least squares (the same
//!   outlier rounds); q = 0 unless the centres span [`MIN_BEND_SPAN_M`] with
//!   [`MIN_BEND_END_CENTRES`] in each outer third (a lone far centre would bend the curve
//!   through it); |q| <= [`MAX_FOLLOW_BEND`] (a change of curvature of 0.01 1/m), a and b
//!   solved again for a clamped q; |b| <= [`MAX_FOLLOW_SLOPE`] (0.2 rad instead of
//!   [`MAX_SLOPE`], with or without q); held at its ends as before.
//!
//! On straight paint it moves a boundary as the straight correction does to within a few
//! millimetres (`highway-straight`: mean ego error 4-13 mm, 0.6-2.7 mm more than without).
//!
//! Only the output moves: the filter's particles and validity are the tracker's own.

use super::adjacent_lanes::WorkingImages;
use super::flat_boundary::FlatBoundary;
use crate::camera::Camera;
use crate::image::Image;
use crate::lane::{Boundary, LaneEstimate, Role};

/// Nearest distance probed, metres.
pub const NEAR_M: f64 = 4.0;
/// Farthest distance probed, metres.
pub const FAR_M: f64 = 40.0;
/// Spacing of the probes along the boundary, metres.
pub const PROBE_STEP_M: f64 = 0.5;
/// How far either side of the boundary the paint's peak is looked for, metres.
pub const SEARCH_M: f64 = 0.3;
/// How far either side the peak is looked for again along a boundary where the search of
/// [`SEARCH_M`] found no run of paint, metres (step 5 of the module docs).
pub const WIDE_SEARCH_M: f64 = 0.6;
/// Spacing of the samples across the boundary, metres.
pub const STEP_M: f64 = 0.02;
/// How far either side of the peak the paint's span may reach, metres.
pub const PAIR_M: f64 = 0.2;
/// Where the road beside the peak is sampled, metres either side of it.
pub const BESIDE_M: f64 = super::adjacent_lanes::BESIDE_M;
/// Smallest excess of the peak over the road beside it (grey levels).
pub const MIN_CONTRAST: f64 = super::adjacent_lanes::MIN_CONTRAST as f64;
/// Largest saturation of grey road.
pub const MAX_ROAD_SATURATION: f64 = super::adjacent_lanes::MAX_ROAD_SATURATION as f64;
/// Residuals beyond which the centres are left out of the next fit, round by round, metres.
pub const OUTLIER_M: [f64; 3] = [0.12, 0.06, 0.04];
/// Fewest centres that move a boundary.
pub const MIN_CENTRES: usize = 6;
/// Smallest spread of the centres' distances for a slope, metres.
pub const MIN_SPAN_M: f64 = 8.0;
/// Largest change of the paint's centre between neighbouring probes of one run of paint,
/// metres.
pub const RUN_STEP_M: f64 = 0.1;
/// Fewest centres on neighbouring probes, in as many rows of the working image, that make a
/// run of paint (1.5 m of marking near the car).
pub const MIN_PAINT_RUN: usize = 4;
/// Largest slope b of the correction (radians, about 1.1 deg).
pub const MAX_SLOPE: f64 = 0.02;
/// With `snap_follows_bends`: the farthest the search's centre follows the paint from the
/// boundary, metres: with [`SEARCH_M`] the search stays under half of a 3 m lane (in the wide
/// search of step 5 the centre follows by as much less as the search reaches farther).
pub const MAX_FOLLOW_M: f64 = 1.2;
/// With `snap_follows_bends`: the distance without a centre after which the search is no
/// longer steered, metres (a dashed line's gap is about 9 m).
pub const MAX_GUIDE_GAP_M: f64 = 15.0;
/// With `snap_follows_bends`: the most recent centres of a run that steer the search.
pub const GUIDE_CENTRES: usize = 8;
/// With `snap_follows_bends`: the largest slope b of the correction and of the search's guide,
/// radians (about 11 deg; 0.02 without).
pub const MAX_FOLLOW_SLOPE: f64 = 0.2;
/// With `snap_follows_bends`: the largest quadratic term q of the correction (half a change of
/// curvature, 1/m).
pub const MAX_FOLLOW_BEND: f64 = 0.005;
/// With `snap_follows_bends`: the smallest spread of the centres' distances for a quadratic
/// term, metres.
pub const MIN_BEND_SPAN_M: f64 = 12.0;
/// With `snap_follows_bends`: the fewest centres in each outer third of their span for a
/// quadratic term (a lone centre would have the curve through it; a far dash seen at a few
/// probes is enough: with 3 or 4 `s-curve`'s error doubles, the test of the bends).
pub const MIN_BEND_END_CENTRES: usize = 2;

/// Probes along a boundary, at most.
const PROBES: usize = ((FAR_M - NEAR_M) / PROBE_STEP_M) as usize + 1;
/// Samples across a boundary at one distance, for the widest search: δ from
/// -(WIDE_SEARCH + PAIR) to +(WIDE_SEARCH + PAIR).
const HALF: usize = ((WIDE_SEARCH_M + PAIR_M) / STEP_M + 0.5) as usize;
const SAMPLES: usize = 2 * HALF + 1;
/// Samples between two projected knots; the knots span the samples exactly.
const KNOT: usize = 5;
const KNOTS: usize = (SAMPLES - 1) / KNOT + 1;
const _: () = assert!((SAMPLES - 1) % KNOT == 0);
// The narrow search's span falls on knots too (see `paint_centre`).
const _: () = assert!((HALF - ((SEARCH_M + PAIR_M) / STEP_M + 0.5) as usize) % KNOT == 0);

/// Moves every boundary of `boundaries` onto the paint beside it (the module docs); a boundary
/// without enough paint stays as it is. Returns how far the ego boundaries moved and where
/// paint begins to run along them ([`Snapped`]).
pub fn snap_to_paint(
    camera: &Camera,
    boundaries: &mut [Boundary],
    images: WorkingImages<'_>,
    bends: bool,
) -> Snapped {
    follow_paint(camera, boundaries, images, true, bends)
}

/// [`snap_to_paint`], the boundaries moved only when `moves` (without, what the snap finds).
pub fn follow_paint(
    camera: &Camera,
    boundaries: &mut [Boundary],
    images: WorkingImages<'_>,
    moves: bool,
    bends: bool,
) -> Snapped {
    let mut snapped = Snapped::default();
    for b in boundaries.iter_mut() {
        let Some(flat) = FlatBoundary::new(camera, b) else {
            continue;
        };
        let side = match b.role {
            Role::EgoLeft => Some(0),
            Role::EgoRight => Some(1),
            _ => None,
        };
        // Without moving, only the ego boundaries' paint is asked for.
        if side.is_none() && !moves {
            continue;
        }
        let mut found = correction(camera, images, &flat, bends && moves, SEARCH_M);
        if found.1.is_infinite() {
            found = correction(camera, images, &flat, bends && moves, WIDE_SEARCH_M);
        }
        let (c, from) = found;
        if let Some(k) = side {
            snapped.painted_from_m[k] = from;
        }
        let Some(c) = c else {
            continue;
        };
        if !moves {
            continue;
        }
        if let Some(moved) = flat.offset(camera, &|x| c.at(x), b.role) {
            if let Some(k) = side {
                snapped.moved_at_car[k] = c.at(0.0);
            }
            *b = moved;
        }
    }
    snapped
}

/// What [`snap_to_paint`] did to an estimate's ego boundaries (ego-left, ego-right).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapped {
    /// How far each moved at the car (x = 0, metres, positive left; 0 for one not moved).
    pub moved_at_car: [f64; 2],
    /// Where the first run of paint along each begins (at least [`MIN_PAINT_RUN`] centres on
    /// neighbouring probes, each within [`RUN_STEP_M`] of the last: step 4 of the module
    /// docs), metres beyond the nearest probe; infinite where paint runs nowhere along it.
    pub painted_from_m: [f64; 2],
}

impl Default for Snapped {
    fn default() -> Self {
        Self {
            moved_at_car: [0.0; 2],
            painted_from_m: [f64::INFINITY; 2],
        }
    }
}

/// Keeps an estimate's lateral offset and lane width those of its drawn ego boundaries after
/// they moved by `moved_at_car` ([`Snapped`]): the lane's centre moved by the mean of the
/// two, its width by their difference. The heading and curvature stay the filter's.
pub fn move_lane_figures(estimate: &mut LaneEstimate, moved_at_car: [f64; 2]) {
    let has = |role: Role| estimate.boundaries.iter().any(|b| b.role == role);
    // Without the pair the figures are not the pair's (liu-ppf then reports zeros).
    if !(has(Role::EgoLeft) && has(Role::EgoRight)) {
        return;
    }
    let [left, right] = moved_at_car;
    estimate.lateral_offset_m -= (left + right) / 2.0;
    estimate.lane_width_m += left - right;
}

/// The correction a + b t + q t^2, t = x - x̄ (q = 0 without `snap_follows_bends`), held at
/// its ends beyond the distances of the centres it was fitted to.
#[derive(Debug, Clone, Copy)]
struct Correction {
    a: f64,
    b: f64,
    q: f64,
    mid: f64,
    near: f64,
    far: f64,
}

impl Correction {
    /// The lateral move at distance `x`, metres.
    fn at(&self, x: f64) -> f64 {
        let t = crate::math::clamp(x, self.near, self.far) - self.mid;
        self.a + self.b * t + self.q * t * t
    }
}

/// The correction for `flat` (steps 1-3 of the module docs) and where the first run of
/// [`MIN_PAINT_RUN`] paint centres found along it began beyond the nearest probe
/// ([`Snapped::painted_from_m`]).
fn correction(
    camera: &Camera,
    images: WorkingImages<'_>,
    flat: &FlatBoundary,
    bends: bool,
    search_m: f64,
) -> (Option<Correction>, f64) {
    // The guide's reach shrinks as the search widens: together they stay within half a lane.
    let max_follow = MAX_FOLLOW_M + SEARCH_M - search_m;
    let (near, far) = flat.range();
    let (from, to) = (near.max(NEAR_M), far.min(FAR_M));
    // The centres found, [x, c], on the stack: a frame allocates nothing here.
    let mut centres = [[0.0f64; 2]; PROBES];
    let mut n = 0;
    // The run of paint in progress: its length in working-image rows (probes that fall in the
    // row of the last one counted add nothing: far off, one row spans several probes, and a
    // blob there would make a run) and that row.
    let (mut run, mut run_row) = (0usize, i64::MIN);
    // With `bends`: the line (x0, c at x0, slope) through the latest run of paint's last
    // centres, on which the next probe's search is centred, and where that run began.
    let mut guide: Option<(f64, f64, f64)> = None;
    let mut run_start = 0usize;
    // Where the first run of paint (MIN_PAINT_RUN rows) began, metres.
    let (mut run_x, mut painted_from) = (0.0f64, f64::INFINITY);
    for k in 0..PROBES {
        let x = from + k as f64 * PROBE_STEP_M;
        if x > to {
            break;
        }
        // A guide that has seen no paint for MAX_GUIDE_GAP_M steers no more.
        if guide.is_some() && n > 0 && x - centres[n - 1][0] > MAX_GUIDE_GAP_M {
            guide = None;
        }
        let shift = guide.map_or(0.0, |(x0, c0, slope)| {
            crate::math::clamp(c0 + slope * (x - x0), -max_follow, max_follow)
        });
        let y = flat.y_at(x) + shift;
        if let Some(c) = paint_centre(camera, images, x, y, search_m).map(|c| c + shift) {
            let row = camera
                .road_to_pixel(x, flat.y_at(x) + c)
                .map_or(i64::MIN, |[_, v]| (v / images.2 as f64).floor() as i64);
            let continues = n > 0 && {
                let [px, pc] = centres[n - 1];
                (x - px - PROBE_STEP_M).abs() < 1e-6 && (c - pc).abs() <= RUN_STEP_M
            };
            if !continues {
                (run, run_row, run_start, run_x) = (1, row, n, x);
            } else if row != run_row {
                (run, run_row) = (run + 1, row);
            }
            if run >= MIN_PAINT_RUN && painted_from.is_infinite() {
                painted_from = run_x - from;
            }
            centres[n] = [x, c];
            n += 1;
            if bends && run >= MIN_PAINT_RUN {
                guide = line_fit_any(&centres[run_start.max(n.saturating_sub(GUIDE_CENTRES))..n])
                    .map(|(x0, c0, slope)| {
                        (x0, c0, slope.clamp(-MAX_FOLLOW_SLOPE, MAX_FOLLOW_SLOPE))
                    });
            }
        }
    }
    (fit_centres(&mut centres, n, bends), painted_from)
}

/// (x̄, c at x̄, slope) of the least-squares line through `points` ([x, c]), two or more at
/// different distances.
fn line_fit_any(points: &[[f64; 2]]) -> Option<(f64, f64, f64)> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let mid = points.iter().map(|p| p[0]).sum::<f64>() / n;
    let a = points.iter().map(|p| p[1]).sum::<f64>() / n;
    let (sxx, sxc) = points.iter().fold((0.0, 0.0), |(sxx, sxc), &[x, c]| {
        (sxx + (x - mid) * (x - mid), sxc + (x - mid) * (c - a))
    });
    (sxx > 0.0).then(|| (mid, a, sxc / sxx))
}

/// The correction through the first `n` of `centres` after the outlier rounds (step 3).
fn fit_centres(centres: &mut [[f64; 2]; PROBES], mut n: usize, bends: bool) -> Option<Correction> {
    let fit_any = |points: &[[f64; 2]]| {
        if bends {
            curve_fit(points)
        } else {
            line_fit(points).map(|(a, b, mid)| (a, b, 0.0, mid))
        }
    };
    // Each round drops the centres off the last fit by more than its tolerance.
    let mut fit = fit_any(&centres[..n])?;
    for tolerance in OUTLIER_M {
        let (a, b, q, mid) = fit;
        let mut kept = 0;
        for k in 0..n {
            let [x, c] = centres[k];
            let t = x - mid;
            if (c - a - b * t - q * t * t).abs() <= tolerance {
                centres[kept] = centres[k];
                kept += 1;
            }
        }
        n = kept;
        fit = fit_any(&centres[..n])?;
    }
    let (a, b, q, mid) = fit;
    let max_b = if bends { MAX_FOLLOW_SLOPE } else { MAX_SLOPE };
    Some(Correction {
        a,
        b: b.clamp(-max_b, max_b),
        q,
        mid,
        near: centres[0][0],
        far: centres[n - 1][0],
    })
}

/// Least squares a + b t + q t^2 (t = x - x̄) through `points`: (a, b, q, x̄), |q| at most
/// [`MAX_FOLLOW_BEND`] with a and b solved again for the clamped q. q = 0 ([`line_fit`]'s)
/// unless the centres span [`MIN_BEND_SPAN_M`] and each outer third of the span holds
/// [`MIN_BEND_END_CENTRES`] of them: a lone far centre would bend the curve through it.
pub(super) fn curve_fit(points: &[[f64; 2]]) -> Option<(f64, f64, f64, f64)> {
    let (a, b, mid) = line_fit(points)?;
    let (first, last) = (points[0][0], points[points.len() - 1][0]);
    let span = last - first;
    let near = points.iter().filter(|p| p[0] <= first + span / 3.0).count();
    let far = points.iter().filter(|p| p[0] >= last - span / 3.0).count();
    if span < MIN_BEND_SPAN_M || near.min(far) < MIN_BEND_END_CENTRES {
        return Some((a, b, 0.0, mid));
    }
    // Normal equations in (a, b, q) with t centred (sum t = 0):
    //   n a + s2 q = sc,  s2 b + s3 q = stc,  s2 a + s3 b + s4 q = st2c.
    let (mut s2, mut s3, mut s4, mut sc, mut stc, mut st2c) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for &[x, c] in points {
        let t = x - mid;
        s2 += t * t;
        s3 += t * t * t;
        s4 += t * t * t * t;
        sc += c;
        stc += t * c;
        st2c += t * t * c;
    }
    let n = points.len() as f64;
    // a and b from the first two for a given q, put into the third: q times the spread of t^2
    // left after fitting 1 and t (positive for three or more distances) is the same of c.
    let spread = s4 - s2 * s2 / n - s3 * s3 / s2;
    if spread <= 1e-12 * s4 {
        return Some((a, b, 0.0, mid));
    }
    let q =
        ((st2c - s2 * sc / n - s3 * stc / s2) / spread).clamp(-MAX_FOLLOW_BEND, MAX_FOLLOW_BEND);
    // The first two equations give a and b for any q: the clamped q's.
    Some(((sc - s2 * q) / n, (stc - s3 * q) / s2, q, mid))
}

/// Least-squares a + b (x - x̄) through `points` ([x, c]): (a, b, x̄); b = 0 when they span
/// less than [`MIN_SPAN_M`]; `None` with fewer than [`MIN_CENTRES`].
fn line_fit(points: &[[f64; 2]]) -> Option<(f64, f64, f64)> {
    if points.len() < MIN_CENTRES {
        return None;
    }
    let (mid, a, b) = line_fit_any(points)?;
    let span = points[points.len() - 1][0] - points[0][0];
    Some((a, if span >= MIN_SPAN_M { b } else { 0.0 }, mid))
}

/// The centre of the paint across road point (x, y), as an offset from y (step 2 of the
/// module docs); `None` without paint or out of view.
fn paint_centre(
    camera: &Camera,
    images: WorkingImages<'_>,
    x: f64,
    y: f64,
    search_m: f64,
) -> Option<f64> {
    let (m, saturation, scale) = images;
    let at = |image: &Image<u8>, d: f64| -> Option<f64> {
        let [u, v] = camera.road_to_pixel(x, y + d)?;
        bilinear(image, scale, u, v)
    };
    // Only the samples this search reads, [lo, hi] of the widest layout (centre HALF), so a
    // narrow search near the image's edge is not lost to samples it never needs.
    let reach = (search_m / STEP_M).round() as usize;
    let pair = (PAIR_M / STEP_M).round() as usize;
    let (lo, hi) = (HALF - reach - pair, HALF + reach + pair);
    // The samples' pixels interpolated between projected knots every KNOT samples: across
    // 10 cm of road the image of the lateral line is straight to well under a pixel.
    // lo and hi fall on knots (both searches' spans are whole multiples of KNOT samples): the
    // sample at hi is its knot itself (t = 0), so no knot beyond it is projected.
    let mut knots = [[0.0f64; 2]; KNOTS];
    let last_knot = hi.div_ceil(KNOT).min(KNOTS - 1);
    for (k, p) in knots
        .iter_mut()
        .enumerate()
        .take(last_knot + 1)
        .skip(lo / KNOT)
    {
        *p = camera.road_to_pixel(x, y + ((k * KNOT) as f64 - HALF as f64) * STEP_M)?;
    }
    let mut profile = [0.0f64; SAMPLES];
    for (k, p) in profile.iter_mut().enumerate().take(hi + 1).skip(lo) {
        let (i, t) = ((k / KNOT).min(KNOTS - 2), (k % KNOT) as f64 / KNOT as f64);
        let t = if k == SAMPLES - 1 { 1.0 } else { t };
        let ([u0, v0], [u1, v1]) = (knots[i], knots[i + 1]);
        *p = bilinear(m, scale, u0 + t * (u1 - u0), v0 + t * (v1 - v0))?;
    }
    let (peak, &top) = profile[HALF - reach..=HALF + reach]
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))?;
    let peak = peak + HALF - reach;
    let delta = (peak as f64 - HALF as f64) * STEP_M;
    let mut road = f64::MIN;
    let mut grey = false;
    for side in [-BESIDE_M, BESIDE_M] {
        let level = at(m, delta + side)?;
        if top - level < MIN_CONTRAST {
            return None;
        }
        road = road.max(level);
        grey |= at(saturation, delta + side)? <= MAX_ROAD_SATURATION;
    }
    if !grey {
        return None;
    }
    let half = (top + road) / 2.0;
    let first = (peak - pair..=peak).find(|&k| profile[k] >= half)?;
    let last = (peak..=peak + pair).rev().find(|&k| profile[k] >= half)?;
    // The crossings of the half level, interpolated between the samples either side.
    let crossing = |inside: usize, outside: usize| -> f64 {
        let (vi, vo) = (profile[inside], profile[outside]);
        let t = if vi > vo {
            (vi - half) / (vi - vo)
        } else {
            0.0
        };
        inside as f64 + t.clamp(0.0, 1.0) * (outside as f64 - inside as f64)
    };
    let left = if first > lo {
        crossing(first, first - 1)
    } else {
        first as f64
    };
    let right = if last < hi {
        crossing(last, last + 1)
    } else {
        last as f64
    };
    Some(((left + right) / 2.0 - HALF as f64) * STEP_M)
}

/// The working image `image` (blocks of `scale` pixels) at full-resolution pixel (u, v),
/// bilinear between block centres; `None` outside them.
fn bilinear(image: &Image<u8>, scale: usize, u: f64, v: f64) -> Option<f64> {
    let s = scale as f64;
    let (i, j) = ((u - (s - 1.0) / 2.0) / s, (v - (s - 1.0) / 2.0) / s);
    let (w, h) = (image.width(), image.height());
    if !(i >= 0.0 && j >= 0.0 && i <= (w - 1) as f64 && j <= (h - 1) as f64) {
        return None;
    }
    let (i0, j0) = (i.floor() as usize, j.floor() as usize);
    let (i1, j1) = ((i0 + 1).min(w - 1), (j0 + 1).min(h - 1));
    let (ti, tj) = (i - i0 as f64, j - j0 as f64);
    let g = |i: usize, j: usize| f64::from(image.get(i, j));
    let top = g(i0, j0) * (1.0 - ti) + g(i1, j0) * ti;
    let bottom = g(i0, j1) * (1.0 - ti) + g(i1, j1) * ti;
    Some(top * (1.0 - tj) + bottom * tj)
}
