//! strak-sim (under construction)
fn main() {}
