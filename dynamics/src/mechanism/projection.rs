//! Projection onto the joint manifold (docs/mechanisms.md §M5): Gauss–Newton steps on the positions, then the
//! velocities projected in the kinetic metric, after a step or onto a start that breaks the joints.

use crate::algebra::Algebra;
use crate::constraints::{Constraint, ConstraintError, Stabilisation};
use crate::exponential::exp;
use crate::mechanism::joint_rows::{velocity_screw, wrench_screw, Rows};
use crate::mechanism::model::{BodyTerms, Condition, Mechanism, MechanismWorkspace};
use crate::mechanism::solve::{dot6, Consistency};
use crate::motor;
use crate::state::State;

/// The projection leaves a system alone whose joints are within these: position residuals below
/// `POSITION_TOLERANCE` (m, or unit-size coefficients of pinned objects) and velocity residuals below
/// `VELOCITY_TOLERANCE`, each raised to [`ROUND_OFF_ULPS`] ulp of the largest coordinate (body position, body
/// velocity). A Gauss–Newton step cannot improve on the round-off of the coordinates: 40 m out on a 64-link
/// chain an ulp is 7e-15, and a fixed 1e-14 made two Gauss–Newton steps and two factorisations in most steps.
const POSITION_TOLERANCE: f64 = 1e-14;

/// Drift up to which one Gauss–Newton step brings the joints to round-off (it squares the residual, in units of
/// the joints' size): the projection after a step takes the one-factorisation path below it.
const ONE_STEP_DRIFT: f64 = 1e-8;

const VELOCITY_TOLERANCE: f64 = 1e-12;

const ROUND_OFF_ULPS: f64 = 16.0;

/// A position residual still above this after a projection's Gauss–Newton steps means the joints cannot hold
/// together (a step leaves about 1e-10 before projection and round-off after it; two contradictory joints
/// leave their whole disagreement): an error, never a run with a broken joint.
const UNREACHABLE_RESIDUAL: f64 = 1e-6;

/// How far [`Mechanism::project`] moved each body of a start onto its joints, by body index.
#[derive(Clone, Debug, PartialEq)]
pub struct Correction {
    /// How far each body's centre of mass moved (m).
    pub moved: Vec<f64>,
    /// How far each body turned (rad).
    pub turned: Vec<f64>,
}

