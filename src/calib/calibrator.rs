//! The online calibrator: frames in, a camera estimate with its confidence out.

use super::bend_regression::yaw_at_zero_bend;
use super::hough::{bend, Hough, HoughParams, LineFit, BEND_BAND_PX};
use super::marking_image::{marking_intensity, working_scale, MarkingScratch};
use super::pose::{lateral_at_unit_height, pose_from_vanishing_point, vanishing_point, Pinhole};
use super::ridges::{find_ridges, keep_continuous, RidgePixel};
use super::road_colour::keep_on_grey_road;
use super::tangent::{tangent_column, NearestPixel, HORIZON_SEARCH_PX};
use super::vp_votes::VpVotes;
use crate::camera::{Camera, CameraFile, Distortion};
use crate::error::{require_within, Error, Result};
use crate::image::{check_dimensions, check_rgba, Image};
use crate::math;
use serde::Serialize;
use std::collections::VecDeque;

/// Options of the [`Calibrator`]; every field has a documented range, checked by
/// [`Calibrator::new`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CalibratorConfig {
    /// Lane width prior W, metres (2.5 to 5): the camera height is W / w_1.
    pub lane_width_m: f64,
    /// Horizontal field of view, degrees (20 to 150), used for the focal length when the
    /// intrinsics are not given: fx = fy = (width / 2) / tan(hfov / 2).
    pub hfov_deg: f64,
    /// Frames (1 to 120) whose vanishing points must agree for a frame to count as straight
    /// road; 1 accepts every frame on its own (independent still images).
    pub stable_frames: usize,
    /// Largest common bend of the ego boundaries on straight road, in working pixels (0.1 to
    /// 10; see [`super::hough`]).
    pub max_bend_px: f64,
    /// The yaw from the lane's tangent at the car (a fit of both boundaries with a curvature
    /// term, [`super::tangent`]) from the first frame, instead of the straight boundaries'
    /// crossing until `tangent_yaw_after` frames have one (ours; off by default). On the
    /// simulator's long drives it takes the gentle bends' pull out of the yaw; on Caltech's
    /// frames, the only real ones with a reference yaw, it lands 0.1 degrees from the labels'
    /// yaw (0.45 against 0.35). Off by default: on short clips the trackers do worse with its
    /// cameras (adachi-mmpf, whose lane is straight, 8-10 points on the simulator's 5 s
    /// s-curves, where the crossing's yaw towards the bend's inside suits it; 1.1 on Caltech;
    /// RESULTS.md, *Auto-calibration*).
    pub tangent_yaw: bool,
    /// The estimate's yaw switches from the crossing's to the tangent's once this many frames
    /// that agree on the pose have a tangent (0 to [`MAX_SAMPLES`]; 0: never, the crossing's
    /// yaw throughout; ours), and stays the tangent's until [`Calibrator::reset`]. On the
    /// simulator no tracker lost more than 2 points to the tangent's cameras on drives that
    /// used 136 frames or more, and adachi-mmpf lost 4-10 points on those that used 33-67 (its
    /// s-curves at 5 and 10 s), while the crossing's yaw was off by more than 0.5 degrees on 9
    /// of 12 drives at 20 s: the crossing's yaw on short clips, the tangent's on long ones.
    pub tangent_yaw_after: usize,
}

impl Default for CalibratorConfig {
    fn default() -> Self {
        Self {
            lane_width_m: 3.6,
            hfov_deg: 60.0,
            stable_frames: 5,
            max_bend_px: 1.5,
            tangent_yaw: false,
            tangent_yaw_after: DEFAULT_TANGENT_YAW_AFTER,
        }
    }
}

/// The default of [`CalibratorConfig::tangent_yaw_after`]: between the simulator's drives that
/// used 67 frames, where the tangent's camera still cost adachi-mmpf 4 points, and 136, where no
/// tracker lost more than 2 (RESULTS.md, *Auto-calibration*).
pub const DEFAULT_TANGENT_YAW_AFTER: usize = 100;

impl CalibratorConfig {
    /// Whether frames fit the lane's tangent at the car (for `tangent_yaw` or, later,
    /// `tangent_yaw_after`).
    fn fits_tangent(&self) -> bool {
        self.tangent_yaw || self.tangent_yaw_after > 0
    }

    /// Checks every option against its range.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the option.
    pub fn validate(&self) -> Result<()> {
        require_within(
            "lane_width_m",
            self.lane_width_m,
            2.5..=5.0,
            "must be 2.5 to 5 metres",
        )?;
        require_within(
            "hfov_deg",
            self.hfov_deg,
            20.0..=150.0,
            "must be 20 to 150 degrees",
        )?;
        require_within(
            "max_bend_px",
            self.max_bend_px,
            0.1..=10.0,
            "must be 0.1 to 10 pixels",
        )?;
        if !(1..=120).contains(&self.stable_frames) {
            return Err(Error::parameter(
                "stable_frames",
                self.stable_frames,
                "must be 1 to 120 frames",
            ));
        }
        if self.tangent_yaw_after > MAX_SAMPLES {
            return Err(Error::parameter(
                "tangent_yaw_after",
                self.tangent_yaw_after,
                "must be 0 (never) to 2000 frames",
            ));
        }
        Ok(())
    }
}

/// What one frame showed.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct FrameObservation {
    /// Lines through marking pixels, in undistorted pixels, strongest first.
    pub lines: Vec<LineFit>,
    /// Indices in `lines` of the ego boundaries (left, right).
    pub ego: Option<[usize; 2]>,
    /// Where the ego boundaries meet, undistorted pixels.
    pub vanishing_point: Option<[f64; 2]>,
    /// The ego boundaries are straight: their common bend is at most `max_bend_px`, their
    /// opposite bend (a crest or a dip) at most three times that.
    pub straight: bool,
    /// The vanishing points of the last `stable_frames` frames agree.
    pub stable: bool,
    /// The frame was used for the estimate.
    pub used: bool,
}

