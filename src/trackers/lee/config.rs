//! Settings of the Lee tracker (all optional in the tracker config; defaults documented).

use crate::error::{Error, Result};
use crate::num_text::Num;
use crate::vision::{CannyConfig, DldConfig};
use serde::{Deserialize, Serialize};

/// Which filter runs: the paper's cascade or one of the single-stage baselines it compares
/// against (same cues, same particle count).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Variant {
    /// The cascade particle filter: stage 1 [psi, y0, w, w'], stage 2 [c, delta] (Algorithm 1).
    Cascade,
    /// PF1: one filter over the first-order model [psi, y0, w, w'] (no curve).
    FirstOrder,
    /// PF2/PF3: one filter over all six states, weighed by both measurement models.
    FullModel,
}

/// Settings of `lee-cpf`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LeeConfig {
    /// Filter structure.
    pub variant: Variant,
    /// Particles of stage 2 (stage 1 and the single-stage filters use `particles`); 0: the
    /// same as stage 1.
    pub stage2_particles: usize,
    /// Nearest road distance measured, metres (raised to the first visible distance).
    pub near_m: f64,
    /// End of the near range (DLD, stage 1) and start of the far range (Canny, stage 2), m.
    pub split_m: f64,
    /// End of the far range, metres.
    pub far_m: f64,
    /// Spacing of the evaluation points x = 1..M of eqs. 31-32 in the near range, metres.
    pub near_step_m: f64,
    /// Spacing of the far-range evaluation points, metres.
    pub far_step_m: f64,
    /// Lateral half-range of the likelihood map, metres.
    pub lateral_range_m: f64,
    /// Cell size of the likelihood map (square cells), metres.
    pub cell_m: f64,
    /// DLD detector (eqs. 21-24): averaging window N (pixels) and threshold gamma.
    pub dld: DldConfig,
    /// Largest pattern length of a marking candidate (eq. 26), metres.
    pub max_marking_width_m: f64,
    /// Spread sigma_D that turns a distance d (m) into the likelihood exp(-d^2 / 2 sigma_D^2)
    /// of the map D (eq. 31).
    pub map_sigma_m: f64,
    /// Canny detector of the far range.
    pub canny: CannyConfig,
    /// Marking width assumed when matching far points to Canny edges, metres.
    pub marking_width_m: f64,
    /// Weight alpha of the boundary points (eq. 32).
    pub alpha: f64,
    /// Weight beta of the points inside the lane (eq. 32; negative: a marking there counts
    /// against the particle).
    pub beta: f64,
    /// Distance tau of the inside points from the boundaries (eqs. 29-30), metres.
    pub tau_m: f64,
    /// Standard deviation sigma of the Gaussian on q (eq. 33), in units of q (whose ideal
    /// value mu = 2 alpha).
    pub sigma_q: f64,
    /// Standard deviation of the stage-2 Gaussian on the fraction of far points on an edge.
    pub sigma_far: f64,
    /// Spiral length s_o of the clothoid (eq. 12), metres.
    pub spiral_length_m: f64,
    /// Diagonal of the process noise Q per frame (eq. 20): psi (rad), y0 (m), w (m), w' (m/m),
    /// c (m), delta (1/m). Calibrated, as the paper calibrates Q on ground-truth markings, on
    /// the simulator's truth (`examples/lee_calibrate_q.rs`): the largest frame-to-frame change
    /// at 30 fps of psi, y0 (a lane change) and w; for w', whose largest change is a step at
    /// the start of a width change, 0.0005 (the cloud follows the step in about 20 frames; a
    /// looser w' trades off against w, which the near range alone cannot separate); c moves by
    /// up to the distance driven per frame, about 1 m.
    pub process_sd: [f64; 6],
    /// Resample a stage when its effective sample size falls below this fraction of N
    /// (N_thr of Algorithm 1).
    pub ess_threshold: f64,
    /// Limits of the initial distribution and of the states: |psi| (rad).
    pub max_heading_rad: f64,
    /// Accepted lane widths [min, max], metres.
    pub width_range_m: [f64; 2],
    /// Largest |w'|.
    pub max_width_rate: f64,
    /// Largest c, metres (c ranges over [-spiral_length_m, max_transition_m]).
    pub max_transition_m: f64,
    /// Largest |delta|, 1/m.
    pub max_curvature: f64,
    /// Filter iterations on the first frame (and after a reset): the paper does not say how
    /// the filter starts; a uniform start needs a few rounds on the same frame to find the lane.
    pub start_iterations: usize,
    /// How much wider than Q the process noise of the first start iteration is; it narrows
    /// linearly to Q by the last (ours, like the start iterations: a cloud diffusing by Q
    /// alone stays where the uniform start's luckiest particles were, often on one marking
    /// at a wrong width).
    pub start_spread: f64,
    /// Share of the stage-1 particles drawn anew from the initial distribution in each of the
    /// first half of the start iterations (ours; 0 turns it off).
    pub start_fresh: f64,
    /// Restart from the initial distribution after this many consecutive frames in which no
    /// marking supports either boundary of the estimate (ours; 0: never).
    pub lost_restart: usize,
    /// Share of the stage-1 particles replaced, each frame the auto-calibration's line
    /// detector finds an ego pair, by draws around that pair on the road (its centre, width
    /// and heading with the process noise Q; w', c and delta kept): a data-driven proposal
    /// that lets a cloud stuck on a wrong lane re-lock (ours, beyond the paper; 0: off, the
    /// paper's filter).
    pub relock_share: f64,
    /// Share of the stage-1 particles of a first frame (the start, and after a restart) drawn
    /// around the ego pair the same bottom-up line detector finds in that frame, the rest
    /// from the initial distribution (ours: the paper does not say how the filter starts;
    /// 0.5 by default; 0: the uniform start alone, as before 2026-11-26). The detector then
    /// runs on first frames only, unless `relock_share` or an output option (`adjacent_lanes`,
    /// `snap_to_paint`, `valid_needs_paint`) needs it on every frame.
    pub start_pair_share: f64,
    /// Share of the stage-1 particles replaced, each frame after one on which one boundary of
    /// the estimate had near support (at least `valid_fraction`) and the other had none (under
    /// 0.05), by draws that keep the supported boundary where it is and take the width anew,
    /// uniform over `width_range_m`: a search for the lost side where the lane widens or
    /// narrows faster than the process noise lets the width follow (a turn pocket, a merge;
    /// ours, beyond the paper; 0: off, the paper's filter).
    pub side_search_share: f64,
    /// Standard deviation, 1/m, of a zero-mean Gaussian prior on the curvature delta,
    /// multiplied into stage 2's weights: p(c, delta | z) ~ N(f; 1, sigma_far^2) N(delta; 0,
    /// sd^2) (ours, beyond the paper, whose curvature is uniform within `max_curvature`; 0: off,
    /// the paper's filter). Where the far band holds little of the markings (a low camera
    /// looking level, low contrast near the horizon), a uniform prior lets the curve follow
    /// whatever edges are there: a barrier's top, a seam, roadside texture. Highway design
    /// keeps radii above a few hundred metres (delta under about 0.003 /m); 0.004 makes a 250 m
    /// radius cost half a nat and a 67 m one seven.
    pub curvature_prior_sd: f64,
    /// Report the lanes beside the ego lane (`left-adjacent`, `right-adjacent`) where the
    /// bottom-up detector's markings run beside an ego boundary at a lane's width
    /// ([`crate::trackers::adjacent_lanes`]; ours, beyond the paper, which follows the ego lane
    /// only; off by default).
    pub adjacent_lanes: bool,
    /// Kalman smoothing of the CPF output (Fig. 4).
    pub kalman: bool,
    /// Kalman process noise per frame, same order as `process_sd`.
    pub kalman_process_sd: [f64; 6],
    /// Kalman measurement noise (spread of the raw CPF estimate), same order.
    pub kalman_measurement_sd: [f64; 6],
    /// A frame is valid when, on each boundary, at least this fraction of the estimate's near
    /// points lie within sigma_D of a marking candidate (D >= exp(-1/2)).
    pub valid_fraction: f64,
    /// Validity: a side under `valid_fraction` this frame still counts when its mean support
    /// over the last this many frames (this one included; fewer since a reset) reaches
    /// `valid_fraction` and the other side this frame holds at least twice it
    /// ([`crate::trackers::support_memory`]; ours, beyond the paper; 1: this frame's alone,
    /// the default).
    pub valid_support_frames: usize,
    /// Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
    /// is not held back): the lane counts again only when a marking
    /// supports one of its boundaries within this many metres beyond the nearest measured
    /// distance, or within the longest such reach of the last 30 valid frames that saw both
    /// boundaries (a lane tracked between dashed lines accepts their gaps; see
    /// [`crate::trackers::reacquire`]; ours, beyond the paper; 0: off, the default; 4 in `real-roads`).
    /// Markings that begin only further ahead, past an unmarked crossing, are not yet the
    /// car's lane.
    pub reacquire_near_m: f64,
    /// Move each reported boundary onto the centre of the paint it lies on: a straight
    /// sideways correction fitted to the marking centres the bottom-up detector's marking
    /// image shows within 0.3 m of it, or 0.6 m where no run of paint lies within 0.3 m
    /// ([`crate::trackers::paint_snap`]; ours, beyond the
    /// paper; output only: the filter and the validity are unchanged; off by default).
    pub snap_to_paint: bool,
    /// With `snap_to_paint`: the snap follows the paint round a bend: each probe's search is
    /// centred on the line through the last run of paint centres, and the correction gets a
    /// quadratic term ([`crate::trackers::paint_snap`]; ours; off by default).
    pub snap_follows_bends: bool,
    /// Report a valid frame not valid when no run of paint begins along either drawn ego
    /// boundary within 12 m of its nearest probe (4 m ahead, or where the boundary comes
    /// into view; 12 m: a dashed line's longest common gap, so the paint beyond a crossing
    /// does not keep its near side valid): a run of at least four paint centres 0.5 m apart
    /// (1.5 m) and in four rows of the image, each within 10 cm of the last, found within
    /// 0.3 m of the boundary from 4 to 40 m ahead in the bottom-up detector's marking image
    /// ([`crate::trackers::paint_output`]; ours, beyond the paper; output only: the filter's
    /// own validity, which its other rules read, is unchanged; off by default).
    pub valid_needs_paint: bool,
    /// Report as valid a frame the filter finds not valid when paint runs along both drawn ego
    /// boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
    /// counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
    /// dashed line's gap), in the bottom-up detector's marking image
    /// ([`crate::trackers::paint_output`]; ours, beyond the paper; output only: the filter's
    /// own validity, which its other rules read, is unchanged; off by default).
    pub valid_from_paint: bool,
}

