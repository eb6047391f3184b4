//! Measurement support remembered over the last frames (ours, beyond the papers): the option
//! `valid_support_frames` of the trackers whose validity counts, per boundary, the share of the
//! estimate's points (liu-ppf: top-view rows) with image evidence beside them (adachi-mmpf,
//! danescu-mono, danescu-stereo, lee-cpf, liu-ppf).
//!
//! A dashed line shows paint along only part of the boundary in any one frame (3 m dashes every
//! 12 m: a quarter), and which part moves as the car drives, so one frame's share swings
//! between 0 and twice the duty cycle with the dashes' phase. The share averaged over the last
//! K frames,
//!
//!   s̄_side(t) = (1 / K') Σ_{k=0}^{K'-1} s_side(t - k),   K' = min(K, frames since the reset),
//!
//! tends to the duty cycle instead; K = 1 is the single-frame rule (the default).

/// The last `frames` supports per side, [left, right], in a ring allocated once.
#[derive(Debug, Clone)]
pub struct SupportMemory {
    history: Vec<[f64; 2]>,
    next: usize,
    len: usize,
}

impl SupportMemory {
    /// A memory of the last `frames` frames (at least one).
    pub fn new(frames: usize) -> Self {
        Self {
            history: vec![[0.0; 2]; frames.max(1)],
            next: 0,
            len: 0,
        }
    }

    /// Adds this frame's support and returns the mean over the frames kept, this one included.
    pub fn push(&mut self, support: [f64; 2]) -> [f64; 2] {
        let k = self.history.len();
        self.history[self.next] = support;
        self.next = (self.next + 1) % k;
        self.len = (self.len + 1).min(k);
        let mut sum = [0.0; 2];
        for s in self.history.iter().take(self.len) {
            sum[0] += s[0];
            sum[1] += s[1];
        }
        [sum[0] / self.len as f64, sum[1] / self.len as f64]
    }

    /// The support pushed last; zero when none was since the start or the last `clear`.
    pub fn last(&self) -> [f64; 2] {
        if self.len == 0 {
            return [0.0; 2];
        }
        let k = self.history.len();
        self.history[(self.next + k - 1) % k]
    }

    /// Forgets every frame (after a reset or a still).
    pub fn clear(&mut self) {
        self.next = 0;
        self.len = 0;
    }
}

/// Whether both boundaries are supported: each this frame (`now`, the single-frame rule), or
/// the weaker one over the remembered frames (`mean`) while the stronger one this frame holds
/// at least twice `threshold`. A lane keeps one boundary it sees well and one it saw lately;
/// where both fade at once (an unmarked crossing, a lost lock) memory does not hold it.
pub fn supported(now: [f64; 2], mean: [f64; 2], threshold: f64) -> bool {
    if now.iter().all(|&s| s >= threshold) {
        return true;
    }
    let (strong, weak) = if now[0] >= now[1] { (0, 1) } else { (1, 0) };
    now[strong] >= 2.0 * threshold && mean[weak] >= threshold
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_frame_is_the_frame_itself() {
        let mut m = SupportMemory::new(1);
        assert_eq!(m.push([0.3, 0.1]), [0.3, 0.1]);
        assert_eq!(m.push([0.0, 0.5]), [0.0, 0.5]);
    }

    #[test]
    fn the_mean_covers_the_last_k_frames_and_starts_again_after_clear() {
        let mut m = SupportMemory::new(3);
        assert_eq!(m.push([0.6, 0.0]), [0.6, 0.0]);
        assert_eq!(m.push([0.0, 0.3]), [0.3, 0.15]);
        let s = m.push([0.3, 0.3]);
        assert!(
            (s[0] - 0.3).abs() < 1e-12 && (s[1] - 0.2).abs() < 1e-12,
            "{s:?}"
        );
        // The first frame drops out.
        let s = m.push([0.0, 0.0]);
        assert!(
            (s[0] - 0.1).abs() < 1e-12 && (s[1] - 0.2).abs() < 1e-12,
            "{s:?}"
        );
        m.clear();
        assert_eq!(m.push([0.9, 0.9]), [0.9, 0.9]);
    }

    #[test]
    fn memory_holds_a_faded_side_only_beside_a_well_seen_one() {
        // The single-frame rule.
        assert!(supported([0.2, 0.15], [0.0, 0.0], 0.15));
        // A dashed right line between dashes beside a solid left line: remembered.
        assert!(supported([0.9, 0.05], [0.8, 0.2], 0.15));
        assert!(supported([0.0, 0.35], [0.3, 0.3], 0.15));
        // ... but not when it was not seen lately either.
        assert!(!supported([0.9, 0.05], [0.8, 0.1], 0.15));
        // Both sides fading at once (an unmarked crossing): not held, whatever the memory.
        assert!(!supported([0.2, 0.05], [0.6, 0.5], 0.15));
        assert!(!supported([0.0, 0.0], [0.9, 0.9], 0.15));
    }

    #[test]
    fn zero_frames_is_taken_as_one() {
        let mut m = SupportMemory::new(0);
        assert_eq!(m.push([0.2, 0.4]), [0.2, 0.4]);
    }
}
