//! The library's error type.
//!
//! Every failure that depends on user input is an [`Error`] carrying enough data to tell the
//! user what to fix: the file, the field, the value, and what is allowed. Non-convergence of
//! a solve is *not* an error: it is a field of the solve report, so the last iterate is kept.

use std::path::PathBuf;

/// Result alias used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in hemicontact.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scenario value is invalid.
    #[error("{file}: field `{field}` = {value}: {allowed}")]
    Scenario {
        /// The scenario file (or `<built-in>`).
        file: String,
        /// Dotted path of the offending field, e.g. `material.poisson`.
        field: String,
        /// The value found, as written.
        value: String,
        /// What is allowed instead.
        allowed: String,
    },
    /// A parameter of a law, a setting or a datum of a problem built in code is out of its
    /// range. `field` is the path of the parameter in the library's types (e.g.
    /// `newton.armijo`, `contact[0].friction.mu`); the scenario layer reports the same
    /// error as [`Error::Scenario`] with the path of the field in the file
    /// ([`Error::in_file`]).
    #[error("`{field}` = {value}: {allowed}")]
    Invalid {
        /// Dotted path of the offending parameter.
        field: String,
        /// The value found.
        value: String,
        /// What is allowed instead.
        allowed: String,
    },
    /// The scenario file could not be parsed (syntax error, unknown field, wrong type).
    #[error("{file}: {message}")]
    Parse {
        /// The scenario file.
        file: String,
        /// The parser's message, including line and column.
        message: String,
    },
    /// The mesh is invalid (degenerate or inverted cell, untagged boundary facet, …).
    #[error("invalid mesh: {0}")]
    Mesh(String),
    /// A mesh file could not be read: it is not a Gmsh 4.1 file, it is truncated or
    /// malformed, or the mesh it describes is not a valid P1 simplicial mesh.
    #[error("{file}{location}: {message}")]
    MeshFile {
        /// The mesh file (as given, or the name passed to the parser).
        file: String,
        /// Where in the file the problem is.
        location: FileLocation,
        /// What is wrong, and what is expected instead.
        message: String,
    },
    /// The linear system is not positive definite (the problem is singular or unstable).
    #[error(
        "the stiffness matrix is not positive definite ({context}); \
         is every rigid motion blocked by a Dirichlet part?"
    )]
    NotPositiveDefinite {
        /// Where it happened.
        context: String,
    },
    /// Rigid motions of a body that neither the Dirichlet conditions nor a contact part
    /// block (see [`crate::rigid`]): the stiffness matrix is singular, and the solution
    /// does not exist or is not unique.
    #[error(
        "{file}: the problem is singular: no Dirichlet condition blocks, and no contact part \
         carries, the rigid motion(s) {motions}"
    )]
    RigidMotion {
        /// The scenario file (or `problem` for a problem built in code).
        file: String,
        /// Each free motion in words with what would block it, per mesh component.
        motions: String,
    },
    /// The load pulls a body off the contact that was to carry its free rigid motions (see
    /// [`crate::rigid::RigidMotions::runaway`] and [`crate::solver::held`]): there is
    /// no equilibrium.
    #[error(
        "the load pulls the body off its contact: no equilibrium along the rigid motions \
         that the Dirichlet conditions leave free: {motions}; block them by Dirichlet \
         conditions or change the load"
    )]
    ContactLost {
        /// The motion the body moved along, in words, and how far it moved (or would have
        /// to).
        motions: String,
    },
    /// The load along a rigid motion of a body that only friction carries (it moves no
    /// contact point along its normal: a block without supports pushed along the
    /// foundation) exceeds the largest force friction can exert along it (see
    /// [`crate::solver::held`]): the body slides away, there is no equilibrium.
    #[error(
        "friction cannot hold the body: the load along its {motion} (a motion that only \
         friction carries) is {load}, above the friction limit {limit}; lower that load, \
         raise the friction, or block the motion by a Dirichlet condition"
    )]
    FrictionLimit {
        /// The motion in words (e.g. `translation along x`), with the mesh component when
        /// there are several.
        motion: String,
        /// The load along it with its unit (a force in N, N/m in 2D; a moment in N·m,
        /// N·m/m in 2D, for a rotation), e.g. `6.06 N/m`.
        load: String,
        /// The friction limit with its unit and how it is made up, e.g.
        /// `μ × normal force = 0.3 × 20 N/m = 6 N/m`.
        limit: String,
    },
    /// A user-defined law failed during a solve: its function returned an error, or a value
    /// that is not finite or is negative (see [`crate::contact::slip_law`]).
    #[error("law `{law}`: {message}")]
    Law {
        /// The law, by its path and name, e.g. `contact[0].friction.mu (my_law)`.
        law: String,
        /// What went wrong, naming the slip (m) or the point where it did.
        message: String,
    },
    /// A numerical breakdown (NaN or infinity) during a solve.
    #[error("numerical breakdown: {0}")]
    Breakdown(String),
    /// The caller interrupted the solve (the stop flag of
    /// [`crate::solver::solve_interruptible`] was raised); there is no result.
    #[error("interrupted")]
    Interrupted,
    /// Not enough memory for a requested allocation.
    #[error("out of memory: {0}")]
    OutOfMemory(String),
    /// Another process is writing results into the same output folder (it holds the
    /// folder's lock, see [`crate::io::result_set`]).
    #[error(
        "{}: another process{} is writing results into this folder (lock file {}); wait for \
         it to finish or choose another output folder",
        .dir.display(),
        .pid.map(|p| format!(" (PID {p})")).unwrap_or_default(),
        .lock.display()
    )]
    OutputBusy {
        /// The output folder.
        dir: PathBuf,
        /// The id of the process holding the lock, if it could be read.
        pid: Option<u32>,
        /// The lock file.
        lock: PathBuf,
    },
    /// An input/output error on a file.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder concerned.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
}

