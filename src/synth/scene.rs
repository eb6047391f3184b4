//! A scene: road, markings, ego motion, objects and appearance, all in one serde struct so
//! that a scenario is data (named ones live in [`super::scenarios`]).

use super::ego::EgoConfig;
use super::markings::MarkingConfig;
use super::road::RoadConfig;
use crate::error::{require_finite, require_positive, Error, Result};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// Road surface shape in the vehicle frame (Danescu eq. 4): height of the road at distance
/// x ahead is z(x) = C_V x^2 / 2 (the camera's pitch and height come from the ego pose).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VerticalProfile {
    /// Vertical curvature C_V, 1/m (positive: the road bends up, a sag).
    pub curvature: f64,
}

/// Another vehicle: a box that drives in a lane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Vehicle {
    /// Lane (0 leftmost); the vehicle keeps to its centre.
    pub lane: usize,
    /// Arc length of its rear at t = 0, metres.
    pub start_s: f64,
    /// Speed, metres per second.
    pub speed_mps: f64,
    /// Length, width, height, metres.
    pub size_m: [f64; 3],
    /// Body colour, sRGB 0..255.
    pub rgb: [u8; 3],
    /// Lateral offset from the lane centre, metres (a parked car sits on the boundary).
    #[serde(default)]
    pub offset_m: f64,
}

/// A shadow on the road.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Shadow {
    /// A band across the whole road between two arc lengths (a bridge).
    Band {
        /// Start, metres along the road.
        from_s: f64,
        /// End.
        to_s: f64,
        /// Darkening factor, 0..1 (0: black).
        light: f64,
    },
    /// Dappled tree shadows on one side of the road between two arc lengths.
    Trees {
        /// Start, metres along the road.
        from_s: f64,
        /// End.
        to_s: f64,
        /// Shadows reach from the road edge on this side (true: left) this far in, metres.
        left: bool,
        /// Reach, metres.
        reach_m: f64,
        /// Darkening factor, 0..1.
        light: f64,
    },
}

/// Painted writing on the road: a white rectangle (a bar of a letter or an arrow's stem).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoadPaint {
    /// Arc length of its near end, metres.
    pub s: f64,
    /// Lateral offset of its centre, metres.
    pub d: f64,
    /// Length along the road and width across, metres.
    pub size_m: [f64; 2],
}

/// Look of the frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Appearance {
    /// Asphalt grey level 0..255.
    pub asphalt: f64,
    /// Strength of the asphalt texture, grey levels.
    pub texture: f64,
    /// Darker repair patches (probability per 4 x 4 m cell).
    pub patches: f64,
    /// Concrete slab seams every this many metres (0: none).
    pub seam_period_m: f64,
    /// Night: low ambient light, headlights light the road ahead.
    pub night: bool,
    /// Sun glare: a bright blob at this image position (fractions of width and height), with
    /// a radius in fractions of the width.
    pub glare: Option<[f64; 3]>,
    /// Gaussian sensor noise standard deviation, grey levels.
    pub noise: f64,
    /// Box blur radius in pixels (0: sharp).
    pub blur: usize,
    /// Exposure gain oscillation amplitude (0.2: +-20 %) with a 4 s period.
    pub exposure: f64,
    /// Draw the car's hood over the bottom of the image (fraction of the height).
    pub hood: f64,
    /// Vignette strength 0..1 (darkening at the corners).
    pub vignette: f64,
}

impl Default for Appearance {
    fn default() -> Self {
        Self {
            asphalt: 95.0,
            texture: 10.0,
            patches: 0.0,
            seam_period_m: 0.0,
            night: false,
            glare: None,
            noise: 2.0,
            blur: 0,
            exposure: 0.0,
            hood: 0.0,
            vignette: 0.0,
        }
    }
}

/// A whole scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneConfig {
    /// Road layout.
    pub road: RoadConfig,
    /// Markings.
    #[serde(default)]
    pub markings: MarkingConfig,
    /// Ego motion.
    #[serde(default)]
    pub ego: EgoConfig,
    /// Vertical profile.
    #[serde(default)]
    pub vertical: VerticalProfile,
    /// Other vehicles.
    #[serde(default)]
    pub vehicles: Vec<Vehicle>,
    /// Shadows.
    #[serde(default)]
    pub shadows: Vec<Shadow>,
    /// Writing and arrows.
    #[serde(default)]
    pub road_paint: Vec<RoadPaint>,
    /// Time intervals [t0, t1) in seconds when the camera sees nothing (a black frame).
    #[serde(default)]
    pub blackouts: Vec<[f64; 2]>,
    /// Appearance.
    #[serde(default)]
    pub appearance: Appearance,
    /// Number of frames the scenario is meant to run (the road is built long enough).
    pub frames: u32,
}

impl SceneConfig {
    /// Checks what the parts do not check themselves.
    ///
    /// # Errors
    /// [`Error::Parameter`] / [`Error::Config`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        self.markings.validate()?;
        self.ego.validate(self.road.lanes)?;
        require_finite("vertical.curvature", self.vertical.curvature)?;
        if self.vertical.curvature.abs() > 0.01 {
            return Err(Error::parameter(
                "vertical.curvature",
                Num(self.vertical.curvature),
                "must be within +-0.01 1/m",
            ));
        }
        for v in &self.vehicles {
            require_finite("vehicles.start_s", v.start_s)?;
            require_finite("vehicles.speed_mps", v.speed_mps)?;
            require_finite("vehicles.offset_m", v.offset_m)?;
            for x in v.size_m {
                require_positive("vehicles.size_m", x)?;
            }
            if v.lane >= self.road.lanes {
                return Err(Error::Config(format!(
                    "a vehicle in lane {} is off the road",
                    v.lane
                )));
            }
        }
        let a = &self.appearance;
        for (name, v) in [
            ("asphalt", a.asphalt),
            ("texture", a.texture),
            ("patches", a.patches),
            ("seam_period_m", a.seam_period_m),
            ("noise", a.noise),
            ("exposure", a.exposure),
            ("hood", a.hood),
            ("vignette", a.vignette),
        ] {
            require_finite(name, v)?;
            if v < 0.0 {
                return Err(Error::parameter(name, Num(v), "must not be negative"));
            }
        }
        if a.hood > 0.5 || a.vignette > 1.0 || a.exposure > 0.9 || a.blur > 8 {
            return Err(Error::Config(
                "appearance: hood <= 0.5, vignette <= 1, exposure <= 0.9, blur <= 8".into(),
            ));
        }
        if self.frames == 0 {
            return Err(Error::parameter("frames", 0, "must be at least 1"));
        }
        Ok(())
    }

    /// Road length needed for all frames plus the view ahead.
    pub fn road_length(&self) -> f64 {
        let t = self.frames as f64 / self.ego.fps;
        self.ego.start_s.max(0.0) + self.ego.speed_mps * t + 400.0
    }
}
