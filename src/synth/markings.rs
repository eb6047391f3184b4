//! Lane markings of the simulator: which boundary carries which paint, where.
//!
//! Markings are centred on the boundary lines d_k(s) of [`Road`], so the lane width W is the
//! distance between marking centres; Danescu's W_0 (between the inner edges) is then
//! W - (W_L + W_R) / 2, which the ground truth reports. A boundary between two existing lanes
//! gets the `inner` style (dashed by default), a boundary with an existing lane on one side
//! only gets the `outer` style (solid), per-boundary overrides win over both, and wear
//! stretches scale the paint's visibility (0 = missing).
//!
//! Coverage is anti-aliased with a box filter over the pixel's footprint on the road: the
//! fraction of [d - f_d/2, d + f_d/2] x [s - f_s/2, s + f_s/2] that is paint.

use super::road::Road;
use crate::error::{require_positive, require_within, Error, Result};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// The dash pattern of a marking.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Pattern {
    /// A continuous line.
    Solid,
    /// Dashes of length `dash_m` every `period_m` metres.
    Dashed {
        /// Dash length, metres.
        dash_m: f64,
        /// Dash period (dash + gap), metres.
        period_m: f64,
    },
    /// Two solid lines `gap_m` apart (inner edges).
    Double {
        /// Gap between the two lines, metres.
        gap_m: f64,
    },
    /// A kerb: its inner face stands on the boundary line and everything beyond it (a
    /// concrete band 0.3 m wide, then the pavement) is raised by
    /// [`MarkingConfig::curb_height_m`] (see the renderer's `kerbs` module).
    Curb,
    /// No marking (an unmarked road edge: asphalt meets the verge).
    None,
}

/// Paint colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Paint {
    /// White paint.
    White,
    /// Yellow paint.
    Yellow,
}

impl Paint {
    /// Linear RGB in 0..255 of fresh paint in daylight.
    pub fn rgb(self) -> [f32; 3] {
        match self {
            Paint::White => [225.0, 225.0, 220.0],
            Paint::Yellow => [225.0, 180.0, 40.0],
        }
    }
}

/// A marking's look.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MarkingStyle {
    /// Dash pattern.
    pub pattern: Pattern,
    /// Colour.
    pub paint: Paint,
    /// Line width, metres (Danescu's W_L / W_R).
    pub width_m: f64,
}

/// A per-boundary style.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryStyle {
    /// Boundary index (0 leftmost).
    pub boundary: usize,
    /// Its style.
    pub style: MarkingStyle,
}

/// A stretch of worn paint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wear {
    /// Start, metres along the road.
    pub from_s: f64,
    /// End.
    pub to_s: f64,
    /// The boundary, or every boundary when absent.
    #[serde(default)]
    pub boundary: Option<usize>,
    /// Remaining visibility, 0 (gone) to 1 (fresh).
    pub visibility: f64,
}

/// All markings of a road.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MarkingConfig {
    /// Style of boundaries with a lane on one side only.
    pub outer: MarkingStyle,
    /// Style of boundaries between two lanes.
    pub inner: MarkingStyle,
    /// Per-boundary styles.
    pub overrides: Vec<BoundaryStyle>,
    /// Worn stretches.
    pub wear: Vec<Wear>,
    /// Height of kerbs and the pavement behind them above the road, metres (0 to 0.5).
    pub curb_height_m: f64,
}

impl Default for MarkingConfig {
    fn default() -> Self {
        Self {
            outer: MarkingStyle {
                pattern: Pattern::Solid,
                paint: Paint::White,
                width_m: 0.15,
            },
            inner: MarkingStyle {
                pattern: Pattern::Dashed {
                    dash_m: 3.0,
                    period_m: 12.0,
                },
                paint: Paint::White,
                width_m: 0.15,
            },
            overrides: vec![],
            wear: vec![],
            curb_height_m: CURB_HEIGHT_M,
        }
    }
}

/// Width of a kerb band, metres.
pub const CURB_WIDTH_M: f64 = 0.3;

/// Default kerb height, metres (a common urban kerb).
pub const CURB_HEIGHT_M: f64 = 0.15;

/// What a pixel's footprint sees of the markings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    /// Fraction of the footprint covered, 0..1 (after wear).
    pub alpha: f32,
    /// Colour of what covers it.
    pub rgb: [f32; 3],
}

