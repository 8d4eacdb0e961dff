//! Why a scene file cannot run, or its run failed ([`SceneFileError`]): every message names the entry and the value.

use dynamics::constraints::ConstraintError;
use dynamics::simulate::SimulationError;
use dynamics::{BodyError, MechanismError};

/// Why a scene file cannot run, or its run failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneFileError {
    /// The file could not be read.
    #[error("cannot read the file: {0}")]
    Read(std::io::Error),
    /// Not TOML, or not this format (unknown key or kind, missing field, wrong type); the message gives
    /// the line and column.
    #[error("{0}")]
    Format(#[from] toml::de::Error),
    /// An unknown key in a table that the TOML reader can only point at as a whole (a joint or constraint, whose
    /// kind decides its keys): the key's own line.
    #[error("TOML parse error at line {line}: {message} (in the table from line {table_line})")]
    UnknownKey {
        /// The line of the unknown key (1-based).
        line: usize,
        /// The line the table starts at (1-based).
        table_line: usize,
        /// The reader's message: the key and the keys expected.
        message: String,
    },
    /// A value the format allows but a run cannot use.
    #[error("{what}: {reason}")]
    Invalid {
        /// The entry and key, as the file names them: "body arm: initial.position".
        what: String,
        /// What is wrong with the value.
        reason: String,
    },
    /// The body's mass or moments of inertia are not physical.
    #[error("body: {0}")]
    Body(#[from] BodyError),
    /// `dt` (or `tolerance`), `duration` and `sample_interval` make no schedule.
    #[error("dt or tolerance, duration, sample_interval: {0}")]
    Schedule(SimulationError),
    /// A joint's geometry was refused, or the joints cannot hold at the initial state or their reactions cannot
    /// be solved for; the message names the joints.
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// A body, force, joint or the stabilisation was refused while building the system.
    #[error(transparent)]
    Mechanism(#[from] MechanismError),
    /// A pinned joint needs a sphere or a circle, which only CGA has.
    #[error(
        "constraint {name}: pinning needs a {object}, which {algebra} does not have; write \
         formulation = \"virtual_power\", or algebra = \"cga\""
    )]
    NotExpressible {
        /// The joint's name in messages.
        name: String,
        /// "sphere" or "circle".
        object: &'static str,
        /// The algebra that lacks it.
        algebra: &'static str,
    },
    /// The run itself failed.
    #[error("the {algebra} run failed: {message}")]
    Run {
        /// The algebra it ran in.
        algebra: &'static str,
        /// The simulator's message.
        message: String,
    },
}

pub(crate) fn invalid(what: impl Into<String>, reason: impl Into<String>) -> SceneFileError {
    SceneFileError::Invalid {
        what: what.into(),
        reason: reason.into(),
    }
}
