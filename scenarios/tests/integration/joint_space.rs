//! The joint-space API of `dynamics::Mechanism` (`states_from_joints`, `joint_positions`, `joint_velocities`,
//! `mass_matrix`, `bias_forces`, `joint_accelerations`, `inverse_dynamics`) on random kinematic trees, against the
//! textbook CRBA and RNEA of `reference::joint_space` (RBDA, in Plücker coordinates in each body's joint frame), and
//! the articulated solve against the project's independent constraint-space solve of the same joints' rows.
//!
//! The trees (a seeded generator, [`random_tree`]): 1–8 bodies, each joined to a random earlier body or the world
//! by a revolute or prismatic joint about a random non-unit axis, a weld or (rarely) a free joint, with joint
//! frames of random position and rotation on both sides; a third of the trees float on a free root. The bodies have
//! full random inertia tensors (positive definite, physical), given about their centre, their frame's origin or a
//! random point, with centres of mass off their frame's origin, and are added with `add_body_with_frame`, so the
//! body's reference frame (the one its joints and coordinates are given in) differs from its principal frame (the
//! one the dynamics integrates). The joints are connected in a random order, not parents first. Gravity is
//! `Force::gravity()` on every body.
//!
//! Every test runs [`TREES`] trees in both algebras and prints its worst error and the seed that gave it
//! (`cargo test --release -p scenarios --test integration joint_space:: -- --nocapture`).

use crate::common;

use common::Random;
use dynamics::{Algebra, Body, BodyId, Force, JointKind, JointModel, Mechanism, PrincipalFrame, Reference, State};
use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Point3, Translation3, Unit, Vector3};
use reference::joint_space::{Tree, TreeBody, TreeJoint};

/// Random trees per test and algebra.
const TREES: u64 = 500;

/// A joint of the random tree (axes in the joint frame, not unit).
#[derive(Clone, Copy, Debug)]
enum Kind {
    Revolute(Vector3<f64>),
    Prismatic(Vector3<f64>),
    Weld,
    Free,
}

/// One body of a random tree and the joint to its parent, in the body's reference frame.
#[derive(Clone, Debug)]
struct RandomBody {
    /// The parent body (an earlier one), or the world.
    parent: Option<usize>,
    /// The joint; `None` for a free root (a body no joint model holds).
    kind: Option<Kind>,
    /// The joint frame in the parent's reference frame (or the world).
    parent_side: Isometry3<f64>,
    /// The joint frame in this body's reference frame.
    child_side: Isometry3<f64>,
    mass: f64,
    /// The centre of mass in the reference frame.
    centre: Vector3<f64>,
    /// The inertia tensor about the centre of mass, reference axes.
    inertia: Matrix3<f64>,
    /// The point the tensor is given about to `Body::from_inertia_tensor`.
    about: Vector3<f64>,
}

#[derive(Clone, Debug)]
struct RandomTree {
    bodies: Vec<RandomBody>,
    /// The bodies with a joint, in the order their joints are connected.
    connect_order: Vec<usize>,
}

/// A number uniform in [lo, hi).
fn uniform(random: &mut Random, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * 0.5 * (random.next() + 1.0)
}

/// An index uniform in 0..n.
fn index(random: &mut Random, n: usize) -> usize {
    ((uniform(random, 0.0, n as f64)) as usize).min(n - 1)
}

/// A direction of length 0.2–3.5, not unit.
fn axis(random: &mut Random) -> Vector3<f64> {
    loop {
        let v = random.vector(2.0);
        if v.norm() > 0.2 {
            return v;
        }
    }
}

fn frame(random: &mut Random) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(random.vector(0.4)), random.rotation())
}

