//! The reference robots (`reference::robots`: the UR5 arm on a fixed base, the Solo-12 quadruped on a floating base)
//! built from their URDFs (`scenarios::build_robot`) against Pinocchio's reference and against the textbook
//! joint-space algorithms of `reference::joint_space`, in both algebras:
//!
//! * the joint accelerations at t = 0 (and Solo-12's base acceleration in its own axes) against Pinocchio's ABA;
//! * the passive motion over 1 s (RKMK8-body at dt = 5 ms) against Pinocchio's DOP853 run, every 0.01 s sample;
//! * the energy over that run, and at t = 0 against the reference's;
//! * the mass matrix and the bias forces at the start against the textbook CRBA and RNEA of the same model, built
//!   here from the imported model (`Robot::model`) independently of `Robot::build`.
//!
//! Each test prints its largest measured error (`cargo test --release -p scenarios --test integration robots:: -- --nocapture`).

use std::cell::RefCell;
use std::ops::ControlFlow;

use dynamics::simulate::Plan;
use dynamics::{simulate, Algebra, Integrator, JointMethod, Mechanism, Method, Schedule, State};
use nalgebra::{DMatrix, DVector, Quaternion, UnitQuaternion, Vector3};
use reference::joint_space::{Tree, TreeBody, TreeJoint};
use reference::robots::{RobotId, RobotReference};
use scenarios::{build_robot, RobotScene};
use urdf_import::{JointKind as UrdfJoint, RobotModel};

/// The number of velocity coordinates before the first joint's: a floating base's six.
fn base_velocities(reference: &RobotReference) -> usize {
    if reference.free_base {
        6
    } else {
        0
    }
}

/// The number of position coordinates before the first joint's: a floating base's seven.
fn base_positions(reference: &RobotReference) -> usize {
    if reference.free_base {
        7
    } else {
        0
    }
}

fn scene<A: Algebra>(id: RobotId) -> RobotScene<A> {
    let scene = build_robot::<A>(id).unwrap();
    // The coordinates are the joints in URDF file order, after the floating base's: the order the reference uses.
    let space = scene.robot.mechanism().joint_space().unwrap();
    let offset = base_velocities(&scene.reference);
    assert_eq!(space.velocity_count(), offset + scene.reference.joints.len());
    for (k, name) in scene.reference.joints.iter().enumerate() {
        let group = space.group(name).unwrap();
        assert_eq!(group.velocity_offset(), offset + k, "{name}");
        assert_eq!(group.position_offset(), base_positions(&scene.reference) + k, "{name}");
        // The parents: the UR5 is one chain from the world; each of Solo-12's legs a chain from the base (HAA).
        let expected = if name.ends_with("_HAA") {
            scene.robot.base()
        } else if k == 0 {
            None
        } else {
            Some(space.group(&scene.reference.joints[k - 1]).unwrap().body())
        };
        assert_eq!(group.parent(), expected, "{name}");
    }
    scene
}

/// `|ours − reference| / max(|reference|, 1)`, the largest over the pairs.
fn largest_relative(ours: &[f64], reference: &[f64]) -> f64 {
    assert_eq!(ours.len(), reference.len());
    ours.iter()
        .zip(reference)
        .map(|(a, b)| (a - b).abs() / b.abs().max(1.0))
        .fold(0.0, f64::max)
}

