//! The options of `danescu-stereo` and `danescu-mono` (all optional; unknown ones are refused).
//!
//! Where the paper gives a value it is used: the discrete 3-D space of 200 x 300 cells of
//! 1 cm x 10 cm, D_3D = 15 m, the 11 x 11 triangular filter. The rest is ours and named so:
//! the particle budget and initialisation share, the diffusion noise, the distance range and
//! point count P of the image mapping, the likelihood widths, the validation limits and the
//! preliminary pitch detection's histogram.

use super::elevation::CurbConfig;
use crate::error::{Error, Result};
use crate::num_text::Num;
use crate::vision::{CannyConfig, DensityConfig, DisparityConfig, HGradientConfig};
use serde::{Deserialize, Serialize};

/// Every option of the Danescu trackers.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DanescuConfig {
    /// Share of each frame's particles drawn from the generic initialisation distribution
    /// (Sec. III), in [0, 1).
    pub init_fraction: f64,
    /// Nearest distance of the image-space mapping, metres (raised to the first visible row).
    pub near_m: f64,
    /// Farthest distance of the image-space mapping, metres.
    pub far_m: f64,
    /// Points P per delimiter edge in image space and in the 3-D space (eq. 5).
    pub points: usize,
    /// D_3D: range of the 3-D mapping (eq. 5), metres.
    pub range_3d_m: f64,
    /// Diffusion: standard deviation per frame of each parameter, in the order of
    /// `Lane3d::NAMES` (w0, ch, wl, cv, y0, xcw, alpha, gamma, psi, wl_mark, wr_mark).
    pub diffusion: [f64; 11],
    /// The generic initialisation distribution: uniform lane width (inner edges), metres.
    pub init_width_m: [f64; 2],
    /// The generic initialisation distribution: uniform |X_CW| up to this, metres.
    pub init_offset_m: f64,
    /// The generic initialisation distribution: uniform |psi| up to this, radians.
    pub init_yaw_rad: f64,
    /// The generic initialisation distribution: uniform |C_H| up to this, 1/m.
    pub init_curvature: f64,
    /// The generic initialisation distribution: uniform |W_l| up to this.
    pub init_width_rate: f64,
    /// The generic initialisation distribution: uniform marking widths W_L, W_R, metres.
    pub init_marking_m: [f64; 2],
    /// The generic initialisation distribution: uniform |alpha - calibrated pitch| up to this,
    /// radians (stereo only).
    pub init_pitch_rad: f64,
    /// The generic initialisation distribution: uniform |Y_0| up to this, metres (stereo only).
    pub init_height_m: f64,
    /// Validation (Sec. VII-D): the lane width W(Z) must stay in this range over the mapped
    /// distances, metres (the paper rejects a lane "too narrow, too wide" and gives no
    /// limits; [2.2, 4.5] in `real-roads` for danescu-mono).
    pub width_range_m: [f64; 2],
    /// Validation: the car may be at most this far outside the lane, |X_CW| <= W_0/2 + margin.
    pub offset_margin_m: f64,
    /// Validation: largest marking width, metres.
    pub max_marking_m: f64,
    /// sigma of the road-edge likelihood (DT^E), pixels.
    pub sigma_edge_px: f64,
    /// sigma of the marking likelihood (DT^S), pixels.
    pub sigma_marking_px: f64,
    /// sigma_G of eq. 12, HG units.
    pub sigma_gradient: f64,
    /// sigma_D of eq. 14, cells (the paper gives no value). 1 cell: with 0.5 the density
    /// cue alone left a median effective sample size of 19 of 500 particles, and the
    /// parameters it does not see (the marking widths above all) wandered.
    pub sigma_density: f64,
    /// Negative points lie this far inside the lane from the inner edges, metres.
    pub negative_offset_m: f64,
    /// A negative point costs c - DT when an edge is closer than c pixels.
    pub negative_reach_px: f64,
    /// The marking-width model and the gradient cue (Sec. II, VI-A c, VII-B). `false` runs
    /// the authors' previous approach the paper compares with (Fig. 10): W_L = W_R = 0 and no
    /// gradient likelihood.
    pub marking_widths: bool,
    /// The variable-width gradient.
    pub hgradient: HGradientConfig,
    /// Marking detection on HG: smallest |g| of a marking edge, grey levels.
    pub marking_contrast: f32,
    /// Marking detection: accepted marking widths on the road, metres.
    pub marking_width_range_m: [f64; 2],
    /// Road edges (Canny).
    pub canny: CannyConfig,
    /// The discrete 3-D space and its density threshold (stereo only).
    pub density: DensityConfig,
    /// Curbs from the elevation map, added to DT^S (stereo only).
    pub curbs: CurbConfig,
    /// The stereo matcher (stereo only; `max_disparity` is set from the camera: the
    /// disparity of the nearest visible road point).
    pub disparity: DisparityConfig,
    /// Preliminary pitch detection: histogram bin, radians.
    pub pitch_bin_rad: f64,
    /// Preliminary pitch detection: searched pitch changes, +- radians.
    pub pitch_range_rad: f64,
    /// Road points lie within this height of the detected road line, metres.
    pub road_tolerance_m: f64,
    /// The 3-D data counts (the density cue of eqs. 13-14 and the curbs) only in a frame
    /// whose road points are at least this share of the road region's pixels (ours; the
    /// paper does not say what a frame without usable stereo data does). Measured at 320x240
    /// on drawn roads: 20-30 % by day, 4.7-8 % at night, 0.5-1.2 % in a blacked-out frame
    /// (matches of sensor noise). With those noise points weighing the particles while the
    /// image cues were empty, the cloud drifted in width and offset through a blackout and
    /// re-locked 9 frames after it on average, 24 at worst (`occlusion`, seeds 1000-1002).
    /// 0.02 by default, between the blackout and the night; 0 uses the 3-D data of every
    /// frame, as before (a share of 0.05 cut the night's density cue too: width MAE 5 -> 28
    /// cm).
    pub min_road_share: f64,
    /// MBSAS: distance threshold on X_CW, metres.
    pub cluster_threshold_m: f64,
    /// MBSAS: at most this many clusters S.
    pub max_clusters: usize,
    /// Validity: a frame is valid when, on each side, at least `valid_support` of the
    /// estimate's inner-edge points are within this many pixels of a road edge (and its
    /// cluster holds `valid_cluster_share` of the particles).
    pub valid_distance_px: f64,
    /// Validity: the tolerance as a distance on the road, metres, where that is more pixels
    /// than `valid_distance_px` (ours; 0: pixels only). The tolerance at distance Z is
    /// max(`valid_distance_px`, f_x `valid_distance_m` / Z): a pixel tolerance alone is
    /// physically four times tighter through a 1280-pixel camera of 1156 px focal length than
    /// through a 640-pixel one of 309 px, and a blurred marking's Canny edge on a video frame
    /// falls a few pixels off the model's edge.
    pub valid_distance_m: f64,
    /// Validity: the share of the estimate's inner-edge points on each side that must be
    /// within `valid_distance_px` of a road edge (a dashed line of 3 m dashes every 12 m gives
    /// about 0.25).
    pub valid_support: f64,
    /// Validity: a side under `valid_support` this frame still counts when its mean support
    /// over the last this many frames (this one included; fewer since a reset) reaches
    /// `valid_support` and the other side this frame holds at least twice it: a dashed line's
    /// support swings with the dashes' phase ([`crate::trackers::support_memory`]; ours,
    /// beyond the paper; 1: this frame's alone, the default).
    pub valid_support_frames: usize,
    /// Validity: an inner-edge point supports its side only when a marking edge (the marking
    /// image of DT^S) also lies within this many times its tolerance (`valid_distance_px`,
    /// `valid_distance_m`), besides the road edge (ours, beyond the paper; 0: off, any road
    /// edge supports, the default). A tree shadow's edge or a seam is a road edge with no
    /// marking beside it, and would otherwise keep a lane through an unmarked crossing; so is
    /// a kerb to danescu-mono, whose lane bounded by a kerb without paint is then never valid
    /// (danescu-stereo puts the kerbs' feet into the marking image).
    pub valid_marking_factor: f64,
    /// Validity with a positive `valid_marking_factor`: on how many sides (1 or 2) the support
    /// must come from points with a marking edge beside the road edge. 2 (the default): on
    /// both, each side's support counts only such points. 1 (ours): on at least one side (its
    /// share of such points, averaged over the last `valid_support_frames` frames, reaches
    /// `valid_support`), while each side's support counts any road edge as without the factor;
    /// so a lane between a painted line and a kerb without paint stays valid, and a crossing
    /// without paint on either side, where only shadow edges or kerbs remain, is not.
    pub valid_marking_sides: usize,
    /// Validity: the estimate's MBSAS cluster holds at least this share of the resampled
    /// particles.
    pub valid_cluster_share: f64,
    /// Share of the particles replaced, after the drift, each frame the auto-calibration's
    /// line detector finds an ego pair, by draws around that pair on the road (X_CW, psi and
    /// W_0 from it with the diffusion's spreads, the rest kept): a data-driven proposal beside
    /// the generic one of `init_fraction` (ours, beyond the paper; 0: off, the paper's
    /// filter; see [`crate::trackers::relock`]).
    pub relock_share: f64,
    /// Filter rounds on the first frame (and after a reset), each: resample, inject, diffuse
    /// (no ego motion), weigh on the same frame (ours; 0: the paper's start, whose first frame
    /// is weighed once from the initial distribution: its most populous cluster then holds
    /// about a quarter of the cloud, under `valid_cluster_share`, and the first estimate is
    /// not valid).
    pub start_iterations: usize,
    /// Report the lanes beside the ego lane (`left-adjacent`, `right-adjacent`) where the
    /// bottom-up detector's markings run beside an ego boundary at a lane's width
    /// ([`crate::trackers::adjacent_lanes`]; ours, beyond the paper, which follows the ego lane
    /// only; off by default).
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

