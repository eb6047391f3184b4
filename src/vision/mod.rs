//! Image preprocessing, one operation per file.
