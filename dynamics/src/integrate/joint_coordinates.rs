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
        written,
    } = buffers;
    let same = |end: &[State<A>]| {
        end.len() == states.len()
            && end
                .iter()
                .zip(states.iter())
                .all(|(a, b)| a.motor == b.motor && a.momentum == b.momentum)
    };
    match written.iter().position(|(end, _, _)| same(end)) {
        Some(k) => {
            start_positions.copy_from_slice(&written[k].1);
            start_velocities.copy_from_slice(&written[k].2);
        }
        None => dynamics.read_joints(states, start_positions, start_velocities, workspace)?,
    }
    for s in 0..=S {
        // Stage s (or, for s = S, the step's end): positions and velocities from the slopes of the earlier stages.
        let weight = |j: usize| if s == S { b[j] } else { a[s][j] };
        let stages = (0..s.min(S)).filter(|&j| weight(j) != 0.0);
        positions.copy_from_slice(start_positions);
        velocities.copy_from_slice(start_velocities);
        sigmas.iter_mut().for_each(|sigma| *sigma = Vector3::zeros());
        for j in stages {
            let w = weight(j) * dt;
            for &(p, v) in &layout.vectors {
                positions[p] += w * stage_velocities[j][v];
            }
            for (velocity, acceleration) in velocities.iter_mut().zip(&stage_accelerations[j]) {
                *velocity += w * acceleration;
            }
            for (sigma, slope) in sigmas.iter_mut().zip(&rotation_slopes[j]) {
                *sigma += slope * weight(j);
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
        if s == S {
            break;
        }
        dynamics.joint_rates(
            t + c[s] * dt,
            positions,
            velocities,
            &mut stage_accelerations[s],
            workspace,
        )?;
        powers[s] = dynamics.power(workspace);
        stage_velocities[s].copy_from_slice(velocities);
        for (k, &(_, v)) in layout.rotations.iter().enumerate() {
            let omega = vector_at(velocities, v) * dt;
            rotation_slopes[s][k] = if s == 0 {
                omega
            } else {
                dexp_inverse(&sigmas[k], &omega, order)
            };
        }
        for (k, &(_, v, rotation)) in layout.translations.iter().enumerate() {
            translation_rates[s][k] = quaternion_at(positions, rotation) * vector_at(velocities, v);
        }
    }
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