/// q̈ at t = 0 from the mechanism's own solve (the articulated recursion the integrators step) against
/// Pinocchio's ABA in the JSON, and for Solo-12 the base's `v̇` in its own axes (Pinocchio's free-flyer local
/// acceleration, linear then angular). Both are the same equations of motion evaluated in double precision, so
/// they agree to round-off amplified by the conditioning of the joint-space inertia (Solo-12's M has condition
/// number 1.4e4: its lower legs and feet weigh 38 g): 1e-10 relative to max(|ref|, 1) allows cond(M) · 30 ulps.
/// Measured, identical in PGA and CGA: UR5 2.0e-14; Solo-12 joints 7.4e-13 (HL_HAA), base 3.5e-15.
fn accelerations_at_the_start<A: Algebra>() {
    for id in RobotId::ALL {
        let scene = scene::<A>(id);
        let mechanism = scene.robot.mechanism();
        let q_ddot = mechanism.joint_accelerations(0.0, &scene.initial).unwrap();
        let offset = base_velocities(&scene.reference);
        let joints = largest_relative(&q_ddot[offset..], &scene.reference.accelerations);
        let base = scene
            .reference
            .base_acceleration
            .map_or(0.0, |b| largest_relative(&q_ddot[..6], &b.local));
        println!(
            "{} {}: q̈(0) joints {joints:.2e}, base v̇ {base:.2e} (relative to max(|ref|, 1))",
            A::NAME,
            id.name()
        );
        assert!(joints <= 1e-10, "{} {}: joints {joints:e}", A::NAME, id.name());
        assert!(base <= 1e-10, "{} {}: base {base:e}", A::NAME, id.name());
    }
}

/// What the run observes every 0.01 s: the joint positions and the energy.
struct Observed {
    q: Vec<f64>,
    energy: f64,
}

/// Runs the robot for 1 s with `integrator` at dt = 5e-3, and returns the joint positions (taken nearest the
/// previous sample's, so angles unwrap and the base quaternion stays continuous) and the energy every 0.01 s, the
/// start included.
fn observe<A: Algebra>(scene: &RobotScene<A>, integrator: impl Into<Integrator>) -> Vec<Observed> {
    let mechanism: &Mechanism<A> = scene.robot.mechanism();
    let start = mechanism.joint_positions(&scene.initial, None).unwrap();
    let samples = RefCell::new(vec![Observed {
        energy: mechanism.energy(&scene.initial).expect("one state per body"),
        q: start,
    }]);
    let schedule = Schedule::new(5e-3, 1.0).unwrap();
    let observer = |t: f64, states: &[State<A>]| {
        let k = (t / 0.01).round();
        if (t / 0.01 - k).abs() < 1e-6 {
            let mut samples = samples.borrow_mut();
            assert_eq!(samples.len() as f64, k, "a sample missed at t = {t}");
            let previous = samples.last().unwrap().q.clone();
            let q = mechanism.joint_positions(states, Some(&previous)).unwrap();
            samples.push(Observed {
                q,
                energy: mechanism.energy(states).expect("one state per body"),
            });
        }
        ControlFlow::Continue(())
    };
    let run = simulate(
        mechanism,
        &scene.initial,
        integrator,
        Plan::new(&schedule).observer(observer),
    )
    .unwrap();
    assert_eq!((run.statistics.accepted, run.stopped), (200, None));
    let samples = samples.into_inner();
    assert_eq!(samples.len(), scene.reference.samples.len());
    samples
}

/// The angle (rad) of the turn between two orientations, `q_ref⁻¹ q_ours`, whatever their quaternions' signs.
fn angle_between(reference: &UnitQuaternion<f64>, ours: &[f64]) -> f64 {
    let ours = UnitQuaternion::from_quaternion(Quaternion::new(ours[0], ours[1], ours[2], ours[3]));
    reference.rotation_to(&ours).angle()
}