impl LeeConfig {
    /// The options of [`crate::trackers::paint_output`] (`snap_to_paint`, `valid_needs_paint`,
    /// `adjacent_lanes`).
    pub fn paint_options(&self) -> crate::trackers::paint_output::PaintOptions {
        crate::trackers::paint_output::PaintOptions {
            snap_to_paint: self.snap_to_paint,
            snap_follows_bends: self.snap_follows_bends,
            valid_needs_paint: self.valid_needs_paint,
            valid_from_paint: self.valid_from_paint,
            adjacent_lanes: self.adjacent_lanes,
        }
    }

    /// Whether an option needs the line detector on every frame (`relock_share`,
    /// `adjacent_lanes`, `snap_to_paint`, `valid_needs_paint`), not only on first frames
    /// (`start_pair_share`).
    pub fn detector_every_frame(&self) -> bool {
        self.relock_share > 0.0 || self.paint_options().any()
    }
}

impl Default for LeeConfig {
    fn default() -> Self {
        Self {
            variant: Variant::Cascade,
            stage2_particles: 0,
            near_m: 5.0,
            split_m: 20.0,
            far_m: 50.0,
            near_step_m: 1.0,
            far_step_m: 2.0,
            lateral_range_m: 8.0,
            cell_m: 0.1,
            dld: DldConfig {
                window: 3,
                gamma: 20.0,
            },
            max_marking_width_m: 0.45,
            map_sigma_m: 0.2,
            canny: CannyConfig {
                sigma: 1.0,
                low: 40.0,
                high: 100.0,
            },
            marking_width_m: 0.15,
            alpha: 1.0,
            beta: -0.5,
            tau_m: 0.6,
            sigma_q: 0.25,
            sigma_far: 0.25,
            spiral_length_m: 60.0,
            process_sd: [0.004, 0.06, 0.01, 0.0005, 1.5, 0.0002],
            ess_threshold: 0.5,
            max_heading_rad: 0.1,
            width_range_m: [2.5, 4.5],
            max_width_rate: 0.02,
            max_transition_m: 60.0,
            max_curvature: 0.02,
            start_iterations: 20,
            start_spread: 10.0,
            start_fresh: 0.2,
            lost_restart: 2,
            relock_share: 0.0,
            start_pair_share: 0.5,
            side_search_share: 0.0,
            curvature_prior_sd: 0.0,
            adjacent_lanes: false,
            snap_to_paint: false,
            snap_follows_bends: false,
            valid_needs_paint: false,
            valid_from_paint: false,
            kalman: true,
            kalman_process_sd: [0.003, 0.03, 0.01, 0.0005, 2.0, 0.0002],
            kalman_measurement_sd: [0.006, 0.05, 0.05, 0.002, 6.0, 0.0005],
            valid_fraction: 0.15,
            valid_support_frames: 1,
            reacquire_near_m: 0.0,
        }
    }
}

