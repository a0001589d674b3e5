//! strak-ref (under construction)