/// A well-mixed xorshift seed from a small one (splitmix64): xorshift's first numbers from seeds 1, 2, … are tiny.
fn scrambled(seed: u64) -> u64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The tree of `seed` (see the module docs).
fn random_tree(seed: u64) -> RandomTree {
    let mut random = Random::new(scrambled(seed));
    let count = 1 + index(&mut random, 8);
    let free_root = uniform(&mut random, 0.0, 1.0) < 1.0 / 3.0;
    let mut bodies = Vec::with_capacity(count);
    for i in 0..count {
        let root = i == 0 && free_root;
        let parent = if root {
            None
        } else {
            let k = index(&mut random, i + 1);
            (k < i).then_some(k)
        };
        let kind = (!root).then(|| {
            let u = uniform(&mut random, 0.0, 1.0);
            if u < 0.45 {
                Kind::Revolute(axis(&mut random))
            } else if u < 0.8 {
                Kind::Prismatic(axis(&mut random))
            } else if u < 0.93 {
                Kind::Weld
            } else {
                Kind::Free
            }
        });
        // A free root's coordinates are its reference frame's pose: its joint frame is that frame.
        let (parent_side, child_side) = if root {
            (Isometry3::identity(), Isometry3::identity())
        } else {
            (frame(&mut random), frame(&mut random))
        };
        // Second moments of a mass distribution along its principal axes make physical moments.
        let second: Vec<f64> = (0..3).map(|_| uniform(&mut random, 0.002, 0.05)).collect();
        let mass = uniform(&mut random, 0.5, 2.0);
        let moments = Vector3::new(second[1] + second[2], second[0] + second[2], second[0] + second[1]) * mass;
        let axes = random.rotation().to_rotation_matrix().into_inner();
        let inertia = axes * Matrix3::from_diagonal(&moments) * axes.transpose();
        let centre = random.vector(0.3);
        let about = match index(&mut random, 3) {
            0 => centre,
            1 => Vector3::zeros(),
            _ => random.vector(0.3),
        };
        bodies.push(RandomBody {
            parent,
            kind,
            parent_side,
            child_side,
            mass,
            centre,
            inertia,
            about,
        });
    }
    // A random order of the joints (Fisher–Yates).
    let mut connect_order: Vec<usize> = (0..count).filter(|&i| bodies[i].kind.is_some()).collect();
    for k in (1..connect_order.len()).rev() {
        let j = index(&mut random, k + 1);
        connect_order.swap(k, j);
    }
    RandomTree { bodies, connect_order }
}

impl Kind {
    fn joint_kind(self) -> JointKind {
        match self {
            Kind::Revolute(axis) => JointKind::Revolute { axis },
            Kind::Prismatic(axis) => JointKind::Prismatic { axis },
            Kind::Weld => JointKind::Weld,
            Kind::Free => JointKind::Free,
        }
    }
}

impl RandomBody {
    fn tree_joint(&self) -> TreeJoint {
        match self.kind {
            None | Some(Kind::Free) => TreeJoint::Free,
            Some(Kind::Revolute(axis)) => TreeJoint::Revolute(Unit::new_normalize(axis)),
            Some(Kind::Prismatic(axis)) => TreeJoint::Prismatic(Unit::new_normalize(axis)),
            Some(Kind::Weld) => TreeJoint::Fixed,
        }
    }
}

