//! The single-body reference scenes of `docs/scenes.md` (built from the GA-independent [`mod@reference`] parameters) as
//! systems with their initial states, per algebra and per constraint formulation: one place for tests,
//! examples and sweeps over scenes × integrators × step sizes.
//!
//! | scene | virtual power (theory §6) | pinning (theory §7, §9) |
//! |---|---|---|
//! | 1 cuboid | free | free |
//! | 2 hinged rod | 3 forces + 2 couples | line + point, rank 5 |
//! | 3a/3b top | ball joint: 3 forces | point, rank 3 |
//! | 4 sphere | force towards the centre | CGA only: `P ∧ S = 0`, rank 1 |
//! | 4 circle | sphere + plane forces | CGA only: `P ∧ C = 0`, rank 2 |
//!
//! PGA has no spheres or circles (theory §13), so scene 4 by pinning is CGA only.

use std::sync::Arc;

use nalgebra::Vector3;
use reference::{SceneConstraint, SceneId, SceneParameters, Trajectory, TrajectoryError};

use dynamics::constraints::{
    linear, pinning, Constraint, ConstraintError, PinningAlgebra, Stabilisation, VirtualPower,
};
use dynamics::simulate::Sample;
use dynamics::{Algebra, Body, BodyError, Cga, Force, Mechanism, MechanismError, Pga, State};

/// How a scene's constraint is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Formulation {
    /// Constraint wrenches (theory §6).
    VirtualPower,
    /// Pinned multivectors and linear functions of them (theory §7, §9).
    Pinning,
}

impl Formulation {
    /// Both formulations, virtual power first.
    pub const ALL: [Formulation; 2] = [Formulation::VirtualPower, Formulation::Pinning];

    /// Lower-case name for labels and error messages, e.g. `"virtual power"`.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::VirtualPower => "virtual power",
            Formulation::Pinning => "pinning",
        }
    }
}

/// Why a scene could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The algebra cannot write the scene's constraint in this formulation (scene 4 by pinning in PGA, which has no
    /// spheres or circles).
    #[error("scene {scene} cannot be written by {formulation} in {algebra}")]
    NotExpressible {
        /// The scene's label.
        scene: &'static str,
        /// The formulation's name.
        formulation: &'static str,
        /// The algebra's name, e.g. `"PGA"`.
        algebra: &'static str,
    },
    /// A mechanism's offset ([`crate::build_mechanism_at`]) that is not finite or lies beyond
    /// [`dynamics::state::LARGEST_COORDINATE`], where the joints' points would lose every digit below a micrometre.
    #[error(
        "the offset {offset:?} must be finite and within {largest:e} m of the origin in each coordinate \
         (dynamics::state::LARGEST_COORDINATE)"
    )]
    Offset {
        /// The offset asked for (m).
        offset: [f64; 3],
        /// The largest coordinate accepted (m).
        largest: f64,
    },
    /// The scene's mass or moments of inertia were rejected.
    #[error(transparent)]
    Body(#[from] BodyError),
    /// The scene's constraint could not be built.
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// Assembling the system or projecting the initial state onto the constraint failed.
    #[error(transparent)]
    Mechanism(#[from] MechanismError),
}

/// An algebra in which the scenes can be built. Only CGA can pin a point to a sphere or a circle.
pub trait SceneAlgebra: PinningAlgebra {
    /// `P ∧ S = 0` (theory §9), if the algebra has spheres.
    fn point_on_sphere_pin(
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>>;
    /// `P ∧ C = 0` (theory §9), if the algebra has circles.
    fn point_on_circle_pin(
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>>;
}

impl SceneAlgebra for Pga {
    fn point_on_sphere_pin(_: Vector3<f64>, _: Vector3<f64>, _: f64) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }

    fn point_on_circle_pin(_: Vector3<f64>, _: (Vector3<f64>, f64, Vector3<f64>)) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }
}

impl SceneAlgebra for Cga {
    fn point_on_sphere_pin(
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_sphere(
            "rod end on sphere",
            body_point,
            centre,
            radius,
        )))
    }

    fn point_on_circle_pin(
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_circle(
            "rod end on circle",
            body_point,
            circle,
        )))
    }
}

/// A scene ready to run: the system (a single body held by the world: a [`Mechanism`] of one body), its initial
/// state (projected onto the constraint manifold, theory §10) and how long `docs/scenes.md` runs it.
#[derive(Clone, Debug)]
pub struct Scene<A: Algebra> {
    /// Which reference scene this is.
    pub id: SceneId,
    /// How its constraint is written.
    pub formulation: Formulation,
    /// The GA-independent parameters it was built from.
    pub parameters: SceneParameters,
    /// The body, its constraint, gravity and stabilisation.
    pub system: Mechanism<A>,
    /// The initial state, projected onto the constraint manifold.
    pub initial: State<A>,
    /// Simulated time T (s), as in `docs/scenes.md`.
    pub duration: f64,
}