/// One straight, stable frame's measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Sample {
    pub(super) pitch: f64,
    /// The yaw of the boundaries' straight crossing.
    pub(super) yaw: f64,
    /// The yaw of the lane's tangent at the car, when the calibrator fits it and the fit
    /// succeeds (`tangent_yaw`, `tangent_yaw_after`).
    pub(super) tangent_yaw: Option<f64>,
    /// Lane width seen from one metre above the road.
    pub(super) width_at_unit_height: f64,
    /// How far the boundaries bent: |common bend| + |opposite bend| / 3, working pixels.
    pub(super) bend: f64,
    /// The signed common bend (b_left + b_right) / 2, working pixels (see
    /// [`super::bend_regression`]).
    pub(super) common_bend: f64,
}

/// The calibrator's current answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibrationEstimate {
    /// The estimated camera (pitch, yaw, height; roll 0; intrinsics given or from the field of
    /// view).
    pub camera: CameraFile,
    /// 0 (nothing known) to 1 (pitch and yaw known to well within 0.5 degrees and the height
    /// to well within 10 %): see the module docs.
    pub confidence: f64,
    /// Frames that measured the camera (straight road, stable vanishing point).
    pub frames_used: usize,
    /// Frames fed in.
    pub frames_seen: usize,
    /// Spread (1.4826 MAD) of the per-frame pitch, degrees.
    pub pitch_sd_deg: f64,
    /// Spread of the per-frame yaw, degrees.
    pub yaw_sd_deg: f64,
    /// Spread of the per-frame height, metres.
    pub height_sd_m: f64,
    /// Vanishing point of the estimate, undistorted pixels.
    pub vanishing_point: [f64; 2],
    /// Whether the intrinsics were given (false: focal length from `hfov_deg`).
    pub intrinsics_known: bool,
    /// Whether the yaw is the lane's tangent at the car (`tangent_yaw`, or enough frames for
    /// `tangent_yaw_after`) rather than the boundaries' straight crossing.
    pub yaw_from_tangent: bool,
}

/// Share of the frame height above the horizon (or the principal point's row, when higher)
/// from which the marking image is computed once a horizon is known
/// (`Calibrator::first_working_row`): room for a camera's roll and a lens's bend.
pub const ROAD_TOP_MARGIN: f64 = 0.05;

/// Least ridge contrast of a marking pixel, grey levels of the marking intensity (see
/// [`super::ridges`]).
pub const MIN_RIDGE_CONTRAST: i32 = 12;
/// Most samples kept (the oldest go first): about a minute of straight road at 30 fps.
pub const MAX_SAMPLES: usize = 2000;
/// The mounts a vanishing point may imply: pitch (down positive) and |yaw|, degrees. A
/// dash-cam looks at the road ahead; two lines meeting where no mounted camera looks (tree
/// trunks, poles, the side of a truck) are not the lane.
pub const PITCH_RANGE_DEG: [f64; 2] = [-10.0, 20.0];
/// See [`PITCH_RANGE_DEG`].
pub const MAX_YAW_DEG: f64 = 15.0;
/// The camera heights, metres, an ego pair may imply with the lane-width prior: from a low
/// car's dashboard to a truck's cab. A wider or narrower pair is not the ego lane.
pub const HEIGHT_RANGE_M: [f64; 2] = [0.8, 4.0];
/// Largest distance of the camera from the middle of the ego pair it measures, as a share of
/// the lane width: a car on a straight stretch keeps near its lane's middle, while a pair of a
/// marking and a car's edge, or two lines of one neighbouring vehicle, rarely has the camera
/// between them in the middle. 0.35 keeps each boundary at least 0.15 lane widths (0.54 m of a
/// 3.6 m lane) from the camera.
pub const MAX_LANE_OFFSET: f64 = 0.35;
/// Samples for full confidence by count.
const FULL_COUNT: f64 = 30.0;
/// Samples that must agree on the pose before the estimate sets the rows searched and picks
/// the ego pair ([`Calibrator::prior_vanishing_point`]): five stills that each imply a pose of
/// their own make a "consensus" of the earliest one, and a band searched from a wrong horizon
/// finds trees and buildings that keep it wrong.
const MIN_PRIOR_AGREEING: usize = 3;

/// Estimates a camera's pitch, yaw and height from the lane markings of the frames it is fed
/// (see the [module docs](super)).
#[derive(Debug, Clone)]
pub struct Calibrator {
    config: CalibratorConfig,
    width: usize,
    height: usize,
    pinhole: Pinhole,
    distortion: Distortion,
    intrinsics_known: bool,
    scale: usize,
    /// Working pixel -> undistorted pixel / scale, when the lens distorts.
    undistort: Option<Vec<[f32; 2]>>,
    work: Image<u8>,
    /// Saturation of the working image (see [`super::road_colour`]).
    saturation: Image<u8>,
    marking_scratch: MarkingScratch,
    ridge_scratch: Vec<i32>,
    ridges: Vec<RidgePixel>,
    points: Vec<[f32; 2]>,
    weights: Vec<u8>,
    /// Scratch of the tangent's fit (`tangent_yaw`).
    tangent_rows: Vec<[NearestPixel; 2]>,
    hough: Hough,
    votes: VpVotes,
    recent: VecDeque<Option<[f64; 2]>>,
    samples: VecDeque<Sample>,
    frames_seen: usize,
    last: FrameObservation,
    /// Where the road vanishes when the camera is known (see
    /// [`Calibrator::set_known_vanishing_point`]).
    known_vanishing_point: Option<[f64; 2]>,
    /// `tangent_yaw_after` frames that agree on the pose have had a tangent since the last
    /// reset: the yaw is the tangent's from then on, so a consensus that later shrinks does
    /// not switch it back.
    tangent_switched: bool,
}

