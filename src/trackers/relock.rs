//! The bottom-up lane detector behind the trackers' `relock_share` option (ours, beyond the
//! papers): the auto-calibration's ridge and Hough-line detector run on every frame with the
//! tracker's camera, its ego pair taken to the road ([`crate::calib::ego_on_road`]). A tracker
//! replaces a share of its particles by draws around that pair (a data-driven proposal, as in
//! mixture Monte Carlo localisation), so that a cloud stuck on a wrong lane, or lost after a
//! gap, locks on again where the markings are; a wrong detection costs only the replaced
//! particles, which the measurement then weighs like any other.

use crate::calib::ego_on_road::{ego_on_road, EgoOnRoad};
use crate::calib::{Calibrator, CalibratorConfig};
use crate::camera::Camera;
use crate::error::Result;
use nalgebra::Vector3;

/// The detector and its answer for the frame in progress.
#[derive(Debug, Clone)]
pub struct RelockDetector {
    calibrator: Calibrator,
    detection: Option<EgoOnRoad>,
}

impl RelockDetector {
    /// A detector for `camera`'s frames (its intrinsics and lens; the pose is the tracker's).
    ///
    /// # Errors
    /// As [`Calibrator::new`].
    pub fn new(camera: &Camera) -> Result<Self> {
        let mut calibrator = Calibrator::new(
            camera.width(),
            camera.height(),
            Some(&camera.to_file()),
            // Only its lines are used: no frame fits the lane's tangent.
            CalibratorConfig {
                tangent_yaw_after: 0,
                ..CalibratorConfig::default()
            },
        )?;
        calibrator.set_known_vanishing_point(vanishing_point(camera))?;
        Ok(Self {
            calibrator,
            detection: None,
        })
    }

    /// Detects the ego pair of a frame (already checked against the camera).
    ///
    /// # Errors
    /// As [`Calibrator::feed_rgba`].
    pub fn feed(
        &mut self,
        camera: &Camera,
        rgba: &[u8],
        width: usize,
        height: usize,
    ) -> Result<()> {
        let observation = self.calibrator.feed_rgba(rgba, width, height)?;
        self.detection = ego_on_road(camera, observation);
        Ok(())
    }

    /// Computes the marking image of a frame (already checked against the camera) and no
    /// lines: for a tracker that needs [`Self::working_images`] only, at a fraction of the
    /// cost of [`Self::feed`]. The images are those [`Self::feed`] computes; there is no
    /// [`Self::detection`] afterwards.
    ///
    /// # Errors
    /// As [`Calibrator::feed_rgba_markings_only`].
    pub fn feed_markings_only(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        self.detection = None;
        self.calibrator.feed_rgba_markings_only(rgba, width, height)
    }

    /// [`Self::feed`] when the tracker needs this frame's ego pair (`lines`: its
    /// `relock_share`, or a start on the detected pair), else [`Self::feed_markings_only`].
    ///
    /// # Errors
    /// As [`Self::feed`].
    pub fn feed_as_needed(
        &mut self,
        camera: &Camera,
        rgba: &[u8],
        width: usize,
        height: usize,
        lines: bool,
    ) -> Result<()> {
        if lines {
            self.feed(camera, rgba, width, height)
        } else {
            self.feed_markings_only(rgba, width, height)
        }
    }

    /// The ego pair on the road of the last frame fed, if one was found.
    pub fn detection(&self) -> Option<EgoOnRoad> {
        self.detection
    }

    /// The last frame's marking intensity and saturation images and their block size (see
    /// [`Calibrator::working_images`]).
    pub fn working_images(&self) -> (&crate::image::Image<u8>, &crate::image::Image<u8>, usize) {
        self.calibrator.working_images()
    }

    /// Forgets every frame (a new video).
    pub fn reset(&mut self) {
        self.calibrator.reset();
        self.detection = None;
    }
}

