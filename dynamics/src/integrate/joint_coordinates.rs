//! Stepping in joint coordinates (docs/mechanisms.md §M9): for a mechanism whose joints are joint models in a
//! tree, a step reads the joint positions and velocities from the bodies' states, integrates `q̇ = v`,
//! `v̇ = q̈(q, v)` by an explicit Runge–Kutta tableau — Munthe-Kaas on the rotations of spherical joints and free
//! roots, whose positions are unit quaternions — with q̈ from the articulated solve at the bodies placed by exact
//! forward kinematics, and writes the bodies' states back by forward kinematics. The joints hold exactly at every
//! stage, so no projection is needed, and a stage costs one forward kinematics and one articulated solve (no
//! per-body Lie-group update, no `dexp⁻¹` per body: only per rotating joint).
//!
//! The coordinates: a coordinate whose rate is its velocity (a revolute angle, a slide, a universal or planar
//! coordinate) is a vector coordinate; a rotation (a spherical joint, a free root's orientation) is a unit
//! quaternion r turned by its angular velocity ω in its own axes, `ṙ = ½ r ⊗ ω`, advanced as `r₀ exp(σ)` with
//! `σ̇ = dexp⁻¹_{−σ}(ω)`; a free root's position p moves with its velocity v in the rotation's axes, `ṗ = R(r) v`.

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::integrate::tableaux::DOP853_EXTENDED_STAGES;
use crate::joint_layout::{quaternion_at, vector_at, write_quaternion};
use crate::motion::Dynamics;
use crate::state::State;

// The method and layout types, also reachable here where joint-coordinate stepping is described.
pub use crate::integrate::methods::JointMethod;
pub use crate::joint_layout::JointLayout;

/// The buffers of the joint-coordinate steps, sized once for a system.
pub(crate) struct JointBuffers<A: Algebra> {
    layout: JointLayout,
    start_positions: Vec<f64>,
    start_velocities: Vec<f64>,
    positions: Vec<f64>,
    velocities: Vec<f64>,
    /// Per stage: the velocities (the vector coordinates' rates), the accelerations, the rotations' Lie-algebra
    /// slopes `K = dexp⁻¹(h ω)` and the translations' rates `R v`.
    stage_velocities: Vec<Vec<f64>>,
    stage_accelerations: Vec<Vec<f64>>,
    rotation_slopes: Vec<Vec<Vector3<f64>>>,
    translation_rates: Vec<Vec<Vector3<f64>>>,
    /// Per rotation: the stage's σ.
    sigmas: Vec<Vector3<f64>>,
    /// The last steps' end states with the joint coordinates they were written from, newest first: a step that starts
    /// from one of them takes its coordinates as they were rather than reading them back from the states, whose world
    /// momenta about the origin and poses far from it would round them (a floating base falling 5 m loses ~1e-14 rad
    /// of its legs' angles per read).
    written: Vec<Written<A>>,
}

impl<A: Algebra> JointBuffers<A> {
    pub(crate) fn new(layout: JointLayout, stages: usize) -> Self {
        let (nq, nv) = (layout.positions, layout.velocities);
        let (rotations, translations) = (layout.rotations.len(), layout.translations.len());
        JointBuffers {
            start_positions: vec![0.0; nq],
            start_velocities: vec![0.0; nv],
            positions: vec![0.0; nq],
            velocities: vec![0.0; nv],
            stage_velocities: vec![vec![0.0; nv]; stages],
            stage_accelerations: vec![vec![0.0; nv]; stages],
            rotation_slopes: vec![vec![Vector3::zeros(); rotations]; stages],
            translation_rates: vec![vec![Vector3::zeros(); translations]; stages],
            sigmas: vec![Vector3::zeros(); rotations],
            written: Vec::with_capacity(WRITTEN),
            layout,
        }
    }
}

/// An end state a step wrote, with the positions and velocities it was written from.
type Written<A> = (Vec<State<A>>, Vec<f64>, Vec<f64>);

/// How many written end states are kept: a run's whole steps and the partial steps to its samples alternate.
const WRITTEN: usize = 2;

/// `dexp⁻¹_{−σ}(k) = k + ½ σ×k + ¹⁄₁₂ σ×(σ×k) − ¹⁄₇₂₀ ad⁴ + ¹⁄₃₀₂₄₀ ad⁶` on so(3) (`[a, b] = a × b`), truncated after the
/// term the method's order needs (as `integrate::dexp_inverse` on screws).
fn dexp_inverse(sigma: &Vector3<f64>, k: &Vector3<f64>, order: u32) -> Vector3<f64> {
    let first = sigma.cross(k);
    let second = sigma.cross(&first);
    let mut result = k + first * 0.5 + second * (1.0 / 12.0);
    if order > 4 {
        let fourth = sigma.cross(&sigma.cross(&second));
        result += fourth * (-1.0 / 720.0);
        if order > 6 {
            let sixth = sigma.cross(&sigma.cross(&fourth));
            result += sixth * (1.0 / 30240.0);
        }
    }
    result
}

