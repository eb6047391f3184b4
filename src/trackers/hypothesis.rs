//! One particle drawn as lane boundaries: what the demo shows as the faint cloud of hypotheses
//! around the estimate, in the image and on the road.

use crate::lane::Boundary;
use serde::Serialize;

/// A particle as the boundaries it stands for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Hypothesis {
    /// The particle's normalised weight (the cloud's weights sum to 1).
    pub weight: f64,
    /// The particle's group, as each tracker documents it: adachi-mmpf the model r (1..4),
    /// lee-cpf the stage (1 or 2; 0 for a single-stage variant), danescu-* the MBSAS cluster
    /// (-1 for none), liu-ppf 0.
    pub group: i32,
    /// The boundaries, as image polylines (bottom first) and road polylines (near first).
    pub boundaries: Vec<Boundary>,
}

/// At most `max` indices spread evenly over `0..n` (all of them when `n <= max`), so that a
/// drawing of a sample of the cloud shows its spread, not only its first particles.
pub fn spread_indices(n: usize, max: usize) -> impl Iterator<Item = usize> {
    let count = n.min(max);
    // In u64: k * n overflows a 32-bit usize (wasm32) from about 65 536 particles.
    (0..count).map(move |k| (k as u64 * n as u64 / count.max(1) as u64) as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_indices_cover_the_cloud_without_repeats() {
        assert_eq!(
            spread_indices(5, 10).collect::<Vec<_>>(),
            vec![0, 1, 2, 3, 4]
        );
        let picked: Vec<usize> = spread_indices(1000, 100).collect();
        assert_eq!(picked.len(), 100);
        assert!(picked.windows(2).all(|w| w[1] == w[0] + 10));
        assert_eq!(spread_indices(1000, 0).count(), 0);
        assert_eq!(spread_indices(0, 10).count(), 0);
        let odd: Vec<usize> = spread_indices(7, 3).collect();
        assert_eq!(odd, vec![0, 2, 4]);
    }
}
