//! The colour of a figure's primitives.

/// An RGB colour.
pub type Rgb = [u8; 3];
