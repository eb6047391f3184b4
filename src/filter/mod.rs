//! The generic particle-filter core.
