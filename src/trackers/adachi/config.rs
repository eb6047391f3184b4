//! Settings of the Adachi tracker (all optional in the tracker config; defaults documented).

use crate::error::{Error, Result};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// Which side of a marking votes (Sec. 3.2 uses the left edge of each white line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Polarity {
    /// Dark to light going right: the left edge of a bright marking (the paper's choice).
    LeftEdge,
    /// Light to dark going right: the right edge.
    RightEdge,
    /// Both edges.
    Both,
}

/// What an edge point's strength is (Sec. 3.2: "the edge image"; the paper names no operator).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EdgeResponse {
    /// The horizontal Sobel response g_x of the polarity (our reading since the first
    /// increment). A boundary at lateral distance Y seen from a camera h metres high crosses
    /// the image at an angle whose tangent is h / |Y|, and g_x falls with it: the neighbours'
    /// outer lines (|Y| about 1.5 w, 5-6 m) give a fifth to a third of an ego line's g_x.
    Horizontal,
    /// Ours: the Sobel gradient magnitude sqrt(g_x^2 + g_y^2), with the polarity still from
    /// the sign of g_x (a left edge is dark to light going right). The same threshold then
    /// passes a line at any angle (see [`super::votes`]).
    Gradient,
}

/// The lane boundaries' shape along the road.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LaneShape {
    /// Straight lines parallel to the car: the paper's model (Sec. 3.2).
    Straight,
    /// Not in the paper: the edge points are straightened by the road's bend and heading
    /// before they vote ([`super::road_shape`]), and the boundaries are drawn bent.
    Curved,
}

/// Settings of `adachi-mmpf`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AdachiConfig {
    /// Nearest road distance of the voting region (the box of Fig. 3a), metres.
    pub near_m: f64,
    /// Farthest road distance of the voting region, metres.
    pub far_m: f64,
    /// Half-range of the rho axis, metres (bins cover [-rho_range, rho_range)).
    pub rho_range_m: f64,
    /// Histogram bin size, metres.
    pub bin_m: f64,
    /// Edge polarity.
    pub polarity: Polarity,
    /// Sobel response an edge point needs (grey levels x 4): g_x, or the gradient magnitude
    /// with `edge_response: "gradient"`.
    pub edge_threshold: f64,
    /// `horizontal` (g_x of the polarity, the default) or `gradient` (ours: the gradient
    /// magnitude, the polarity from the sign of g_x), see [`EdgeResponse`].
    pub edge_response: EdgeResponse,
    /// Marking width assumed by the template H_bar, metres.
    pub marking_width_m: f64,
    /// Spread of edge positions around the template's edge, metres (added to the bin width in
    /// quadrature).
    pub edge_sigma_m: f64,
    /// Filter iterations on the first frame (and after a reset) before the first estimate:
    /// the paper does not say how the filter starts; a uniform start needs a few predict /
    /// weigh / resample rounds on the same votes to find the lane.
    pub start_iterations: usize,
    /// Weight beta of the noise histogram N_j (eq. 4).
    pub beta: f64,
    /// Random-walk standard deviation sigma_q of the lane position per frame, metres (eq. 8).
    pub sigma_q_m: f64,
    /// Random-walk standard deviation sigma_w of the lane width per frame, metres (eq. 7).
    pub sigma_w_m: f64,
    /// Lane widths accepted, metres ([min, max]); particles outside are clamped.
    pub width_range_m: [f64; 2],
    /// Model transition matrix pi (rows: from model 1..4), Table 1 by default.
    pub transitions: Vec<Vec<f64>>,
    /// A frame is valid when each ego boundary of the estimate has at least this vote support:
    /// the share of the voting region's rows in which its edge voted (see
    /// [`super::likelihood::Likelihood::support`]). Not in the paper, which does not define a
    /// valid frame.
    pub valid_support: f64,
    /// Validity: a side under `valid_support` this frame still counts when its mean support
    /// over the last this many frames (this one included; fewer since a reset) reaches
    /// `valid_support` and the other side this frame holds at least twice it
    /// ([`crate::trackers::support_memory`]; ours; 1: this frame's alone, the default).
    pub valid_support_frames: usize,
    /// `straight` (the paper) or `curved` (ours: see [`super::road_shape`]).
    pub lane_shape: LaneShape,
    /// `curved` only: the largest heading of the lane to the car searched, radians (0 to 0.5).
    pub max_heading_rad: f64,
    /// `curved` only: the largest curvature searched, 1/m (0 to 0.05, a 20 m radius).
    pub max_curvature_per_m: f64,
    /// `curved` only: how far the followed shape moves to each frame's best (0.01 to 1).
    pub shape_gain: f64,
    /// Share of the particles replaced, each frame the auto-calibration's line detector finds
    /// an ego pair, by draws around that pair on the road (its centre where the votes measure
    /// q, its width, with sigma_q and sigma_w; the model r kept): a data-driven proposal that
    /// lets a cloud stuck on a wrong lane re-lock (ours, beyond the paper; 0: off, the
    /// paper's filter; see [`crate::trackers::relock`]).
    pub relock_share: f64,
    /// Share of the initial particles (first frame, and after a reset) drawn around the ego
    /// pairs the first frame's vote histogram forms ([`super::pairs`]), the rest uniform; their
    /// model r uniform. The paper leaves the start open; 0 gives the uniform start we had until
    /// 2026-11-26, which locks in on false modes (see [`super::pairs`]).
    pub start_pair_share: f64,
    /// Share of the particles redrawn each frame around the ego pairs of the frame's vote
    /// histogram ([`super::pairs`]), model r uniform: a data-driven proposal from the paper's
    /// own cue that lets a locked or lost cloud find the lane again (ours, beyond the paper;
    /// 0: off, the paper's filter). It also finds a false lane where that is the likelihood's
    /// maximum (a guard rail's foot beside a line: RESULTS, *Accuracy on real data*).
    pub vote_pair_share: f64,
    /// Share of the particles replaced, each frame after one whose estimate had one ego
    /// boundary with vote support (at least `valid_support`) and the other none (under 0.05),
    /// by lanes that keep the supported boundary where it is and take the width w anew,
    /// uniform over `width_range_m`, their model r kept (ours, beyond the paper; 0: off, the
    /// paper's filter; see [`crate::trackers::side_search`]).
    pub side_search_share: f64,
    /// Validity after the lane was lost (a valid frame, then one not valid; a run's first lock
    /// is not held back): the lane counts again only when an edge voted for one of its
    /// boundaries within this many metres beyond the voting region's nearest row, or within
    /// the longest such reach of the last 30 valid frames that saw both boundaries
    /// ([`crate::trackers::reacquire`]; ours, beyond the paper; 0: off, the default). Markings
    /// that begin only further ahead, past an unmarked crossing, are not yet the car's lane.
    pub reacquire_near_m: f64,
    /// Only marking edges vote: an edge point votes when the opposite edge of a bright stripe
    /// lies beside it, at most [`PAIRED_EDGE_MAX_M`] away on the road, on the marking's side
    /// (ours, beyond the paper; false: every edge point votes, the paper's Sec. 3.2). A seam
    /// between asphalt and concrete, a barrier's foot or a shadow's edge is one edge with no
    /// partner and does not vote; a dark stripe (crack sealant) has its edges in the wrong order.
    pub paired_edges: bool,
    /// `edge_threshold` holds up to [`THRESHOLD_WIDTH_PX`] pixels of image width; a wider image
    /// scales it by 640 / width (ours, beyond the paper; false: grey levels per pixel at any
    /// size). A lens and a codec blur an edge over a share of the image, so at twice the width
    /// the same edge's gradient per pixel is about half: the markings of 1280x720 dash-cam
    /// video fall under the threshold that suits 640x480.
    pub width_scaled_threshold: bool,
    /// Report the lanes beside the ego lane that the estimate's model r leaves out, where the
    /// bottom-up detector's markings run beside an ego boundary at a lane's width
    /// ([`crate::trackers::adjacent_lanes`]; ours, beyond the paper, whose neighbours come
    /// from r alone; off by default).
    pub adjacent_lanes: bool,
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