impl Calibrator {
    /// A calibrator for `width` x `height` frames. `intrinsics`, when given, supplies fx, fy,
    /// cx, cy and the lens distortion (its pose fields are ignored); without it the focal length
    /// comes from `config.hfov_deg`, the principal point is the image centre and the lens is
    /// taken as distortion-free.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size or one that does not match `intrinsics`;
    /// [`Error::Parameter`] for an option out of range or invalid intrinsics.
    pub fn new(
        width: usize,
        height: usize,
        intrinsics: Option<&CameraFile>,
        config: CalibratorConfig,
    ) -> Result<Self> {
        check_dimensions(width, height)?;
        config.validate()?;
        let scale = working_scale(width);
        if height < scale * 16 || width < scale * 32 {
            return Err(Error::Dimensions(format!(
                "{width}x{height}: the calibrator needs frames of at least 32x16 pixels"
            )));
        }
        let (pinhole, distortion) = match intrinsics {
            Some(file) => {
                if (file.width, file.height) != (width, height) {
                    return Err(Error::Dimensions(format!(
                        "the intrinsics are for {}x{} frames, not {width}x{height}",
                        file.width, file.height
                    )));
                }
                let cam = Camera::from_file(file)?;
                let [fx, fy] = cam.focal();
                let [cx, cy] = cam.principal_point();
                (Pinhole { fx, fy, cx, cy }, *cam.distortion())
            }
            None => {
                let f = 0.5 * width as f64 / math::tan(math::deg_to_rad(0.5 * config.hfov_deg));
                let pinhole = Pinhole {
                    fx: f,
                    fy: f,
                    cx: 0.5 * (width as f64 - 1.0),
                    cy: 0.5 * (height as f64 - 1.0),
                };
                (pinhole, Distortion::default())
            }
        };
        let mut calibrator = Self {
            config,
            width,
            height,
            pinhole,
            distortion,
            intrinsics_known: intrinsics.is_some(),
            scale,
            undistort: None,
            work: Image::new(width / scale, height / scale)?,
            saturation: Image::new(width / scale, height / scale)?,
            marking_scratch: MarkingScratch::default(),
            ridge_scratch: Vec::new(),
            ridges: Vec::new(),
            points: Vec::new(),
            weights: Vec::new(),
            tangent_rows: Vec::new(),
            hough: Hough::default(),
            votes: VpVotes::new(width, height),
            recent: VecDeque::with_capacity(config.stable_frames + 1),
            samples: VecDeque::with_capacity(MAX_SAMPLES),
            frames_seen: 0,
            last: FrameObservation::default(),
            tangent_switched: false,
            known_vanishing_point: None,
        };
        if !distortion.is_none() {
            calibrator.undistort = Some(calibrator.undistortion_table());
        }
        Ok(calibrator)
    }