impl MarkingConfig {
    /// Checks every style.
    ///
    /// # Errors
    /// [`Error::Parameter`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        let styles = [self.outer, self.inner]
            .into_iter()
            .chain(self.overrides.iter().map(|o| o.style));
        for st in styles {
            require_positive("width_m", st.width_m)?;
            if st.width_m > 1.0 {
                return Err(Error::parameter(
                    "width_m",
                    Num(st.width_m),
                    "must be at most 1 m",
                ));
            }
            match st.pattern {
                Pattern::Dashed { dash_m, period_m } => {
                    require_positive("dash_m", dash_m)?;
                    require_positive("period_m", period_m)?;
                    if dash_m > period_m {
                        return Err(Error::parameter(
                            "dash_m",
                            Num(dash_m),
                            "must not exceed period_m",
                        ));
                    }
                }
                Pattern::Double { gap_m } => {
                    require_within("gap_m", gap_m, 0.0..=1.0, "must be 0 to 1 m")?;
                }
                _ => {}
            }
        }
        require_within(
            "curb_height_m",
            self.curb_height_m,
            0.0..=0.5,
            "must be 0 to 0.5 m",
        )?;
        for w in &self.wear {
            require_within("wear.visibility", w.visibility, 0.0..=1.0, "must be 0 to 1")?;
        }
        Ok(())
    }

    /// Whether any style is a kerb.
    pub fn has_curbs(&self) -> bool {
        [self.outer, self.inner]
            .iter()
            .chain(self.overrides.iter().map(|o| &o.style))
            .any(|st| st.pattern == Pattern::Curb)
    }

    /// The style of boundary `k` at `s`, or `None` when no lane touches it there.
    pub fn style(&self, road: &Road, k: usize, s: f64) -> Option<MarkingStyle> {
        let left = k > 0 && road.lane_exists(k - 1, s);
        let right = road.lane_exists(k, s);
        if !left && !right {
            return None;
        }
        if let Some(o) = self.overrides.iter().find(|o| o.boundary == k) {
            return Some(o.style);
        }
        Some(if left && right {
            self.inner
        } else {
            self.outer
        })
    }

    /// Paint visibility of boundary `k` at `s` (1 unless worn).
    pub fn visibility(&self, k: usize, s: f64) -> f64 {
        self.wear
            .iter()
            .filter(|w| s >= w.from_s && s < w.to_s && w.boundary.is_none_or(|b| b == k))
            .fold(1.0, |v, w| v * w.visibility)
    }

    /// Whether boundary `k` is painted at arc length `s` (inside a dash; always for solid and
    /// double lines; never for kerbs and unmarked edges). Dashes of boundary k are offset by
    /// k * 1.7 m so that neighbouring lines do not dash in step.
    pub fn painted_at(&self, style: &MarkingStyle, k: usize, s: f64) -> bool {
        match style.pattern {
            Pattern::Solid | Pattern::Double { .. } => true,
            Pattern::Dashed { dash_m, period_m } => {
                (s + 1.7 * k as f64).rem_euclid(period_m) < dash_m
            }
            Pattern::Curb | Pattern::None => false,
        }
    }

    /// Coverage of the footprint centred at (s, d) of size `fd` x `fs` metres by the markings
    /// near lateral offset d.
    pub fn coverage(&self, road: &Road, s: f64, d: f64, fd: f64, fs: f64) -> Coverage {
        let w = road.lane_width(s);
        let n = road.lanes() as f64;
        let nearest = (n / 2.0 - d / w).round();
        let mut best = Coverage {
            alpha: 0.0,
            rgb: [0.0; 3],
        };
        for k in [nearest - 1.0, nearest, nearest + 1.0] {
            if k < 0.0 || k > n {
                continue;
            }
            let k = k as usize;
            let Some(style) = self.style(road, k, s) else {
                continue;
            };
            let centre = road.boundary_offset(k, s);
            let (alpha, rgb) = match style.pattern {
                Pattern::None => continue,
                Pattern::Curb => {
                    // Outside the road: left of boundary 0 / right of the last boundary.
                    let outward = if k == 0 { 1.0 } else { -1.0 };
                    let mid = centre + outward * (CURB_WIDTH_M / 2.0);
                    (
                        interval(d - mid, CURB_WIDTH_M / 2.0, fd),
                        [170.0, 168.0, 160.0],
                    )
                }
                Pattern::Double { gap_m } => {
                    let off = (gap_m + style.width_m) / 2.0;
                    let a = interval(d - centre - off, style.width_m / 2.0, fd)
                        + interval(d - centre + off, style.width_m / 2.0, fd);
                    (a.min(1.0), style.paint.rgb())
                }
                Pattern::Solid => (
                    interval(d - centre, style.width_m / 2.0, fd),
                    style.paint.rgb(),
                ),
                Pattern::Dashed { dash_m, period_m } => {
                    let lateral = interval(d - centre, style.width_m / 2.0, fd);
                    if lateral == 0.0 {
                        continue;
                    }
                    (
                        lateral * dash_fraction(s + 1.7 * k as f64, dash_m, period_m, fs),
                        style.paint.rgb(),
                    )
                }
            };
            let alpha = alpha * self.visibility(k, s) as f32;
            if alpha > best.alpha {
                best = Coverage { alpha, rgb };
            }
        }
        best
    }
}

