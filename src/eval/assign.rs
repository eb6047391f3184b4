//! Exact one-to-one matching of predicted and ground-truth lanes.
//!
//! Both the Caltech (Aly) and the CULane metrics pair each ground-truth lane with at most one
//! prediction and vice versa. Given, for every pair (i, j), either "not admissible" or a
//! quality q_ij in [0, 1], [`match_pairs`] returns the matching that
//!
//! 1. has the largest number of admissible pairs, and among those
//! 2. the largest total quality.
//!
//! It solves one maximum-weight assignment with w_ij = K + q_ij for admissible pairs and
//! w_ij = 0 otherwise, where K = min(rows, cols) + 1 exceeds any possible sum of qualities, so
//! one more match always outweighs any gain in quality. The assignment is the Hungarian
//! (Kuhn-Munkres) algorithm with row and column potentials and shortest augmenting paths,
//! O(n^2 m) for n <= m: exact, and instant for the handful of lanes in a frame. Assigned pairs
//! with weight 0 (not admissible) are dropped from the result. Greedy matching (best pair
//! first) can lose matches: see the tests.

/// Indices (row, column) of the matched admissible pairs, in row order. `quality(i, j)` is
/// `Some(q)` (q in [0, 1], clamped) for an admissible pair.
pub fn match_pairs(
    rows: usize,
    cols: usize,
    quality: impl Fn(usize, usize) -> Option<f64>,
) -> Vec<(usize, usize)> {
    if rows == 0 || cols == 0 {
        return Vec::new();
    }
    let k = rows.min(cols) as f64 + 1.0;
    let weight: Vec<Vec<f64>> = (0..rows)
        .map(|i| {
            (0..cols)
                .map(|j| match quality(i, j) {
                    Some(q) if q.is_finite() => k + q.clamp(0.0, 1.0),
                    Some(_) => k,
                    None => 0.0,
                })
                .collect()
        })
        .collect();
    max_weight_assignment(&weight)
        .into_iter()
        .filter(|&(i, j)| weight[i][j] > 0.0)
        .collect()
}

/// A maximum-weight assignment of the rows x cols matrix `weight` (finite entries): every row
/// of the smaller side is assigned to a distinct index of the other side. Returns (row, col)
/// pairs in row order.
pub fn max_weight_assignment(weight: &[Vec<f64>]) -> Vec<(usize, usize)> {
    let rows = weight.len();
    let cols = weight.first().map_or(0, Vec::len);
    if rows == 0 || cols == 0 {
        return Vec::new();
    }
    let mut pairs = if rows <= cols {
        min_cost_rows_to_cols(rows, cols, |i, j| -weight[i][j])
    } else {
        min_cost_rows_to_cols(cols, rows, |i, j| -weight[j][i])
            .into_iter()
            .map(|(j, i)| (i, j))
            .collect()
    };
    pairs.sort_unstable();
    pairs
}

