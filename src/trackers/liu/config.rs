//! Settings of the Liu trackers (all optional in the tracker config; defaults documented).
//!
//! Values the paper gives are its defaults: the gradient mask threshold 10 (Sec. IV-C),
//! sigma_x^2 = sigma_y^2 = 1 (Sec. III-A), y_m at half the top-view height (Sec. III-C),
//! N' = 50 initialisation particles (Sec. IV-D), mu_0 = 1 and sigma_0^2 = 0.5 for the intensity
//! kernel (Sec. V-A), three boundaries (Fig. 3). The paper's validity checks are in pixels of
//! its top view (spacing > 12 px, spacing difference < 5 px); here they are in metres so they
//! hold at any resolution. What the paper leaves open is our choice, said so below.

use crate::error::{Error, Result};
use crate::num_text::Num;
use crate::vision::TopViewConfig;
use serde::{Deserialize, Serialize};

/// Largest number of boundaries n_l.
pub const MAX_BOUNDARIES: usize = 6;

/// Settings of `liu-ppf` and `liu-ppf-nokernel`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LiuConfig {
    /// The top view (IPM) the model lives on. Ours: 6 to 36 m ahead, 6 m to each side, 10 cm
    /// per pixel (120 x 300 pixels): three boundaries of 3.5 m lanes fit with room to move,
    /// and a 15 cm marking is 1.5 pixels wide, so sigma_x = 1 pixel is 10 cm.
    pub top_view: TopViewConfig,
    /// Number of boundaries n_l tracked (Fig. 3: 3).
    pub boundaries: usize,
    /// The split row y_m as a fraction of the top-view height (the paper: 0.5).
    pub split: f64,
    /// Gradient-magnitude threshold of the measurement mask (Sobel on 0-255 grey levels).
    pub gradient_threshold: f64,
    /// Variances sigma_x^2 and sigma_y^2 of the position kernels, pixels^2.
    pub position_variance_px2: f64,
    /// Mean mu_c of the intensity kernel K_c on the normalised image.
    pub intensity_mean: f64,
    /// Variance sigma_c^2 of the intensity kernel (the paper gives it for PPF-NoKernel only;
    /// we use the same for PPF-Kernel). 0.5 makes K_c nearly flat (a grey-40 pixel weighs 0.49
    /// of a white one); 0.05 (ours) discounts the noise the gradient mask passes on dark
    /// asphalt and halves the offset error on `night` (RESULTS, liu-ppf on curves, at night).
    pub intensity_variance: f64,
    /// Gauss-Hermite nodes of the parabolic kernel integral (eq. 12; the paper does not say how
    /// many). Three reproduce a fine numerical integral to 2.5e-4 relative on the slopes and
    /// bends a top view has (five: 5e-7), far below the kernels' own modelling error.
    pub quadrature_nodes: usize,
    /// Half-width, in pixels across the boundary, of the band whose mask pixels are "near the
    /// predicted lane" (the paper does not say; 3 = 3 sigma_x).
    pub band_px: usize,
    /// Initialisation particles N' added every frame (Sec. IV-D).
    pub init_particles: usize,
    /// Random walk of the linear part (eq. 19): sigma_rho (pixels) and sigma_theta (rad).
    pub sigma_rho_px: f64,
    /// See `sigma_rho_px`.
    pub sigma_theta: f64,
    /// Random walk of the parabolic part (eq. 23): sigma_d (pixels per pixel).
    pub sigma_d: f64,
    /// Smallest spacing between neighbouring boundaries, metres (the paper: 12 px).
    pub min_spacing_m: f64,
    /// Largest difference between neighbouring spacings, metres (the paper: 5 px).
    pub max_spacing_difference_m: f64,
    /// A frame is valid when both ego boundaries of the estimate have a strong edge pixel of
    /// their orientation (within 0.1 rad, gradient at least twice the threshold) within 1 pixel
    /// (sigma_x) in at least this fraction of the near rows (the paper does not define valid
    /// frames; this is ours, as for lee-cpf; a dashed line gives about 0.25).
    pub valid_fraction: f64,
    /// Validity: a side under `valid_fraction` this frame still counts when its mean support
    /// over the last this many frames (this one included; fewer since a reset) reaches
    /// `valid_fraction` and the other side this frame holds at least twice it
    /// ([`crate::trackers::support_memory`]; ours; 1: this frame's alone, the default).
    pub valid_support_frames: usize,
    /// Validity (ours, beyond the paper; 0: off, the default): besides the edge support, one
    /// ego boundary at least must show paint in `valid_fraction` of the near rows: a top-view
    /// pixel within 2 columns of its line brighter by this many grey levels than the road
    /// 0.3 m to either side ([`super::PAINT_REACH_M`]). A tree shadow's edge along the road is
    /// an edge of the boundary's orientation with no bright stripe, and would otherwise keep
    /// a lane through an unmarked crossing; one side is enough, so a kerb may bound the other.
    pub valid_paint_contrast: f64,
    /// Default lane model (Sec. IV-D): range of lane widths, metres.
    pub default_width_m: [f64; 2],
    /// Default lane model: largest heading of the straight boundaries, radians.
    pub default_heading_rad: f64,
    /// Default lane model: spread of each boundary about the parallel set, metres.
    pub default_jitter_m: f64,
    /// Share of the particles replaced, after the linear part's random walk, each frame the
    /// auto-calibration's line detector finds an ego pair, by default-model lanes placed on
    /// that pair (its width and heading, boundaries jittered by `default_jitter_m`): a
    /// data-driven proposal beside the paper's N' default-model particles (ours, beyond the
    /// paper; 0: off; see [`crate::trackers::relock`]).
    pub relock_share: f64,
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
    /// own validity, which its other rules read, is unchanged, and it stands on frames under
    /// 32x16, where the detector cannot run; off by default).
    pub valid_needs_paint: bool,
    /// Report as valid a frame the filter finds not valid when paint runs along both drawn ego
    /// boundaries, along one from the car (its first run of paint, as `valid_needs_paint`
    /// counts one, begins within 2 m of the nearest probe) and along the other within 10 m (a
    /// dashed line's gap), in the bottom-up detector's marking image
    /// ([`crate::trackers::paint_output`]; ours, beyond the paper; output only: the filter's
    /// own validity, which its other rules read, is unchanged; off by default).
    pub valid_from_paint: bool,
    /// Also report the lanes beside the ego lane on the sides the partitions leave out
    /// (`left-adjacent`, `right-adjacent`), where markings run beside an ego boundary at a
    /// lane's width in the bottom-up detector's marking image
    /// ([`crate::trackers::adjacent_lanes`]; ours, beyond the paper, whose boundaries are the
    /// partitions' alone; off by default).
    pub adjacent_lanes: bool,
    /// Ends the top view where the camera still resolves it (ours, beyond the paper, which
    /// names no range): its far end at most [`LiuConfig::resolved_distance_m`], where one
    /// top-view pixel spans [`MIN_COLUMNS_PER_TOP_VIEW_PIXEL`] image columns, but at least
    /// [`MIN_TOP_VIEW_LENGTH_M`] beyond its start; and a valid frame's support is counted over
    /// the view's nearest [`VALID_WINDOW_M`] (the default view's near part) rather than its
    /// near part, which a shorter view halves. Off: `top_view` and the near part as given.
    pub top_view_resolved: bool,
    /// Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
    /// is not held back): the lane counts again only when a strong edge supports one of its
    /// ego boundaries within this many metres beyond the top view's near end, or within the
    /// longest such reach of the last 30 valid frames that saw both boundaries (see
    /// [`crate::trackers::reacquire`]; ours, beyond the paper; 0: off, the default; 4 in
    /// `real-roads`). Markings that begin only further ahead, past an unmarked crossing, are
    /// not yet the car's lane.
    pub reacquire_near_m: f64,
    /// How the estimate picks its mode (the paper does not say how it reads its estimate off
    /// the particles): among the particles within half the minimum lane spacing of each of the
    /// `mode_candidates` heaviest particles, the set of the largest total weight, whose weighted
    /// mean is the estimate. 1 (the default): the heaviest particle's mode. More (ours, 32 in
    /// `real-roads`): a mode that many particles share wins over one heavy particle's, which on
    /// real footage is often a lane tilted about a far point.
    pub mode_candidates: usize,
}