/// The constraint of a scene in one formulation (`None` for a free body).
fn scene_constraint<A: SceneAlgebra>(
    id: SceneId,
    parameters: &SceneParameters,
    formulation: Formulation,
) -> Result<Option<Arc<dyn Constraint<A>>>, SceneError> {
    let not_expressible = || SceneError::NotExpressible {
        scene: id.label(),
        formulation: formulation.name(),
        algebra: A::NAME,
    };
    let constraint: Arc<dyn Constraint<A>> = match (parameters.constraint, formulation) {
        (SceneConstraint::Free, _) => return Ok(None),
        (
            SceneConstraint::Hinge {
                pivot,
                axis,
                body_anchor,
            },
            _,
        ) => {
            let body_axis = parameters.initial_orientation.inverse() * axis;
            let (body, world) = ((body_anchor, body_axis), (pivot, axis));
            match formulation {
                Formulation::VirtualPower => Arc::new(VirtualPower::hinge("hinge", body, world)?),
                Formulation::Pinning => Arc::new(pinning::hinge::<A>("hinge", body, world)?),
            }
        }
        (SceneConstraint::BallJoint { pivot, body_anchor }, Formulation::VirtualPower) => {
            Arc::new(VirtualPower::ball_joint("ball joint", body_anchor, pivot))
        }
        (SceneConstraint::BallJoint { pivot, body_anchor }, Formulation::Pinning) => {
            Arc::new(pinning::point::<A>("pinned tip", body_anchor, pivot))
        }
        (
            SceneConstraint::PointOnSphere {
                body_anchor,
                centre,
                radius,
            },
            Formulation::VirtualPower,
        ) => Arc::new(VirtualPower::point_on_sphere(
            "rod end on sphere",
            body_anchor,
            centre,
            radius,
        )?),
        (
            SceneConstraint::PointOnSphere {
                body_anchor,
                centre,
                radius,
            },
            Formulation::Pinning,
        ) => A::point_on_sphere_pin(body_anchor, centre, radius).ok_or_else(not_expressible)?,
        (
            SceneConstraint::PointOnCircle {
                body_anchor,
                centre,
                radius,
                normal,
            },
            Formulation::VirtualPower,
        ) => Arc::new(VirtualPower::point_on_circle(
            "rod end on circle",
            body_anchor,
            (centre, radius, normal),
        )?),
        (
            SceneConstraint::PointOnCircle {
                body_anchor,
                centre,
                radius,
                normal,
            },
            Formulation::Pinning,
        ) => A::point_on_circle_pin(body_anchor, (centre, radius, normal)).ok_or_else(not_expressible)?,
    };
    Ok(Some(constraint))
}

/// Builds scene `id` in algebra `A` with the constraint written by `formulation`, stabilised by
/// `stabilisation`; the initial state is projected onto the constraint manifold.
pub fn build<A: SceneAlgebra>(
    id: SceneId,
    formulation: Formulation,
    stabilisation: Stabilisation,
) -> Result<Scene<A>, SceneError> {
    let parameters = id.parameters();
    let body = Body::new(parameters.mass, parameters.principal_moments)?;
    let mut system = Mechanism::<A>::single(body);
    if parameters.gravity != 0.0 {
        system = system.with_force(Force::Gravity {
            acceleration: Vector3::new(0.0, 0.0, -parameters.gravity),
        })?;
    }
    if let Some(constraint) = scene_constraint::<A>(id, &parameters, formulation)? {
        system = system.with_constraint(constraint)?;
    }
    let system = system.with_stabilisation(stabilisation)?;
    let initial = State::new(
        &body,
        parameters.initial_com,
        &parameters.initial_orientation,
        parameters.initial_body_angular_velocity,
        parameters.initial_com_velocity,
    );
    let mut initial = [initial];
    system.project(0.0, &mut initial)?;
    let [initial] = initial;
    Ok(Scene {
        id,
        formulation,
        parameters,
        system,
        initial,
        duration: parameters.duration,
    })
}

/// One body's samples as a reference trajectory, for the metrics of the `reference` crate.
pub fn trajectory(samples: &[Sample]) -> Result<Trajectory, TrajectoryError> {
    Trajectory::new(
        samples
            .iter()
            .map(|s| reference::Sample {
                t: s.t,
                position: s.position,
                orientation: s.orientation,
                velocity: s.velocity,
                angular_velocity: s.angular_velocity,
            })
            .collect(),
    )
}