impl Correction {
    /// The body that moved or turned the most, and by how much (m or rad, whichever is larger); `None` without
    /// bodies.
    pub fn largest(&self) -> Option<(usize, f64)> {
        (self.moved.iter().zip(&self.turned))
            .map(|(moved, turned)| moved.max(*turned))
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// Gauss–Newton steps at most when projecting initial conditions, which may start far from the joints.
const INITIAL_PROJECTION_STEPS: usize = 50;

impl<A: Algebra> Mechanism<A> {
    /// The joints' rows (positions and velocities only) at `states`.
    pub(super) fn position_rows(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        purpose: Rows,
    ) -> Result<(), ConstraintError> {
        for (i, state) in states.iter().enumerate() {
            workspace.motors[i] = state.motor;
            workspace.momenta[i] = state.body_momentum();
        }
        let motors = std::mem::take(&mut workspace.motors);
        let momenta = std::mem::take(&mut workspace.momenta);
        self.body_kinematics(t, &motors, &momenta, workspace, BodyTerms::Kinematics)?;
        workspace.motors = motors;
        workspace.momenta = momenta;
        self.joint_rows(t, workspace, purpose)
    }

    /// Projects states onto the joint manifold (theory §10, docs/mechanisms.md §M5): normalise every motor,
    /// Gauss–Newton steps on the positions of the whole system (at most as many as [`Stabilisation::Projection`]
    /// says and at least enough to converge from afar, stopping once the residuals are round-off; skipped if a
    /// joint has no position residual), then the kinetic-metric velocity projection. Use it on initial
    /// conditions, which must satisfy both the position and the velocity constraints; joints that cannot hold
    /// together are an error naming them. Returns how far each body moved: a start off its joints by round-off moves
    /// by round-off, one that breaks a joint moves by as much as it breaks it, which the caller may refuse.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::constraints::VirtualPower;
    /// use dynamics::{Body, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::cuboid(1.0, Vector3::new(0.1, 0.1, 1.0))?;
    /// let mut pendulum = Mechanism::<Pga>::new();
    /// let arm = pendulum.add_body("arm", rod)?;
    /// let top = (Vector3::new(0.0, 0.0, 0.5), Vector3::x());
    /// pendulum.add_joint(arm, Reference::World, Arc::new(VirtualPower::hinge("pivot", top, (Vector3::zeros(), Vector3::x()))?))?;
    /// // The rod's top end 13 cm below its pivot.
    /// let still = Vector3::zeros();
    /// let mut start = [State::new(&rod, Vector3::new(0.0, 0.0, -0.63), &UnitQuaternion::identity(), still, still)];
    /// let correction = pendulum.project(0.0, &mut start)?;
    /// assert!((correction.moved[0] - 0.13).abs() < 1e-12); // m
    /// assert!(correction.turned[0] < 1e-15); // rad
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn project(&self, t: f64, states: &mut [State<A>]) -> Result<Correction, ConstraintError> {
        self.check_count("states", states.len())?;
        let iterations = match self.stabilisation {
            Stabilisation::Projection { position_iterations } => position_iterations,
            _ => 2,
        };
        let mut workspace = self.new_workspace();
        let before: Vec<_> = states.iter().map(State::pose).collect();
        self.project_with(t, states, iterations.max(INITIAL_PROJECTION_STEPS), &mut workspace)?;
        let (moved, turned) = (before.iter().zip(states.iter()))
            .map(|((position, orientation), state)| {
                let (now, turned_to) = state.pose();
                ((now - position).norm(), orientation.angle_to(&turned_to))
            })
            .unzip();
        Ok(Correction { moved, turned })
    }

    pub(super) fn project_with(
        &self,
        t: f64,
        states: &mut [State<A>],
        iterations: usize,
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        if self.articulation.is_some() {
            self.project_coordinates(t, states, &mut workspace.previous_positions, &workspace.held)?;
            return self.place_held_contacts(t, states, workspace);
        }
        for state in states.iter_mut() {
            state.motor = motor::normalise::<A>(state.motor);
        }
        if self.joints.is_empty() {
            return Ok(());
        }
        let position_level = self.joints.iter().all(|j| j.constraint.has_position_residual());
        self.position_rows(t, states, workspace, Rows::Projection)?;
        let mut tolerances = Tolerances::of(workspace);
        let drift = largest_position_residual(workspace);
        // The factors of the integrator's last stage, if any, serve only this projection.
        let stage_factors = std::mem::take(&mut workspace.stage_factors);
        let mut steps = 0;
        if position_level && iterations > 0 && drift > tolerances.position && drift <= ONE_STEP_DRIFT {
            // The common case after a step, a drift so small that one Gauss–Newton step squares it to round-off
            // (docs/mechanisms.md M5). Its factorisation of K can be a chord: the factors of the integrator's
            // last stage, whose K is this one to O(dt²) for the usual methods. Whether a chord step (or one with
            // factors from before a move) reached round-off is checked exactly to first order, e and ė being
            // `e + J δ` and `ė + J Δx` after the bodies move by δ or change velocity by Δx (the second order is
            // the square of the drift), and what is left is solved again with fresh factors.
            let mut fresh = !stage_factors || !workspace.joints.iter().all(|rows| rows.reduced.direct);
            if fresh {
                self.factor_system(workspace)?;
            }
            self.solve_factored(workspace, Condition::Position, Consistency::Skip)?;
            self.move_positions(states, workspace);
            if !fresh && self.remaining_residual(workspace, Condition::Position) > tolerances.position {
                self.factor_system(workspace)?;
                fresh = true;
                self.solve_factored(workspace, Condition::Position, Consistency::Skip)?;
                self.move_positions(states, workspace);
            }
            steps = 1;
            // The velocity projection can use the rows from before the move when that leaves ė = O(|δ| |x|) —
            // about drift × the largest body velocity — within the velocity tolerance: one evaluation for the
            // whole projection. Otherwise (a rod end on a sphere, RK4 at dt = 1e-3, ended 3.5e-9 from the exact
            // projection's run after 2 s) the rows are evaluated again at the moved positions, which also checks
            // the position step, and K's factors from before the move serve as a chord.
            let evaluate_again = drift * tolerances.velocity_scale > tolerances.velocity;
            if !evaluate_again {
                // Rows and (fresh) factors both from before the move need no check.
                return self.project_velocities(states, workspace, !fresh, tolerances.velocity);
            }
            self.position_rows(t, states, workspace, Rows::Projection)?;
            if largest_position_residual(workspace) <= tolerances.position
                && workspace.joints.iter().all(|rows| rows.reduced.direct)
            {
                return self.project_velocities(states, workspace, true, tolerances.velocity);
            }
            // Not at round-off after all, or rows whose basis the reduction chose afresh: the checked loop.
            tolerances = Tolerances::of(workspace);
        }
        // Initial conditions and large drifts: Gauss–Newton steps, each checked by an evaluation.
        while position_level && steps < iterations && largest_position_residual(workspace) > tolerances.position {
            self.solve_reactions(workspace, Condition::Position, Consistency::Skip)?;
            self.move_positions(states, workspace);
            steps += 1;
            self.position_rows(t, states, workspace, Rows::Projection)?;
            tolerances = Tolerances::of(workspace);
        }
        let unreachable: Vec<usize> = (0..self.joints.len())
            .filter(|&j| workspace.joints[j].position_residual > UNREACHABLE_RESIDUAL)
            .collect();
        if position_level && !unreachable.is_empty() {
            let residual = unreachable
                .iter()
                .map(|&j| workspace.joints[j].position_residual)
                .fold(0.0, f64::max);
            return Err(ConstraintError::Unreachable {
                names: self.names(unreachable),
                residual,
            });
        }
        // Positions left alone and velocities within round-off: nothing to do.
        if steps == 0
            && workspace
                .joints
                .iter()
                .all(|rows| rows.velocity_residual <= tolerances.velocity)
        {
            return Ok(());
        }
        if steps == 0 && stage_factors && workspace.joints.iter().all(|rows| rows.reduced.direct) {
            // Positions left alone: the last stage's factors serve as a chord, checked.
            return self.project_velocities(states, workspace, true, tolerances.velocity);
        }
        self.solve_reactions(workspace, Condition::Velocity, Consistency::Skip)?;
        self.change_momenta(states, workspace);
        Ok(())
    }

    /// The velocity projection with the factors in `workspace`; with `check`, when they are not those of the
    /// current rows, its result is checked ([`Mechanism::remaining_residual`]) and what is left solved again with
    /// fresh factors.
    fn project_velocities(
        &self,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
        check: bool,
        tolerance: f64,
    ) -> Result<(), ConstraintError> {
        self.solve_factored(workspace, Condition::Velocity, Consistency::Skip)?;
        self.change_momenta(states, workspace);
        if check && self.remaining_residual(workspace, Condition::Velocity) > tolerance {
            self.factor_system(workspace)?;
            self.solve_factored(workspace, Condition::Velocity, Consistency::Skip)?;
            self.change_momenta(states, workspace);
        }
        Ok(())
    }

    /// The residuals of `condition` left after the bodies moved by the reactions in `workspace`
    /// ([`Mechanism::move_positions`] or [`Mechanism::change_momenta`]): ė is linear in the velocities and e is to
    /// first order (the rest is the square of the step), so each joint's row gains `a·Δ_b + a'·Δ_a` from the
    /// bodies' changes `Δ = G Jᵀλ` (a' the row acting on the reference). Stores the new right-hand sides `−e` or
    /// `−ė` and returns their largest size.
    fn remaining_residual(&self, workspace: &mut MechanismWorkspace<A>, condition: Condition) -> f64 {
        let MechanismWorkspace {
            joints,
            reactions,
            inverse_metric,
            ..
        } = workspace;
        let change =
            |body: usize| -> [f64; 6] { std::array::from_fn(|k| reactions[body][k] * inverse_metric[body][k]) };
        let mut largest = 0.0f64;
        for (joint, rows) in self.joints.iter().zip(joints.iter_mut()) {
            let body = change(joint.body);
            let reference = joint.reference.map(change);
            let reduced = &mut rows.reduced;
            for k in 0..reduced.rank {
                let mut gained = dot6(&reduced.rows[k], &body);
                if let Some(reference) = &reference {
                    gained += dot6(&rows.reference_rows[k], reference);
                }
                let value = &mut reduced.values[condition as usize][k];
                *value -= gained;
                largest = largest.max(value.abs());
            }
        }
        largest
    }

    /// The Gauss–Newton position step from the reactions λ of `K λ = −e`: `δᵢ = Gᵢ Jᵢᵀλ`,
    /// `Rᵢ ← Rᵢ exp(−½δᵢ)`, the motion with body velocity δᵢ for unit time.
    fn move_positions(&self, states: &mut [State<A>], workspace: &MechanismWorkspace<A>) {
        for (i, state) in states.iter_mut().enumerate() {
            let y = workspace.reactions[i];
            let delta: [f64; 6] = std::array::from_fn(|k| y[k] * workspace.inverse_metric[i][k]);
            let step = A::screw(velocity_screw(&delta)) * -0.5;
            state.motor = motor::normalise::<A>(A::compose(state.motor, exp::<A>(step)));
        }
    }

    /// The velocity projection from the reactions λ of `K λ = −ė`: `Δxᵢ = Gᵢ Jᵢᵀλ`, so the momentum changes by
    /// `H Δx = Jᵀλ`. Only this (tiny) change goes through the frame change, not Ω itself: a round trip
    /// Ω → Ω_b → Ω every step biases the energy by about an ulp per step (measured: +1e-15 J per step on a
    /// pendulum, 1e-10 rad after 1e5 steps).
    fn change_momenta(&self, states: &mut [State<A>], workspace: &MechanismWorkspace<A>) {
        for (i, state) in states.iter_mut().enumerate() {
            let change = wrench_screw(&workspace.reactions[i]);
            let frame = &workspace.bodies[i].kinematics.frame;
            state.central_momentum = state.central_momentum + A::screw(frame.turn_to_world(&change));
        }
    }
}

/// The projection's tolerances at the bodies' kinematics (see [`POSITION_TOLERANCE`]).
struct Tolerances {
    position: f64,
    velocity: f64,
    /// The largest body velocity coordinate (rad/s or m/s).
    velocity_scale: f64,
}

impl Tolerances {
    fn of<A: Algebra>(workspace: &MechanismWorkspace<A>) -> Self {
        let (position, velocity_scale) = workspace.bodies.iter().fold((0.0f64, 0.0f64), |(p, v), body| {
            let kinematics = &body.kinematics;
            (
                p.max(kinematics.frame.position.amax()),
                v.max(kinematics.velocity.amax()),
            )
        });
        let ulps = ROUND_OFF_ULPS * f64::EPSILON;
        Tolerances {
            position: POSITION_TOLERANCE.max(ulps * position),
            velocity: VELOCITY_TOLERANCE.max(ulps * velocity_scale),
            velocity_scale,
        }
    }
}

/// The largest position residual over the joints.
fn largest_position_residual<A: Algebra>(workspace: &MechanismWorkspace<A>) -> f64 {
    workspace
        .joints
        .iter()
        .map(|rows| rows.position_residual)
        .fold(0.0, f64::max)
}