/// The motion over 1 s against Pinocchio's (DOP853 at rtol 1e-13, itself accurate to 3e-14): every sample's joint
/// positions, and Solo-12's base origin and orientation. RKMK8 at 5 ms has a local error of order
/// (ω dt)⁹ ≈ 1e-16 at the joints' rates (~3 rad/s), so the run is limited by round-off: 1e-9 rad and 1e-9 m.
/// Measured, identical in PGA and CGA: UR5 joints 1.8e-13 rad; Solo-12 joints 3.6e-11 rad, base 3.4e-14 m and
/// 4.6e-13 rad. Solo-12's joint error is not truncation (2.0e-11, 3.6e-11, 4.3e-11, 5.1e-11 rad at dt = 10, 5,
/// 2.5, 1.25 ms) but round-off growing as the base falls away from the world origin (some 5 m in 1 s): the same run
/// started 10 m along x gives 4.4e-10 rad (maximal coordinates in world axes lose the legs' relative precision
/// with the distance; the reference's joint coordinates do not).
fn motion_over_one_second<A: Algebra>() {
    for id in RobotId::ALL {
        let scene = scene::<A>(id);
        let observed = observe(&scene, Method::Rkmk8Body);
        let offset = base_positions(&scene.reference);
        let (mut joints, mut origin, mut turn) = (0.0f64, 0.0f64, 0.0f64);
        for (ours, reference) in observed.iter().zip(&scene.reference.samples) {
            let error = ours.q[offset..]
                .iter()
                .zip(&reference.joints)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            joints = joints.max(error);
            if let Some((position, orientation)) = &reference.base {
                origin = origin.max((Vector3::new(ours.q[0], ours.q[1], ours.q[2]) - position).norm());
                turn = turn.max(angle_between(orientation, &ours.q[3..7]));
            }
        }
        println!(
            "{} {}: over 1 s, joints {joints:.2e} rad, base origin {origin:.2e} m, base orientation {turn:.2e} rad",
            A::NAME,
            id.name()
        );
        assert!(joints <= 1e-9, "{} {}: joints {joints:e} rad", A::NAME, id.name());
        assert!(origin <= 1e-9, "{} {}: base origin {origin:e} m", A::NAME, id.name());
        assert!(turn <= 1e-9, "{} {}: base orientation {turn:e} rad", A::NAME, id.name());
    }
}

/// Stepping in joint coordinates (RKMK8-joint at dt = 5e-3) keeps the joint positions themselves between steps, so
/// the run has no round-off growing with the base's fall: every sample within 1e-12 of the reference (rad, m), whose
/// own accuracy is 2e-14 (UR5) and 3.4e-14 (Solo-12), and the energy constant to 1e-12 J. Measured, identical in PGA
/// and CGA: UR5 joints 5.7e-14 rad; Solo-12 joints 7.0e-14 rad, base 4.3e-14 m and 6.3e-15 rad; energy within
/// 3.3e-13 J.
fn joint_coordinates_reach_the_references_round_off<A: Algebra>() {
    for id in RobotId::ALL {
        let scene = scene::<A>(id);
        let observed = observe(&scene, JointMethod::Rkmk8);
        let offset = base_positions(&scene.reference);
        let (mut joints, mut origin, mut turn, mut drift) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (ours, reference) in observed.iter().zip(&scene.reference.samples) {
            let error = ours.q[offset..]
                .iter()
                .zip(&reference.joints)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            joints = joints.max(error);
            drift = drift.max((ours.energy - observed[0].energy).abs());
            if let Some((position, orientation)) = &reference.base {
                origin = origin.max((Vector3::new(ours.q[0], ours.q[1], ours.q[2]) - position).norm());
                turn = turn.max(angle_between(orientation, &ours.q[3..7]));
            }
        }
        println!(
            "{} {} RKMK8-joint: joints {joints:.2e} rad, base {origin:.2e} m, {turn:.2e} rad, energy {drift:.2e} J",
            A::NAME,
            id.name()
        );
        assert!(joints <= 1e-12, "{} {}: joints {joints:e} rad", A::NAME, id.name());
        assert!(
            origin <= 1e-12 && turn <= 1e-12,
            "{} {}: base {origin:e} m, {turn:e} rad",
            A::NAME,
            id.name()
        );
        assert!(drift <= 1e-12, "{} {}: energy drift {drift:e} J", A::NAME, id.name());
    }
}

