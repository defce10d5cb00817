//! The friction law of a `[contact.friction]` table, from the current form
//! (`potential = { kind = "nonconvex", a = 0.5 }`, `regularization = …`) or the deprecated
//! one (`potential = "nonconvex"` with a sibling `a`, `[solver.outer]
//! friction_regularization`), which is read with a note.

use super::schema::{FrictionSpec, PotentialKind, PotentialLaw, PotentialSpec};
use super::Scenario;
use crate::contact::friction::DEFAULT_REGULARIZATION;
use crate::contact::{Friction, FrictionPotential, NormTreatment};
use crate::error::Result;

/// The name of a potential kind in the scenario file.
fn kind_name(kind: PotentialKind) -> &'static str {
    match kind {
        PotentialKind::Norm => "norm",
        PotentialKind::Nonconvex => "nonconvex",
        PotentialKind::Regularized => "regularized",
    }
}

impl Scenario {
    /// The potential of the friction table `fs` of contact entry `k`, with the prefix of the
    /// fields holding its parameters (`contact[k].friction.potential.` in the table form,
    /// `contact[k].friction.` in the deprecated one).
    fn potential_law(&self, k: usize, fs: &FrictionSpec) -> Result<(PotentialLaw, String)> {
        let f = |name: &str| format!("contact[{k}].friction.{name}");
        if let Some(PotentialSpec::Law(law)) = fs.potential {
            for (name, v) in [("a", fs.a), ("rho", fs.rho)] {
                if let Some(v) = v {
                    return Err(self.err(
                        &f(name),
                        v,
                        concat!(
                            "no sibling parameter with potential = { kind = … }: one form only, ",
                            "the parameter inside the table (e.g. potential = { kind = ",
                            "\"nonconvex\", a = 0.5 })",
                        ),
                    ));
                }
            }
            return Ok((law, f("potential.")));
        }
        let kind = match fs.potential {
            Some(PotentialSpec::Name(kind)) => kind,
            _ => PotentialKind::Norm,
        };
        if kind != PotentialKind::Nonconvex && fs.a.is_some() {
            return Err(self.err(
                &f("a"),
                fs.a.unwrap_or(0.0),
                "only with potential = { kind = \"nonconvex\", a = … }",
            ));
        }
        if kind != PotentialKind::Regularized && fs.rho.is_some() {
            return Err(self.err(
                &f("rho"),
                fs.rho.unwrap_or(0.0),
                "only with potential = { kind = \"regularized\", rho = … }",
            ));
        }
        let law = match kind {
            PotentialKind::Norm => PotentialLaw::Norm {},
            PotentialKind::Nonconvex => PotentialLaw::Nonconvex {
                a: self.required(&f("a"), fs.a, "a parameter 0 < a < 1")?,
            },
            PotentialKind::Regularized => PotentialLaw::Regularized {
                rho: self.required(&f("rho"), fs.rho, "a regularization length ρ > 0 (m)")?,
            },
        };
        Ok((law, f("")))
    }

    /// The treatment of the norm of the friction table `fs` of contact entry `k`: exact, or
    /// smoothed with the part's `regularization`, else the deprecated `[solver.outer]
    /// friction_regularization`, else the default.
    fn norm_treatment(&self, k: usize, fs: &FrictionSpec) -> Result<NormTreatment> {
        let field = format!("contact[{k}].friction.regularization");
        if fs.exact {
            if let Some(v) = fs.regularization {
                return Err(self.err(
                    &field,
                    v,
                    "no regularization with exact = true (exact stick/slip is not smoothed)",
                ));
            }
            return Ok(NormTreatment::Exact);
        }
        let outer = self.file.solver.outer.friction_regularization;
        let regularization = match (fs.regularization, outer) {
            (Some(part), Some(global)) if part != global => {
                return Err(self.err(
                    &field,
                    part,
                    &format!(
                        "the value of the deprecated solver.outer.friction_regularization = \
                         {global:e}, which also sets it: give one of them"
                    ),
                ))
            }
            (Some(part), _) => part,
            (None, Some(global)) => global,
            (None, None) => DEFAULT_REGULARIZATION,
        };
        Ok(NormTreatment::Smoothed { regularization })
    }

    /// The friction law of the table `fs` of contact entry `k`.
    pub(super) fn build_friction(&self, k: usize, fs: &FrictionSpec) -> Result<Friction> {
        let f = |name: &str| format!("contact[{k}].friction.{name}");
        let (law, prefix) = self.potential_law(k, fs)?;
        let mu = self
            .given_friction
            .iter()
            .find(|(entry, _)| *entry == k)
            .map_or_else(|| fs.mu.clone(), |(_, mu)| mu.clone());
        mu.validate()
            .map_err(|msg| self.err(&f("mu"), format!("{mu:?}"), &msg))?;
        let potential = match law {
            PotentialLaw::Norm {} => FrictionPotential::Norm {
                treatment: self.norm_treatment(k, fs)?,
            },
            PotentialLaw::Nonconvex { a } => FrictionPotential::Nonconvex {
                a,
                unit: 1.0,
                treatment: self.norm_treatment(k, fs)?,
            },
            PotentialLaw::Regularized { rho } => {
                if fs.exact {
                    return Err(self.err(
                        &f("exact"),
                        true,
                        "exact = true only with potential = \"norm\" or \"nonconvex\" \
                         (the regularized law (19) is smooth)",
                    ));
                }
                if let Some(v) = fs.regularization {
                    return Err(self.err(
                        &f("regularization"),
                        v,
                        "only with potential = \"norm\" or \"nonconvex\" (the regularized law \
                         (19) is smooth and has its own rho)",
                    ));
                }
                FrictionPotential::Regularized { rho }
            }
        };
        // The ranges are the law's to check; the error names the field of the file.
        potential.validate().map_err(|e| {
            e.in_file(&self.source, |field| match field {
                "regularization" if fs.regularization.is_none() => {
                    "solver.outer.friction_regularization".to_string()
                }
                "regularization" => f("regularization"),
                other => format!("{prefix}{other}"),
            })
        })?;
        Ok(Friction {
            bound: fs.bound,
            mu,
            potential,
        })
    }

    /// Notes on the deprecated forms of friction data the file uses.
    pub(super) fn friction_notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        for (k, c) in self.file.contact.iter().enumerate() {
            let Some(fs) = &c.friction else { continue };
            if let Some(PotentialSpec::Name(kind)) = fs.potential {
                let name = kind_name(kind);
                let example = match kind {
                    PotentialKind::Norm => "{ kind = \"norm\" }".to_string(),
                    PotentialKind::Nonconvex => format!(
                        "{{ kind = \"nonconvex\", a = {} }}",
                        fs.a.map_or("…".into(), |a| format!("{a:?}"))
                    ),
                    PotentialKind::Regularized => format!(
                        "{{ kind = \"regularized\", rho = {} }}",
                        fs.rho.map_or("…".into(), |r| format!("{r:?}"))
                    ),
                };
                notes.push(format!(
                    "contact[{k}].friction.potential = \"{name}\" is deprecated: write \
                     potential = {example}"
                ));
            }
        }
        if let Some(v) = self.file.solver.outer.friction_regularization {
            notes.push(format!(
                "solver.outer.friction_regularization = {v:?} is deprecated: write \
                 regularization = {v:?} in each [contact.friction] table"
            ));
        }
        notes
    }
}
