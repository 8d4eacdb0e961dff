//! Rigid-body dynamics with constraints in CGA and PGA, from one generic source: single bodies and
//! mechanisms of many bodies joined by pinned multivectors.
//!
//! A brick thrown up while tumbling: its centre of mass follows the parabola and the energy holds. The same code
//! runs in CGA with [`Cga`] in place of [`Pga`].
//!
//! ```
//! use dynamics::{simulate, Body, Force, FreeBody, Method, Pga, Schedule, State};
//! use nalgebra::{UnitQuaternion, Vector3};
//!
//! let brick = Body::cuboid(1.0, Vector3::new(0.1, 0.2, 0.3))?; // 1 kg, sides in m
//! let system = FreeBody::<Pga>::new(brick).with_force(Force::gravity());
//! let (spin, throw) = (Vector3::new(0.1, 5.0, 0.1), Vector3::new(1.0, 0.0, 3.0)); // rad/s and m/s, world axes
//! let start = State::from_world_twist(&brick, Vector3::zeros(), &UnitQuaternion::identity(), spin, throw);
//! let run = simulate(&system, &[start], Method::Rkmk4Body, &Schedule::new(1e-3, 0.5)?)?;
//!
//! let end = run.body(0).last().unwrap();
//! let t = end.t;
//! assert!((end.position - Vector3::new(t, 0.0, 3.0 * t - 0.5 * 9.81 * t * t)).norm() < 1e-9); // m
//! assert!((end.energy - run.body(0)[0].energy).abs() < 1e-9); // J
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Implements Hadfield & Lasenby, *Constrained Dynamics in Conformal and Projective Geometric
//! Algebra*, as derived and corrected in `docs/theory.md`, and extends it to bodies held to each other
//! (`docs/mechanisms.md`). The pipeline, in the order the modules are declared below (each refers only to those
//! before it; `tests/integration/module_order.rs`, docs/architecture.md):
//! 1. the algebra layer: [`algebra`] (the trait; [`Pga`] and [`Cga`] built with `algebra!`, their
//!    [`equivalence`] checked at compile time), [`motor`], [`exponential`] and [`convert`] (rigid transforms);
//! 2. bodies and their state: [`body`], [`inertia`], [`state`];
//! 3. forces: [`forces`];
//! 4. constraints: [`surfaces`] (quadrics in QCGA and tori in DCGA, `docs/surfaces.md`), [`constraints`] (one
//!    constraint's rows), [`limits`] (`docs/limits.md`), [`joint_models`] (joints as robotics describes them) and
//!    [`contacts`] (body points above planes, `docs/contacts.md`);
//! 5. the equations of motion: [`joint_layout`] and [`motion`] (the [`Dynamics`] interface the integrators step,
//!    and the free body);
//! 6. [`mechanism`]: bodies held by joints, laid out by algorithm (building, evaluation, projection, joint space,
//!    one-sided constraints, force elements);
//! 7. time stepping: [`integrate`] (methods, tableaux, steps on the group, splittings, joint-coordinate stepping,
//!    step-size control) and [`simulate`](mod@simulate) (schedules, events, one-sided transitions, the run).

#![deny(missing_docs)]

#[cfg(test)]
mod test_random;
// The algebra layer: the trait, its two implementations (each from one `algebra!`), their equivalence.
pub mod algebra;
pub mod pga;
pub mod cga;
pub mod equivalence;
// Rigid transforms, interop with nalgebra, and the one dense decomposition the dynamics needs.
pub mod motor;
pub mod exponential;
pub mod convert;
mod eigen;
// Bodies and their state.
pub mod body;
pub mod inertia;
pub mod state;
// Forces.
pub mod forces;
// Constraints: the surfaces a point can be held on, one constraint's rows, joint limits, joint models, contacts.
pub mod surfaces;
pub mod constraints;
pub mod limits;
pub mod joint_models;
pub mod contacts;
// The equations of motion: the interface the integrators step (with where a system's joint coordinates are), and
// the free body.
pub mod joint_layout;
pub mod motion;
// Mechanisms: bodies held by joints, their reactions, joint space and one-sided constraints.
pub mod mechanism;
// Time stepping: integrators, step-size control, joint-coordinate stepping, and the run.
pub mod integrate;
pub mod simulate;

// Root paths of modules that live in the rooms above (`dynamics::step_control::Tolerance` and the like).
pub use integrate::{joint_coordinates as joint_integration, step_control};
pub use joint_models as joints;
pub use mechanism::force_elements;

pub use algebra::{Algebra, MotorCoordinates, ScrewCoordinates};
pub use body::{Body, BodyError, PrincipalFrame};
pub use cga::Cga;
pub use constraints::{Constraint, ConstraintError, Stabilisation};
pub use force_elements::{ForceElement, JointState, OfTime};
pub use forces::Force;
pub use integrate::step_control::{StepStatistics, Tolerance};
pub use integrate::{Integrator, JointMethod, KineticSplitting, Method, SplittingMethod, StepError, Stepper};
pub use joint_models::{JointKind, JointModel};
pub use mechanism::{
    BodyId, CoordinateGroup, Correction, JointId, JointSpace, Mechanism, MechanismError, Reference, SolverSettings,
    Violation,
};
pub use motion::{BodyRates, Dynamics, FreeBody, FreeBodyWorkspace, Rates};
pub use pga::Pga;
pub use simulate::{simulate, Crossing, Event, EventHit, Plan, Schedule, Simulation, SimulationError, Stop};
pub use state::{State, WorldMomentum, WorldVelocity};

/// Systems, states, results and errors cross threads: a run keeps its failure in its own `Result`,
/// with no shared slot, so parallel runs never see each other's errors. Checked at compile time.
const _: () = {
    const fn send_and_sync<T: Send + Sync>() {}
    send_and_sync::<Mechanism<Pga>>();
    send_and_sync::<Mechanism<Cga>>();
    send_and_sync::<FreeBody<Pga>>();
    send_and_sync::<FreeBody<Cga>>();
    send_and_sync::<mechanism::MechanismWorkspace<Pga>>();
    send_and_sync::<mechanism::MechanismWorkspace<Cga>>();
    send_and_sync::<Stepper<'static, Pga, Mechanism<Pga>>>();
    send_and_sync::<Stepper<'static, Cga, Mechanism<Cga>>>();
    send_and_sync::<State<Pga>>();
    send_and_sync::<State<Cga>>();
    send_and_sync::<Simulation<Pga>>();
    send_and_sync::<Simulation<Cga>>();
    send_and_sync::<Body>();
    send_and_sync::<SimulationError>();
    send_and_sync::<StepError>();
    send_and_sync::<MechanismError>();
    send_and_sync::<ConstraintError>();
    send_and_sync::<BodyError>();
};
