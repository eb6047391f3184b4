//! Estimators: the weighted mean, the MAP particle, and MBSAS clustering with Danescu's
//! estimate from the most populous cluster (Danescu & Nedevschi 2011, Sec. VIII, eq. 15).
//!
//! MBSAS (modified basic sequential algorithmic scheme, Theodoridis & Koutroumbas): one pass
//! creates clusters: a point farther than the threshold from every cluster representative
//! opens a new cluster, while fewer than the maximum exist; a second pass assigns every point
//! to its nearest representative and updates that representative to the running mean of its
//! members. Danescu's estimate is then
//!
//! ```text
//! E(x) = sum_{i >= R} x_i pi_i delta_i / sum_{i >= R} pi_i delta_i             (eq. 15)
//! ```
//!
//! over the non-initialisation particles (i >= R), where delta_i = 1 for particles of the most
//! populous cluster whose weight is above the average weight, 0 otherwise.

use crate::error::{require_positive, Error, Result};

/// sum_i w_i f(x_i) / sum_i w_i, computed on the projection `f` of each state.
pub fn weighted_mean<S, const D: usize>(
    states: &[S],
    weights: &[f64],
    f: impl Fn(&S) -> [f64; D],
) -> [f64; D] {
    let mut acc = [0.0; D];
    let mut total = 0.0;
    for (s, &w) in states.iter().zip(weights) {
        if w <= 0.0 {
            continue;
        }
        let v = f(s);
        for k in 0..D {
            acc[k] += w * v[k];
        }
        total += w;
    }
    if total > 0.0 {
        for a in acc.iter_mut() {
            *a /= total;
        }
    }
    acc
}

/// sum_i w_i f(x_i) for weights that sum to one (a filter's normalised weights): the estimate
/// x = sum_i w_i x_i of Lee's Algorithm 1. Unlike [`weighted_mean`] it neither skips zero
/// weights nor divides by the total, which is 1 only up to rounding (so the two differ in the
/// last bits).
pub fn expectation<S, const D: usize>(
    states: &[S],
    weights: &[f64],
    f: impl Fn(&S) -> [f64; D],
) -> [f64; D] {
    let mut acc = [0.0; D];
    for (s, &w) in states.iter().zip(weights) {
        let v = f(s);
        for k in 0..D {
            acc[k] += w * v[k];
        }
    }
    acc
}

/// Index of the highest weight (the first one on ties); 0 for an empty slice.
pub fn map_index(weights: &[f64]) -> usize {
    let mut best = 0;
    for (i, &w) in weights.iter().enumerate() {
        if w > weights[best] {
            best = i;
        }
    }
    best
}

/// MBSAS clustering with reusable buffers.
#[derive(Debug, Clone)]
pub struct Mbsas<const D: usize> {
    threshold: f64,
    max_clusters: usize,
    centres: Vec<[f64; D]>,
    means: Vec<[f64; D]>,
    counts: Vec<usize>,
    labels: Vec<usize>,
}

impl<const D: usize> Mbsas<D> {
    /// Clusters at most `max_clusters`, opening a new one for points farther than
    /// `threshold` from every representative.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a non-positive threshold or zero clusters.
    pub fn new(threshold: f64, max_clusters: usize) -> Result<Self> {
        require_positive("cluster_threshold", threshold)?;
        if max_clusters == 0 {
            return Err(Error::parameter("max_clusters", 0, "must be at least 1"));
        }
        Ok(Self {
            threshold,
            max_clusters,
            centres: Vec::with_capacity(max_clusters),
            means: Vec::with_capacity(max_clusters),
            counts: Vec::with_capacity(max_clusters),
            labels: Vec::new(),
        })
    }

    /// Cluster label of each point of the last call.
    pub fn labels(&self) -> &[usize] {
        &self.labels
    }
    /// Member count of each cluster of the last call.
    pub fn counts(&self) -> &[usize] {
        &self.counts
    }
    /// Representatives (member means) of the last call.
    pub fn centres(&self) -> &[[f64; D]] {
        &self.centres
    }

