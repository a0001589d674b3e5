//! Polynomial bases.