/// Fewest image columns one top-view pixel must span across the road (`top_view_resolved`):
/// the image resolves f_x / x columns a metre at distance x, so a 10 cm pixel spans 1.5
/// columns out to x = f_x 0.1 / 1.5 (20.6 m for Caltech's f_x 309, 36 m from f_x 540).
pub const MIN_COLUMNS_PER_TOP_VIEW_PIXEL: f64 = 1.5;

/// Shortest top view `top_view_resolved` leaves, metres.
pub const MIN_TOP_VIEW_LENGTH_M: f64 = 10.0;

/// Length of the near window over which `top_view_resolved` counts a valid frame's support,
/// metres: the near part of the default 6-36 m view (split at half), more than one 12 m
/// cycle of a dashed line.
pub const VALID_WINDOW_M: f64 = 15.0;

impl Default for LiuConfig {
    fn default() -> Self {
        Self {
            top_view: TopViewConfig {
                x_min_m: 6.0,
                x_max_m: 36.0,
                y_left_m: 6.0,
                y_right_m: -6.0,
                m_per_px: 0.1,
            },
            boundaries: 3,
            split: 0.5,
            gradient_threshold: 10.0,
            position_variance_px2: 1.0,
            intensity_mean: 1.0,
            intensity_variance: 0.5,
            quadrature_nodes: 3,
            band_px: 3,
            init_particles: 50,
            sigma_rho_px: 1.0,
            sigma_theta: 0.004,
            sigma_d: 0.01,
            min_spacing_m: 2.4,
            max_spacing_difference_m: 0.5,
            valid_fraction: 0.15,
            valid_support_frames: 1,
            valid_paint_contrast: 0.0,
            default_width_m: [3.0, 4.0],
            default_heading_rad: 0.05,
            default_jitter_m: 0.1,
            relock_share: 0.0,
            snap_to_paint: false,
            snap_follows_bends: false,
            valid_needs_paint: false,
            valid_from_paint: false,
            adjacent_lanes: false,
            top_view_resolved: false,
            reacquire_near_m: 0.0,
            mode_candidates: 1,
        }
    }
}

