//! For each of n points, how many of the points lie within a square around it: |dx| <= tol and
//! |dy| <= tol (the point itself included), in O(n log n) instead of comparing every pair.
//!
//! A sweep over the points in x order keeps the points whose x is within `tol` of the current
//! one in a Fenwick tree indexed by their rank in y; the count is then a range sum over the
//! ranks whose y is within `tol`.

/// The count of every point (see the module docs), in the points' order. Non-finite
/// coordinates are never within `tol` of anything but count themselves.
pub fn box_counts(points: &[[f64; 2]], tol: f64) -> Vec<usize> {
    let mut counts = vec![1; points.len()];
    let finite: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].iter().all(|v| v.is_finite()))
        .collect();
    let n = finite.len();
    let mut by_x = finite.clone();
    sort_indices_by(&mut by_x, &|i| points[i][0]);
    let mut by_y = finite;
    sort_indices_by(&mut by_y, &|i| points[i][1]);
    let ys: Vec<f64> = by_y.iter().map(|&i| points[i][1]).collect();
    let mut rank = vec![0; points.len()];
    for (r, &i) in by_y.iter().enumerate() {
        rank[i] = r;
    }
    let mut tree = Fenwick::new(n);
    let (mut lo, mut hi) = (0, 0);
    for &i in &by_x {
        let [x, y] = points[i];
        while hi < n && points[by_x[hi]][0] <= x + tol {
            tree.add(rank[by_x[hi]], 1);
            hi += 1;
        }
        while points[by_x[lo]][0] < x - tol {
            tree.add(rank[by_x[lo]], -1);
            lo += 1;
        }
        let first = ys.partition_point(|&v| v < y - tol);
        let end = ys.partition_point(|&v| v <= y + tol);
        counts[i] = (tree.prefix(end) - tree.prefix(first)) as usize;
    }
    counts
}

/// Sorts indices by a key with the stable sort (`total_cmp`'s order; equal keys keep their
/// order). One function for every caller, so the package has one instance of the stable sort
/// for them instead of one per closure (about 6 kB of WebAssembly each).
#[inline(never)]
pub(crate) fn sort_indices_by(indices: &mut [usize], key: &dyn Fn(usize) -> f64) {
    indices.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
}

/// Prefix sums over n slots with point updates, both O(log n).
struct Fenwick(Vec<i64>);

impl Fenwick {
    fn new(n: usize) -> Self {
        Self(vec![0; n + 1])
    }

    fn add(&mut self, slot: usize, v: i64) {
        let mut k = slot + 1;
        while k < self.0.len() {
            self.0[k] += v;
            k += k & k.wrapping_neg();
        }
    }

    /// Sum of the slots before `end`.
    fn prefix(&self, end: usize) -> i64 {
        let (mut k, mut s) = (end, 0);
        while k > 0 {
            s += self.0[k];
            k -= k & k.wrapping_neg();
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::box_counts;

    /// Against the count of every pair, on scattered points with ties and points on the edges.
    #[test]
    fn counts_match_the_pairwise_count() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 33) % 40) as f64 * 0.25
        };
        let points: Vec<[f64; 2]> = (0..300).map(|_| [next(), next()]).collect();
        for tol in [0.0, 0.25, 1.0, 3.0] {
            let brute: Vec<usize> = points
                .iter()
                .map(|a| {
                    points
                        .iter()
                        .filter(|b| (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol)
                        .count()
                })
                .collect();
            assert_eq!(box_counts(&points, tol), brute, "tol {tol}");
        }
        assert!(box_counts(&[], 1.0).is_empty());
        assert_eq!(
            box_counts(
                &[
                    [-f64::NAN, 0.0],
                    [0.0, 0.0],
                    [0.5, f64::INFINITY],
                    [0.5, 0.5]
                ],
                1.0
            ),
            vec![1, 2, 1, 2]
        );
    }
}
