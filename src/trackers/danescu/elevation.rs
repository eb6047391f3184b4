//! Curbs from the elevation map (Sec. VI-A b): the paper takes them from the authors' ref.
//! \[10\] (Oniga et al. 2007), which grids the 3-D points on the road plane into an elevation
//! map and classifies its cells as road, traffic isle (curbs) or obstacle by their height.
//! Ours, in that spirit:
//!
//! 1. **Elevation map**: cells of `cell_m` = (ahead, lateral) metres over x in
//!    [0, `range_m`] and |y| <= `half_width_m` in the calibrated road frame. Each point
//!    votes in its cell by its height h above the detected road plane (z - m x, the
//!    preliminary pitch's line): road where |h| < `height_m[0]`, raised (a curb or traffic
//!    isle) for h in [`height_m[0]`, `height_m[1]`], obstacle above, nothing below the road.
//! 2. **Classes**: a cell takes the class with most votes if that class has at least
//!    `min_points` and more than half of all the cell's points; otherwise it is unknown.
//!    (Oniga takes the highest point per cell of a dense, accurate stereo system; a majority
//!    vote is our choice against the mismatches and sub-pixel noise of a software matcher,
//!    which moved a cell's mean or maximum by up to 2 m on `urban`.)
//! 3. **Curb edges**: on each row of cells, scanning outward from the car's axis on each side,
//!    the first raised cell that follows a road cell (at most `max_gap` unknown cells apart)
//!    and is followed by raised cells (three of the next four, no road) is a curb; its foot is
//!    the raised cell's inner edge. An obstacle ends the scan:
//!    what stands behind a parked car cannot be seen. A foot with no other on its side within
//!    two rows and two cells across is dropped (a curb is a line). (Oniga's region-level
//!    classification is reduced to this scan: a lane tracker needs only the nearest curb on
//!    each side.)
//! 4. The feet are drawn as segments at road height into the marking-edge image, so that
//!    markings and curbs are "processed together" in DT^S as the paper says; each pixel
//!    snaps to the nearest road edge (Canny) within `snap_m` on its row, which places the foot
//!    to a pixel where the map places it to a cell (our refinement).

use crate::error::{require_finite, require_positive, require_within, Error, Result};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// Options of the curb detection (stereo only).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CurbConfig {
    /// Detect curbs and add them to DT^S (`false`: markings only).
    pub enabled: bool,
    /// Cell size of the elevation map: ahead, lateral, metres.
    pub cell_m: [f64; 2],
    /// Farthest distance mapped, metres (the paper's D_3D by default: the road is taken as
    /// the plane z = m x, which a vertical curve bends away from further out).
    pub range_m: f64,
    /// Lateral half-width mapped, metres.
    pub half_width_m: f64,
    /// Fewest votes for a cell's class (fewer: unknown).
    pub min_points: u16,
    /// A cell is raised (a curb) between these elevations, metres; above, an obstacle.
    pub height_m: [f64; 2],
    /// Most unknown cells between a road cell and the curb after it.
    pub max_gap: usize,
    /// In the image, a foot moves to the nearest road edge within this many metres.
    pub snap_m: f64,
}

impl Default for CurbConfig {
    fn default() -> Self {
        Self {
            enabled: true,
            cell_m: [0.25, 0.1],
            range_m: 15.0,
            half_width_m: 8.0,
            min_points: 5,
            height_m: [0.06, 0.35],
            max_gap: 2,
            snap_m: 0.2,
        }
    }
}

impl CurbConfig {
    /// Checks every option.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        require_positive("curbs.cell_m", self.cell_m[0])?;
        require_positive("curbs.cell_m", self.cell_m[1])?;
        require_positive("curbs.range_m", self.range_m)?;
        require_positive("curbs.half_width_m", self.half_width_m)?;
        require_within("curbs.snap_m", self.snap_m, 0.0..=1.0, "must be 0 to 1 m")?;
        require_finite("curbs.height_m", self.height_m[0])?;
        require_finite("curbs.height_m", self.height_m[1])?;
        if !(self.height_m[0] > 0.0 && self.height_m[0] < self.height_m[1]) {
            return Err(Error::parameter(
                "curbs.height_m",
                Num(self.height_m[0]),
                "must be a positive [lowest, highest] curb height with lowest < highest",
            ));
        }
        let cells = (self.range_m / self.cell_m[0]) * (2.0 * self.half_width_m / self.cell_m[1]);
        if cells > 4e6 {
            return Err(Error::parameter(
                "curbs.cell_m",
                Num(self.cell_m[0]),
                "makes an elevation map of over 4 million cells",
            ));
        }
        Ok(())
    }
}

/// A curb's foot over one row of cells: at lateral `y` from `x0` to `x1` ahead (metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurbFoot {
    /// Near end, metres ahead.
    pub x0: f64,
    /// Far end, metres ahead.
    pub x1: f64,
    /// Lateral offset of the foot (left positive), metres.
    pub y: f64,
}