impl LiuConfig {
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

    /// Reads the tracker-specific options.
    ///
    /// # Errors
    /// [`Error::Config`] for an unknown option or a wrong type; [`Error::Parameter`] for a bad
    /// value.
    pub fn from_options(id: &str, options: &crate::trackers::Options) -> Result<Self> {
        let config: Self = options.read(id, |t| match t {
            crate::trackers::TrackerOptions::LiuPpf(c) if id == super::ID => Some(c),
            crate::trackers::TrackerOptions::LiuPpfNokernel(c) if id == super::ID_NOKERNEL => {
                Some(c)
            }
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
        // Every single value's range is checked above (`ranges::LIU`); what follows are the
        // checks between values.
        let (w, h) = self.top_view.size()?;
        if w * h > 2_000_000 {
            return Err(Error::parameter(
                "top_view",
                format!("{w}x{h}"),
                "is larger than 2 million pixels",
            ));
        }
        let [lo, hi] = self.default_width_m;
        if hi < lo {
            return Err(Error::parameter(
                "default_width_m",
                Num(hi),
                "max must not be below min",
            ));
        }
        Ok(())
    }

    /// How far one top-view pixel spans [`MIN_COLUMNS_PER_TOP_VIEW_PIXEL`] image columns for a
    /// camera of horizontal focal length `fx` pixels: f_x m_per_px / x >= c gives x <= f_x
    /// m_per_px / c, metres.
    pub fn resolved_distance_m(&self, fx: f64) -> f64 {
        fx * self.top_view.m_per_px / MIN_COLUMNS_PER_TOP_VIEW_PIXEL
    }

    /// `top_view` for a camera of horizontal focal length `fx`: with `top_view_resolved` its far
    /// end brought in to [`LiuConfig::resolved_distance_m`], no nearer than
    /// [`MIN_TOP_VIEW_LENGTH_M`] beyond its start; as given otherwise.
    pub fn fitted_top_view(&self, fx: f64) -> TopViewConfig {
        let mut view = self.top_view;
        if self.top_view_resolved {
            let shortest = view.x_min_m + MIN_TOP_VIEW_LENGTH_M;
            view.x_max_m = view.x_max_m.min(self.resolved_distance_m(fx).max(shortest));
        }
        view
    }

    /// The first (farthest) top-view row of the support window of a view `height` rows high
    /// with split row `split_row` (rows run from the far end down to the near one): the rows
    /// below the split, or with `top_view_resolved` the rows of the nearest [`VALID_WINDOW_M`]
    /// (all rows of a shorter view). Both give row y_m + 1 on the default view.
    pub fn support_first_row(&self, height: usize, split_row: f64) -> usize {
        let first = if self.top_view_resolved {
            let v = &self.top_view;
            let beyond = (v.x_max_m - v.x_min_m - VALID_WINDOW_M) / v.m_per_px;
            if beyond > 0.0 {
                beyond.round() as usize + 1
            } else {
                0
            }
        } else {
            split_row.floor() as usize + 1
        };
        first.min(height)
    }

    /// The split row y_m of a top view `height` rows high.
    pub fn split_row(&self, height: usize) -> f64 {
        self.split * height as f64
    }
}
