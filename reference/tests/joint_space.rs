//! `reference::joint_space` against closed forms (pendulum, planar double pendulum, free body by Newton–Euler),
//! and against itself on random trees: inverse ∘ forward dynamics = identity, the energy balance along an RK4
//! integration, symmetry and definiteness of M, gravity forces as the gradient of the potential.

use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix3, Matrix6, Quaternion, Translation3, Unit, UnitQuaternion, Vector3,
};
use reference::joint_space::{JointSpaceError, Tree, TreeBody, TreeJoint};

const G: f64 = 9.81;

/// SplitMix64: a small deterministic generator, so that every run checks the same trees.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn vector(&mut self, scale: f64) -> Vector3<f64> {
        Vector3::new(
            self.uniform(-scale, scale),
            self.uniform(-scale, scale),
            self.uniform(-scale, scale),
        )
    }

    fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// An axis from a random, non-unit vector.
    fn axis(&mut self) -> Unit<Vector3<f64>> {
        loop {
            let v = self.vector(2.0);
            if v.norm() > 0.1 {
                return Unit::new_normalize(v);
            }
        }
    }

    fn rotation(&mut self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(
            self.uniform(-3.1, 3.1),
            self.uniform(-1.5, 1.5),
            self.uniform(-3.1, 3.1),
        )
    }

    /// A full (off-diagonal) inertia tensor: R diag(p₂ + p₃, p₁ + p₃, p₁ + p₂) Rᵀ from positive second moments,
    /// so the triangle inequality holds.
    fn inertia(&mut self) -> Matrix3<f64> {
        let p = Vector3::new(
            self.uniform(0.01, 0.2),
            self.uniform(0.01, 0.2),
            self.uniform(0.01, 0.2),
        );
        let rotation = self.rotation().to_rotation_matrix().into_inner();
        rotation * Matrix3::from_diagonal(&Vector3::new(p.y + p.z, p.x + p.z, p.x + p.y)) * rotation.transpose()
    }

    fn dvector(&mut self, n: usize, scale: f64) -> DVector<f64> {
        DVector::from_fn(n, |_, _| self.uniform(-scale, scale))
    }
}

/// A random tree of `n` bodies: body 0 on a free joint to the world, the others on revolute, prismatic or
/// (one in five) fixed joints to a random earlier body, with random rpy placements and full inertias.
fn random_tree(rng: &mut Rng, n: usize) -> Tree {
    let mut bodies = Vec::with_capacity(n);
    for index in 0..n {
        let (parent, joint) = if index == 0 {
            (None, TreeJoint::Free)
        } else {
            let joint = match rng.index(5) {
                0 => TreeJoint::Fixed,
                1 => TreeJoint::Prismatic(rng.axis()),
                _ => TreeJoint::Revolute(rng.axis()),
            };
            (Some(rng.index(index)), joint)
        };
        bodies.push(TreeBody {
            parent,
            placement: Isometry3::from_parts(Translation3::from(rng.vector(0.6)), rng.rotation()),
            joint,
            mass: rng.uniform(0.5, 2.0),
            centre_of_mass: rng.vector(0.3),
            inertia: rng.inertia(),
        });
    }
    Tree {
        bodies,
        gravity: Vector3::new(0.0, 0.0, -G),
    }
}

/// A random configuration: random joint values, a random position and unit quaternion for free joints.
fn random_configuration(rng: &mut Rng, tree: &Tree) -> DVector<f64> {
    let mut q = Vec::with_capacity(tree.nq());
    for body in &tree.bodies {
        match body.joint {
            TreeJoint::Revolute(_) => q.push(rng.uniform(-3.0, 3.0)),
            TreeJoint::Prismatic(_) => q.push(rng.uniform(-0.5, 0.5)),
            TreeJoint::Fixed => {}
            TreeJoint::Free => {
                q.extend(rng.vector(1.0).iter());
                q.extend(rng.rotation().coords.iter().copied().cycle().skip(3).take(4));
                // (x, y, z, w) → (w, x, y, z)
            }
        }
    }
    DVector::from_vec(q)
}