/// The elevation map and the curb feet found in it.
#[derive(Debug, Clone)]
pub struct ElevationMap {
    config: CurbConfig,
    rows: usize,
    cols: usize,
    /// Per cell, the points voting road, raised, obstacle, and below the road.
    votes: Vec<[u16; 4]>,
    feet: Vec<CurbFoot>,
    isolated: Vec<bool>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Unknown,
    Road,
    Raised,
    Obstacle,
}

impl ElevationMap {
    /// An empty map.
    ///
    /// # Errors
    /// Option errors of [`CurbConfig::validate`].
    pub fn new(config: CurbConfig) -> Result<Self> {
        config.validate()?;
        let rows = (config.range_m / config.cell_m[0]).ceil() as usize;
        let cols = 2 * (config.half_width_m / config.cell_m[1]).ceil() as usize;
        Ok(Self {
            config,
            rows,
            cols,
            votes: vec![[0; 4]; rows * cols],
            feet: Vec::with_capacity(2 * rows),
            isolated: Vec::with_capacity(2 * rows),
        })
    }

    /// The options.
    pub fn config(&self) -> &CurbConfig {
        &self.config
    }

    /// Empties the map.
    pub fn clear(&mut self) {
        self.votes.fill([0; 4]);
        self.feet.clear();
    }

    /// Adds a point `x` ahead, `y` left, `height` above the road plane (metres).
    #[inline]
    pub fn add(&mut self, x: f64, y: f64, height: f64) {
        let r = x / self.config.cell_m[0];
        let c = y / self.config.cell_m[1] + (self.cols / 2) as f64;
        if r >= 0.0 && c >= 0.0 && (r as usize) < self.rows && (c as usize) < self.cols {
            let [lo, hi] = self.config.height_m;
            let k = if height.abs() < lo {
                0
            } else if height >= lo && height <= hi {
                1
            } else if height > hi {
                2
            } else {
                3
            };
            let v = &mut self.votes[r as usize * self.cols + c as usize][k];
            *v = v.saturating_add(1);
        }
    }

    fn class(&self, i: usize) -> Class {
        let v = self.votes[i];
        let total: u32 = v.iter().map(|&n| n as u32).sum();
        let (k, &n) = v[..3]
            .iter()
            .enumerate()
            .max_by_key(|(_, &n)| n)
            .unwrap_or((0, &0));
        if n < self.config.min_points.max(1) || 2 * n as u32 <= total {
            return Class::Unknown;
        }
        [Class::Road, Class::Raised, Class::Obstacle][k]
    }

    /// Whether the raised cell (`r`, `c`) is confirmed by the next cells outward: among the
    /// next four, at least three raised and none road (a kerbstone is 3 cells wide at the
    /// default size; a lone raised cell on the road is noise).
    fn confirmed(&self, r: usize, c: isize, side: isize) -> bool {
        let (mut raised, mut road) = (0, 0);
        for k in 1..=4 {
            let cc = c + k * side;
            if cc < 0 || cc as usize >= self.cols {
                break;
            }
            match self.class(r * self.cols + cc as usize) {
                Class::Raised => raised += 1,
                Class::Road => road += 1,
                _ => {}
            }
        }
        raised >= 3 && road == 0
    }

    /// Finds the curb feet on each side of every row of cells (step 3 of the module docs).
    pub fn find(&mut self) -> &[CurbFoot] {
        self.feet.clear();
        let [dx, dy] = self.config.cell_m;
        let half = self.cols / 2;
        for r in 0..self.rows {
            for side in [1isize, -1] {
                // Columns outward from the axis: half, half + 1, ... (left) or half - 1, ...
                let mut last_road: Option<isize> = None;
                let mut c = if side > 0 {
                    half as isize
                } else {
                    half as isize - 1
                };
                while c >= 0 && (c as usize) < self.cols {
                    match self.class(r * self.cols + c as usize) {
                        Class::Road => last_road = Some(c),
                        Class::Raised if !self.confirmed(r, c, side) => {}
                        Class::Raised => {
                            if let Some(l) = last_road {
                                if (c - l).unsigned_abs() <= self.config.max_gap + 1 {
                                    // The raised cell's inner edge: the face's points vote
                                    // raised where most of a cell is behind the face, so the
                                    // face is within half a cell of that edge. (Unknown cells
                                    // before it are road without texture enough to match.)
                                    let edge = if side > 0 { c } else { c + 1 };
                                    let y = (edge - half as isize) as f64 * dy;
                                    self.feet.push(CurbFoot {
                                        x0: r as f64 * dx,
                                        x1: (r + 1) as f64 * dx,
                                        y,
                                    });
                                }
                            }
                            break;
                        }
                        Class::Obstacle => break,
                        Class::Unknown => {}
                    }
                    c += side;
                }
            }
        }
        // A curb is a line: a foot with no other on its side within two rows and two cells
        // across is noise.
        let n = self.feet.len();
        self.isolated.clear();
        self.isolated.extend((0..n).map(|i| {
            let a = self.feet[i];
            !self.feet.iter().enumerate().any(|(j, b)| {
                j != i
                    && (a.y > 0.0) == (b.y > 0.0)
                    && (a.x0 - b.x0).abs() <= 2.0 * dx + 1e-9
                    && (a.y - b.y).abs() <= 2.0 * dy + 1e-9
            })
        }));
        let mut k = 0;
        self.feet.retain(|_| {
            k += 1;
            !self.isolated[k - 1]
        });
        &self.feet
    }

