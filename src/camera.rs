//! Camera geometry (filled in by the camera work).