    /// Working pixel (x, y) -> its undistorted full-resolution pixel divided by the scale;
    /// NaN where the lens model cannot be inverted.
    fn undistortion_table(&self) -> Vec<[f32; 2]> {
        let (w, h, s) = (self.work.width(), self.work.height(), self.scale as f64);
        let k = self.pinhole;
        let mut table = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (self.full(x as f64), self.full(y as f64));
                let entry = match self
                    .distortion
                    .undistort((u - k.cx) / k.fx, (v - k.cy) / k.fy)
                {
                    Ok([xn, yn]) => [
                        ((k.cx + k.fx * xn) / s) as f32,
                        ((k.cy + k.fy * yn) / s) as f32,
                    ],
                    Err(_) => [f32::NAN, f32::NAN],
                };
                table.push(entry);
            }
        }
        table
    }

    /// Full-resolution coordinate of the centre of working pixel `i`.
    fn full(&self, i: f64) -> f64 {
        let s = self.scale as f64;
        s * i + 0.5 * (s - 1.0)
    }

    /// The options.
    pub fn config(&self) -> &CalibratorConfig {
        &self.config
    }

    /// Frame size, pixels.
    pub fn size(&self) -> [usize; 2] {
        [self.width, self.height]
    }

    /// Frames fed in since the start or the last reset.
    pub fn frames_seen(&self) -> usize {
        self.frames_seen
    }

    /// Frames that measured the camera and are still kept (at most [`MAX_SAMPLES`]).
    pub fn frames_used(&self) -> usize {
        self.samples.len()
    }

    /// What the last frame showed.
    pub fn last_observation(&self) -> &FrameObservation {
        &self.last
    }

    /// The last frame's marking pixels, in undistorted pixels.
    pub fn marking_pixels(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        let s = self.scale as f64;
        self.points
            .iter()
            .map(move |p| [p[0] as f64 * s, p[1] as f64 * s])
    }

    /// The last frame's working images: marking intensity and saturation (see
    /// [`super::marking_image`]), and the block size s they were averaged over (working pixel
    /// (i, j) covers full-resolution pixels s i .. s i + s - 1, s j .. s j + s - 1).
    pub fn working_images(&self) -> (&Image<u8>, &Image<u8>, usize) {
        (&self.work, &self.saturation, self.scale)
    }

    /// Uses `vp` (undistorted pixels), where a known camera's road vanishes, as the prior of
    /// every frame instead of learning it from the frames: the ego pair is then the pair of
    /// lines through it nearest the middle, from the first frame on. For a lane detector
    /// whose camera is known (`relock_share` of the trackers), not for calibrating.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a non-finite `vp`.
    pub fn set_known_vanishing_point(&mut self, vp: [f64; 2]) -> Result<()> {
        for v in vp {
            crate::error::require_finite("vanishing point", v)?;
        }
        self.known_vanishing_point = Some(vp);
        Ok(())
    }

    /// Forgets every frame.
    pub fn reset(&mut self) {
        self.recent.clear();
        self.samples.clear();
        self.votes.clear();
        self.frames_seen = 0;
        self.last = FrameObservation::default();
        self.tangent_switched = false;
    }

    /// Feeds one RGBA frame; returns what it showed.
    ///
    /// # Errors
    /// [`Error::Dimensions`] / [`Error::BufferSize`] when the frame is not `width` x `height`
    /// RGBA; the calibrator is unchanged then.
    pub fn feed_rgba(
        &mut self,
        rgba: &[u8],
        width: usize,
        height: usize,
    ) -> Result<&FrameObservation> {
        // Counted before the prior is read (its vote needs more than five frames seen); not
        // counted when the frame is refused.
        self.frames_seen += 1;
        // Where the road vanishes as known before this frame: it sets the rows computed and
        // searched and picks the ego pair.
        let prior = self.prior_vanishing_point();
        if let Err(e) = self.compute_working_images(rgba, width, height, prior) {
            self.frames_seen -= 1;
            return Err(e);
        }
        self.observe(prior);
        Ok(&self.last)
    }

    /// Computes the working images of one RGBA frame ([`Self::working_images`]) and nothing
    /// else: no lines are found, and what the calibrator has learnt, its frame count and its
    /// last observation stay as they were. For a tracker that needs the marking image only
    /// (its output options, `snap_to_paint`, `valid_needs_paint`, `valid_from_paint` or
    /// `adjacent_lanes`, without
    /// `relock_share`); with a known
    /// vanishing point ([`Self::set_known_vanishing_point`]) the images are those
    /// [`Self::feed_rgba`] computes, at a fraction of its cost.
    ///
    /// # Errors
    /// As [`Self::feed_rgba`].
    pub fn feed_rgba_markings_only(
        &mut self,
        rgba: &[u8],
        width: usize,
        height: usize,
    ) -> Result<()> {
        let prior = self.prior_vanishing_point();
        self.compute_working_images(rgba, width, height, prior)
    }

    /// The working images of a frame checked to be `width` x `height` RGBA, from the first row
    /// the `prior` vanishing point needs.
    fn compute_working_images(
        &mut self,
        rgba: &[u8],
        width: usize,
        height: usize,
        prior: Option<[f64; 2]>,
    ) -> Result<()> {
        if (width, height) != (self.width, self.height) {
            return Err(Error::Dimensions(format!(
                "{width}x{height}: this calibrator takes {}x{} frames",
                self.width, self.height
            )));
        }
        check_rgba(rgba, width, height)?;
        let first_row = self.first_working_row(prior);
        marking_intensity(
            rgba,
            width,
            height,
            self.scale,
            first_row,
            &mut self.marking_scratch,
            &mut self.work,
            &mut self.saturation,
        )
    }

    /// The first working row of the marking image a frame needs: [`ROAD_TOP_MARGIN`] of the
    /// height above the higher of the prior horizon row and the principal point's (a barrel
    /// lens, a dash-cam's, bends the horizon towards the centre row, and the road lies below
    /// it); 0, every row, without a prior. The rows searched for markings start below the
    /// horizon, and the trackers' neighbouring-lane probes ([`crate::trackers::adjacent_lanes`])
    /// look at road points, below it too; the sky above is not computed. The margin covers a
    /// roll of a few degrees; a pincushion lens or a camera rolled far more would leave the
    /// probes' farthest points in zeroed rows, where they find no paint (a neighbouring lane
    /// found over a shorter range), never a wrong one.
    fn first_working_row(&self, prior: Option<[f64; 2]>) -> usize {
        let Some(vp) = prior else {
            return 0;
        };
        let top = vp[1].min(self.pinhole.cy) - ROAD_TOP_MARGIN * self.height as f64;
        if !top.is_finite() || top <= 0.0 {
            return 0;
        }
        // Never below the first row searched (a principal point far down the frame).
        ((top / self.scale as f64) as usize).min(self.search_rows(prior).0)
    }

    /// Rows (working pixels) searched for markings: from just below the `prior` horizon (or
    /// a quarter of the way down before there is one) to 5 % above the bottom.
    fn search_rows(&self, prior: Option<[f64; 2]>) -> (usize, usize) {
        let h = self.work.height();
        let bottom = (0.95 * h as f64) as usize;
        let top = match prior {
            Some(vp) => {
                let v = vp[1] / self.scale as f64 + 0.03 * h as f64;
                crate::math::clamp(v, 0.0, 0.8 * h as f64) as usize
            }
            None => h / 4,
        };
        (top, bottom.max(top + 1))
    }

    fn observe(&mut self, prior: Option<[f64; 2]>) {
        let (top, bottom) = self.search_rows(prior);
        debug_assert!(
            top >= self.first_working_row(prior),
            "the rows searched lie in the marking image's computed rows"
        );
        self.ridges.clear();
        find_ridges(
            &self.work,
            top..bottom,
            MIN_RIDGE_CONTRAST,
            &mut self.ridge_scratch,
            &mut self.ridges,
        );
        keep_on_grey_road(
            &mut self.ridges,
            &self.work,
            &self.saturation,
            MIN_RIDGE_CONTRAST,
        );
        keep_continuous(&mut self.ridges, 2);
        self.points.clear();
        self.weights.clear();
        let (w, s) = (self.work.width(), self.scale as f64);
        for p in &self.ridges {
            let (x, y) = (p.x as usize, p.y as usize);
            let q = match &self.undistort {
                Some(table) => table[y * w + x],
                None => [
                    (self.full(x as f64) / s) as f32,
                    (self.full(y as f64) / s) as f32,
                ],
            };
            if q[0].is_finite() && q[1].is_finite() {
                self.points.push(q);
                self.weights.push(p.contrast);
            }
        }
        let span = (bottom - top) as f64;
        let params = HoughParams {
            width: w,
            y_ref: 0.5 * (top + bottom) as f64,
            min_support: ((0.08 * span) as usize).max(8),
            min_extent: 0.15 * span,
            max_lines: 8,
        };
        // The last frame's line buffer is reused: no allocation once it has grown.
        let mut lines = std::mem::take(&mut self.last.lines);
        lines.clear();
        self.hough
            .detect(&self.points, &self.weights, &params, &mut lines);
        for l in &mut lines {
            // Working pixels to full-resolution ones.
            l.x_ref *= s;
            l.y_ref *= s;
            l.y_top *= s;
            l.y_bottom *= s;
            l.bend *= s;
        }
        let bottom_row = bottom as f64 * s;
        let (left, right) = self.sides(&lines);
        let ego = self.ego_pair(&lines, &left, &right, prior, bottom_row);
        self.vote_crossings(&lines, &left, &right, bottom_row);
        let vanishing_point = ego.and_then(|[l, r]| crossing(&lines[l], &lines[r]));
        if let (Some([l, r]), Some(vp)) = (ego, vanishing_point) {
            let rows = rows_below(vp, bottom, s, BEND_ROW_SHARE);
            for i in [l, r] {
                lines[i].bend = bend(&self.points, &working_line(&lines[i], s), rows) * s;
            }
        }
        // A bend in the road bends both boundaries the same way; a crest or a dip bends them
        // in opposite ways (and matters less: it tilts the near road, which is what a tracker
        // looks at).
        let straight = ego.is_some_and(|[l, r]| {
            let (bl, br) = (lines[l].bend, lines[r].bend);
            let limit = self.config.max_bend_px * s;
            (bl + br).abs() / 2.0 <= limit && (bl - br).abs() / 2.0 <= 3.0 * limit
        });
        let vp_straight = vanishing_point.filter(|_| straight);
        self.recent.push_back(vp_straight);
        while self.recent.len() > self.config.stable_frames {
            self.recent.pop_front();
        }
        let stable = self.stable();
        let mut used = false;
        if let (Some(vp), true, Some([l, r])) = (vp_straight, stable, ego) {
            // The boundaries' bends in working pixels, and their common bend.
            let (bl, br) = (lines[l].bend / s, lines[r].bend / s);
            let common_bend = (bl + br) / 2.0;
            let tangent_vp = if self.config.fits_tangent() {
                let pair = [&working_line(&lines[l], s), &working_line(&lines[r], s)];
                let rows = rows_below(vp, bottom, s, TANGENT_ROW_SHARE);
                // The crossing's row is the horizon on a straight frame; a bend lifts it, and
                // there the fit takes the row too.
                let search = if common_bend.abs() > BENT_SHARE * self.config.max_bend_px {
                    HORIZON_SEARCH_PX
                } else {
                    0.0
                };
                tangent_column(
                    &self.points,
                    pair,
                    vp[1] / s,
                    rows,
                    BEND_BAND_PX,
                    search,
                    &mut self.tangent_rows,
                )
                .map(|(u, _)| [u * s, vp[1]])
            } else {
                None
            };
            if let Some(mut sample) = self.sample(vp, tangent_vp, &lines[l], &lines[r], bottom_row)
            {
                sample.bend = common_bend.abs() + (bl - br).abs() / 6.0;
                sample.common_bend = common_bend;
                self.add_sample(sample);
                used = true;
            }
        }
        self.last = FrameObservation {
            lines,
            ego,
            vanishing_point,
            straight,
            stable,
            used,
        };
    }

    /// Where the road vanishes, as far as is known before this frame: the mode of the recent
    /// line crossings once it holds a fair share of them (it follows the road and cannot lock
    /// onto the calibrator's own earlier choices), else the estimate once a few frames agree on
    /// it.
    pub(super) fn prior_vanishing_point(&self) -> Option<[f64; 2]> {
        if self.known_vanishing_point.is_some() {
            return self.known_vanishing_point;
        }
        match self.votes.mode() {
            Some((mode, share))
                if self.frames_seen > 5 && share >= 0.15 && self.votes.total() >= 50.0 =>
            {
                Some(mode)
            }
            _ if self.samples.len() >= 5 => self.agreed_vanishing_point(),
            _ => None,
        }
    }

    /// The strong left-leaning (dx/dy < 0) and right-leaning lines: with at least a quarter of
    /// the strongest line's support, or an eighth when the vanishing point is known (a weak
    /// line through a known vanishing point is most likely a dashed boundary beside a solid
    /// one, a dash covering about a quarter of its line).
    fn sides(&self, lines: &[LineFit]) -> (Vec<usize>, Vec<usize>) {
        let strongest = lines.iter().map(|l| l.support).max().unwrap_or(0);
        let ratio = if self.known_vanishing_point.is_some() {
            8
        } else {
            4
        };
        let strong = |l: &LineFit| ratio * l.support >= strongest;
        let pick = |left: bool| {
            (0..lines.len())
                .filter(|&i| strong(&lines[i]) && (lines[i].slope < 0.0) == left)
                .collect()
        };
        (pick(true), pick(false))
    }

    /// Where `left` and `right` meet, if that is a possible vanishing point of the road: above
    /// most of the points of both, and implying a mount within [`PITCH_RANGE_DEG`] and
    /// [`MAX_YAW_DEG`]. (Asking both lines to reach down towards the car as well, to refuse
    /// tree trunks, also refused dashed boundaries whose nearest dash is far: not kept.)
    fn meeting(&self, left: &LineFit, right: &LineFit) -> Option<[f64; 2]> {
        let vp = crossing(left, right)?;
        let mid = |l: &LineFit| 0.5 * (l.y_top + l.y_bottom);
        let above = vp[1] <= mid(left).min(mid(right));
        let [pitch, yaw] = pose_from_vanishing_point(&self.pinhole, vp);
        let [lo, hi] = PITCH_RANGE_DEG;
        let mount =
            (lo..=hi).contains(&pitch.to_degrees()) && yaw.to_degrees().abs() <= MAX_YAW_DEG;
        (above && mount).then_some(vp)
    }

    /// Every left/right pair votes where it meets (see [`VpVotes`]).
    fn vote_crossings(
        &mut self,
        lines: &[LineFit],
        left: &[usize],
        right: &[usize],
        bottom_row: f64,
    ) {
        self.votes.decay();
        for &l in left {
            for &r in right {
                let vp = self.meeting(&lines[l], &lines[r]).filter(|&vp| {
                    self.sample(vp, None, &lines[l], &lines[r], bottom_row)
                        .is_some()
                });
                if let Some(vp) = vp {
                    let weight = lines[l].support.min(lines[r].support) as f32;
                    self.votes.vote(vp, weight);
                }
            }
        }
    }

    /// The ego boundaries among the `left`- and `right`-leaning `lines`. With a prior vanishing
    /// point: of the lines passing within 6 % of the width of it, the left-leaning and the
    /// right-leaning one nearest the middle at the bottom row. Without one: the pair with the
    /// most support that meets where a road can vanish.
    fn ego_pair(
        &self,
        lines: &[LineFit],
        left: &[usize],
        right: &[usize],
        prior: Option<[f64; 2]>,
        bottom_row: f64,
    ) -> Option<[usize; 2]> {
        let pair = match prior {
            Some(vp) => {
                let tol = 0.06 * self.width as f64;
                let near = |&&i: &&usize| (lines[i].x_at(vp[1]) - vp[0]).abs() <= tol;
                let at_bottom = |&i: &usize| lines[i].x_at(bottom_row);
                let l = *left
                    .iter()
                    .filter(near)
                    .max_by(|a, b| at_bottom(a).total_cmp(&at_bottom(b)))?;
                let r = *right
                    .iter()
                    .filter(near)
                    .min_by(|a, b| at_bottom(a).total_cmp(&at_bottom(b)))?;
                [l, r]
            }
            None => {
                let mut best = None;
                for &l in left {
                    for &r in right {
                        let score = lines[l].support + lines[r].support;
                        let plausible = self.meeting(&lines[l], &lines[r]).is_some_and(|vp| {
                            self.sample(vp, None, &lines[l], &lines[r], bottom_row)
                                .is_some()
                        });
                        if plausible && best.is_none_or(|(s, _)| score > s) {
                            best = Some((score, [l, r]));
                        }
                    }
                }
                best?.1
            }
        };
        self.meeting(&lines[pair[0]], &lines[pair[1]]).map(|_| pair)
    }

    /// The last `stable_frames` frames all had straight boundaries whose vanishing points lie
    /// within 1.5 % of the image width of their median.
    fn stable(&self) -> bool {
        if self.recent.len() < self.config.stable_frames {
            return false;
        }
        let vps: Option<Vec<[f64; 2]>> = self.recent.iter().copied().collect();
        let Some(vps) = vps else { return false };
        let us: Vec<f64> = vps.iter().map(|p| p[0]).collect();
        let vs: Vec<f64> = vps.iter().map(|p| p[1]).collect();
        let (mu, mv) = (median(&us), median(&vs));
        let tol = 0.015 * self.width as f64;
        vps.iter()
            .all(|p| (p[0] - mu).abs() <= tol && (p[1] - mv).abs() <= tol)
    }

    /// The frame's sample from its vanishing point `vp`; its yaw from `tangent_vp` when given
    /// (`tangent_yaw`).
    fn sample(
        &self,
        vp: [f64; 2],
        tangent_vp: Option<[f64; 2]>,
        left: &LineFit,
        right: &LineFit,
        row: f64,
    ) -> Option<Sample> {
        let [pitch, yaw] = pose_from_vanishing_point(&self.pinhole, vp);
        let k = &self.pinhole;
        let yl = lateral_at_unit_height(k, pitch, yaw, [left.x_at(row), row])?;
        let yr = lateral_at_unit_height(k, pitch, yaw, [right.x_at(row), row])?;
        let width_at_unit_height = yl - yr;
        let height = self.config.lane_width_m / width_at_unit_height;
        let [lo, hi] = HEIGHT_RANGE_M;
        // The camera (lateral 0) inside the lane, near its middle.
        let centred = (yl + yr).abs() / 2.0 <= MAX_LANE_OFFSET * width_at_unit_height;
        // The width through the crossing's pose: the lines' own geometry at the bottom row.
        let tangent_yaw = tangent_vp.map(|t| pose_from_vanishing_point(&self.pinhole, t)[1]);
        (width_at_unit_height > 0.0 && (lo..=hi).contains(&height) && centred).then_some(Sample {
            pitch,
            yaw,
            tangent_yaw,
            width_at_unit_height,
            bend: 0.0,
            common_bend: 0.0,
        })
    }

    /// The estimate's vanishing point once [`MIN_PRIOR_AGREEING`] samples agree on the pose.
    fn agreed_vanishing_point(&self) -> Option<[f64; 2]> {
        self.estimate_angles()
            .filter(|&(.., n, _)| n >= MIN_PRIOR_AGREEING)
            .map(|(pitch, yaw, ..)| vanishing_point(&self.pinhole, pitch, yaw))
    }

    /// The samples the estimate uses: of those that agree with the consensus pose (`agreeing`,
    /// see [`consensus`]), from ten on the straighter half (a gentle bend that passed as
    /// straight shifts the vanishing point sideways).
    fn chosen_samples<'a>(agreeing: &[&'a Sample]) -> Vec<&'a Sample> {
        let mut chosen = agreeing.to_vec();
        if chosen.len() >= 10 {
            // The same order as `chosen.sort_by(|a, b| a.bend.total_cmp(&b.bend))` (stable),
            // through the one instance of the stable sort in box_counts.
            let mut order: Vec<usize> = (0..chosen.len()).collect();
            super::box_counts::sort_indices_by(&mut order, &|i| chosen[i].bend);
            order.truncate(chosen.len().div_ceil(2));
            chosen = order.iter().map(|&i| chosen[i]).collect();
        }
        chosen
    }

    /// Median pitch, yaw and width at unit height over the chosen samples, their spreads
    /// (1.4826 MAD), the number of samples and whether the yaw is the tangent's; the yaw at
    /// zero bend instead of the median when the samples that agree on the pose fix it
    /// ([`super::bend_regression`]); the tangent's (with `tangent_yaw`, or once
    /// `tangent_yaw_after` frames had one) is the median and spread of the tangent's yaw over
    /// every sample that agrees on the pose and has one (the count stays the chosen samples',
    /// so the confidence errs low there).
    fn estimate_angles(&self) -> Option<(f64, f64, f64, [f64; 3], usize, bool)> {
        if self.samples.is_empty() {
            return None;
        }
        let agreeing = consensus(self.samples.iter().collect());
        let chosen = Self::chosen_samples(&agreeing);
        let column = |samples: &[&Sample], f: fn(&Sample) -> f64| -> (f64, f64) {
            let v: Vec<f64> = samples.iter().map(|s| f(s)).collect();
            let m = median(&v);
            let dev: Vec<f64> = v.iter().map(|x| (x - m).abs()).collect();
            (m, 1.4826 * median(&dev))
        };
        let (pitch, sp) = column(&chosen, |s| s.pitch);
        // The tangent's yaw does not follow the bend: the median over every frame that agrees
        // on the pose and has a tangent. Choosing the straighter frames would choose those
        // whose pixels happen to bend less, and with them a tangent pulled towards the chord.
        let tangents: Vec<&Sample> = agreeing
            .iter()
            .copied()
            .filter(|s| s.tangent_yaw.is_some())
            .collect();
        let from_tangent =
            (self.config.tangent_yaw || self.tangent_switched) && !tangents.is_empty();
        let (yaw, sy) = if from_tangent {
            column(&tangents, |s| s.tangent_yaw.unwrap_or(s.yaw))
        } else {
            let (median_yaw, sy) = column(&chosen, |s| s.yaw);
            // The yaw of a frame that does not bend, over every frame that agrees on the pose.
            let at_zero_bend = yaw_at_zero_bend(agreeing.iter().map(|s| (s.common_bend, s.yaw)));
            (at_zero_bend.unwrap_or(median_yaw), sy)
        };
        let (w1, sw) = column(&chosen, |s| s.width_at_unit_height);
        Some((pitch, yaw, w1, [sp, sy, sw], chosen.len(), from_tangent))
    }

    /// Keeps a frame's sample (the oldest goes beyond [`MAX_SAMPLES`]) and notes when
    /// `tangent_yaw_after` frames that agree on the pose have a tangent.
    fn add_sample(&mut self, sample: Sample) {
        if self.samples.len() == MAX_SAMPLES {
            self.samples.pop_front();
        }
        self.samples.push_back(sample);
        let after = self.config.tangent_yaw_after;
        if after > 0 && !self.config.tangent_yaw && !self.tangent_switched {
            let agreeing = consensus(self.samples.iter().collect());
            self.tangent_switched =
                agreeing.iter().filter(|s| s.tangent_yaw.is_some()).count() >= after;
        }
    }

    /// Adds a measured sample as a frame would (for the tests of the prior and the switch).
    #[cfg(test)]
    pub(super) fn push_sample(&mut self, sample: Sample) {
        self.add_sample(sample);
    }

    /// The median yaw over the samples the estimate chooses, radians: the estimate's yaw
    /// before the yaw at zero bend (for the test that compares them).
    #[cfg(test)]
    pub(super) fn median_yaw(&self) -> Option<f64> {
        let chosen = Self::chosen_samples(&consensus(self.samples.iter().collect()));
        let yaws: Vec<f64> = chosen.iter().map(|s| s.yaw).collect();
        (!yaws.is_empty()).then(|| median(&yaws))
    }

    /// The current estimate, or `None` before any frame has measured the camera.
    ///
    /// Confidence = min(1, n / 30) exp(-(e_pitch^2 + e_yaw^2) / (2 (0.25 deg)^2) - e_h^2 /
    /// (2 (5 %)^2)), where n is the number of samples the estimate uses and e = 1.2533 sd /
    /// sqrt(n) is the
    /// standard error of each median: it nears 1 when the estimate is well inside the goal
    /// (0.5 degrees, 10 % of the height).
    pub fn estimate(&self) -> Option<CalibrationEstimate> {
        let (pitch, yaw, w1, [sp, sy, sw], n, yaw_from_tangent) = self.estimate_angles()?;
        let n = n as f64;
        let height_m = self.config.lane_width_m / w1;
        let height_sd_m = height_m * sw / w1;
        let se = |sd: f64| 1.2533 * sd / n.sqrt();
        let (ep, ey) = (math::rad_to_deg(se(sp)), math::rad_to_deg(se(sy)));
        let eh = se(height_sd_m) / height_m;
        let confidence = (n / FULL_COUNT).min(1.0)
            * math::exp(-(ep * ep + ey * ey) / (2.0 * 0.25 * 0.25) - eh * eh / (2.0 * 0.05 * 0.05));
        let k = self.pinhole;
        let d = self.distortion;
        let camera = CameraFile {
            width: self.width,
            height: self.height,
            fx: k.fx,
            fy: k.fy,
            cx: k.cx,
            cy: k.cy,
            height_m,
            pitch_deg: math::rad_to_deg(pitch),
            yaw_deg: math::rad_to_deg(yaw),
            roll_deg: 0.0,
            k1: d.k1,
            k2: d.k2,
            p1: d.p1,
            p2: d.p2,
            k3: d.k3,
            baseline_m: None,
        };
        Camera::from_file(&camera).ok()?;
        Some(CalibrationEstimate {
            camera,
            confidence,
            frames_used: self.samples.len(),
            frames_seen: self.frames_seen,
            pitch_sd_deg: math::rad_to_deg(sp),
            yaw_sd_deg: math::rad_to_deg(sy),
            height_sd_m,
            vanishing_point: vanishing_point(&k, pitch, yaw),
            intrinsics_known: self.intrinsics_known,
            yaw_from_tangent,
        })
    }
}