/// Largest |x_k| (at least 1), for relative comparisons.
fn scale(x: &DVector<f64>) -> f64 {
    x.amax().max(1.0)
}

fn pendulum_tree(axis: Unit<Vector3<f64>>, centre_of_mass: Vector3<f64>, inertia: Matrix3<f64>, mass: f64) -> Tree {
    Tree {
        bodies: vec![TreeBody {
            parent: None,
            placement: Isometry3::identity(),
            joint: TreeJoint::Revolute(axis),
            mass,
            centre_of_mass,
            inertia,
        }],
        gravity: Vector3::new(0.0, 0.0, -G),
    }
}

#[test]
fn single_revolute_pendulum_matches_closed_form() {
    let mut rng = Rng(1);
    // Hinge about world x; the centre of mass hangs d below it (and 0.2 m along the axis, which changes neither
    // the moment arm nor the potential's angle dependence); a full inertia tensor about the centre of mass.
    let (mass, d) = (1.7, 0.45);
    let inertia = rng.inertia();
    let tree = pendulum_tree(Vector3::x_axis(), Vector3::new(0.2, 0.0, -d), inertia, mass);
    let axis_moment = inertia[(0, 0)] + mass * d * d;
    for theta in [0.0, 0.3, -1.1, 2.0, 3.0] {
        let q = DVector::from_element(1, theta);
        for rate in [0.0, 2.5] {
            let v = DVector::from_element(1, rate);
            let m = tree.mass_matrix(&q).unwrap();
            let h = tree.bias(&q, &v).unwrap();
            let expected_h = mass * G * d * theta.sin();
            assert!(
                (m[(0, 0)] - axis_moment).abs() <= 1e-14 * axis_moment,
                "M = {m}, expected {axis_moment}"
            );
            assert!(
                (h[0] - expected_h).abs() <= 1e-14 * (mass * G * d),
                "h = {h}, expected {expected_h}"
            );
        }
    }
}

#[test]
fn planar_double_pendulum_matches_lagrangian() {
    // Point masses m₁, m₂ at the ends of massless rods l₁, l₂, both hinges about y, hanging along −z at q = 0;
    // θ₂ is relative to link 1.
    let (m1, m2, l1, l2) = (1.3, 0.7, 0.9, 0.6);
    let point = |parent: Option<usize>, offset: f64, mass: f64, length: f64| TreeBody {
        parent,
        placement: Isometry3::translation(0.0, 0.0, -offset),
        joint: TreeJoint::Revolute(Vector3::y_axis()),
        mass,
        centre_of_mass: Vector3::new(0.0, 0.0, -length),
        inertia: Matrix3::zeros(),
    };
    let tree = Tree {
        bodies: vec![point(None, 0.0, m1, l1), point(Some(0), l1, m2, l2)],
        gravity: Vector3::new(0.0, 0.0, -G),
    };
    let mut rng = Rng(2);
    for _ in 0..20 {
        let (t1, t2) = (rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0));
        let (w1, w2) = (rng.uniform(-4.0, 4.0), rng.uniform(-4.0, 4.0));
        let q = DVector::from_vec(vec![t1, t2]);
        let v = DVector::from_vec(vec![w1, w2]);
        let c2 = t2.cos();
        let k = m2 * l1 * l2;
        let expected_m = DMatrix::from_row_slice(
            2,
            2,
            &[
                (m1 + m2) * l1 * l1 + m2 * l2 * l2 + 2.0 * k * c2,
                m2 * l2 * l2 + k * c2,
                m2 * l2 * l2 + k * c2,
                m2 * l2 * l2,
            ],
        );
        let expected_h = DVector::from_vec(vec![
            -k * t2.sin() * (2.0 * w1 * w2 + w2 * w2) + (m1 + m2) * G * l1 * t1.sin() + m2 * G * l2 * (t1 + t2).sin(),
            k * t2.sin() * w1 * w1 + m2 * G * l2 * (t1 + t2).sin(),
        ]);
        let m = tree.mass_matrix(&q).unwrap();
        let h = tree.bias(&q, &v).unwrap();
        assert!(
            (&m - &expected_m).amax() <= 1e-14 * expected_m.amax(),
            "M = {m}, expected {expected_m}"
        );
        assert!(
            (&h - &expected_h).amax() <= 1e-13 * scale(&expected_h),
            "h = {h}, expected {expected_h}"
        );
    }
}