/// A position in a file, for error messages: a line of a text file, a byte offset of a
/// binary file, or the file as a whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileLocation {
    /// The whole file (no particular position).
    Whole,
    /// A line (1-based) of a text file; displayed `file:line`.
    Line(u64),
    /// A byte offset (0-based) of a binary file; displayed `file (byte offset)`.
    Byte(u64),
}

impl std::fmt::Display for FileLocation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FileLocation::Whole => Ok(()),
            FileLocation::Line(n) => write!(f, ":{n}"),
            FileLocation::Byte(n) => write!(f, " (byte {n})"),
        }
    }
}

impl Error {
    /// Shorthand for [`Error::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The same error with the field path of an [`Error::Invalid`] prefixed by `prefix`
    /// (`prefix.field`; `field` alone if `prefix` is empty; indexed paths such as
    /// `contact[0]` join without a dot before `[`). Other errors pass unchanged. Composite
    /// settings use it to report the path from their own root.
    pub fn within(self, prefix: &str) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Invalid {
                field: join_path(prefix, &field),
                value,
                allowed,
            },
            e => e,
        }
    }

    /// The error as the scenario file `file` reports it: an [`Error::Invalid`] becomes an
    /// [`Error::Scenario`] whose field is `map(field)`, the path of the parameter in the
    /// file. Other errors pass unchanged.
    pub fn in_file(self, file: &str, map: impl FnOnce(&str) -> String) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Scenario {
                file: file.to_string(),
                field: map(&field),
                value,
                allowed,
            },
            e => e,
        }
    }

    /// Shorthand for [`Error::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// `prefix.field`, or `prefix[…]` when `field` starts with an index, or one of the two
/// alone when the other is empty.
fn join_path(prefix: &str, field: &str) -> String {
    if prefix.is_empty() {
        field.to_string()
    } else if field.is_empty() {
        prefix.to_string()
    } else if field.starts_with('[') {
        format!("{prefix}{field}")
    } else {
        format!("{prefix}.{field}")
    }
}

/// `Ok(())` if `ok`, else [`Error::Invalid`] for `field` = `value` with `allowed`: the one
/// line of every range check of a `validate` method.
pub(crate) fn require(
    ok: bool,
    field: &str,
    value: impl std::fmt::Display,
    allowed: &str,
) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(field, value, allowed))
    }
}