/// A frame whose common bend exceeds this share of `max_bend_px` counts as bent for
/// `tangent_yaw`: its straight lines' crossing row is lifted by the bend, so the tangent's fit
/// takes the horizon row too ([`super::tangent`]); on a straighter frame the crossing's row is
/// the horizon and a free row would only add noise.
pub const BENT_SHARE: f64 = 0.5;

/// The boundaries' bend is measured on the rows from this share of the way down from the
/// vanishing point to the bottom row.
pub const BEND_ROW_SHARE: f64 = 0.15;

/// `tangent_yaw` fits the boundaries' pixels from this share of the way down from the
/// vanishing point to the bottom row (the bend from [`BEND_ROW_SHARE`]): the 1 / t
/// term of the fit is fixed by the rows near the horizon, and the more of them it has the
/// less the tangent's column follows the far pixels' noise. With 0.15 each frame's tangent
/// yaw moved against its measured bend by 1 to 1.7 degrees a working pixel on straight road
/// in the simulator, and Caltech's estimate lay 0.5 degrees from its labels' pose.
/// Measured 2026-11-30 (`calibration_eval 101 112 150|300|600 --tangent-yaw --no-trackers`,
/// median / worst yaw error, 0.15 -> 0.08): 150 frames 0.18 / 0.40 -> 0.13 / 0.47, 600
/// frames 0.21 / 0.42 -> 0.12 / 0.30; Caltech 0.89 -> 0.45 deg (labels 0.35); 0.05 gave
/// 0.14 / 0.51, 0.15 / 0.43 and 0.30 (RESULTS.md, *Auto-calibration*).
pub const TANGENT_ROW_SHARE: f64 = 0.08;

