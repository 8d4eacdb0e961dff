//! The mechanism's reaction solve against a dense one. For random trees of bodies joined by virtual-power
//! joints (ball, hinge, cylindrical, point on plane, point on sphere; their rows are defined at any state, so
//! random states are valid) at random states, the reactions of [`Mechanism`] — reduced rows, joint-space matrix
//! factored front by front over the spanning tree — equal those of a dense kinetic-metric solve written here
//! from the formulation (docs/mechanisms.md §M2, §M4): rows from the relative kinematics of each joint,
//! `J G Jᵀ λ = β − J G g` solved by a dense LU, reactions `Jᵀλ`.

use crate::common;

use std::sync::Arc;

use common::Random;
use dynamics::constraints::{Constraint, Kinematics, RowBuffer, VirtualPower};
use dynamics::motor::{self, ScrewFrame};
use dynamics::{
    Algebra, Body, BodyId, BodyRates, Cga, Dynamics, Force, Mechanism, Pga, Reference, ScrewCoordinates, State,
};
use nalgebra::{DMatrix, DVector, Vector3};
use proptest::prelude::*;

/// A joint of the random tree: its constraint, its body and its reference (None: the world).
struct TreeJoint<A: Algebra> {
    constraint: Arc<dyn Constraint<A>>,
    body: usize,
    reference: Option<usize>,
}

/// A random tree of `n` bodies: body i hangs from a random earlier body or the world by a random joint.
fn random_tree<A: Algebra>(random: &mut Random, n: usize) -> (Mechanism<A>, Vec<Body>, Vec<TreeJoint<A>>) {
    let mut mechanism = Mechanism::<A>::new();
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    let mut ids: Vec<BodyId> = Vec::new();
    for i in 0..n {
        let extents = Vector3::new(
            0.2 + random.next().abs(),
            0.2 + random.next().abs(),
            0.2 + random.next().abs(),
        );
        let body = Body::cuboid(0.5 + 2.0 * random.next().abs(), extents).unwrap();
        let id = mechanism.add_body(format!("body {i}"), body).unwrap();
        mechanism.add_force(id, Force::gravity()).unwrap();
        let parent = ((random.next().abs() * (i + 1) as f64) as usize).min(i);
        let reference = (parent < i).then_some(parent);
        let (point, other) = (random.vector(0.5), random.vector(0.5));
        let (axis, other_axis) = (random.vector(1.0), random.vector(1.0));
        let name = format!("joint {i}");
        let constraint: Arc<dyn Constraint<A>> = match (random.next().abs() * 5.0) as usize {
            0 => Arc::new(VirtualPower::ball_joint(name, point, other)),
            1 => Arc::new(VirtualPower::hinge(name, (point, axis), (other, other_axis)).unwrap()),
            2 => Arc::new(VirtualPower::cylindrical(name, (point, axis), (other, other_axis)).unwrap()),
            3 => Arc::new(VirtualPower::point_on_plane(name, point, (other_axis, 0.3)).unwrap()),
            _ => Arc::new(VirtualPower::point_on_sphere(name, point, other, 0.7).unwrap()),
        };
        let attachment = reference.map_or(Reference::World, |r| Reference::Body(ids[r]));
        mechanism.add_joint(id, attachment, constraint.clone()).unwrap();
        joints.push(TreeJoint {
            constraint,
            body: i,
            reference,
        });
        bodies.push(body);
        ids.push(id);
    }
    (mechanism, bodies, joints)
}

/// Wrench (covector) coordinates `(τ; f)` of screw coordinates, and back.
fn covector(c: &ScrewCoordinates) -> [f64; 6] {
    [c.t.x, c.t.y, c.t.z, c.l.x, c.l.y, c.l.z]
}

fn wrench(y: &[f64]) -> ScrewCoordinates {
    ScrewCoordinates {
        l: Vector3::new(y[3], y[4], y[5]),
        t: Vector3::new(y[0], y[1], y[2]),
    }
}

/// Velocity coordinates `(ω; v)` of screw coordinates.
fn velocity(c: &ScrewCoordinates) -> [f64; 6] {
    [c.l.x, c.l.y, c.l.z, c.t.x, c.t.y, c.t.z]
}