/// Fraction of [x - f/2, x + f/2] inside [-half, half].
pub fn interval(x: f64, half: f64, f: f64) -> f32 {
    let f = f.max(1e-6);
    let lo = (x - f / 2.0).max(-half);
    let hi = (x + f / 2.0).min(half);
    ((hi - lo) / f).clamp(0.0, 1.0) as f32
}

/// Fraction of [s - f/2, s + f/2] covered by dashes [j P, j P + L).
fn dash_fraction(s: f64, dash: f64, period: f64, f: f64) -> f32 {
    if f >= period {
        return (dash / period) as f32;
    }
    let f = f.max(1e-6);
    let lo = s - f / 2.0;
    let start = (lo / period).floor() * period;
    let mut covered = 0.0;
    let mut j = start;
    while j < s + f / 2.0 {
        let a = lo.max(j);
        let b = (s + f / 2.0).min(j + dash);
        covered += (b - a).max(0.0);
        j += period;
    }
    (covered / f).clamp(0.0, 1.0) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::road::{LaneGap, RoadConfig, Segment};

    fn road(gaps: Vec<LaneGap>) -> Road {
        let config = RoadConfig {
            segments: vec![Segment {
                length_m: 100.0,
                curvature: 0.0,
                curvature_rate: 0.0,
            }],
            lanes: 3,
            lane_width_m: 3.5,
            width_changes: vec![],
            lane_gaps: gaps,
        };
        Road::new(config, 500.0).unwrap()
    }

    #[test]
    fn styles_follow_the_lanes_that_exist() {
        let gaps = vec![LaneGap {
            lane: 2,
            from_s: 100.0,
            to_s: 200.0,
        }];
        let r = road(gaps);
        let m = MarkingConfig::default();
        assert_eq!(m.style(&r, 0, 50.0), Some(m.outer));
        assert_eq!(m.style(&r, 2, 50.0), Some(m.inner));
        // Lane 2 absent: boundary 2 becomes the road edge, boundary 3 disappears.
        assert_eq!(m.style(&r, 2, 150.0), Some(m.outer));
        assert_eq!(m.style(&r, 3, 150.0), None);
    }

    #[test]
    fn coverage_is_the_painted_fraction_of_the_footprint() {
        let r = road(vec![]);
        let m = MarkingConfig::default();
        // Boundary 1 at d = 1.75 (solid inner? no: dashed inner). Boundary 0 at 5.25 is solid.
        assert_eq!(m.coverage(&r, 10.0, 5.25, 0.01, 0.01).alpha, 1.0);
        let half = m.coverage(&r, 10.0, 5.25 + 0.075, 0.02, 0.01).alpha;
        assert!((half - 0.5).abs() < 1e-6, "{half}");
        assert_eq!(m.coverage(&r, 10.0, 4.0, 0.01, 0.01).alpha, 0.0);
        // Dashes of boundary 1 cover s in [j 12 - 1.7, j 12 - 1.7 + 3).
        assert_eq!(m.coverage(&r, 11.0, 1.75, 0.01, 0.01).alpha, 1.0);
        assert_eq!(m.coverage(&r, 5.0, 1.75, 0.01, 0.01).alpha, 0.0);
        // A footprint longer than a period sees the duty cycle.
        let avg = m.coverage(&r, 5.0, 1.75, 0.01, 24.0).alpha;
        assert!((avg - 0.25).abs() < 1e-6);
    }

    #[test]
    fn wear_fades_paint_and_bad_styles_are_errors() {
        let r = road(vec![]);
        let mut m = MarkingConfig::default();
        m.wear.push(Wear {
            from_s: 0.0,
            to_s: 50.0,
            boundary: Some(0),
            visibility: 0.25,
        });
        assert_eq!(m.coverage(&r, 10.0, 5.25, 0.01, 0.01).alpha, 0.25);
        assert_eq!(m.coverage(&r, 60.0, 5.25, 0.01, 0.01).alpha, 1.0);
        m.inner.pattern = Pattern::Dashed {
            dash_m: 5.0,
            period_m: 2.0,
        };
        assert!(m.validate().unwrap_err().to_string().contains("dash_m"));
    }
}
