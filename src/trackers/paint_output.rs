//! Our output options beyond the papers that read the paint, applied in one order by every
//! mono tracker to its estimate's boundaries (ours; each off by default):
//!
//! 1. `snap_to_paint` moves each boundary onto the centre of the paint it lies on
//!    ([`super::paint_snap`]);
//! 2. `valid_needs_paint` reports a valid frame not valid when no run of paint lies along
//!    either ego boundary ([`Snapped::painted`]): a filter holds its lane through an unmarked
//!    crossing or on a car's edges by its own support, which counts edges, not paint. The
//!    test reads the snap's own probes, so with `snap_to_paint` a frame it reports not valid
//!    has had its boundaries moved already (onto scattered paint: a move needs centres that
//!    fit a line, not a run); the frame is drawn as not valid either way;
//! 3. `adjacent_lanes` adds the neighbours on the sides the tracker's own boundaries leave out
//!    ([`super::adjacent_lanes`]), moved onto their paint with `snap_to_paint`, on a frame
//!    still valid.
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
}

impl PaintOptions {
    /// Whether any of them is on (the tracker then needs its line detector's marking image).
    pub fn any(&self) -> bool {
        self.snap_to_paint || self.valid_needs_paint || self.adjacent_lanes
    }
}

/// Applies `options` to `boundaries`, a frame's estimate, `valid` by the filter's own rule, in
/// the marking image of `detector` (the frame's; `None` when the tracker has none). Returns
/// the frame's reported validity and what the snap did to the ego boundaries (nothing moves,
/// and the validity is the filter's, on a frame the filter found not valid).
pub fn apply_paint_options(
    camera: &Camera,
    boundaries: &mut Vec<Boundary>,
    detector: Option<&RelockDetector>,
    valid: bool,
    options: PaintOptions,
) -> (bool, Snapped) {
    let Some(images) = detector
        .filter(|_| valid)
        .map(RelockDetector::working_images)
    else {
        return (valid, Snapped::default());
    };
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
    let valid = !options.valid_needs_paint || snapped.painted.iter().any(|&p| p);
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
