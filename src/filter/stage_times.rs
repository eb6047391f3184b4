//! Time spent per stage of a frame, and the clock that measures it (the
//! [`Stepper`](super::Stepper) charges each operation of a schedule to its stage).

/// Time spent per stage of one frame, milliseconds.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct StageTimes {
    /// Grey conversion, top view, gradients, edges, distance maps (and stereo matching).
    pub preprocess: f64,
    /// Of `preprocess`: the stereo matching (disparity) of a stereo tracker.
    pub disparity: f64,
    /// Motion model: drift and diffusion (and injection).
    pub predict: f64,
    /// Measurement model: likelihoods of all particles.
    pub weigh: f64,
    /// Resampling.
    pub resample: f64,
    /// Estimation and conversion to boundaries.
    pub estimate: f64,
}

/// Milliseconds from a monotonic clock (0 where none is available, e.g. plain wasm).
pub(crate) fn now() -> f64 {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use std::sync::OnceLock;
        static START: OnceLock<std::time::Instant> = OnceLock::new();
        START
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_secs_f64()
            * 1e3
    }
    #[cfg(target_arch = "wasm32")]
    {
        0.0
    }
}