impl<A: Algebra> JointBuffers<A> {
    /// The positions and velocities at `start + Σ_j w_j K_j` over the stages `j` of `weights` (nonzero ones only:
    /// the later stages' slopes are another step's): vector coordinates by their rates, velocities by their
    /// accelerations, rotations by `r₀ exp(Σ w_j K_j)`, a free root's position by its rates `R v`.
    fn combine(&mut self, weights: &[f64], dt: f64) {
        let JointBuffers {
            layout,
            start_positions,
            start_velocities,
            positions,
            velocities,
            stage_velocities,
            stage_accelerations,
            rotation_slopes,
            translation_rates,
            sigmas,
            ..
        } = self;
        positions.copy_from_slice(start_positions);
        velocities.copy_from_slice(start_velocities);
        sigmas.iter_mut().for_each(|sigma| *sigma = Vector3::zeros());
        for (j, &weight) in weights.iter().enumerate().filter(|(_, &w)| w != 0.0) {
            let w = weight * dt;
            for &(p, v) in &layout.vectors {
                positions[p] += w * stage_velocities[j][v];
            }
            for (velocity, acceleration) in velocities.iter_mut().zip(&stage_accelerations[j]) {
                *velocity += w * acceleration;
            }
            for (sigma, slope) in sigmas.iter_mut().zip(&rotation_slopes[j]) {
                *sigma += slope * weight;
            }
            for (k, &(p, _, _)) in layout.translations.iter().enumerate() {
                let moved = translation_rates[j][k] * w;
                for axis in 0..3 {
                    positions[p + axis] += moved[axis];
                }
            }
        }
        for (sigma, &(p, _)) in sigmas.iter().zip(&layout.rotations) {
            let turned = quaternion_at(start_positions, p) * UnitQuaternion::from_scaled_axis(*sigma);
            write_quaternion(positions, p, &turned);
        }
    }

    /// Stage `s` at the positions and velocities [`JointBuffers::combine`] left, at time `t`: its accelerations
    /// and power, and its slopes (the rotations' `dexp⁻¹_{−σ}(h ω)`, truncated for `order`).
    fn evaluate<D: Dynamics<A> + ?Sized>(
        &mut self,
        dynamics: &D,
        (s, t, dt, order): (usize, f64, f64, u32),
        powers: &mut [f64],
        workspace: &mut D::Workspace,
    ) -> Result<(), ConstraintError> {
        dynamics.joint_rates(
            t,
            &self.positions,
            &self.velocities,
            &mut self.stage_accelerations[s],
            workspace,
        )?;
        powers[s] = dynamics.power(workspace);
        self.stage_velocities[s].copy_from_slice(&self.velocities);
        for (k, &(_, v)) in self.layout.rotations.iter().enumerate() {
            let omega = vector_at(&self.velocities, v) * dt;
            self.rotation_slopes[s][k] = dexp_inverse(&self.sigmas[k], &omega, order);
        }
        for (k, &(_, v, rotation)) in self.layout.translations.iter().enumerate() {
            self.translation_rates[s][k] = quaternion_at(&self.positions, rotation) * vector_at(&self.velocities, v);
        }
        Ok(())
    }

    /// The stages DOP853's continuous extension adds to the last step from `t` of length `dt` (rows over the earlier
    /// stages and their nodes), as a step's are evaluated.
    pub(crate) fn extend<D: Dynamics<A> + ?Sized>(
        &mut self,
        dynamics: &D,
        (t, dt, order): (f64, f64, u32),
        (first, rows): (usize, &[([f64; DOP853_EXTENDED_STAGES], f64)]),
        powers: &mut [f64],
        workspace: &mut D::Workspace,
    ) -> Result<(), ConstraintError> {
        for (k, (row, node)) in rows.iter().enumerate() {
            self.combine(&row[..first + k], dt);
            self.evaluate(dynamics, (first + k, t + node * dt, dt, order), powers, workspace)?;
        }
        Ok(())
    }

    /// The state at `start + Σ w_j K_j` of the last step (from `t`, of length `dt`) written into `out` by forward
    /// kinematics at time `at`: DOP853's continuous extension, with its dense-output weights at the fraction wanted.
    pub(crate) fn dense<D: Dynamics<A> + ?Sized>(
        &mut self,
        dynamics: &D,
        (weights, dt, at): (&[f64], f64, f64),
        out: &mut [State<A>],
        workspace: &mut D::Workspace,
    ) -> Result<(), ConstraintError> {
        self.combine(weights, dt);
        dynamics.write_joints(at, &self.positions, &self.velocities, out, workspace)
    }