/// The energy (kinetic plus gravity's potential, zero at z = 0: the reference's definition) at t = 0 against the
/// reference's first sample, and its drift over the run of `motion_over_one_second`. The start is the same state
/// evaluated twice, so the energies agree to round-off of its terms (~1 J): 1e-12 J. The run conserves energy to
/// its truncation and round-off; the reference's own energy spans 9e-14 J (UR5) and 1e-12 J (Solo-12). The scale
/// is the reference's |E(0)| (1.35 J, 0.53 J), taken at least 1 J: drift ≤ 1e-10 J · max(|E_ref(0)|, 1 J).
/// Measured, identical in PGA and CGA: at t = 0, UR5 2.0e-14 J (the CSV prints 15 digits: −1.34884698878668),
/// Solo-12 4.4e-16 J; drift UR5 3.3e-12 J, Solo-12 3.8e-11 J. Solo-12's drift is the projection onto the joints
/// after each step (without it, 7e-14 J over the same run).
fn energy_is_the_reference_and_constant<A: Algebra>() {
    for id in RobotId::ALL {
        let scene = scene::<A>(id);
        let observed = observe(&scene, Method::Rkmk8Body);
        let reference_start = scene.reference.samples[0].energy;
        let start = (observed[0].energy - reference_start).abs();
        let drift = observed
            .iter()
            .map(|o| (o.energy - observed[0].energy).abs())
            .fold(0.0, f64::max);
        println!(
            "{} {}: energy {:.15} J, reference {reference_start:.15} J (difference {start:.2e} J), drift over 1 s \
             {drift:.2e} J",
            A::NAME,
            id.name(),
            observed[0].energy
        );
        assert!(start <= 1e-12, "{} {}: start {start:e} J", A::NAME, id.name());
        let scale = reference_start.abs().max(1.0);
        assert!(drift <= 1e-10 * scale, "{} {}: drift {drift:e} J", A::NAME, id.name());
    }
}

/// The imported model as a textbook tree (RBDA's body frame = the joint frame = the child's reference link, as
/// URDF has it): one body per moving joint, the root a free joint with the identity placement when it floats (its
/// coordinates are then the root link frame's pose and twist in its own axes, as the mechanism's free root), else
/// the world. The centres and inertias are the merged bodies' own, in their reference-link frames. Returns the
/// tree and, per tree velocity, the mechanism's velocity index (and the same for positions).
fn textbook_tree(model: &RobotModel, free: bool, gravity: Vector3<f64>) -> (Tree, Vec<usize>, Vec<usize>) {
    let root = usize::from(!free); // model bodies below this are the world
    let index = |body: usize| body.checked_sub(root);
    let mut bodies = Vec::new();
    let (mut velocities, mut positions) = (Vec::new(), Vec::new());
    let joints_start = if free { 6 } else { 0 };
    let positions_start = if free { 7 } else { 0 };
    for (b, rigid) in model.bodies.iter().enumerate().skip(root) {
        let tree_body = |parent, placement, joint| TreeBody {
            parent,
            placement,
            joint,
            mass: rigid.mass,
            centre_of_mass: rigid.centre_of_mass,
            inertia: rigid.inertia,
        };
        if b == 0 {
            bodies.push(tree_body(None, nalgebra::Isometry3::identity(), TreeJoint::Free));
            velocities.extend(0..6);
            positions.extend(0..7);
            continue;
        }
        let (j, joint) = model
            .joints
            .iter()
            .enumerate()
            .find(|(_, joint)| joint.child == b)
            .expect("every body but the root has its joint");
        let kind = match joint.kind {
            UrdfJoint::Revolute | UrdfJoint::Continuous => TreeJoint::Revolute(joint.axis),
            UrdfJoint::Prismatic => TreeJoint::Prismatic(joint.axis),
            other => panic!("{}: no textbook joint for {other}", joint.name),
        };
        assert!(index(joint.parent).is_none_or(|p| p < bodies.len()));
        bodies.push(tree_body(index(joint.parent), joint.origin, kind));
        velocities.push(joints_start + j);
        positions.push(positions_start + j);
    }
    (Tree { bodies, gravity }, velocities, positions)
}

/// The largest entry of `ours − reference` relative to the largest entry of `reference`.
fn relative_matrix_error(ours: &DMatrix<f64>, reference: &DMatrix<f64>) -> f64 {
    (ours - reference).amax() / reference.amax()
}