    /// What the map says of road point (`x` ahead, `y` left): 0 unknown or outside the map,
    /// 1 road, 2 raised (curb), 3 obstacle.
    pub fn class_at(&self, x: f64, y: f64) -> u8 {
        let r = x / self.config.cell_m[0];
        let c = y / self.config.cell_m[1] + (self.cols / 2) as f64;
        if !(r >= 0.0 && c >= 0.0 && (r as usize) < self.rows && (c as usize) < self.cols) {
            return 0;
        }
        match self.class(r as usize * self.cols + c as usize) {
            Class::Unknown => 0,
            Class::Road => 1,
            Class::Raised => 2,
            Class::Obstacle => 3,
        }
    }

    /// The feet found by the last [`ElevationMap::find`].
    pub fn feet(&self) -> &[CurbFoot] {
        &self.feet
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Road points between a left curb at y = 3 and a right one at y = -2, raised points
    /// behind them, a parked car (1 m tall) in front of the left curb from 12 to 14 m.
    fn street() -> ElevationMap {
        let mut map = ElevationMap::new(CurbConfig {
            range_m: 20.0,
            ..CurbConfig::default()
        })
        .unwrap();
        let mut k = 0u32;
        for xi in 0..320 {
            let x = 4.0 + xi as f64 * 0.05;
            for yi in 0..320 {
                let y = -4.0 + yi as f64 * 0.025;
                k = k.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                let noise = ((k >> 16) % 100) as f64 / 100.0 * 0.04 - 0.02;
                let height = if (12.0..14.0).contains(&x) && y > 2.0 && y < 3.5 {
                    1.0
                } else if !(-2.0..=3.0).contains(&y) {
                    0.15
                } else {
                    0.0
                };
                map.add(x, y, height + noise);
            }
        }
        map
    }

    #[test]
    fn curb_feet_are_found_where_the_road_steps_up() {
        let mut map = street();
        let feet = map.find().to_vec();
        assert_eq!(map.class_at(10.0, 0.0), 1, "road");
        assert_eq!(map.class_at(10.0, 3.5), 2, "behind the left curb");
        assert_eq!(map.class_at(13.0, 2.5), 3, "the parked car");
        assert_eq!(map.class_at(30.0, 0.0), 0, "beyond the map");
        assert_eq!(map.class_at(f64::NAN, 0.0), 0);
        let left: Vec<_> = feet.iter().filter(|f| f.y > 0.0).collect();
        let right: Vec<_> = feet.iter().filter(|f| f.y < 0.0).collect();
        // Rows of 0.25 m from 4 m to 20 m: 64 rows, less the car's 8 on the left.
        assert!(right.len() >= 60, "{}", right.len());
        assert!(left.len() >= 52 && left.len() <= 56, "{}", left.len());
        for f in &left {
            assert!((f.y - 3.0).abs() <= 0.1, "{f:?}");
            assert!(!(f.x1 > 12.0 && f.x0 < 14.0), "behind the car: {f:?}");
        }
        for f in &right {
            assert!((f.y + 2.0).abs() <= 0.1, "{f:?}");
        }
    }

    #[test]
    fn a_flat_road_has_no_curbs_and_bad_options_are_errors() {
        let mut map = ElevationMap::new(CurbConfig::default()).unwrap();
        for xi in 0..80 {
            for yi in 0..120 {
                map.add(4.0 + xi as f64 * 0.2, -4.0 + yi as f64 * 0.075, 0.02);
            }
        }
        assert!(map.find().is_empty());
        map.clear();
        assert!(map.find().is_empty());
        for (bad, name) in [
            (
                CurbConfig {
                    height_m: [0.3, 0.1],
                    ..CurbConfig::default()
                },
                "curbs.height_m",
            ),
            (
                CurbConfig {
                    cell_m: [f64::NAN, 0.1],
                    ..CurbConfig::default()
                },
                "curbs.cell_m",
            ),
            (
                CurbConfig {
                    cell_m: [0.001, 0.001],
                    ..CurbConfig::default()
                },
                "curbs.cell_m",
            ),
        ] {
            let e = ElevationMap::new(bad).unwrap_err().to_string();
            assert!(e.contains(name), "{e}");
        }
    }
}