fn free_body(rng: &mut Rng) -> (Tree, f64, Vector3<f64>, Matrix3<f64>) {
    let (mass, c, inertia) = (1.9, rng.vector(0.4), rng.inertia());
    let tree = Tree {
        bodies: vec![TreeBody {
            parent: None,
            placement: Isometry3::identity(),
            joint: TreeJoint::Free,
            mass,
            centre_of_mass: c,
            inertia,
        }],
        gravity: Vector3::new(0.0, 0.0, -G),
    };
    (tree, mass, c, inertia)
}

#[test]
fn free_body_mass_matrix_is_the_local_spatial_inertia() {
    let mut rng = Rng(3);
    let (tree, mass, c, inertia) = free_body(&mut rng);
    assert_eq!((tree.nq(), tree.nv()), (7, 6));
    let q = random_configuration(&mut rng, &tree);
    // (v, ω) ordering: p = m (v + ω × c), L_O = m c × v + (I_c − m c× c×) ω.
    let cx = Matrix3::new(0.0, -c.z, c.y, c.z, 0.0, -c.x, -c.y, c.x, 0.0);
    let mut expected = Matrix6::zeros();
    expected
        .fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(mass * Matrix3::identity()));
    expected.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-mass * cx));
    expected.fixed_view_mut::<3, 3>(3, 0).copy_from(&(mass * cx));
    expected
        .fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(inertia - mass * cx * cx));
    let m = tree.mass_matrix(&q).unwrap();
    let difference = (&m - DMatrix::from_column_slice(6, 6, expected.as_slice())).amax();
    assert!(difference <= 1e-14 * mass, "M = {m}, expected {expected}");
}

#[test]
fn free_body_forward_dynamics_is_newton_euler() {
    let mut rng = Rng(4);
    for _ in 0..10 {
        let (tree, mass, c, inertia) = free_body(&mut rng);
        let q = random_configuration(&mut rng, &tree);
        let (v, tau) = (rng.dvector(6, 3.0), rng.dvector(6, 5.0));
        let rotation = UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[4], q[5], q[6]));
        let (v_origin, omega) = (v.fixed_rows::<3>(0).into_owned(), v.fixed_rows::<3>(3).into_owned());
        let (force, torque_origin) = (tau.fixed_rows::<3>(0).into_owned(), tau.fixed_rows::<3>(3).into_owned());
        // Euler about the centre of mass, body axes: I_c ω̇ + ω × I_c ω = n_O − c × f (gravity acts at c).
        let omega_dot =
            inertia.try_inverse().unwrap() * (torque_origin - c.cross(&force) - omega.cross(&(inertia * omega)));
        // Newton: m R (v̇_c + ω × v_c) = R f + m g with v_c = v_O + ω × c, and v̇_c = v̇_O + ω̇ × c.
        let v_centre = v_origin + omega.cross(&c);
        let gravity_body = rotation.inverse_transform_vector(&tree.gravity);
        let v_origin_dot = force / mass + gravity_body - omega.cross(&v_centre) - omega_dot.cross(&c);
        let expected = DVector::from_iterator(6, v_origin_dot.iter().chain(omega_dot.iter()).copied());
        let a = tree.forward_dynamics(&q, &v, &tau).unwrap();
        assert!(
            (&a - &expected).amax() <= 1e-12 * scale(&expected),
            "q̈ = {a}, expected {expected}"
        );

        // The body's world velocities in the same convention.
        let velocity = tree.body_velocities(&q, &v).unwrap()[0];
        assert!((velocity.angular - rotation * omega).norm() <= 1e-14 * omega.norm());
        assert!((velocity.centre_of_mass - rotation * v_centre).norm() <= 1e-14 * v_centre.norm().max(1.0));
    }
}