impl Default for DanescuConfig {
    fn default() -> Self {
        Self {
            init_fraction: 0.1,
            near_m: 5.0,
            far_m: 35.0,
            points: 20,
            range_3d_m: 15.0,
            // The vertical ones (C_V, Y_0, alpha, gamma) are for the stereo tracker. The paper
            // takes the pitch as quasi-stationary; a car on bumps changes it by up to 5 mrad
            // and its height by 1 cm per frame. 4 mrad of pitch per frame still follows the
            // `pitch-bumps` scenario (3.2 mrad RMS) without spreading the particles so widely
            // that the density cue leaves few of them alive (RESULTS.md, danescu: sigma_D and
            // the vertical diffusion).
            diffusion: [
                0.03, 0.0003, 0.001, 0.00005, 0.015, 0.04, 0.004, 0.0003, 0.004, 0.01, 0.01,
            ],
            init_width_m: [2.6, 4.2],
            init_offset_m: 1.2,
            init_yaw_rad: 0.06,
            init_curvature: 0.003,
            init_width_rate: 0.01,
            init_marking_m: [0.0, 0.3],
            init_pitch_rad: 0.01,
            init_height_m: 0.05,
            width_range_m: [2.2, 5.0],
            offset_margin_m: 0.5,
            max_marking_m: 0.5,
            sigma_edge_px: 3.0,
            sigma_marking_px: 3.0,
            sigma_gradient: 30.0,
            sigma_density: 1.0,
            negative_offset_m: 0.3,
            negative_reach_px: 3.0,
            marking_widths: true,
            hgradient: HGradientConfig {
                gain: 1.0,
                ..HGradientConfig::default()
            },
            marking_contrast: 40.0,
            marking_width_range_m: [0.05, 0.5],
            canny: CannyConfig::default(),
            density: DensityConfig::default(),
            curbs: CurbConfig::default(),
            disparity: DisparityConfig::default(),
            pitch_bin_rad: 0.0005,
            pitch_range_rad: 0.05,
            road_tolerance_m: 0.1,
            min_road_share: 0.02,
            cluster_threshold_m: 0.4,
            max_clusters: 5,
            valid_distance_px: 2.0,
            valid_distance_m: 0.0,
            valid_support: 0.15,
            valid_support_frames: 1,
            valid_marking_factor: 0.0,
            valid_marking_sides: 2,
            valid_cluster_share: 0.3,
            relock_share: 0.0,
            start_iterations: 0,
            adjacent_lanes: false,
            snap_to_paint: false,
            snap_follows_bends: false,
            valid_needs_paint: false,
            valid_from_paint: false,
        }
    }
}