    /// Clusters the projections `f(x_i)` of the particles `first..` with distance `dist`.
    pub fn cluster<S>(
        &mut self,
        states: &[S],
        first: usize,
        f: &impl Fn(&S) -> [f64; D],
        dist: &impl Fn(&[f64; D], &[f64; D]) -> f64,
    ) {
        self.centres.clear();
        self.counts.clear();
        self.labels.clear();
        self.labels.resize(states.len(), usize::MAX);
        let nearest = |centres: &[[f64; D]], p: &[f64; D]| {
            centres
                .iter()
                .enumerate()
                .map(|(k, c)| (k, dist(c, p)))
                .fold(
                    (usize::MAX, f64::INFINITY),
                    |a, b| if b.1 < a.1 { b } else { a },
                )
        };
        // Pass 1: representatives.
        for s in states.iter().skip(first) {
            let p = f(s);
            let (_, d) = nearest(&self.centres, &p);
            if d > self.threshold && self.centres.len() < self.max_clusters {
                self.centres.push(p);
            }
        }
        // Pass 2: assignment with running means.
        self.counts.resize(self.centres.len(), 0);
        self.means.clear();
        self.means.resize(self.centres.len(), [0.0; D]);
        for (i, s) in states.iter().enumerate().skip(first) {
            let p = f(s);
            let (k, _) = nearest(&self.centres, &p);
            if k == usize::MAX {
                continue;
            }
            self.labels[i] = k;
            self.counts[k] += 1;
            let n = self.counts[k] as f64;
            for (m, v) in self.means[k].iter_mut().zip(p) {
                *m += (v - *m) / n;
            }
        }
        self.centres.copy_from_slice(&self.means);
    }

    /// Danescu eq. 15 after [`Mbsas::cluster`]: the weighted mean of the most populous
    /// cluster's particles with above-average weight (average over that cluster). `None`
    /// when nothing was clustered.
    pub fn estimate<S>(
        &self,
        states: &[S],
        weights: &[f64],
        f: &impl Fn(&S) -> [f64; D],
    ) -> Option<[f64; D]> {
        let (best, _) = self.counts.iter().enumerate().max_by_key(|(_, &c)| c)?;
        let members = || {
            states
                .iter()
                .zip(weights)
                .zip(&self.labels)
                .filter(move |(_, &l)| l == best)
                .map(|(sw, _)| sw)
        };
        let (sum, n) = members().fold((0.0, 0usize), |(s, n), (_, &w)| (s + w, n + 1));
        if n == 0 {
            return None;
        }
        let average = sum / n as f64;
        let mut acc = [0.0; D];
        let mut total = 0.0;
        for (s, &w) in members() {
            if w >= average {
                let v = f(s);
                for d in 0..D {
                    acc[d] += w * v[d];
                }
                total += w;
            }
        }
        (total > 0.0).then(|| acc.map(|a| a / total))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weighted_mean_and_map() {
        let states = [1.0, 2.0, 4.0];
        let w = [0.5, 0.25, 0.25];
        let m = weighted_mean(&states, &w, |&x| [x, x * x]);
        assert_eq!(m, [0.5 + 0.5 + 1.0, 0.5 + 1.0 + 4.0]);
        assert_eq!(expectation(&states, &w, |&x| [x, x * x]), m);
        // Weights that do not sum to one: the mean divides by the total, the expectation
        // does not.
        let half = [0.25, 0.125, 0.125];
        assert_eq!(weighted_mean(&states, &half, |&x| [x]), [2.0]);
        assert_eq!(expectation(&states, &half, |&x| [x]), [1.0]);
        assert_eq!(map_index(&w), 0);
        assert_eq!(map_index(&[0.1, 0.7, 0.2]), 1);
    }

    #[test]
    fn mbsas_keeps_the_populous_cluster_and_its_heavier_half() {
        // 60 particles around x = 0 (light), 40 around x = 5 (heavy): the populous cluster
        // wins even though the other carries more weight, as Danescu intends.
        let mut states = Vec::new();
        let mut weights = Vec::new();
        for i in 0..60 {
            states.push(-0.3 + 0.01 * i as f64);
            weights.push(if i % 2 == 0 { 0.004 } else { 0.002 });
        }
        for i in 0..40 {
            states.push(5.0 + 0.01 * i as f64);
            weights.push(0.0175);
        }
        let mut m = Mbsas::<1>::new(1.0, 4).unwrap();
        m.cluster(&states, 0, &|&x| [x], &|a, b| (a[0] - b[0]).abs());
        assert_eq!(m.counts(), &[60, 40]);
        let e = m.estimate(&states, &weights, &|&x| [x]).unwrap();
        // Only the heavier (even-index) particles of the first cluster: -0.3 + 0.01 * (0, 2, .. 58).
        let want = (0..30).map(|k| -0.3 + 0.02 * k as f64).sum::<f64>() / 30.0;
        assert!((e[0] - want).abs() < 1e-12, "{} vs {want}", e[0]);
        // Initialisation particles (the first R) are left out.
        m.cluster(&states, 60, &|&x| [x], &|a, b| (a[0] - b[0]).abs());
        assert_eq!(m.counts(), &[40]);
        assert!(Mbsas::<1>::new(0.0, 3).is_err() && Mbsas::<1>::new(1.0, 0).is_err());
    }
}
