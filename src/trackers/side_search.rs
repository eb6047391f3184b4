//! The side search (ours, beyond the papers; `side_search_share` of lee-cpf and adachi-mmpf):
//! after a frame whose estimate had one ego boundary on markings and the other bare, a share
//! of the particles keeps the supported boundary where it is and takes the lane width anew,
//! uniform over the tracker's width limits. Each paper's width moves by its process noise
//! alone (a few centimetres a frame), so where the lane widens or narrows faster (a turn
//! pocket opening beside the lane, a merge, the road's pitch swinging the apparent width
//! through a fixed camera) the cloud keeps one boundary and loses the other for many frames.

/// Support (the tracker's own share of a boundary's points on a marking) under which a
/// boundary counts as bare.
pub const BARE_SUPPORT: f64 = 0.05;

/// The boundary a side search keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kept {
    /// The ego-left boundary.
    Left,
    /// The ego-right boundary.
    Right,
}

/// The boundary to keep after a frame whose estimate had support `[left, right]`: the one
/// with at least `held` (the tracker's validity threshold) when the other has under
/// [`BARE_SUPPORT`]; `None` otherwise (both seen, both lost, or neither clearly).
pub fn kept_side([left, right]: [f64; 2], held: f64) -> Option<Kept> {
    if left >= held && right < BARE_SUPPORT {
        Some(Kept::Left)
    } else if right >= held && left < BARE_SUPPORT {
        Some(Kept::Right)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_one_held_side_beside_a_bare_one_is_kept() {
        assert_eq!(kept_side([0.5, 0.0], 0.15), Some(Kept::Left));
        assert_eq!(kept_side([0.04, 0.15], 0.15), Some(Kept::Right));
        assert_eq!(
            kept_side([0.5, 0.05], 0.15),
            None,
            "the right side has a little"
        );
        assert_eq!(
            kept_side([0.1, 0.0], 0.15),
            None,
            "the left side is not held"
        );
        assert_eq!(kept_side([0.5, 0.5], 0.15), None);
        assert_eq!(kept_side([0.0, 0.0], 0.15), None);
    }
}