/// The mechanism of a random tree, and each body's joint model (`None` for a free root). With `rows`, every joint
/// is added by its virtual-power rows (`Mechanism::add_joint`, the general constraint-space solve) instead of
/// `connect` (the articulated solve); free joints, which have no rows, are then left out.
fn mechanism<A: Algebra>(tree: &RandomTree, rows: bool) -> (Mechanism<A>, Vec<Option<JointModel>>) {
    let mut mechanism = Mechanism::<A>::new();
    let mut ids: Vec<BodyId> = Vec::new();
    let mut principal = Vec::new();
    for (i, b) in tree.bodies.iter().enumerate() {
        let (body, frame) = b.body();
        principal.push(Isometry3::from_parts(frame.centre_of_mass.into(), frame.rotation));
        let id = mechanism.add_body_with_frame(format!("b{i}"), body, frame).unwrap();
        mechanism.add_force(id, Force::gravity()).unwrap();
        ids.push(id);
    }
    // The joint frames in the bodies' principal frames, where `JointModel` takes them.
    let models: Vec<Option<JointModel>> = tree
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            b.kind.map(|kind| {
                let parent_frame = b
                    .parent
                    .map_or(b.parent_side, |p| principal[p].inverse() * b.parent_side);
                let child_frame = principal[i].inverse() * b.child_side;
                JointModel::new(format!("j{i}"), kind.joint_kind(), parent_frame, child_frame).unwrap()
            })
        })
        .collect();
    for &i in &tree.connect_order {
        let parent = tree.bodies[i]
            .parent
            .map_or(Reference::World, |p| Reference::Body(ids[p]));
        let model = models[i].clone().unwrap();
        if rows {
            if let Some(constraint) = model.virtual_power::<A>().unwrap() {
                mechanism.add_joint(ids[i], parent, constraint).unwrap();
            }
        } else {
            mechanism.connect(ids[i], parent, model).unwrap();
        }
    }
    (mechanism, models)
}

impl RandomBody {
    /// The body and its principal frame in the reference frame, from the tensor given about `about`.
    fn body(&self) -> (Body, PrincipalFrame) {
        let d = self.centre - self.about;
        let tensor = self.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * self.mass;
        Body::from_inertia_tensor(self.mass, tensor, self.about, self.centre).unwrap()
    }

    /// The inertia about the centre of mass in the reference axes as the body holds it: its principal moments along
    /// its principal axes. It is the generated tensor only up to `Body::from_inertia_tensor`'s eigendecomposition,
    /// which is off by up to 5e-9 of it for some tensors (`from_inertia_tensor_keeps_the_tensor`); the textbook is
    /// given the body's own, so that the tests below test the joint-space algorithms and not that.
    fn held_inertia(&self) -> (Vector3<f64>, Matrix3<f64>) {
        let (body, frame) = self.body();
        let axes = frame.rotation.to_rotation_matrix().into_inner();
        (
            frame.centre_of_mass,
            axes * Matrix3::from_diagonal(&body.moments()) * axes.transpose(),
        )
    }
}

/// The textbook tree of a random tree: RBDA's body frame is the joint frame (the child side), its placement the
/// joint frame in the parent's joint frame, and the centre and inertia are moved into the joint frame.
fn textbook(tree: &RandomTree) -> Tree {
    let bodies = tree
        .bodies
        .iter()
        .map(|b| {
            let placement = b
                .parent
                .map_or(b.parent_side, |p| tree.bodies[p].child_side.inverse() * b.parent_side);
            let rotation = b.child_side.rotation.to_rotation_matrix().into_inner();
            let (centre, inertia) = b.held_inertia();
            TreeBody {
                parent: b.parent,
                placement,
                joint: b.tree_joint(),
                mass: b.mass,
                centre_of_mass: b.child_side.inverse_transform_point(&Point3::from(centre)).coords,
                inertia: rotation.transpose() * inertia * rotation,
            }
        })
        .collect();
    Tree {
        bodies,
        gravity: Vector3::new(0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY),
    }
}