/// The dense solve: every body's reaction (wrench coordinates, body frame).
fn dense_reactions<A: Algebra>(
    bodies: &[Body],
    joints: &[TreeJoint<A>],
    motors: &[A::Motor],
    momenta: &[A::Screw],
) -> (Vec<[f64; 6]>, f64) {
    let n = bodies.len();
    let t = 0.0;
    // Per body: velocity Ḃ, inverse metric g, free wrench (Ḃ × Ω_b + gravity in the body frame).
    let velocities: Vec<A::Screw> = bodies.iter().zip(momenta).map(|(b, m)| b.velocity::<A>(*m)).collect();
    let mut metric = DVector::zeros(6 * n);
    let mut drive = DVector::zeros(6 * n);
    for i in 0..n {
        let frame = ScrewFrame::of::<A>(motors[i]);
        let gravity = frame
            .rotation
            .inverse_transform_vector(&(bodies[i].mass() * Vector3::new(0.0, 0.0, -9.81)));
        let free = A::screw_coordinates(A::commutator(velocities[i], momenta[i]))
            + ScrewCoordinates {
                l: gravity,
                t: Vector3::zeros(),
            };
        let inverse = bodies[i].kinetic_metric().diagonal().map(|h| 1.0 / h);
        for k in 0..6 {
            metric[6 * i + k] = inverse[k];
            drive[6 * i + k] = covector(&free)[k];
        }
    }
    // Rows: each joint's constraint at the relative kinematics, acting on its body as a, on its reference as
    // −(a in the reference's frame); right-hand side −bias + a·(Ḃ_b × Ḃ_a').
    let mut jacobian: Vec<Vec<f64>> = Vec::new();
    let mut rhs: Vec<f64> = Vec::new();
    for joint in joints {
        let (motor, reference_velocity) = match joint.reference {
            None => (motors[joint.body], A::screw(ScrewCoordinates::default())),
            Some(r) => {
                let motor = A::compose(A::reverse(motors[r]), motors[joint.body]);
                let frame = ScrewFrame::of::<A>(motor);
                (motor, A::screw(frame.to_body(&A::screw_coordinates(velocities[r]))))
            }
        };
        let frame = ScrewFrame::of::<A>(motor);
        let relative = velocities[joint.body] - reference_velocity;
        let kinematics = Kinematics::new(t, motor, relative);
        let correction = velocity(&A::screw_coordinates(A::commutator(
            velocities[joint.body],
            reference_velocity,
        )));
        let mut rows = RowBuffer::new();
        joint.constraint.rows(&kinematics, &mut rows).unwrap();
        for row in rows.rows() {
            let mut full = vec![0.0; 6 * n];
            full[6 * joint.body..6 * joint.body + 6].copy_from_slice(&row.jacobian);
            if let Some(r) = joint.reference {
                let moved = covector(&frame.to_world(&wrench(&row.jacobian)));
                for k in 0..6 {
                    full[6 * r + k] = -moved[k];
                }
            }
            let correction: f64 = row.jacobian.iter().zip(&correction).map(|(a, c)| a * c).sum();
            jacobian.push(full);
            rhs.push(-row.bias + correction);
        }
    }
    let j = DMatrix::from_fn(jacobian.len(), 6 * n, |r, c| jacobian[r][c]);
    let g = DMatrix::from_diagonal(&metric);
    let k = &j * &g * j.transpose();
    let right = DVector::from_vec(rhs) - &j * &g * &drive;
    let singular = k.clone().singular_values();
    let condition = singular.max() / singular.min();
    let lambda = k.lu().solve(&right).expect("a tree's joint-space matrix is regular");
    let reactions = j.transpose() * lambda;
    let reactions = (0..n).map(|i| std::array::from_fn(|k| reactions[6 * i + k])).collect();
    (reactions, condition)
}

fn sparse_matches_dense<A: Algebra>(seed: u64, n: usize) -> Result<(), TestCaseError> {
    let mut random = Random::new(seed);
    let (mechanism, bodies, joints) = random_tree::<A>(&mut random, n);
    let poses: Vec<_> = (0..n).map(|_| (random.vector(2.0), random.rotation())).collect();
    let motors: Vec<A::Motor> = poses
        .iter()
        .map(|(position, rotation)| motor::from_pose::<A>(*position, rotation))
        .collect();
    let states: Vec<State<A>> = bodies
        .iter()
        .zip(&poses)
        .map(|(body, (position, rotation))| {
            let (angular, linear) = (random.vector(3.0), random.vector(3.0));
            State::from_body_twist(body, *position, rotation, angular, linear)
        })
        .collect();
    let momenta: Vec<A::Screw> = states.iter().map(State::body_momentum).collect();
    let zero = A::screw(ScrewCoordinates::default());
    let mut rates = vec![
        BodyRates {
            body_velocity: zero,
            body_wrench: zero
        };
        n
    ];
    mechanism
        .body_rates(0.0, &motors, &momenta, &mut rates, &mut mechanism.workspace())
        .map_err(|e| TestCaseError::fail(e.to_string()))?;
    let (dense, condition) = dense_reactions(&bodies, &joints, &motors, &momenta);
    // Random geometry makes some systems ill-conditioned (condition numbers up to 4e9 seen), and two correct
    // solves then differ by their round-off times the condition number: each solve's forward error is about
    // κ(K)·ε (times a small growth factor of the elimination), so the two can differ by a few κ(K)·ε — 4κ(K)·ε
    // here, with a floor of 1e-13 for well-conditioned cases. (With 1·κ(K)·ε, a random 11-body tree with
    // κ = 1.05e4 differed by 2.5e-12 against a bound of 2.3e-12.)
    let tolerance = (4.0 * condition * f64::EPSILON).max(1e-13);
    for (i, (rate, expected)) in rates.iter().zip(&dense).enumerate() {
        // The body wrench is gravity (rotated into the body) plus the reaction.
        let frame = ScrewFrame::of::<A>(motors[i]);
        let gravity = frame
            .rotation
            .inverse_transform_vector(&(bodies[i].mass() * Vector3::new(0.0, 0.0, -9.81)));
        let mut reaction = A::screw_coordinates(rate.body_wrench);
        reaction.l -= gravity;
        let got = covector(&reaction);
        let scale = expected.iter().map(|x| x.abs()).fold(1.0, f64::max);
        for (g, e) in got.iter().zip(expected) {
            prop_assert!(
                (g - e).abs() < tolerance * scale,
                "body {i}: {got:?} vs {expected:?}, condition {condition:e}"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn pga_sparse_solve_equals_dense(seed in 1u64.., n in 1usize..12) {
        sparse_matches_dense::<Pga>(seed, n)?;
    }

    #[test]
    fn cga_sparse_solve_equals_dense(seed in 1u64.., n in 1usize..12) {
        sparse_matches_dense::<Cga>(seed, n)?;
    }
}
