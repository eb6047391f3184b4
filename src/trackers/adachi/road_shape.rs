//! The `lane_shape: "curved"` option of `adachi-mmpf` (ours, not the paper's): before the
//! paper's one-dimensional vote, find the bend of the road and vote each edge point where it
//! would lie on a straight road.
//!
//! Adachi et al. model the boundaries as straight lines parallel to the car: an edge point at
//! distance x ahead and lateral position rho votes into the bin of rho. On a bend of radius R,
//! or with the car at a heading to the lane, a boundary lies at
//!
//! ```text
//! rho(x) = rho_0 + s1 x + s2 x^2        (s1 = -heading, s2 = -curvature / 2; rho = -y)
//! ```
//!
//! and its votes smear over rho_0 + s1 [near, far] + s2 [near^2, far^2]: at 22 m on a 150 m
//! radius that is 1.6 m, so no peak is left and the frame is invalid. Every boundary of the road
//! shares (s1, s2), so the shape that straightens them all is the one that makes the
//! histogram of `rho - s1 x - s2 x^2` sharpest. We take the sharpness as sum_j H_j^2 (the
//! number of pairs of edge points sharing a bin), search it on a grid (coarse, then four times
//! finer around the best), and follow it in time with the gain `shape_gain`
//! (s_t = s_{t-1} + gain (s_best - s_{t-1}), gain 1 on the first frame). The paper's
//! filter then runs unchanged on the straightened votes. A tie keeps the straighter shape, so a
//! straight road stays straight.

/// The shape (s1, s2) of rho(x) = rho_0 + s1 x + s2 x^2.
pub type Shape = [f64; 2];

/// Grid steps of the coarse search, in multiples of the shift each step causes at `far_m`
/// relative to the bin size.
const COARSE_SHIFT_BINS: f64 = 8.0;
/// Finer passes after the coarse one, each halving the step around the best shape so far.
const REFINEMENTS: usize = 4;
/// Most coarse steps to each side of straight, per parameter: bounds the search's work for any
/// bin size, region and limit (the defaults need 11 and 15).
const MAX_SPAN: i64 = 20;
/// The coarse pass scores every k-th point, k chosen to leave at most this many: it only has to
/// land within a coarse step of the best, and it costs most of the search.
const COARSE_POINTS: usize = 500;

/// The shape search of one frame's edge points.
#[derive(Debug, Clone)]
pub struct ShapeSearch {
    /// Largest |s1| searched (the heading limit, radians).
    pub max_s1: f64,
    /// Largest |s2| searched (half the curvature limit, 1/m).
    pub max_s2: f64,
    far_m: f64,
    bin_m: f64,
    rho_min: f64,
    bins: usize,
    counts: Vec<u32>,
    touched: Vec<u32>,
    /// Histograms scored by the last [`ShapeSearch::best`].
    pub evaluations: usize,
}

impl ShapeSearch {
    /// A search for headings up to `max_heading_rad` and curvatures up to `max_curvature_per_m`
    /// over points up to `far_m` ahead, on the rho axis of `bins` bins of `bin_m` from `rho_min`.
    pub fn new(
        max_heading_rad: f64,
        max_curvature_per_m: f64,
        far_m: f64,
        bin_m: f64,
        rho_min: f64,
        bins: usize,
    ) -> Self {
        Self {
            max_s1: max_heading_rad,
            max_s2: max_curvature_per_m / 2.0,
            far_m,
            bin_m,
            rho_min,
            bins,
            counts: vec![0; bins],
            touched: Vec::new(),
            evaluations: 0,
        }
    }

    /// The bin of a point (x, rho) straightened by `shape`, if it stays on the axis.
    pub fn bin(&self, x: f32, rho: f32, shape: Shape) -> Option<usize> {
        let (x, rho) = (f64::from(x), f64::from(rho));
        let j = ((rho - shape[0] * x - shape[1] * x * x - self.rho_min) / self.bin_m).floor();
        (j >= 0.0 && j < self.bins as f64).then_some(j as usize)
    }

    /// sum_j H_j^2 of every `stride`-th point straightened by `shape`.
    fn sharpness(&mut self, points: &[(f32, f32)], stride: usize, shape: Shape) -> u64 {
        self.evaluations += 1;
        let mut score = 0u64;
        for &(x, rho) in points.iter().step_by(stride) {
            if let Some(j) = self.bin(x, rho, shape) {
                let c = &mut self.counts[j];
                if *c == 0 {
                    self.touched.push(j as u32);
                }
                score += 2 * u64::from(*c) + 1;
                *c += 1;
            }
        }
        for &j in &self.touched {
            self.counts[j as usize] = 0;
        }
        self.touched.clear();
        score
    }