#[test]
fn inverse_dynamics_inverts_forward_dynamics_on_random_trees() {
    let mut rng = Rng(5);
    let mut worst: f64 = 0.0;
    for trial in 0..200 {
        let tree = random_tree(&mut rng, 2 + trial % 9);
        let q = random_configuration(&mut rng, &tree);
        let (v, tau) = (rng.dvector(tree.nv(), 2.0), rng.dvector(tree.nv(), 10.0));
        let a = tree.forward_dynamics(&q, &v, &tau).unwrap();
        let recovered = tree.inverse_dynamics(&q, &v, &a).unwrap();
        let error = (&recovered - &tau).amax() / scale(&tau);
        worst = worst.max(error);
        assert!(error <= 1e-12, "trial {trial}: τ = {tau}, recovered {recovered}");
    }
    println!("worst relative |ID(FD(τ)) − τ| = {worst:e}");
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_and_gives_the_kinetic_energy() {
    let mut rng = Rng(6);
    for trial in 0..100 {
        let tree = random_tree(&mut rng, 2 + trial % 9);
        let q = random_configuration(&mut rng, &tree);
        let v = rng.dvector(tree.nv(), 2.0);
        let m = tree.mass_matrix(&q).unwrap();
        assert_eq!(m, m.transpose(), "trial {trial}: M is not symmetric");
        let eigenvalues = m.clone().symmetric_eigenvalues();
        assert!(eigenvalues.min() > 0.0, "trial {trial}: eigenvalues {eigenvalues}");
        assert!(m.clone().cholesky().is_some());
        // ½ vᵀ M v (CRBA) against Σ ½ v_iᵀ I_i v_i (body velocities).
        let quadratic = 0.5 * v.dot(&(&m * &v));
        let kinetic = tree.kinetic_energy(&q, &v).unwrap();
        assert!(
            (quadratic - kinetic).abs() <= 1e-13 * kinetic,
            "trial {trial}: {quadratic} vs {kinetic}"
        );
        // M a = τ − h through the RNEA with and without q̈ (τ(a) − τ(0) = M a).
        let a = rng.dvector(tree.nv(), 3.0);
        let difference = tree.inverse_dynamics(&q, &v, &a).unwrap() - tree.bias(&q, &v).unwrap();
        let expected = &m * &a;
        assert!(
            (&difference - &expected).amax() <= 1e-12 * scale(&expected),
            "trial {trial}"
        );
    }
}

/// q ⊕ δ: the configuration moved by the velocity-coordinate increment δ (a first-order retraction, enough for
/// central differences): joint values add, a free joint's position moves by R δ_v and its orientation by
/// exp(δ_ω) on the right (body axes).
fn retract(tree: &Tree, q: &DVector<f64>, delta: &DVector<f64>) -> DVector<f64> {
    let mut moved = q.clone();
    let (mut iq, mut iv) = (0, 0);
    for body in &tree.bodies {
        match body.joint {
            TreeJoint::Revolute(_) | TreeJoint::Prismatic(_) => moved[iq] += delta[iv],
            TreeJoint::Fixed => {}
            TreeJoint::Free => {
                let rotation =
                    UnitQuaternion::from_quaternion(Quaternion::new(q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]));
                let shift = rotation * Vector3::new(delta[iv], delta[iv + 1], delta[iv + 2]);
                let turned = rotation
                    * UnitQuaternion::from_scaled_axis(Vector3::new(delta[iv + 3], delta[iv + 4], delta[iv + 5]));
                for k in 0..3 {
                    moved[iq + k] += shift[k];
                }
                moved[iq + 3] = turned.w;
                moved[iq + 4] = turned.i;
                moved[iq + 5] = turned.j;
                moved[iq + 6] = turned.k;
            }
        }
        iq += body.joint.nq();
        iv += body.joint.nv();
    }
    moved
}

