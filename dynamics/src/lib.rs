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
//! (`docs/mechanisms.md`). The pipeline, one module per stage:
//! [`algebra`] (the trait; [`Pga`] and [`Cga`] built with `algebra!`) → [`motor`] and
//! [`exponential`] (rigid transforms) → [`body`], [`inertia`] and [`state`] → [`forces`] →
//! [`motion`] (the equations of motion) → [`constraints`] (one constraint's rows), [`mechanism`]
//! (bodies, joints and the reaction solve), [`limits`] (joint limits, `docs/limits.md`) and [`contacts`]
//! (body points above planes, `docs/contacts.md`), with [`surfaces`] (quadrics in QCGA and tori in DCGA, held by
//! [`constraints::SurfacePin`] and [`VirtualPower::point_on_surface`](constraints::VirtualPower::point_on_surface),
//! `docs/surfaces.md`) → [`integrate`] →
//! [`simulate`](mod@simulate).

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
pub mod joints;
pub mod contacts;
// The equations of motion: the interface the integrators step, and the free body.
pub mod joint_layout;
pub mod motion;
// Mechanisms: bodies held by joints, their reactions, joint space and one-sided constraints.
pub mod mechanism;
pub use mechanism::force_elements;
// Time stepping: integrators, step-size control, joint-coordinate stepping, and the run.
pub mod integrate;
pub mod joint_integration;
pub mod step_control;
pub mod simulate;

pub use algebra::{Algebra, MotorCoordinates, ScrewCoordinates};
pub use body::{Body, BodyError, PrincipalFrame};
pub use cga::Cga;
pub use constraints::{Constraint, ConstraintError, Stabilisation};
pub use force_elements::{ForceElement, JointState, OfTime};
pub use forces::Force;
pub use integrate::{Integrator, KineticSplitting, Method, SplittingMethod, StepError, Stepper};
pub use joint_integration::JointMethod;
pub use joints::{JointKind, JointModel};
pub use mechanism::{
    BodyId, CoordinateGroup, Correction, JointId, JointSpace, Mechanism, MechanismError, Reference, SolverSettings,
    Violation,
};
pub use motion::{BodyRates, Dynamics, FreeBody, FreeBodyWorkspace, Rates};
pub use pga::Pga;
pub use simulate::{simulate, Crossing, Event, EventHit, Plan, Schedule, Simulation, SimulationError, Stop};
pub use state::{State, WorldMomentum, WorldVelocity};
pub use step_control::{StepStatistics, Tolerance};

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