impl DanescuConfig {
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

    /// Reads and checks the options.
    ///
    /// # Errors
    /// [`Error::Config`] for an unknown option or a wrong type; [`Error::Parameter`] naming
    /// the option for a value out of range.
    pub fn from_options(options: &crate::trackers::Options, id: &str) -> Result<Self> {
        let c: Self = options.read(id, |t| match t {
            crate::trackers::TrackerOptions::DanescuMono(c) if id == super::ID_MONO => Some(c),
            crate::trackers::TrackerOptions::DanescuStereo(c) if id == super::ID_STEREO => Some(c),
            _ => None,
        })?;
        c.validate()?;
        Ok(c)
    }

    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        crate::trackers::ranges::check_ranges(super::ID_MONO, self)?;
        // Every single value's range is checked above (`ranges::DANESCU`); what follows are
        // the checks between values.
        if self.far_m <= self.near_m {
            return Err(Error::parameter(
                "far_m",
                Num(self.far_m),
                "must exceed near_m",
            ));
        }
        for (name, [lo, hi]) in [
            ("init_width_m", self.init_width_m),
            ("init_marking_m", self.init_marking_m),
            ("width_range_m", self.width_range_m),
            ("marking_width_range_m", self.marking_width_range_m),
        ] {
            if hi < lo {
                return Err(Error::parameter(
                    name,
                    format!("[{}, {}]", Num(lo), Num(hi)),
                    "must be a range [low, high] with 0 <= low <= high",
                ));
            }
        }
        self.curbs.validate()
    }
}