/// Per textbook position and velocity coordinate (body order), the mechanism's index: the documented layout, free
/// roots first (body order), then the joints in the order connected. Checked against the mechanism's own groups.
fn layout<A: Algebra>(tree: &RandomTree, mechanism: &Mechanism<A>) -> (Vec<usize>, Vec<usize>) {
    let order: Vec<usize> = (0..tree.bodies.len())
        .filter(|&i| tree.bodies[i].kind.is_none())
        .chain(tree.connect_order.iter().copied())
        .collect();
    let (mut position_start, mut velocity_start) = (vec![0; tree.bodies.len()], vec![0; tree.bodies.len()]);
    let (mut p, mut v) = (0, 0);
    for &i in &order {
        position_start[i] = p;
        velocity_start[i] = v;
        let joint = tree.bodies[i].tree_joint();
        p += joint.nq();
        v += joint.nv();
    }
    let space = mechanism.joint_space().unwrap();
    assert_eq!((space.position_count(), space.velocity_count()), (p, v));
    for (i, b) in tree.bodies.iter().enumerate() {
        let name = if b.kind.is_some() {
            format!("j{i}")
        } else {
            format!("b{i}")
        };
        let group = space.group(&name).unwrap();
        assert_eq!(
            (group.position_offset(), group.velocity_offset()),
            (position_start[i], velocity_start[i]),
            "{name}"
        );
    }
    let (mut positions, mut velocities) = (Vec::new(), Vec::new());
    for (i, b) in tree.bodies.iter().enumerate() {
        let joint = b.tree_joint();
        positions.extend(position_start[i]..position_start[i] + joint.nq());
        velocities.extend(velocity_start[i]..velocity_start[i] + joint.nv());
    }
    (positions, velocities)
}

/// One random tree in both forms at random joint positions and velocities.
struct Case<A: Algebra> {
    tree: Tree,
    mechanism: Mechanism<A>,
    /// Per textbook velocity coordinate, the mechanism's.
    velocities: Vec<usize>,
    /// Textbook order.
    q: DVector<f64>,
    v: DVector<f64>,
    /// The mechanism's order.
    our_q: Vec<f64>,
    our_v: Vec<f64>,
    states: Vec<State<A>>,
    random: Random,
    random_tree: RandomTree,
}

impl<A: Algebra> Case<A> {
    fn new(seed: u64) -> Self {
        let random_tree = random_tree(seed);
        let (mechanism, _) = mechanism::<A>(&random_tree, false);
        let tree = textbook(&random_tree);
        let (positions, velocities) = layout(&random_tree, &mechanism);
        let mut random = Random::new(scrambled(seed.wrapping_add(1 << 40)));
        let (mut q, mut v) = (Vec::new(), Vec::new());
        for b in &tree.bodies {
            match b.joint {
                // Angles within (−π, π), where `joint_positions` reads them without a previous reading.
                TreeJoint::Revolute(_) => q.push(3.1 * random.next()),
                TreeJoint::Prismatic(_) => q.push(random.next()),
                TreeJoint::Fixed => {}
                TreeJoint::Free => {
                    q.extend(random.vector(1.0).iter());
                    // w ≥ 0, the sign `joint_positions` reads without a previous reading.
                    let r = random.rotation().into_inner();
                    let r = if r.w < 0.0 { -r } else { r };
                    q.extend([r.w, r.i, r.j, r.k]);
                }
            }
            v.extend((0..b.joint.nv()).map(|_| 2.0 * random.next()));
        }
        let (q, v) = (DVector::from_vec(q), DVector::from_vec(v));
        let mut our_q = vec![0.0; q.len()];
        let mut our_v = vec![0.0; v.len()];
        positions.iter().zip(q.iter()).for_each(|(&i, x)| our_q[i] = *x);
        velocities.iter().zip(v.iter()).for_each(|(&i, x)| our_v[i] = *x);
        let states = mechanism.states_from_joints(&our_q, &our_v).unwrap();
        Case {
            tree,
            mechanism,
            velocities,
            q,
            v,
            our_q,
            our_v,
            states,
            random,
            random_tree,
        }
    }

    fn nv(&self) -> usize {
        self.v.len()
    }

    /// A textbook-ordered velocity-space vector in the mechanism's order.
    fn ours(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut out = DVector::zeros(x.len());
        self.velocities
            .iter()
            .zip(x.iter())
            .for_each(|(&i, value)| out[i] = *value);
        out
    }