#[test]
fn gravity_bias_is_the_gradient_of_the_potential() {
    let mut rng = Rng(7);
    let epsilon = 1e-5;
    for trial in 0..30 {
        let tree = random_tree(&mut rng, 2 + trial % 7);
        let q = random_configuration(&mut rng, &tree);
        let h = tree.bias(&q, &DVector::zeros(tree.nv())).unwrap();
        let gradient = DVector::from_fn(tree.nv(), |k, _| {
            let step = DVector::from_fn(tree.nv(), |i, _| if i == k { epsilon } else { 0.0 });
            let up = tree.potential_energy(&retract(&tree, &q, &step)).unwrap();
            let down = tree.potential_energy(&retract(&tree, &q, &-step)).unwrap();
            (up - down) / (2.0 * epsilon)
        });
        // h(q, 0) = g(q) = ∂V/∂q, i.e. minus the generalised gravity force.
        assert!(
            (&h - &gradient).amax() <= 1e-7 * scale(&h),
            "trial {trial}: h = {h}, ∂V/∂q = {gradient}"
        );
    }
}

#[test]
fn body_velocities_are_the_rates_of_the_body_poses() {
    let mut rng = Rng(8);
    let epsilon = 1e-6;
    for trial in 0..30 {
        let tree = random_tree(&mut rng, 2 + trial % 7);
        let q = random_configuration(&mut rng, &tree);
        let v = rng.dvector(tree.nv(), 2.0);
        let qdot = tree.configuration_rate(&q, &v).unwrap();
        let ahead = tree.positions(&(&q + epsilon * &qdot)).unwrap();
        let behind = tree.positions(&(&q - epsilon * &qdot)).unwrap();
        for (index, velocity) in tree.body_velocities(&q, &v).unwrap().iter().enumerate() {
            let c = tree.bodies[index].centre_of_mass;
            let centre_rate = (ahead[index] * nalgebra::Point3::from(c) - behind[index] * nalgebra::Point3::from(c))
                / (2.0 * epsilon);
            let turn = (ahead[index].rotation * behind[index].rotation.inverse()).scaled_axis() / (2.0 * epsilon);
            assert!(
                (centre_rate - velocity.centre_of_mass).norm() <= 1e-7,
                "trial {trial}, body {index}"
            );
            assert!((turn - velocity.angular).norm() <= 1e-7, "trial {trial}, body {index}");
        }
    }
}

#[test]
fn energy_change_equals_the_work_of_the_joint_forces() {
    let mut rng = Rng(9);
    let tree = random_tree(&mut rng, 5);
    let nv = tree.nv();
    let (amplitude, frequency, phase) = (rng.dvector(nv, 3.0), rng.dvector(nv, 6.0), rng.dvector(nv, 3.0));
    let tau = |t: f64| DVector::from_fn(nv, |k, _| amplitude[k] * (frequency[k] * t + phase[k]).sin());
    // State (q, v, W) with Ẇ = vᵀ τ(t), the power of the joint forces.
    let rates = |t: f64, q: &DVector<f64>, v: &DVector<f64>| {
        let force = tau(t);
        (
            tree.configuration_rate(q, v).unwrap(),
            tree.forward_dynamics(q, v, &force).unwrap(),
            v.dot(&force),
        )
    };
    let energy =
        |q: &DVector<f64>, v: &DVector<f64>| tree.kinetic_energy(q, v).unwrap() + tree.potential_energy(q).unwrap();
    let (mut q, mut v, mut work) = (random_configuration(&mut rng, &tree), rng.dvector(nv, 1.5), 0.0);
    let initial = energy(&q, &v);
    let (h, steps) = (1e-3, 500);
    for step in 0..steps {
        let t = step as f64 * h;
        let k1 = rates(t, &q, &v);
        let k2 = rates(t + 0.5 * h, &(&q + 0.5 * h * &k1.0), &(&v + 0.5 * h * &k1.1));
        let k3 = rates(t + 0.5 * h, &(&q + 0.5 * h * &k2.0), &(&v + 0.5 * h * &k2.1));
        let k4 = rates(t + h, &(&q + h * &k3.0), &(&v + h * &k3.1));
        q += h / 6.0 * (&k1.0 + 2.0 * &k2.0 + 2.0 * &k3.0 + &k4.0);
        v += h / 6.0 * (&k1.1 + 2.0 * &k2.1 + 2.0 * &k3.1 + &k4.1);
        work += h / 6.0 * (k1.2 + 2.0 * k2.2 + 2.0 * k3.2 + k4.2);
        let norm = q.rows(3, 4).norm();
        q.rows_mut(3, 4).unscale_mut(norm); // the free root's quaternion
    }
    let change = energy(&q, &v) - initial;
    println!("ΔE = {change}, ∫ vᵀτ dt = {work}, difference {:e}", change - work);
    assert!(
        change.abs() > 0.5 && work.abs() > 0.5,
        "a trivial test: ΔE = {change}, W = {work}"
    );
    assert!((change - work).abs() <= 1e-9, "ΔE = {change}, ∫ vᵀτ dt = {work}");
}

