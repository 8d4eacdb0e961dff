//! The integrators and stabilisations by the names the command line (`--integrators`, `--stabilisation`) and
//! scene files (`integrator`, `stabilisation`) give them, and the algebras and constraint formulations by the names
//! scene files give them.

use dynamics::constraints::Stabilisation;
use dynamics::integrate::{Integrator, Method, SplittingMethod};
use dynamics::JointMethod;
use serde::Deserialize;

/// The integrators by name, on the command line and in scene files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum IntegratorName {
    /// Classic RK4, then renormalisation (the paper's method).
    Rk4,
    /// Runge–Kutta–Munthe-Kaas of order 4, momentum in world axes.
    Rkmk4,
    /// RKMK4 with the momentum in the body frame.
    Rkmk4Body,
    /// RKMK of order 6 with the momentum in the body frame.
    Rkmk6Body,
    /// RKMK of order 8 (Cooper–Verner) with the momentum in the body frame.
    Rkmk8Body,
    /// Dormand–Prince's embedded pair of orders 5 and 4 on the body-momentum RKMK scheme: the integrator of
    /// adaptive runs (`tolerance`), or a 5th-order method at a fixed step.
    #[serde(rename = "dp5-body")]
    #[cfg_attr(feature = "clap", value(name = "dp5-body"))]
    Dp5Body,
    /// Dormand–Prince's pair of order 8 with embedded orders 5 and 3 (DOP853) on the body-momentum RKMK scheme:
    /// the default integrator of adaptive runs, or an 8th-order method at a fixed step.
    #[serde(rename = "dop853-body")]
    #[cfg_attr(feature = "clap", value(name = "dop853-body"))]
    Dop853Body,
    /// Strang splitting, order 2; a free body only.
    Strang,
    /// Yoshida's triple jump of Strang steps, order 4; a free body only.
    Yoshida4,
    /// RK4 stepping in joint coordinates; mechanisms of joint models in a tree (robots) only.
    Rkmk4Joint,
    /// Butcher's order-6 method stepping in joint coordinates; mechanisms of joint models in a tree only.
    Rkmk6Joint,
    /// Cooper–Verner's order-8 method stepping in joint coordinates; mechanisms of joint models in a tree only.
    Rkmk8Joint,
    /// Dormand–Prince's pair of order 8 (DOP853) stepping in joint coordinates: the default integrator of robots
    /// with a `tolerance`, or an 8th-order method at a fixed step; mechanisms of joint models in a tree only.
    #[serde(rename = "dop853-joint")]
    #[cfg_attr(feature = "clap", value(name = "dop853-joint"))]
    Dop853Joint,
}

impl From<IntegratorName> for Integrator {
    fn from(name: IntegratorName) -> Integrator {
        match name {
            IntegratorName::Rk4 => Integrator::General(Method::Rk4),
            IntegratorName::Rkmk4 => Integrator::General(Method::Rkmk4),
            IntegratorName::Rkmk4Body => Integrator::General(Method::Rkmk4Body),
            IntegratorName::Rkmk6Body => Integrator::General(Method::Rkmk6Body),
            IntegratorName::Rkmk8Body => Integrator::General(Method::Rkmk8Body),
            IntegratorName::Dp5Body => Integrator::General(Method::Dopri5Body),
            IntegratorName::Dop853Body => Integrator::General(Method::Dop853Body),
            IntegratorName::Strang => Integrator::Splitting(SplittingMethod::Strang),
            IntegratorName::Yoshida4 => Integrator::Splitting(SplittingMethod::Yoshida4),
            IntegratorName::Rkmk4Joint => Integrator::Joint(JointMethod::Rkmk4),
            IntegratorName::Rkmk6Joint => Integrator::Joint(JointMethod::Rkmk6),
            IntegratorName::Rkmk8Joint => Integrator::Joint(JointMethod::Rkmk8),
            IntegratorName::Dop853Joint => Integrator::Joint(JointMethod::Dop853),
        }
    }
}

/// The stabilisations by name, on the command line and in scene files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum StabilisationName {
    /// Post-step projection onto the constraint manifold (theory §10).
    Projection,
    /// Baumgarte feedback, α = β = 10 (theory §10).
    Baumgarte,
    /// None: bare acceleration-level constraints (they drift).
    None,
}

impl From<StabilisationName> for Stabilisation {
    fn from(name: StabilisationName) -> Stabilisation {
        match name {
            StabilisationName::Projection => Stabilisation::PROJECTION,
            StabilisationName::Baumgarte => Stabilisation::Baumgarte {
                alpha: 10.0,
                beta: 10.0,
            },
            StabilisationName::None => Stabilisation::None,
        }
    }
}

/// The two algebras, as a value (the simulators are generic; this picks the instantiation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum AlgebraKind {
    /// Conformal GA, [`dynamics::Cga`].
    Cga,
    /// Projective GA, [`dynamics::Pga`].
    Pga,
}

impl AlgebraKind {
    /// Both, CGA first (the order of the main job's sweep).
    pub const ALL: [AlgebraKind; 2] = [AlgebraKind::Cga, AlgebraKind::Pga];

    /// "CGA" or "PGA".
    pub fn name(self) -> &'static str {
        match self {
            AlgebraKind::Cga => "CGA",
            AlgebraKind::Pga => "PGA",
        }
    }
}

/// Which algebras run the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AlgebraChoice {
    /// `"pga"`
    Pga,
    /// `"cga"`
    Cga,
    /// `"both"`, to compare them (the default).
    #[default]
    Both,
}

impl AlgebraChoice {
    /// The algebras, in the order they run.
    pub fn algebras(self) -> Vec<AlgebraKind> {
        match self {
            AlgebraChoice::Pga => vec![AlgebraKind::Pga],
            AlgebraChoice::Cga => vec![AlgebraKind::Cga],
            AlgebraChoice::Both => vec![AlgebraKind::Pga, AlgebraKind::Cga],
        }
    }
}

/// How a constraint is written (theory §6 and §7–§9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulationName {
    /// Constraint wrenches (theory §6).
    #[default]
    VirtualPower,
    /// Pinned multivectors and linear functions of them (theory §7, §9).
    Pinning,
}

impl FormulationName {
    /// The name in summaries: "virtual power" or "pinning".
    pub fn name(self) -> &'static str {
        match self {
            FormulationName::VirtualPower => "virtual power",
            FormulationName::Pinning => "pinning",
        }
    }
}