    /// The shape within the limits that makes the straightened histogram of `points`
    /// (x ahead, rho) sharpest; (0, 0) when there are none. Ties keep the straighter shape.
    pub fn best(&mut self, points: &[(f32, f32)]) -> Shape {
        self.evaluations = 0;
        if points.is_empty() {
            return [0.0, 0.0];
        }
        let shift = COARSE_SHIFT_BINS * self.bin_m;
        // At most 2 MAX_SPAN + 1 coarse steps a side, whatever the bin, region and limits.
        let mut step = [
            (shift / self.far_m).max(self.max_s1 / MAX_SPAN as f64),
            (shift / (self.far_m * self.far_m)).max(self.max_s2 / MAX_SPAN as f64),
        ];
        let mut stride = points.len().div_ceil(COARSE_POINTS);
        let mut best = [0.0, 0.0];
        let mut best_score = self.sharpness(points, stride, best);
        let mut best_size = 0.0;
        // Coarse grid over the whole range, then finer grids of +-2 steps around the best.
        let span_of = |max: f64, step: f64| {
            if step > 0.0 {
                ((max / step).ceil() as i64).min(MAX_SPAN)
            } else {
                0
            }
        };
        let mut span = [span_of(self.max_s1, step[0]), span_of(self.max_s2, step[1])];
        let mut centre = best;
        for pass in 0..=REFINEMENTS {
            if pass > 0 {
                step = [step[0] / 2.0, step[1] / 2.0];
                span = [2, 2];
                centre = best;
                if stride > 1 {
                    // Every point from here on: rescore the best so far on all of them.
                    stride = 1;
                    best_score = self.sharpness(points, 1, best);
                }
            }
            for i in -span[0]..=span[0] {
                for k in -span[1]..=span[1] {
                    let shape = [
                        centre[0] + i as f64 * step[0],
                        centre[1] + k as f64 * step[1],
                    ];
                    if shape[0].abs() > self.max_s1 + 1e-12 || shape[1].abs() > self.max_s2 + 1e-12
                    {
                        continue;
                    }
                    let score = self.sharpness(points, stride, shape);
                    // Size: the larger of the two shifts at far_m, in metres.
                    let size = (shape[0] * self.far_m)
                        .abs()
                        .max((shape[1] * self.far_m * self.far_m).abs());
                    if score > best_score || (score == best_score && size < best_size) {
                        (best, best_score, best_size) = (shape, score, size);
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points of boundaries at `rhos` along rho(x) = rho0 + s1 x + s2 x^2, every 0.25 m from
    /// 6 to 22 m.
    fn boundaries(rhos: &[f64], shape: Shape) -> Vec<(f32, f32)> {
        let mut out = Vec::new();
        for &r in rhos {
            for k in 0..=64 {
                let x = 6.0 + 0.25 * f64::from(k);
                out.push((x as f32, (r + shape[0] * x + shape[1] * x * x) as f32));
            }
        }
        out
    }

    fn search() -> ShapeSearch {
        ShapeSearch::new(0.1, 0.012, 22.0, 0.05, -8.0, 320)
    }

    /// Over 6-22 m a heading and a curvature can nearly stand in for each other, so the test
    /// asks what the votes can tell: the found shape straightens the true boundaries to within a
    /// bin and a half (0.075 m) from end to end of the region.
    #[test]
    fn the_bend_of_parallel_boundaries_is_straightened_to_within_a_bin() {
        for shape in [[0.0, 0.0], [0.03, -0.004], [-0.06, 0.005], [0.0, 0.0021]] {
            let points = boundaries(&[-1.8, 1.8, 5.4], shape);
            let got = search().best(&points);
            let residual = |x: f64| (shape[0] - got[0]) * x + (shape[1] - got[1]) * x * x;
            let r: Vec<f64> = (0..=16).map(|k| residual(6.0 + f64::from(k))).collect();
            let spread = r.iter().copied().fold(f64::MIN, f64::max)
                - r.iter().copied().fold(f64::MAX, f64::min);
            assert!(
                spread < 0.075,
                "true {shape:?}, found {got:?}: spread {spread:.3} m"
            );
        }
    }

    #[test]
    fn scattered_points_leave_a_straight_road_straight() {
        // Two straight boundaries plus a few points spread evenly: no bend beats straight.
        let mut points = boundaries(&[-1.7, 1.9], [0.0, 0.0]);
        points.extend((0..40).map(|k| (6.0 + 0.4 * k as f32, -6.0 + 0.3 * k as f32)));
        assert_eq!(search().best(&points), [0.0, 0.0]);
        assert_eq!(search().best(&[]), [0.0, 0.0]);
    }

    /// The finest bin and the farthest region the ranges allow, with the widest limits: the
    /// coarse grid is capped, so the work stays that of (2 MAX_SPAN + 1)^2 histograms plus the
    /// refinements' 25 each (without the cap: 5001 x 50001).
    #[test]
    fn the_work_is_bounded_for_any_options() {
        let mut s = ShapeSearch::new(0.5, 0.05, 200.0, 0.005, -8.0, 3200);
        let points = boundaries(&[-1.8, 1.8], [0.02, 0.001]);
        s.best(&points);
        let cap = (2 * MAX_SPAN as usize + 1).pow(2) + 25 * REFINEMENTS + 2;
        assert!(s.evaluations <= cap, "{} histograms", s.evaluations);
        let mut d = search();
        d.best(&points);
        assert!(
            d.evaluations > 100 && d.evaluations <= cap,
            "{}",
            d.evaluations
        );
    }

    #[test]
    fn the_search_stays_within_its_limits() {
        // A bend beyond the curvature limit: the answer is clamped to the limit.
        let s = search();
        let points = boundaries(&[-1.8, 1.8], [0.0, 0.02]);
        let got = search().best(&points);
        assert!(got[1].abs() <= s.max_s2 + 1e-12 && got[0].abs() <= s.max_s1 + 1e-12);
    }
}