/// Largest distance in pitch or in yaw, degrees, of a sample from the consensus pose for it to
/// count (see `consensus`).
pub const CONSENSUS_DEG: f64 = 2.0;

/// The samples that agree on the pose: the largest group within [`CONSENSUS_DEG`] in pitch
/// and yaw of one of them, then those within [`CONSENSUS_DEG`] of that group's median pitch
/// and yaw. A still of a stopped car, a truck's lines or a bend that passed as straight each
/// imply a pose of their own; the road's markings, frame after frame, imply the same one, so
/// the median is taken over them alone. Ties go to the earlier sample. The groups are counted
/// in O(n log n) ([`super::box_counts`]): the estimate may be asked for every frame, with up
/// to [`MAX_SAMPLES`] samples.
pub(super) fn consensus(samples: Vec<&Sample>) -> Vec<&Sample> {
    let tol = CONSENSUS_DEG.to_radians();
    let near = |a: &Sample, pitch: f64, yaw: f64| {
        (a.pitch - pitch).abs() <= tol && (a.yaw - yaw).abs() <= tol
    };
    let points: Vec<[f64; 2]> = samples.iter().map(|a| [a.pitch, a.yaw]).collect();
    let counts = super::box_counts::box_counts(&points, tol);
    let Some(seed) = samples
        .iter()
        .zip(&counts)
        .enumerate()
        .max_by_key(|&(i, (_, &n))| (n, std::cmp::Reverse(i)))
        .map(|(_, (a, _))| *a)
    else {
        return samples;
    };
    let group: Vec<&Sample> = samples
        .iter()
        .copied()
        .filter(|b| near(b, seed.pitch, seed.yaw))
        .collect();
    let pitches: Vec<f64> = group.iter().map(|a| a.pitch).collect();
    let yaws: Vec<f64> = group.iter().map(|a| a.yaw).collect();
    let (pitch, yaw) = (median(&pitches), median(&yaws));
    let agree: Vec<&Sample> = samples
        .iter()
        .copied()
        .filter(|b| near(b, pitch, yaw))
        .collect();
    if agree.is_empty() {
        group
    } else {
        agree
    }
}