impl LeeConfig {
    /// Reads the tracker-specific options.
    ///
    /// # Errors
    /// [`Error::Config`] for an unknown option or a wrong type; [`Error::Parameter`] for a bad
    /// value.
    pub fn from_options(options: &crate::trackers::Options) -> Result<Self> {
        let config: Self = options.read(super::ID, |t| match t {
            crate::trackers::TrackerOptions::LeeCpf(c) => Some(c),
            _ => None,
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        crate::trackers::ranges::check_ranges(super::ID, self)?;
        // Every single value's range is checked above (`ranges::LEE`); what follows are the
        // checks between values.
        if !(self.near_m < self.split_m && self.split_m < self.far_m) {
            return Err(Error::parameter(
                "split_m",
                Num(self.split_m),
                "must lie between near_m and far_m",
            ));
        }
        let cells = (2.0 * self.lateral_range_m / self.cell_m)
            * ((self.split_m - self.near_m) / self.cell_m);
        if cells > 4.0e6 {
            return Err(Error::parameter(
                "cell_m",
                Num(self.cell_m),
                "gives a likelihood map of more than 4 million cells",
            ));
        }
        for (name, points) in [
            (
                "near_step_m",
                (self.split_m - self.near_m) / self.near_step_m,
            ),
            ("far_step_m", (self.far_m - self.split_m) / self.far_step_m),
        ] {
            if points > 10_000.0 {
                return Err(Error::parameter(
                    name,
                    Num(points),
                    "gives more than 10 000 evaluation points",
                ));
            }
        }
        let [lo, hi] = self.width_range_m;
        if hi <= lo {
            return Err(Error::parameter(
                "width_range_m",
                Num(hi),
                "max must exceed min",
            ));
        }
        // The Fresnel series is exact while the spiral turns by at most 1.5 rad.
        if self.max_curvature * self.spiral_length_m / 2.0 > 1.5 {
            return Err(Error::parameter(
                "max_curvature",
                Num(self.max_curvature),
                "times spiral_length_m / 2 (the spiral's turn) must be at most 1.5 rad",
            ));
        }
        Ok(())
    }
}