/// Undistorted pixel where the road straight ahead of `camera` vanishes: the image of the
/// road direction (1, 0, 0), K R (1, 0, 0)^T.
fn vanishing_point(camera: &Camera) -> [f64; 2] {
    let d = camera.rotation() * Vector3::new(1.0, 0.0, 0.0);
    let [fx, fy] = camera.focal();
    let [cx, cy] = camera.principal_point();
    [cx + fx * d.x / d.z, cy + fy * d.y / d.z]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Eye, Scene};
    use crate::trackers::fresh_roads::after_blackout;

    /// On rendered roads the detector finds the ego lane of the truth. Measured (2026-11-25,
    /// 640x480, the default camera, 80 frames, seeds 1-2, also on `multi-lane`): found in 74
    /// to 80 of 80 frames (worn markings the fewest), all but 0-1 of them right; worst errors
    /// 0.12 m in the centre, 0.25 m in the width, 0.031 rad in the heading. Thresholds (40
    /// frames): found in 90 % of the frames, and where found, the centre within 0.25 m, the
    /// width within 0.3 m (it measures between marking centres) and the heading within 0.02
    /// rad in 95 % of them.
    #[test]
    fn the_detector_finds_the_ego_lane_of_rendered_roads() {
        let camera = default_camera(640, 480).unwrap();
        let mut rgba = vec![0u8; 640 * 480 * 4];
        const FRAMES: u32 = 40;
        for name in ["highway-straight", "worn-markings", "highway-curve"] {
            for seed in 1..=2 {
                let mut config = scenario(name).unwrap();
                config.frames = FRAMES;
                let mut scene = Scene::new(config, camera.clone(), seed).unwrap();
                let mut detector = RelockDetector::new(&camera).unwrap();
                let (mut found, mut right) = (0, 0);
                let mut worst = [0.0f64; 3];
                for f in 0..FRAMES {
                    scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                    detector.feed(&camera, &rgba, 640, 480).unwrap();
                    let Some(d) = detector.detection() else {
                        continue;
                    };
                    let t = crate::trackers::scene_truth(&scene, f);
                    let err = [
                        (d.centre() + t.lateral_offset_m).abs(),
                        (d.width() - t.lane_width_m).abs(),
                        (d.heading() - t.heading_rad).abs(),
                    ];
                    for (w, e) in worst.iter_mut().zip(err) {
                        *w = w.max(e);
                    }
                    found += 1;
                    right += usize::from(err[0] < 0.25 && err[1] < 0.3 && err[2] < 0.02);
                }
                assert!(
                    found as f64 >= 0.9 * FRAMES as f64 && right as f64 >= 0.95 * found as f64,
                    "{name} seed {seed}: found {found} / {FRAMES}, right {right}, worst {worst:?}"
                );
            }
        }
    }

    /// The marking-image-only feed computes exactly the working images of the full one (the
    /// snap and the neighbouring-lane probes of a tracker without `relock_share` read them),
    /// finds no ego pair, and leaves the full feed's detections as they would have been; fed
    /// lines on the first frame only (lee-cpf's start), the images are the full feed's on
    /// every frame.
    #[test]
    fn the_markings_only_feed_gives_the_full_feeds_images() {
        let camera = default_camera(320, 240).unwrap();
        let mut rgba = vec![0u8; 320 * 240 * 4];
        let mut scene = Scene::new(scenario("highway-curve").unwrap(), camera.clone(), 3).unwrap();
        let (mut full, mut markings, mut mixed, mut first_only) = (
            RelockDetector::new(&camera).unwrap(),
            RelockDetector::new(&camera).unwrap(),
            RelockDetector::new(&camera).unwrap(),
            RelockDetector::new(&camera).unwrap(),
        );
        for f in 0..6 {
            scene.render(f * 7, Eye::Left, &mut rgba, None).unwrap();
            full.feed(&camera, &rgba, 320, 240).unwrap();
            markings.feed_markings_only(&rgba, 320, 240).unwrap();
            assert_eq!(
                full.working_images(),
                markings.working_images(),
                "frame {f}"
            );
            assert!(
                full.detection().is_some(),
                "frame {f}: the full feed finds the lane"
            );
            assert!(markings.detection().is_none(), "frame {f}");
            // A markings-only frame between two full ones changes no detection.
            if f % 2 == 0 {
                mixed.feed_markings_only(&rgba, 320, 240).unwrap();
            }
            mixed.feed(&camera, &rgba, 320, 240).unwrap();
            assert_eq!(mixed.detection(), full.detection(), "frame {f}");
            // lee-cpf's start on the pair without `relock_share`: lines on the first frame only.
            first_only
                .feed_as_needed(&camera, &rgba, 320, 240, f == 0)
                .unwrap();
            assert_eq!(
                first_only.working_images(),
                full.working_images(),
                "frame {f}"
            );
            let expected = if f == 0 { full.detection() } else { None };
            assert_eq!(first_only.detection(), expected, "frame {f}");
        }
        let err = markings.feed_markings_only(&rgba[4..], 320, 240);
        assert!(err.is_err(), "a short buffer is refused");
        markings.feed_markings_only(&rgba, 320, 240).unwrap();
        assert_eq!(full.working_images(), markings.working_images());
    }

    /// `occlusion` blacks the camera out for 1 s (frames 150-179). Measured (2026-11-25,
    /// 320x240, 300 particles, scene seed 1, boundary accuracy / valid share over frames
    /// 190-229): adachi-mmpf, the paper's filter, 0.86 / 0.90 with tracker seed 1 and 0.0 / 0.0
    /// with seed 2 (its cloud never finds the lane again); with `relock_share` 0.05, 1.0 / 1.0
    /// with both. (lee-cpf and danescu-mono re-lock without it; their figures do not change.)
    #[test]
    fn adachi_relocks_after_a_blackout_with_the_detector() {
        for seed in 1..=2 {
            let (accuracy, valid) =
                after_blackout("adachi-mmpf", r#", "relock_share": 0.05"#, 1, seed);
            assert!(
                accuracy >= 0.95 && valid >= 0.95,
                "seed {seed}: accuracy {accuracy}, valid {valid}"
            );
        }
    }
}