/// Minimum-cost assignment of every one of `n` rows to a distinct one of `m >= n` columns.
/// Potentials u (rows) and v (columns) keep cost(i, j) - u_i - v_j >= 0 with equality on the
/// matched pairs; each row is added by growing a shortest alternating path (Dijkstra on the
/// reduced costs) to a free column and flipping it.
fn min_cost_rows_to_cols(
    n: usize,
    m: usize,
    cost: impl Fn(usize, usize) -> f64,
) -> Vec<(usize, usize)> {
    // Index 0 is a virtual column/row; real rows and columns are 1-based.
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; m + 1];
    let mut row_of_col = vec![0usize; m + 1];
    let mut prev_col = vec![0usize; m + 1];
    let mut dist = vec![0.0; m + 1];
    let mut done = vec![false; m + 1];
    for row in 1..=n {
        row_of_col[0] = row;
        let mut col = 0usize;
        dist.fill(f64::INFINITY);
        done.fill(false);
        loop {
            done[col] = true;
            let i = row_of_col[col];
            let mut delta = f64::INFINITY;
            let mut next = 0usize;
            for j in 1..=m {
                if done[j] {
                    continue;
                }
                let reduced = cost(i - 1, j - 1) - u[i] - v[j];
                if reduced < dist[j] {
                    dist[j] = reduced;
                    prev_col[j] = col;
                }
                if dist[j] < delta {
                    delta = dist[j];
                    next = j;
                }
            }
            if next == 0 {
                // Only possible with non-finite costs; stop rather than loop.
                break;
            }
            for j in 0..=m {
                if done[j] {
                    u[row_of_col[j]] += delta;
                    v[j] -= delta;
                } else {
                    dist[j] -= delta;
                }
            }
            col = next;
            if row_of_col[col] == 0 {
                break;
            }
        }
        // Flip the alternating path ending at the free column `col`.
        while col != 0 {
            let back = prev_col[col];
            row_of_col[col] = row_of_col[back];
            col = back;
        }
    }
    (1..=m)
        .filter(|&j| row_of_col[j] != 0)
        .map(|j| (row_of_col[j] - 1, j - 1))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Best total weight over all partial injective maps rows -> cols (the slow reference).
    fn brute_force(w: &[Vec<f64>]) -> f64 {
        fn go(w: &[Vec<f64>], i: usize, used: &mut Vec<bool>) -> f64 {
            if i == w.len() {
                return 0.0;
            }
            let mut best = go(w, i + 1, used); // row i unassigned
            for j in 0..used.len() {
                if !used[j] {
                    used[j] = true;
                    best = best.max(w[i][j] + go(w, i + 1, used));
                    used[j] = false;
                }
            }
            best
        }
        let cols = w.first().map_or(0, Vec::len);
        go(w, 0, &mut vec![false; cols])
    }

    #[test]
    fn hungarian_agrees_with_brute_force_on_random_matrices() {
        // A small LCG keeps the test deterministic without extra dependencies.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..300 {
            let rows = 1 + case % 5;
            let cols = 1 + (case / 5) % 6;
            let w: Vec<Vec<f64>> = (0..rows)
                .map(|_| (0..cols).map(|_| (next() * 10.0).floor()).collect())
                .collect();
            let pairs = max_weight_assignment(&w);
            assert_eq!(pairs.len(), rows.min(cols));
            let mut seen_r = vec![false; rows];
            let mut seen_c = vec![false; cols];
            for &(i, j) in &pairs {
                assert!(!seen_r[i] && !seen_c[j], "not one-to-one: {pairs:?}");
                seen_r[i] = true;
                seen_c[j] = true;
            }
            let total: f64 = pairs.iter().map(|&(i, j)| w[i][j]).sum();
            assert!(
                (total - brute_force(&w)).abs() < 1e-9,
                "case {case}: {w:?} -> {pairs:?}"
            );
        }
    }

    #[test]
    fn more_matches_beat_better_quality() {
        // Greedy would take (0, 0) with quality 0.95 and leave row 1 without an admissible
        // partner; the exact matching crosses over and gets two matches.
        let q = [[Some(0.95), Some(0.1)], [Some(0.1), None]];
        let pairs = match_pairs(2, 2, |i, j| q[i][j]);
        assert_eq!(pairs, vec![(0, 1), (1, 0)]);
        // With equal counts the larger total quality wins.
        let q = [[Some(0.9), Some(0.2)], [Some(0.3), Some(0.8)]];
        assert_eq!(match_pairs(2, 2, |i, j| q[i][j]), vec![(0, 0), (1, 1)]);
        assert!(match_pairs(0, 3, |_, _| Some(1.0)).is_empty());
        assert!(match_pairs(2, 2, |_, _| None).is_empty());
        // More rows than columns.
        let pairs = match_pairs(3, 1, |i, _| (i == 2).then_some(0.5));
        assert_eq!(pairs, vec![(2, 0)]);
    }
}
