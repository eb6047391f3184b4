// Golden values that the native unit tests and the wasm tests (tests/web.rs) both assert: the
// same seed gives the same bits on every target. Kept out of the library's API: both sides
// `include!` this file (it is not a test crate of its own: it lies in a subfolder of tests/).

/// `synth::frame_fingerprint` of frame 30 of the `s-curve` reference road, seed 3, through
/// the default camera at 160x120.
pub const SCENE_FINGERPRINT: u64 = 0x34cb_1b29_8606_baa3;

/// The family member, seed and frame whose 160x120 rendering [`FAMILY_FINGERPRINT`] pins.
pub const FINGERPRINT_MEMBER: (&str, u64, u32) = ("lane-change", 7, 60);

/// `synth::frame_fingerprint` of [`FINGERPRINT_MEMBER`].
pub const FAMILY_FINGERPRINT: u64 = 0x74e3_7b1e_e47d_450b;

/// `filter::determinism_fingerprint()`.
pub const DETERMINISM_FINGERPRINT: u64 = 0x10e2_b0a3_4886_2cdf;