    /// The textbook M and h, in the mechanism's order.
    fn textbook_mass_and_bias(&self) -> (DMatrix<f64>, DVector<f64>) {
        let mass = self.tree.mass_matrix(&self.q).unwrap();
        let n = self.nv();
        let mut ours = DMatrix::zeros(n, n);
        for (r, &i) in self.velocities.iter().enumerate() {
            for (c, &j) in self.velocities.iter().enumerate() {
                ours[(i, j)] = mass[(r, c)];
            }
        }
        (ours, self.ours(&self.tree.bias(&self.q, &self.v).unwrap()))
    }
}

/// The worst of a measure over the trees, and the seed it came from.
#[derive(Default)]
struct Worst {
    value: f64,
    seed: u64,
}

impl Worst {
    fn update(&mut self, value: f64, seed: u64) {
        if value > self.value || value.is_nan() {
            *self = Worst { value, seed };
        }
    }
}

impl std::fmt::Display for Worst {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:.2e} (seed {})", self.value, self.seed)
    }
}

fn largest(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// `states_from_joints` then `joint_positions` (without a previous reading) and `joint_velocities` give back q and v:
/// the forward kinematics through the bodies' principal frames and the reading back through the joints' relative
/// poses are each exact to round-off of coordinates of size ≤ 3 (angles within ±3.1 rad, slides and free positions
/// ≤ 1 m, rates ≤ 2; the bodies' velocities, up to tens of m/s at the end of a chain, are differenced at the joint
/// origins), across up to 8 frames: 1e-12 absolute. Measured, identical in PGA and CGA: positions 4.3e-15,
/// velocities 9.4e-14.
fn joint_coordinates_round_trip<A: Algebra>() {
    let (mut positions, mut velocities) = (Worst::default(), Worst::default());
    for seed in 1..=TREES {
        let case = Case::<A>::new(seed);
        let q = case.mechanism.joint_positions(&case.states, None).unwrap();
        let v = case.mechanism.joint_velocities(&case.states).unwrap();
        let (dq, dv) = (largest_difference(&q, &case.our_q), largest_difference(&v, &case.our_v));
        assert!(dq <= 1e-12, "seed {seed}: q {q:?} from {:?}", case.our_q);
        assert!(dv <= 1e-12, "seed {seed}: v {v:?} from {:?}", case.our_v);
        positions.update(dq, seed);
        velocities.update(dv, seed);
    }
    println!("{}: round trip of q {positions}, of v {velocities}", A::NAME);
}

/// `mass_matrix` against the textbook CRBA, and `bias_forces` (gravity and velocity products) against the textbook
/// RNEA with q̈ = 0, relative to their largest entries. The same quantities by two recursions in different frames
/// (world axes about one point, against each joint frame) agree to round-off: M to 1e-11, h to 1e-10 relative.
/// Measured, identical in PGA and CGA: M 4.3e-15, h 3.8e-14 (cond(M) up to 2.7e3).
fn mass_matrix_and_bias_forces_are_the_textbook_ones<A: Algebra>() {
    let (mut mass_error, mut bias_error) = (Worst::default(), Worst::default());
    for seed in 1..=TREES {
        let case = Case::<A>::new(seed);
        if case.nv() == 0 {
            continue;
        }
        let (reference_mass, reference_bias) = case.textbook_mass_and_bias();
        let mass = case.mechanism.mass_matrix(&case.states).unwrap();
        let bias = case.mechanism.bias_forces(0.0, &case.states).unwrap();
        let m = (&mass - &reference_mass).amax() / reference_mass.amax();
        let h = (&bias - &reference_bias).amax() / reference_bias.amax();
        assert!(
            m <= 1e-11,
            "seed {seed}: M relative error {m:e}\n{mass}{reference_mass}"
        );
        assert!(
            h <= 1e-10,
            "seed {seed}: h relative error {h:e}\n{bias}{reference_bias}"
        );
        mass_error.update(m, seed);
        bias_error.update(h, seed);
    }
    println!(
        "{}: M {mass_error}, h {bias_error} (relative to the largest entry)",
        A::NAME
    );
}

/// `joint_accelerations` (the mechanism's articulated solve of its maximal coordinates, read in joint coordinates)
/// without joint torques satisfies the textbook M q̈ + h = 0, to 1e-10 of the largest entry of h (the residual of an
/// exact solution is the round-off of M q̈ and h); and equals the textbook forward dynamics (Cholesky of M), to 1e-10
/// of the largest |q̈| — two backward-stable solves differ by up to cond(M) ε |q̈|, and the trees' cond(M) reaches
/// 2.7e3. Measured, identical in PGA and CGA: residual 9.3e-14 of |h|; against the textbook solve 1.3e-13 of |q̈|.
fn joint_accelerations_are_the_textbook_forward_dynamics<A: Algebra>() {
    let (mut residual_error, mut solve_error, mut condition) = (Worst::default(), Worst::default(), Worst::default());
    for seed in 1..=TREES {
        let case = Case::<A>::new(seed);
        if case.nv() == 0 {
            continue;
        }
        let (mass, bias) = case.textbook_mass_and_bias();
        let q_ddot = DVector::from_vec(case.mechanism.joint_accelerations(0.0, &case.states).unwrap());
        let residual = (&mass * &q_ddot + &bias).amax() / bias.amax();
        assert!(residual <= 1e-10, "seed {seed}: M q̈ + h is {residual:e} of h");
        residual_error.update(residual, seed);
        let reference = case.ours(
            &case
                .tree
                .forward_dynamics(&case.q, &case.v, &DVector::zeros(case.nv()))
                .unwrap(),
        );
        let eigenvalues = mass.symmetric_eigenvalues();
        let cond = eigenvalues.max() / eigenvalues.min();
        condition.update(cond, seed);
        let error = (&q_ddot - &reference).amax() / reference.amax();
        assert!(
            error <= 1e-10,
            "seed {seed}: q̈ {error:e} from the textbook's (cond(M) = {cond:e})"
        );
        solve_error.update(error, seed);
    }
    println!(
        "{}: M q̈ + h {residual_error} of |h|; q̈ against the textbook {solve_error} of |q̈|; cond(M) up to {condition}",
        A::NAME
    );
}

/// `inverse_dynamics` at the forward dynamics' q̈ needs no joint torques: |τ| ≤ 1e-10 of the largest entry of h
/// (τ = M q̈ + h evaluated by the RNEA, zero to its round-off). At a random q̈ (entries in ±5), it equals the textbook
/// M q̈ + h to 1e-11 of the larger of |M q̈| and |h|; and solving the mechanism's own M q̈' = τ − h gives back q̈
/// to 1e-12 of |q̈| (a backward-stable solve loses up to cond(M) ε, cond(M) ≤ 2.7e3 here). Measured, identical in
/// PGA and CGA: τ at the forward q̈ 8.5e-14 of |h|; against the textbook 1.7e-14; q̈' 1.4e-13 of |q̈|.
fn inverse_dynamics_inverts_the_forward_dynamics<A: Algebra>() {
    let (mut at_rest, mut against_textbook, mut round_trip) = (Worst::default(), Worst::default(), Worst::default());
    for seed in 1..=TREES {
        let mut case = Case::<A>::new(seed);
        if case.nv() == 0 {
            continue;
        }
        let (reference_mass, reference_bias) = case.textbook_mass_and_bias();
        let mechanism = &case.mechanism;
        let forward = mechanism.joint_accelerations(0.0, &case.states).unwrap();
        let tau = mechanism.inverse_dynamics(0.0, &case.states, &forward).unwrap();
        let zero = tau.amax() / reference_bias.amax();
        assert!(zero <= 1e-10, "seed {seed}: τ at the forward q̈ is {zero:e} of h: {tau}");
        at_rest.update(zero, seed);

        let q_ddot = DVector::from_iterator(case.nv(), (0..case.nv()).map(|_| 5.0 * case.random.next()));
        let tau = mechanism
            .inverse_dynamics(0.0, &case.states, q_ddot.as_slice())
            .unwrap();
        let expected = &reference_mass * &q_ddot + &reference_bias;
        let scale = (&reference_mass * &q_ddot).amax().max(reference_bias.amax());
        let textbook = (&tau - &expected).amax() / scale;
        assert!(textbook <= 1e-11, "seed {seed}: τ {textbook:e} from the textbook's");
        against_textbook.update(textbook, seed);

        let mass = mechanism.mass_matrix(&case.states).unwrap();
        let bias = mechanism.bias_forces(0.0, &case.states).unwrap();
        let eigenvalues = mass.symmetric_eigenvalues();
        let cond = eigenvalues.max() / eigenvalues.min();
        let back = mass.cholesky().unwrap().solve(&(tau - bias));
        let error = (&back - &q_ddot).amax() / q_ddot.amax();
        assert!(error <= 1e-12, "seed {seed}: q̈' {error:e} from q̈ (cond(M) = {cond:e})");
        round_trip.update(error, seed);
    }
    println!(
        "{}: τ(forward q̈) {at_rest} of |h|; τ(random q̈) against the textbook {against_textbook}; q̈ back {round_trip}",
        A::NAME
    );
}

/// The articulated solve (joints added by `connect`) against the general constraint-space solve of the same
/// joints' virtual-power rows (`JointModel::virtual_power`, added by `add_joint`; free joints have no rows and are
/// left out): the same momentum rate dΩ/dt of every body at the same states, and the same body velocities. Two
/// solves of one well-posed problem (the rows have full rank: no loops) by different algebra, to 1e-10 of the
/// largest momentum-rate coordinate, or of the bodies' weight if larger (a body welded to the world has none).
/// Measured, identical in PGA and CGA: 1.7e-14.
fn articulated_solve_is_the_constraint_solve<A: Algebra>() {
    let mut worst = Worst::default();
    for seed in 1..=TREES {
        let case = Case::<A>::new(seed);
        let (by_rows, _) = mechanism::<A>(&case.random_tree, true);
        let articulated = case.mechanism.rates_at(0.0, &case.states).unwrap();
        let general = by_rows.rates_at(0.0, &case.states).unwrap();
        let coordinates = |rates: &[dynamics::Rates<A>]| -> Vec<f64> {
            rates
                .iter()
                .flat_map(|r| {
                    let c = A::screw_coordinates(r.momentum_rate);
                    [c.l.x, c.l.y, c.l.z, c.t.x, c.t.y, c.t.z]
                })
                .collect()
        };
        let (a, g) = (coordinates(&articulated), coordinates(&general));
        // A body welded to the world has no momentum rate: the scale is at least the bodies' weight.
        let weight: f64 = case.random_tree.bodies.iter().map(|b| b.mass).sum::<f64>() * 9.81;
        let error = largest_difference(&a, &g) / largest(&g).max(weight);
        assert!(error <= 1e-10, "seed {seed}: dΩ/dt {error:e} apart\n{a:?}\n{g:?}");
        for (x, y) in articulated.iter().zip(&general) {
            assert_eq!(x.body_velocity, y.body_velocity, "seed {seed}");
        }
        worst.update(error, seed);
    }
    println!("{}: articulated against constraint-space dΩ/dt {worst}", A::NAME);
}

for_both_algebras!(
    joint_coordinates_round_trip,
    mass_matrix_and_bias_forces_are_the_textbook_ones,
    joint_accelerations_are_the_textbook_forward_dynamics,
    inverse_dynamics_inverts_the_forward_dynamics,
    articulated_solve_is_the_constraint_solve
);

/// The random trees cover what the module docs claim: every kind of joint, free roots, joints to the world and to
/// bodies, out-of-order connections, and between 1 and 8 bodies.
#[test]
fn the_random_trees_cover_the_cases() {
    let (mut kinds, mut roots, mut to_world, mut to_body, mut out_of_order) = ([0; 4], 0, 0, 0, 0);
    let mut sizes = [0; 9];
    for seed in 1..=TREES {
        let tree = random_tree(seed);
        sizes[tree.bodies.len()] += 1;
        for b in &tree.bodies {
            match b.kind {
                None => roots += 1,
                Some(kind) => {
                    kinds[match kind {
                        Kind::Revolute(_) => 0,
                        Kind::Prismatic(_) => 1,
                        Kind::Weld => 2,
                        Kind::Free => 3,
                    }] += 1;
                    if b.parent.is_some() {
                        to_body += 1;
                    } else {
                        to_world += 1;
                    }
                }
            }
        }
        let position: Vec<usize> = (0..tree.bodies.len())
            .map(|i| tree.connect_order.iter().position(|&j| j == i).unwrap_or(0))
            .collect();
        if tree.bodies.iter().enumerate().any(|(i, b)| {
            b.parent
                .is_some_and(|p| tree.bodies[p].kind.is_some() && position[p] > position[i])
        }) {
            out_of_order += 1;
        }
    }
    println!(
        "kinds (revolute, prismatic, weld, free) {kinds:?}, free roots {roots}, to the world {to_world}, to a body \
         {to_body}, trees connected children first {out_of_order}, sizes {sizes:?}"
    );
    assert!(kinds.iter().all(|&k| k >= 20), "{kinds:?}");
    assert!(roots >= 100 && to_world >= 100 && to_body >= 500 && out_of_order >= 50);
    assert!(sizes[1..].iter().all(|&s| s >= 20), "{sizes:?}");
}

/// `Body::from_inertia_tensor` keeps the tensor it is given: its principal moments along its principal axes,
/// `R diag(I₁, I₂, I₃) Rᵀ`, give back the tensor about the centre of mass to round-off (1e-14 of its largest entry,
/// ~50 ulps). This tensor (moments 0.0578974, 0.0898101, 0.0899114 kg m², two of them 1.1e-3 apart relative; from
/// the random tree of seed 262 of the tests above) is one where nalgebra's `SymmetricEigen` returns eigenvectors
/// whose V D Vᵀ is 4.8e-9 relative off the matrix (its eigenvalues right to 1e-16; nalgebra issue #1109), which
/// moved M(q) by 2.5e-11 relative in that tree while `from_inertia_tensor` used it.
#[test]
fn from_inertia_tensor_keeps_the_tensor() {
    let bits: [u64; 9] = [
        4589538291601677601,
        4577730607456967286,
        4576518497748363008,
        4577730607456967286,
        4590715264302329462,
        13795475504101794582,
        4576518497748363008,
        13795475504101794582,
        4590861954615887686,
    ];
    let tensor = Matrix3::from_iterator(bits.iter().map(|&b| f64::from_bits(b)));
    assert_eq!(tensor, tensor.transpose());
    let centre = Vector3::new(0.1, -0.2, 0.3);
    let (body, frame) = Body::from_inertia_tensor(1.5, tensor, centre, centre).unwrap();
    let axes = frame.rotation.to_rotation_matrix().into_inner();
    let rebuilt = axes * Matrix3::from_diagonal(&body.moments()) * axes.transpose();
    let error = (rebuilt - tensor).amax() / tensor.amax();
    let mut eigenvalues: Vec<f64> = tensor.symmetric_eigenvalues().iter().copied().collect();
    eigenvalues.sort_by(f64::total_cmp);
    println!("moments {eigenvalues:?} kg m²: R diag Rᵀ is {error:.2e} of the tensor off");
    assert!(error <= 1e-14, "{error:e}");
}
