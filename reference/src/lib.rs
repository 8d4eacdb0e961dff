//! # reference: an independent classical yardstick for rigid-body simulators
//!
//! The geometric-algebra simulators of this project (CGA and PGA motors, constraints by virtual power and by pinning,
//! following Hadfield & Lasenby, "Constrained Dynamics in Conformal and Projective Geometric Algebra") are tested
//! against this crate, which shares no code or formalism with them: plain vectors and quaternions (nalgebra),
//! textbook closed forms, and reference trajectories integrated with scipy's DOP853 on the classical Newton–Euler
//! equations. The scenes, values and metrics are those of `docs/scenes.md` (what the tests check:
//! `docs/theory.md` §11).
//!
//! One module per concept, declared in this order, each referring only to the ones before it (`tests/module_order.rs`
//! checks it): the data (the trajectory format, the scenes and mechanisms with their reference trajectories, the
//! joint-space trees, the robots), then the closed forms, then the metrics:
//! * [`trajectory`]: [`Sample`], [`Trajectory`] and the CSV format of the reference files;
//! * [`scenes`]: the six reference scenes ([`SceneId`]): parameters, embedded reference trajectories, published end
//!   states and published analytic values;
//! * [`multibody`]: the mechanisms of `docs/scenes.md` (double pendulum, four-bar linkage, N-link chain): parameters,
//!   initial states from joint coordinates, embedded reference trajectories, joint violations from poses;
//! * [`joint_space`]: kinematic trees in joint coordinates (revolute, prismatic, fixed and free joints) and their
//!   dynamics by the textbook recursive algorithms (Featherstone's RNEA and CRBA): M(q), h(q, v), inverse and
//!   forward dynamics, energies and body velocities;
//! * [`robots`]: two real robots (UR5, Solo-12): their URDFs and Pinocchio's reference motion under gravity;
//! * [`elliptic`]: K(m) and the Jacobi elliptic functions sn, cn, dn;
//! * [`analytic`]: the closed forms (Dzhanibekov flips, pendulum, heavy top) that the published values come from;
//! * [`metrics`]: the error metrics (orientation/position errors, energy drift, flip times, pendulum period,
//!   nutation and precession features, constraint violations).
//!
//! The reference data is compiled in (`include_str!`), so nothing is read from disk at run time. No function
//! panics on bad input: errors are returned as `Result`.
//!
//! Typical use, with a simulator's output sampled on the same 0.01 s grid:
//! ```
//! use reference::{energy_drift, flip_time_error, flip_times, trajectory_errors, SceneId};
//!
//! let scene = SceneId::Cuboid;
//! let reference = scene.reference_trajectory()?;
//! let simulated = reference.clone(); // stand-in for a simulator's trajectory
//! let errors = trajectory_errors(&reference, &simulated)?;
//! let drift = energy_drift(&scene.parameters(), &simulated);
//! let flips = flip_times(&simulated, &scene.parameters().principal_moments);
//! let flip_error = flip_time_error(&flips, &reference::scenes::CUBOID_VALUES.flip_instants)?;
//! assert!(errors.max_orientation < 1e-15 && drift < 1e-14 && flip_error < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![deny(missing_docs)]

pub mod trajectory;
pub mod scenes;
pub mod multibody;
pub mod joint_space;
pub mod robots;
pub mod elliptic;
pub mod analytic;
pub mod metrics;

pub use analytic::{
    AnalyticError, DzhanibekovSolution, HeavyTop, Nutation, Pendulum, PendulumSolution, SteadyPrecessionRates,
};
pub use elliptic::{
    complete_elliptic_k, incomplete_elliptic_f, jacobi_elliptic, EllipticError, EllipticParameter, JacobiElliptic,
};
pub use metrics::{
    constraint_violations, energy_drift, flip_time_error, flip_times, nutation_features, orientation_error,
    pendulum_angle, pendulum_period, position_error, steady_precession_features, top_axis_angles, trajectory_errors,
    ConstraintViolations, MetricError, NutationFeatures, SteadyPrecessionFeatures, TopAxisAngles, TrajectoryErrors,
};
pub use scenes::{SceneConstraint, SceneId, SceneParameters};
pub use trajectory::{Sample, Trajectory, TrajectoryError};