    /// The error norm of the last step (of length `dt`) whose embedded difference has the stage weights `weights`:
    /// the largest over every coordinate of `ratio(error, size)`, its error over `absolute + relative · size`
    /// (the tolerance's; docs/dynamics.md
    /// "Adaptive steps in joint coordinates"): a joint's coordinate (rad or m) and a rotation's turn absolutely, a
    /// free root's position relative to its distance from the origin, each velocity relative to its size at the
    /// step's two ends. The largest, not a mean, so that a light distal joint's error is not averaged away; NaN
    /// stays NaN.
    pub(crate) fn error_norm(&self, ratio: impl Fn(f64, f64) -> f64, weights: &[f64], dt: f64) -> f64 {
        let (end_positions, end_velocities) = match self.written.first() {
            Some((_, positions, velocities)) => (positions, velocities),
            None => (&self.positions, &self.velocities),
        };
        let weighted =
            |value: &dyn Fn(usize) -> f64| -> f64 { weights.iter().enumerate().map(|(j, w)| w * value(j)).sum() };
        let mut largest = 0.0f64;
        let mut keep = |ratio: f64| {
            if ratio > largest || ratio.is_nan() {
                largest = ratio;
            }
        };
        for &(_, v) in &self.layout.vectors {
            keep(ratio(dt * weighted(&|j| self.stage_velocities[j][v]).abs(), 0.0));
        }
        for k in 0..self.layout.rotations.len() {
            let turn: Vector3<f64> = (weights.iter().enumerate())
                .map(|(j, w)| self.rotation_slopes[j][k] * *w)
                .sum();
            keep(ratio(turn.norm(), 0.0));
        }
        for (k, &(p, _, _)) in self.layout.translations.iter().enumerate() {
            let shift: Vector3<f64> = (weights.iter().enumerate())
                .map(|(j, w)| self.translation_rates[j][k] * (w * dt))
                .sum();
            let size = vector_at(&self.start_positions, p)
                .norm()
                .max(vector_at(end_positions, p).norm());
            keep(ratio(shift.norm(), size));
        }
        for (i, (start, end)) in self.start_velocities.iter().zip(end_velocities.iter()).enumerate() {
            let change = dt * weighted(&|j| self.stage_accelerations[j][i]).abs();
            keep(ratio(change, start.abs().max(end.abs())));
        }
        largest
    }
}

/// One step of an explicit tableau (`a`, `b`, `c`, order) in joint coordinates from `states` at `t`; the states are
/// replaced by the step's end, and `powers` gets each stage's non-conservative power.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step<A: Algebra, D: Dynamics<A> + ?Sized, const S: usize>(
    (a, b, c, order): (&[[f64; S]; S], &[f64; S], &[f64; S], u32),
    dynamics: &D,
    t: f64,
    states: &mut [State<A>],
    dt: f64,
    buffers: &mut JointBuffers<A>,
    powers: &mut [f64],
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let same = |end: &[State<A>]| {
        end.len() == states.len()
            && end
                .iter()
                .zip(states.iter())
                .all(|(a, b)| a.motor == b.motor && a.central_momentum == b.central_momentum)
    };
    match buffers.written.iter().position(|(end, _, _)| same(end)) {
        Some(k) => {
            let (_, positions, velocities) = &buffers.written[k];
            buffers.start_positions.copy_from_slice(positions);
            buffers.start_velocities.copy_from_slice(velocities);
        }
        None => dynamics.read_joints(
            states,
            &mut buffers.start_positions,
            &mut buffers.start_velocities,
            workspace,
        )?,
    }
    for s in 0..S {
        buffers.combine(&a[s][..s], dt);
        buffers.evaluate(dynamics, (s, t + c[s] * dt, dt, order), powers, workspace)?;
    }
    buffers.combine(b, dt);
    let JointBuffers {
        positions,
        velocities,
        written,
        ..
    } = buffers;
    dynamics.write_joints(t + dt, positions, velocities, states, workspace)?;
    // Keep this end (reusing the oldest entry's storage).
    let mut entry = if written.len() == WRITTEN {
        written.pop().expect("full")
    } else {
        (Vec::new(), Vec::new(), Vec::new())
    };
    entry.0.clear();
    entry.0.extend_from_slice(states);
    entry.1.clear();
    entry.1.extend_from_slice(positions);
    entry.2.clear();
    entry.2.extend_from_slice(velocities);
    written.insert(0, entry);
    Ok(())
}
