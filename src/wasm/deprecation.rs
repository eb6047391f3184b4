//! Warnings for deprecated calls: one `console.warn` per call name and page (or Node process),
//! naming what replaces it, so an integrator sees it once without flooding the console.

use std::sync::atomic::{AtomicBool, Ordering};

/// `setEgoMotion` was called.
pub static SET_EGO_MOTION: AtomicBool = AtomicBool::new(false);
/// `setRight` was called.
pub static SET_RIGHT: AtomicBool = AtomicBool::new(false);

/// Warns with `message` the first time `seen` is set.
pub fn warn_once(seen: &AtomicBool, message: &str) {
    if !seen.swap(true, Ordering::Relaxed) {
        web_sys::console::warn_1(&message.into());
    }
}