/// The image width [`AdachiConfig::width_scaled_threshold`] takes `edge_threshold` for, pixels.
pub const THRESHOLD_WIDTH_PX: f64 = 640.0;

/// The widest bright stripe [`AdachiConfig::paired_edges`] takes for a marking, metres: one
/// line (each line of a double line pairs on its own); a wider bright stripe is road surface.
pub const PAIRED_EDGE_MAX_M: f64 = 0.3;

impl Default for AdachiConfig {
    fn default() -> Self {
        Self {
            near_m: 6.0,
            far_m: 22.0,
            rho_range_m: 8.0,
            bin_m: 0.05,
            polarity: Polarity::LeftEdge,
            edge_threshold: 80.0,
            edge_response: EdgeResponse::Horizontal,
            marking_width_m: 0.15,
            edge_sigma_m: 0.1,
            start_iterations: 20,
            beta: 1.0,
            sigma_q_m: 0.08,
            sigma_w_m: 0.04,
            width_range_m: [2.5, 4.8],
            transitions: vec![
                vec![6.0 / 8.0, 1.0 / 8.0, 1.0 / 8.0, 0.0],
                vec![1.0 / 12.0, 9.0 / 12.0, 1.0 / 12.0, 1.0 / 12.0],
                vec![1.0 / 12.0, 1.0 / 12.0, 9.0 / 12.0, 1.0 / 12.0],
                vec![0.0, 1.0 / 8.0, 1.0 / 8.0, 6.0 / 8.0],
            ],
            valid_support: 0.08,
            valid_support_frames: 1,
            lane_shape: LaneShape::Straight,
            max_heading_rad: 0.1,
            max_curvature_per_m: 0.012,
            shape_gain: 0.5,
            relock_share: 0.0,
            start_pair_share: 0.5,
            vote_pair_share: 0.0,
            side_search_share: 0.0,
            reacquire_near_m: 0.0,
            paired_edges: false,
            width_scaled_threshold: false,
            adjacent_lanes: false,
            snap_to_paint: false,
            snap_follows_bends: false,
            valid_needs_paint: false,
            valid_from_paint: false,
        }
    }
}

impl AdachiConfig {
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
    /// [`Error::Config`] for an unknown option or a wrong type.
    pub fn from_options(options: &crate::trackers::Options) -> Result<Self> {
        let config: Self = options.read(super::ID, |t| match t {
            crate::trackers::TrackerOptions::AdachiMmpf(c) => Some(c),
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
        // Every single value's range is checked above (`ranges::ADACHI`); what follows are the
        // checks between values.
        if self.far_m <= self.near_m {
            return Err(Error::parameter(
                "far_m",
                Num(self.far_m),
                "must be beyond near_m",
            ));
        }
        let [lo, hi] = self.width_range_m;
        if hi <= lo {
            return Err(Error::parameter(
                "width_range_m",
                Num(hi),
                "max must exceed min",
            ));
        }
        if self.transitions.len() != 4 {
            return Err(Error::Config(
                "transitions must be a 4x4 matrix (models 1-4)".into(),
            ));
        }
        Ok(())
    }
}
