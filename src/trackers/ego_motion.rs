//! The car's motion at a frame, the ego-motion input of the trackers that have one.

use crate::error::{Error, Result};
use crate::num_text::Num;
use serde::Deserialize;

/// The car's motion at a frame: its timestamp, speed and yaw rate (the frame interval is the
/// difference of consecutive timestamps). All three fields are required.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct EgoMotion {
    /// Frame timestamp, seconds.
    pub t_s: f64,
    /// Speed, metres per second (|speed| <= 150).
    pub speed_mps: f64,
    /// Yaw rate, radians per second, positive turning left (|yaw rate| <= 5).
    pub yaw_rate: f64,
}

impl EgoMotion {
    /// Largest accepted |speed|, m/s.
    pub const MAX_SPEED_MPS: f64 = 150.0;
    /// Largest accepted |yaw rate|, rad/s.
    pub const MAX_YAW_RATE: f64 = 5.0;

    /// Checks the values.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the value for a NaN or infinite one, a speed beyond
    /// [`EgoMotion::MAX_SPEED_MPS`] or a yaw rate beyond [`EgoMotion::MAX_YAW_RATE`].
    pub fn check(&self) -> Result<()> {
        crate::error::require_finite("t_s", self.t_s)?;
        for (name, v, max) in [
            ("speed_mps", self.speed_mps, Self::MAX_SPEED_MPS),
            ("yaw_rate", self.yaw_rate, Self::MAX_YAW_RATE),
        ] {
            crate::error::require_finite(name, v)?;
            if v.abs() > max {
                return Err(Error::parameter(
                    name,
                    Num(v),
                    &format!("must be within +-{}", Num(max)),
                ));
            }
        }
        Ok(())
    }
}
