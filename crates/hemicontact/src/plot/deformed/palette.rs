//! The colours of the deformed-mesh figure.

use crate::plot::Rgb;

/// The undeformed outline and separated points.
pub(super) const GREY: Rgb = [150, 150, 150];
/// The mesh edges.
pub(super) const MESH: Rgb = [110, 125, 155];
/// Text, axes, and the boundaries and foundations drawn on the mesh.
pub(super) const DARK: Rgb = [30, 30, 30];
/// The interface-force arrows.
pub(super) const ARROW: Rgb = [0, 110, 50];
/// Sticking points.
pub(super) const BLUE: Rgb = [20, 80, 220];
/// Slipping points.
pub(super) const RED: Rgb = [220, 30, 30];
/// Points in contact (frictionless).
pub(super) const CONTACT: Rgb = [70, 70, 70];