#[test]
fn bad_input_is_an_error() {
    let mut rng = Rng(10);
    let tree = random_tree(&mut rng, 4);
    let (q, v) = (tree.neutral_configuration(), DVector::zeros(tree.nv()));
    assert!(tree.mass_matrix(&q).is_ok());
    assert!(matches!(
        tree.mass_matrix(&DVector::zeros(tree.nq() + 1)),
        Err(JointSpaceError::Length { vector: "q", .. })
    ));
    assert!(matches!(
        tree.bias(&q, &DVector::zeros(tree.nv() - 1)),
        Err(JointSpaceError::Length { vector: "v", .. })
    ));
    assert!(matches!(
        tree.forward_dynamics(&q, &v, &DVector::zeros(1)),
        Err(JointSpaceError::Length { vector: "tau", .. })
    ));
    assert!(matches!(
        tree.inverse_dynamics(&q, &v, &DVector::zeros(0)),
        Err(JointSpaceError::Length { vector: "a", .. })
    ));
    let mut bad_v = v.clone();
    bad_v[2] = f64::NAN;
    assert_eq!(
        tree.kinetic_energy(&q, &bad_v),
        Err(JointSpaceError::NonFiniteInput { vector: "v", index: 2 })
    );
    let mut bad_q = q.clone();
    bad_q[3] = 0.0; // the free root's quaternion (0, 0, 0, 0)
    assert!(matches!(
        tree.positions(&bad_q),
        Err(JointSpaceError::QuaternionNorm { body: 0, .. })
    ));

    let mut misordered = tree.clone();
    misordered.bodies[1].parent = Some(1);
    assert_eq!(misordered.nv(), tree.nv());
    assert_eq!(
        misordered.potential_energy(&q),
        Err(JointSpaceError::ParentOrder { body: 1, parent: 1 })
    );
    let mut negative = tree.clone();
    negative.bodies[2].mass = -1.0;
    assert!(matches!(
        negative.mass_matrix(&q),
        Err(JointSpaceError::InvalidBody { body: 2, .. })
    ));
    let mut infinite = tree.clone();
    infinite.bodies[3].inertia[(0, 1)] = f64::INFINITY;
    assert!(matches!(
        infinite.mass_matrix(&q),
        Err(JointSpaceError::InvalidBody { body: 3, .. })
    ));
    let mut no_gravity = tree.clone();
    no_gravity.gravity.z = f64::NAN;
    assert_eq!(no_gravity.bias(&q, &v), Err(JointSpaceError::NonFiniteGravity));

    // A massless pendulum has M = 0: no forward dynamics.
    let massless = pendulum_tree(Vector3::x_axis(), Vector3::zeros(), Matrix3::zeros(), 0.0);
    let one = DVector::zeros(1);
    assert_eq!(
        massless.forward_dynamics(&one, &one, &one),
        Err(JointSpaceError::NotPositiveDefinite)
    );
}