/// M(q) and h(q, v) at the start against the textbook CRBA and RNEA (RBDA §6.2, §5.3, in Plücker coordinates in
/// each body's joint frame) of the tree read from the imported model — independent of `Robot::build`'s choice of
/// body frames (principal axes) and of the mechanism's world-axes recursions. The tree is checked first against
/// Pinocchio: its forward dynamics at the same start must give the JSON's q̈ (1e-10 relative), or
/// the comparison below would test the tree's construction instead (measured UR5 7.6e-15, Solo-12 4.9e-14). Two
/// recursions on the same data in double precision agree to round-off: M to 1e-12 of its largest entry, h to
/// 1e-11 of its largest. Measured, identical in PGA and CGA: M UR5 8.7e-16, Solo-12 2.2e-17; h UR5 3.8e-16,
/// Solo-12 5.5e-17.
fn mass_matrix_and_bias_are_the_textbook_ones<A: Algebra>() {
    for id in RobotId::ALL {
        let scene = scene::<A>(id);
        let mechanism = scene.robot.mechanism();
        let (tree, velocity_index, position_index) =
            textbook_tree(scene.robot.model(), scene.reference.free_base, scene.reference.gravity);
        let q = mechanism.joint_positions(&scene.initial, None).unwrap();
        let v = mechanism.joint_velocities(&scene.initial).unwrap();
        let tree_q = DVector::from_iterator(tree.nq(), position_index.iter().map(|&i| q[i]));
        let tree_v = DVector::from_iterator(tree.nv(), velocity_index.iter().map(|&i| v[i]));
        let n = tree.nv();
        assert_eq!(n, v.len());

        // The tree's forward dynamics is Pinocchio's.
        let tree_q_ddot = tree.forward_dynamics(&tree_q, &tree_v, &DVector::zeros(n)).unwrap();
        let mut q_ddot = vec![0.0; n];
        for (k, &i) in velocity_index.iter().enumerate() {
            q_ddot[i] = tree_q_ddot[k];
        }
        let offset = base_velocities(&scene.reference);
        let mut pinocchio = scene
            .reference
            .base_acceleration
            .map_or_else(Vec::new, |b| b.local.to_vec());
        pinocchio.extend(&scene.reference.accelerations);
        let tree_vs_pinocchio = largest_relative(&q_ddot, &pinocchio);
        assert!(
            tree_vs_pinocchio <= 1e-10,
            "{}: the textbook tree's q̈ is {tree_vs_pinocchio:e} from Pinocchio's: the tree is built wrong",
            id.name()
        );
        assert_eq!(offset + scene.reference.accelerations.len(), n);

        let permute = |x: &DVector<f64>| {
            let mut out = DVector::zeros(n);
            for (k, &i) in velocity_index.iter().enumerate() {
                out[i] = x[k];
            }
            out
        };
        let tree_mass = tree.mass_matrix(&tree_q).unwrap();
        let mut reference_mass = DMatrix::zeros(n, n);
        for (r, &i) in velocity_index.iter().enumerate() {
            for (c, &j) in velocity_index.iter().enumerate() {
                reference_mass[(i, j)] = tree_mass[(r, c)];
            }
        }
        let reference_bias = permute(&tree.bias(&tree_q, &tree_v).unwrap());
        let mass = mechanism.mass_matrix(&scene.initial).unwrap();
        let bias = mechanism.bias_forces(0.0, &scene.initial).unwrap();
        let mass_error = relative_matrix_error(&mass, &reference_mass);
        let bias_error = (&bias - &reference_bias).amax() / reference_bias.amax();
        println!(
            "{} {}: textbook q̈ vs Pinocchio {tree_vs_pinocchio:.2e}; M {mass_error:.2e}, h {bias_error:.2e} \
             (relative to the largest entry)",
            A::NAME,
            id.name()
        );
        assert!(mass_error <= 1e-12, "{} {}: M {mass_error:e}", A::NAME, id.name());
        assert!(bias_error <= 1e-11, "{} {}: h {bias_error:e}", A::NAME, id.name());
    }
}

for_both_algebras!(
    accelerations_at_the_start,
    motion_over_one_second,
    joint_coordinates_reach_the_references_round_off,
    energy_is_the_reference_and_constant,
    mass_matrix_and_bias_are_the_textbook_ones
);
