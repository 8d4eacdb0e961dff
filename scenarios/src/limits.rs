//! Joint-limit scenes (docs/limits.md), as the report shows them: a pendulum released at rest that swings up onto a
//! bound gravity then holds it against, and a double pendulum whose elbow bounces off ±0.3 rad.

use dynamics::joint_models::{JointKind, JointModel};
use dynamics::limits::JointLimit;
use dynamics::{Algebra, Body, Force, Mechanism, MechanismError, Reference, State};
use nalgebra::{Isometry3, Vector3};
use reference::{incomplete_elliptic_f, EllipticError, EllipticParameter};

/// A scene with a limited joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LimitScene {
    /// A 1 m, 1 kg rod hinged at its top end about world x, released at rest from −1 rad (from hanging); its hinge's
    /// upper bound at −0.3 rad (restitution 0) stops it on the way up, and gravity keeps it there.
    StoppingPendulum,
    /// Two such rods, the second hinged to the first's bottom end about the same axis, released at rest with the upper
    /// rod at 1.2 rad and the elbow straight; the elbow is limited to ±0.3 rad with restitution 0.5.
    BouncingDoublePendulum,
}

/// The pendulum's start (rad from hanging) and its bound (rad).
const START: f64 = -1.0;
const BOUND: f64 = -0.3;

impl LimitScene {
    /// Every limit scene.
    pub const ALL: [LimitScene; 2] = [LimitScene::StoppingPendulum, LimitScene::BouncingDoublePendulum];

    /// A short name for tables and figures.
    pub fn label(self) -> &'static str {
        match self {
            LimitScene::StoppingPendulum => "pendulum stopping at a limit",
            LimitScene::BouncingDoublePendulum => "double pendulum bouncing off a limit",
        }
    }

    /// The simulated time (s).
    pub fn duration(self) -> f64 {
        match self {
            LimitScene::StoppingPendulum => 2.0,
            LimitScene::BouncingDoublePendulum => 5.0,
        }
    }

    /// The limited joint's index among the joint coordinates.
    pub fn limited_coordinate(self) -> usize {
        match self {
            LimitScene::StoppingPendulum => 0,
            LimitScene::BouncingDoublePendulum => 1,
        }
    }

    /// The limited joint's range and restitution.
    pub fn limit(self) -> JointLimit {
        let limit = match self {
            LimitScene::StoppingPendulum => JointLimit::new(-2.0, BOUND),
            LimitScene::BouncingDoublePendulum => {
                JointLimit::new(-0.3, 0.3).and_then(|limit| limit.with_restitution(0.5))
            }
        };
        limit.expect("the scenes' limits are valid")
    }

    /// The mechanism and its start.
    pub fn build<A: Algebra>(self) -> Result<(Mechanism<A>, Vec<State<A>>), MechanismError> {
        let mut system = Mechanism::<A>::new();
        let hinge = |name: &str, above: f64| {
            JointModel::new(
                name,
                JointKind::Revolute { axis: Vector3::x() },
                Isometry3::translation(0.0, 0.0, above),
                Isometry3::translation(0.0, 0.0, 0.5),
            )
        };
        let upper = system.add_body("upper", rod())?;
        system.add_force(upper, Force::gravity())?;
        let shoulder = hinge("shoulder", 0.0)?;
        let (q, v) = match self {
            LimitScene::StoppingPendulum => {
                system.connect(upper, Reference::World, shoulder.with_limit(self.limit())?)?;
                (vec![START], vec![0.0])
            }
            LimitScene::BouncingDoublePendulum => {
                let lower = system.add_body("lower", rod())?;
                system.add_force(lower, Force::gravity())?;
                system.connect(upper, Reference::World, shoulder)?;
                system.connect(lower, upper, hinge("elbow", -0.5)?.with_limit(self.limit())?)?;
                (vec![1.2, 0.0], vec![0.0, 0.0])
            }
        };
        let states = system.states_from_joints(&q, &v)?;
        Ok((system, states))
    }

    /// The exact time of the first impact, where the scene has one in closed form: the pendulum swinging up from
    /// rest at −1 rad reaches −0.3 rad after a quarter period less the time from −0.3 rad to the bottom,
    /// `(K(k) − F(φ, k))/ω` with `k = sin ½`, `sin φ = sin 0.15 / k` and `ω = √(m g d / I)` about the pivot.
    pub fn exact_first_impact(self) -> Option<Result<f64, EllipticError>> {
        match self {
            LimitScene::StoppingPendulum => Some((|| {
                let k = (START.abs() / 2.0).sin();
                let parameter = EllipticParameter::new(k * k)?;
                let quarter = incomplete_elliptic_f(std::f64::consts::FRAC_PI_2, parameter)?;
                let rest = incomplete_elliptic_f(((BOUND.abs() / 2.0).sin() / k).asin(), parameter)?;
                let body = rod();
                let pivot_moment = body.moments().x + body.mass() * 0.25;
                let omega = (body.mass() * dynamics::forces::STANDARD_GRAVITY * 0.5 / pivot_moment).sqrt();
                Ok((quarter - rest) / omega)
            })()),
            LimitScene::BouncingDoublePendulum => None,
        }
    }
}

/// 1 kg, 1 m along body z, axial moment 1e-3 kg m².
fn rod() -> Body {
    Body::rod(1.0, 1.0, 1e-3).expect("a valid rod")
}
