//! Our output options beyond the papers that read the paint, applied in one order by every
//! mono tracker to its estimate's boundaries (ours; each off by default; the rescue of a frame
//! not valid, `valid_from_paint`, below them):
//!
//! 1. `snap_to_paint` moves each boundary onto the centre of the paint it lies on
//!    ([`super::paint_snap`]);
//! 2. `valid_needs_paint` reports a valid frame not valid when no run of paint begins along
//!    either ego boundary within [`NEEDS_PAINT_WITHIN_M`] of its nearest probe
//!    ([`Snapped::painted_from_m`]): a filter holds its lane through an unmarked crossing or
//!    on a car's edges by its own support, which counts edges, not paint, and on the near
//!    side of a crossing the paint beyond it is no lane for the car yet. The
//!    test reads the snap's own probes, so with `snap_to_paint` a frame it reports not valid
//!    has had its boundaries moved already (onto scattered paint: a move needs centres that
//!    fit a line, not a run); the frame is drawn as not valid either way;
//! 3. `adjacent_lanes` adds the neighbours on the sides the tracker's own boundaries leave out
//!    ([`super::adjacent_lanes`]), moved onto their paint with `snap_to_paint`, on a frame
//!    still valid.
//!
//! Before them, on a frame the filter finds not valid, `valid_from_paint` reports it valid
//! (and the three then apply) when the same probes find runs of paint along both ego
//! boundaries, the first run along one beginning within [`FROM_PAINT_NEAR_M`] of its nearest
//! probe (4 m ahead, or where the boundary comes into view) and along the other within
//! [`FROM_PAINT_FAR_M`] ([`Snapped::painted_from_m`]): paint from the car on one side and a
//! dashed line's next dash on the other. A filter's validity counts its own cue
//! (danescu-mono: road edges within its tolerance of the inner edges) and can fall short where
//! the paint is plain (Caltech's turn pocket, 200-216); the far side of a crossing, whose
//! paint begins ahead on both sides, stays not valid. The filter, whose rules read its own
//! validity, is unchanged.
//!
//! All read the marking image of the tracker's bottom-up line detector ([`super::relock`]) and
//! change nothing in the filter: its particles and its own validity, which its other rules
//! (support memory, re-acquisition) read, are as without them.

use super::adjacent_lanes::adjacent_boundaries;
use super::paint_snap::{follow_paint, snap_to_paint, Snapped};
use super::relock::RelockDetector;
use crate::camera::Camera;
use crate::lane::Boundary;

/// The options, as a tracker's configuration sets them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PaintOptions {
    /// `snap_to_paint`.
    pub snap_to_paint: bool,
    /// `snap_follows_bends`.
    pub snap_follows_bends: bool,
    /// `valid_needs_paint`.
    pub valid_needs_paint: bool,
    /// `adjacent_lanes`.
    pub adjacent_lanes: bool,
    /// `valid_from_paint`.
    pub valid_from_paint: bool,
}

impl PaintOptions {
    /// Whether any of them is on (the tracker then needs its line detector's marking image).
    pub fn any(&self) -> bool {
        self.snap_to_paint || self.valid_needs_paint || self.adjacent_lanes || self.valid_from_paint
    }
}

/// With `valid_from_paint`: the farthest the first run of paint along one ego boundary may
/// begin beyond its nearest probe (4 m ahead, or where the boundary comes into view), metres
/// (four probe steps: paint from the car).
pub const FROM_PAINT_NEAR_M: f64 = 2.0;
/// With `valid_from_paint`: the farthest the first run of paint along the other ego boundary
/// may begin beyond its nearest probe, metres: a US dashed line's 9 m gap and a probe. A
/// longer gap (12 m on some European motorways), or a dash's tail too short for a run at the
/// nearest probe with the next dash a gap beyond, fails it: the frame stays as the filter
/// found it.
pub const FROM_PAINT_FAR_M: f64 = 10.0;

/// With `valid_needs_paint`: the farthest a run of paint along either ego boundary may begin
/// beyond its nearest probe (4 m ahead, or where the boundary comes into view) for the frame
/// to stay valid, metres: the longest common gap of a dashed line (12 m on European
/// motorways, 9 m in the US), so a lane between two dashed lines stays valid whatever their
/// phase. Paint that begins farther off is the far side of an unmarked stretch (a crossing, a
/// junction). Until 2026-12-01 (session 37) a run anywhere up to 40 m ahead kept a frame
/// valid, and the paint beyond a simulated crossing kept a lane on its near side
/// (`no_lane_eval`: RESULTS.md, *No lane*). With 10 m instead ([`FROM_PAINT_FAR_M`]) the
/// lane came back 2 frames later after each crossing and liu-ppf lost Caltech's frame 123,
/// held across a gap in the sequence, on every tracker seed.
pub const NEEDS_PAINT_WITHIN_M: f64 = 12.0;

/// Whether paint near the car keeps valid a frame the filter found valid
/// (`valid_needs_paint`): a run along either ego boundary beginning within
/// [`NEEDS_PAINT_WITHIN_M`] of its nearest probe.
pub fn paint_keeps_valid(snapped: &Snapped) -> bool {
    snapped
        .painted_from_m
        .iter()
        .any(|&from| from <= NEEDS_PAINT_WITHIN_M)
}

/// Whether runs of paint along the ego boundaries make valid a frame the filter found not
/// valid (`valid_from_paint`): along one from the car ([`FROM_PAINT_NEAR_M`]), along the other
/// within [`FROM_PAINT_FAR_M`] ([`Snapped::painted_from_m`]).
pub fn paint_makes_valid(snapped: &Snapped) -> bool {
    let [left, right] = snapped.painted_from_m;
    left.min(right) <= FROM_PAINT_NEAR_M && left.max(right) <= FROM_PAINT_FAR_M
}

/// Applies `options` to `boundaries`, a frame's estimate, `valid` by the filter's own rule, in
/// the marking image of `detector` (the frame's; `None` when the tracker has none). Returns
/// the frame's reported validity and what the snap did to the ego boundaries (nothing moves,
/// and the validity is the filter's, on a frame the filter found not valid and
/// `valid_from_paint` does not make valid).
pub fn apply_paint_options(
    camera: &Camera,
    boundaries: &mut Vec<Boundary>,
    detector: Option<&RelockDetector>,
    valid: bool,
    options: PaintOptions,
) -> (bool, Snapped) {
    let Some(images) = detector
        .filter(|_| valid || options.valid_from_paint)
        .map(RelockDetector::working_images)
    else {
        return (valid, Snapped::default());
    };
    // Without moving anything: only the ego boundaries' paint is asked for.
    if !valid && !paint_makes_valid(&follow_paint(camera, boundaries, images, false, false)) {
        return (false, Snapped::default());
    }
    let snapped = if options.snap_to_paint || options.valid_needs_paint {
        follow_paint(
            camera,
            boundaries,
            images,
            options.snap_to_paint,
            options.snap_follows_bends,
        )
    } else {
        Snapped::default()
    };
    let valid = !options.valid_needs_paint || paint_keeps_valid(&snapped);
    if valid && options.adjacent_lanes {
        // Only the sides the tracker's own boundaries leave out.
        let mut adjacent = adjacent_boundaries(camera, boundaries, images);
        if options.snap_to_paint {
            snap_to_paint(camera, &mut adjacent, images, options.snap_follows_bends);
        }
        boundaries.extend(adjacent);
    }
    (valid, snapped)
}
