//! PLACEHOLDER (helper 1 writes the generic attribute interpolation here).