/// The working-pixel rows from `share` of the way down from the vanishing point `vp`
/// (full-resolution pixels) to the working row `bottom`; `s` full pixels per working pixel.
fn rows_below(vp: [f64; 2], bottom: usize, s: f64, share: f64) -> (f64, f64) {
    let bottom_row = bottom as f64 * s;
    ((vp[1] + share * (bottom_row - vp[1])) / s, bottom as f64)
}

/// `line` (full-resolution pixels) in working pixels.
fn working_line(line: &LineFit, s: f64) -> LineFit {
    LineFit {
        x_ref: line.x_ref / s,
        y_ref: line.y_ref / s,
        ..*line
    }
}

/// Where two lines x = x_ref + slope (y - y_ref) (same y_ref) cross; `None` when parallel.
fn crossing(a: &LineFit, b: &LineFit) -> Option<[f64; 2]> {
    let ds = a.slope - b.slope;
    if ds.abs() < 1e-6 {
        return None;
    }
    let y = a.y_ref + (b.x_ref - a.x_ref) / ds;
    Some([a.x_at(y), y])
}

/// Median of `v`; NaN when empty.
fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    // By the one instance of the stable sort in box_counts (values equal under total_cmp are
    // the same bits, so any sort gives these middle values); `v` is left as it was.
    let mut order: Vec<usize> = (0..v.len()).collect();
    super::box_counts::sort_indices_by(&mut order, &|i| v[i]);
    let n = v.len();
    if n % 2 == 1 {
        v[order[n / 2]]
    } else {
        0.5 * (v[order[n / 2 - 1]] + v[order[n / 2]])
    }
}
