//! One contact boundary of a problem ([`ContactBoundary`]: a part of the mesh with its
//! foundation, flat, a rigid obstacle or the master part of another body, and its laws),
//! and the master side of a contact pair ([`MasterPart`]).

use super::{ContactObstacle, Friction, NormalLaw};

/// One contact boundary: a part of the mesh facing a rigid foundation, with its laws.
///
/// The foundation is either flat, the boundary itself shifted along its outward normal by
/// `gap` (`obstacle` is `None`), or a rigid obstacle of given shape (`gap` must then be 0),
/// whose closest-point projection gives each contact point its own gap and normal (see
/// [`super::obstacle`] and [`super::nodes`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ContactBoundary {
    /// Boundary part index (see [`crate::mesh::Mesh::part_names`]).
    pub part: usize,
    /// Initial gap g ≥ 0 along the normal to a flat foundation (m); 0 with an obstacle.
    pub gap: f64,
    /// The rigid obstacle the part faces, or `None` for the flat foundation at `gap`.
    pub obstacle: Option<ContactObstacle>,
    /// The *master* boundary part this (slave) part touches: a part of another body, or the
    /// other face of a crack ([`crate::contact::pairing`]). Each node of this part is then
    /// paired with its closest point on the master's facets, and the laws act on the
    /// displacement relative to the master there. `None` for a foundation or an obstacle.
    pub against: Option<MasterPart>,
    /// Normal law: normal compliance or the Signorini constraint.
    pub normal: NormalLaw,
    /// Friction law, or `None` for frictionless contact.
    pub friction: Option<Friction>,
}

impl ContactBoundary {
    /// Checks the laws and the gap of the boundary (not its part, which only a
    /// [`crate::problem::Problem`] can check against its mesh).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the parameter: `gap` finite and ≥ 0 (0 with an
    /// obstacle), and the ranges of [`NormalLaw::validate`] and [`Friction::validate`]
    /// (under `friction.`). The obstacle's shape is checked by
    /// [`crate::problem::Problem::validate`], which knows the dimension.
    pub fn validate(&self) -> crate::Result<()> {
        crate::error::require(
            self.gap.is_finite() && self.gap >= 0.0,
            "gap",
            self.gap,
            "a gap g ≥ 0 (m)",
        )?;
        crate::error::require(
            self.against.is_none() || self.gap == 0.0,
            "gap",
            self.gap,
            "no gap with `against` (0): the positions of the two parts give the gap at each \
             point",
        )?;
        crate::error::require(
            self.obstacle.is_none() || self.gap == 0.0,
            "gap",
            self.gap,
            "no gap with an obstacle (0): the obstacle's shape and position give the gap at \
             each point",
        )?;
        self.normal.validate()?;
        match &self.friction {
            Some(f) => f.validate().map_err(|e| e.within("friction")),
            None => Ok(()),
        }
    }
}

/// The master side of a contact pair: a boundary part, and the units in which its pairing
/// measures gaps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MasterPart {
    /// Boundary part index (see [`crate::mesh::Mesh::part_names`]).
    pub part: usize,
    /// Unit of the mesh's coordinates (m; 1 in the user's problem, the length scale in the
    /// solver's dimensionless one).
    pub length_unit: f64,
    /// Unit of the gaps and displacements (m; 1 in the user's problem, the displacement
    /// scale in the solver's dimensionless one).
    pub gap_unit: f64,
}

impl MasterPart {
    /// The master part `part`, in the user's units.
    pub fn new(part: usize) -> Self {
        MasterPart {
            part,
            length_unit: 1.0,
            gap_unit: 1.0,
        }
    }

    /// The same part in a problem whose lengths are in units of `length` and whose
    /// displacements are in units of `displacement` (m).
    pub fn nondimensional(&self, length: f64, displacement: f64) -> Self {
        MasterPart {
            part: self.part,
            length_unit: self.length_unit * length,
            gap_unit: self.gap_unit * displacement,
        }
    }

    /// A gap `g` measured on the mesh (in units of `length_unit`) in units of `gap_unit`.
    pub fn gap(&self, g: f64) -> f64 {
        g * (self.length_unit / self.gap_unit)
    }
}
