//! Every way to build a body or a mechanism that cannot work ends in its own error variant, naming the cause.
//! Errors met only while running (inconsistent or unreachable joints, non-finite paths or states)
//! are reached in `constraint_machinery.rs` and `integrate`'s unit tests.

use std::sync::Arc;

use dynamics::constraints::{pinning, Composite, Constraint, VirtualPower, MAX_ROWS};
use dynamics::{
    Algebra, Body, BodyError, ConstraintError, Mechanism, MechanismError, Pga, Reference, ScrewCoordinates,
    Stabilisation, State,
};
use nalgebra::{UnitQuaternion, Vector3};

fn body() -> Body {
    Body::new(1.3, Vector3::new(0.4, 0.3, 0.2)).unwrap()
}

#[test]
fn unphysical_bodies_are_refused() {
    assert_eq!(Body::new(-1.0, Vector3::new(1.0, 2.0, 3.0)), Err(BodyError::Mass(-1.0)));
    assert!(matches!(Body::new(f64::NAN, Vector3::repeat(1.0)), Err(BodyError::Mass(m)) if m.is_nan()));
    // Finite but beyond what the weight and momenta can be formed from.
    assert_eq!(Body::new(1e308, Vector3::repeat(1.0)), Err(BodyError::Mass(1e308)));
    // Positive but subnormal or so small that its reciprocal overflows the dynamics' divisions.
    assert_eq!(Body::new(1e-310, Vector3::repeat(1.0)), Err(BodyError::Mass(1e-310)));
    assert_eq!(Body::new(1e-60, Vector3::repeat(1.0)), Err(BodyError::Mass(1e-60)));
    assert_eq!(
        Body::new(1.0, Vector3::new(1e-320, 1e-320, 1e-320)),
        Err(BodyError::Moments([1e-320; 3]))
    );
    // The smallest allowed values build.
    assert!(Body::new(1e-50, Vector3::repeat(1e-50)).is_ok());
    assert_eq!(
        Body::new(1.0, Vector3::new(1e300, 1e300, 1e300)),
        Err(BodyError::Moments([1e300; 3]))
    );
    assert_eq!(
        Body::new(1.0, Vector3::new(-1.0, 2.0, 3.0)),
        Err(BodyError::Moments([-1.0, 2.0, 3.0]))
    );
    assert_eq!(
        Body::new(1.0, Vector3::new(1.0, 1.0, 3.0)),
        Err(BodyError::Triangle([1.0, 1.0, 3.0]))
    );
    assert_eq!(
        Body::cuboid(1.0, Vector3::new(1.0, 0.0, 1.0)),
        Err(BodyError::Dimensions(vec![1.0, 0.0, 1.0]))
    );
    let message = Body::new(1.0, Vector3::new(1.0, 1.0, 3.0)).unwrap_err().to_string();
    assert!(message.contains("triangle inequality"), "{message}");
}

#[test]
fn mechanisms_refuse_bad_bodies_and_joints_naming_them() {
    // A force for body 0 of a mechanism without bodies is refused, not dropped.
    assert!(matches!(
        Mechanism::<Pga>::new().with_force(dynamics::Force::gravity()),
        Err(MechanismError::UnknownBody(0))
    ));
    let mut mechanism = Mechanism::<Pga>::new();
    assert_eq!(mechanism.add_body("", body()), Err(MechanismError::EmptyName("body")));
    let arm = mechanism.add_body("arm", body()).unwrap();
    assert_eq!(
        mechanism.add_body("arm", body()),
        Err(MechanismError::DuplicateBody("arm".into()))
    );
    let ball = || pinning::point::<Pga>("elbow", Vector3::z(), Vector3::zeros());
    // A joint is named in every error and output about it.
    assert_eq!(
        mechanism.add_joint(
            arm,
            Reference::World,
            pinning::point::<Pga>("", Vector3::z(), Vector3::zeros())
        ),
        Err(MechanismError::EmptyName("joint"))
    );
    assert_eq!(
        mechanism.add_joint(arm, Reference::Body(arm), ball()),
        Err(MechanismError::SelfJoint {
            joint: "elbow".into(),
            body: "arm".into()
        })
    );
    // An id from another mechanism.
    let mut other = Mechanism::<Pga>::new();
    other.add_body("a", body()).unwrap();
    let foreign = other.add_body("b", body()).unwrap();
    assert_eq!(
        mechanism.add_joint(foreign, Reference::World, ball()),
        Err(MechanismError::UnknownBody(1))
    );
    let foreign_joint = other.add_joint(foreign, Reference::World, ball()).unwrap();
    assert_eq!(
        mechanism.set_reaction_basis(foreign_joint, vec![]),
        Err(MechanismError::UnknownJoint(0))
    );
    let joint = mechanism.add_joint(arm, Reference::World, ball()).unwrap();
    assert_eq!(
        mechanism.set_reaction_basis(joint, vec![]),
        Err(MechanismError::ReactionBasis {
            joint: "elbow".into(),
            count: 0
        })
    );
    let not_finite = Pga::screw(ScrewCoordinates {
        l: Vector3::new(f64::NAN, 0.0, 0.0),
        t: Vector3::zeros(),
    });
    assert!(matches!(
        mechanism.set_reaction_basis(joint, vec![not_finite]),
        Err(MechanismError::ReactionBasis { count: 1, .. })
    ));
}

#[test]
fn declared_ranks_and_row_counts_are_checked_when_a_joint_is_added() {
    let mut mechanism = Mechanism::<Pga>::new();
    let arm = mechanism.add_body("arm", body()).unwrap();
    let pin = |rank| pinning::Pin::<Pga, _>::new("pin", Pga::point(Vector3::z()), Pga::point(Vector3::zeros()), rank);
    for rank in [0, 7] {
        let error = mechanism.add_joint(arm, Reference::World, pin(rank)).unwrap_err();
        assert!(
            matches!(error, MechanismError::Constraint(ConstraintError::InvalidRank { rank: r, .. }) if r == rank),
            "{error}"
        );
    }
    // More rows than the solver's capacity.
    let many: Vec<Arc<dyn Constraint<Pga>>> = (0..MAX_ROWS / 3 + 1)
        .map(|k| {
            Arc::new(pinning::point::<Pga>(
                format!("ball {k}"),
                Vector3::z(),
                Vector3::zeros(),
            )) as _
        })
        .collect();
    let error = mechanism
        .add_joint(arm, Reference::World, Composite::new("many balls", many, 3))
        .unwrap_err();
    assert!(
        matches!(error, MechanismError::Constraint(ConstraintError::TooManyRows { ref name, capacity, .. })
            if name == "many balls" && capacity == MAX_ROWS),
        "{error}"
    );
    // Projection needs a position residual, which user wrenches do not have.
    mechanism.set_stabilisation(Stabilisation::PROJECTION).unwrap();
    let wrenches = VirtualPower::<Pga>::from_wrenches(
        "user",
        [|_t: f64| dynamics::constraints::WrenchPoint::fixed(dynamics::forces::couple::<Pga>(Vector3::z()))],
    );
    let error = mechanism.add_joint(arm, Reference::World, wrenches).unwrap_err();
    assert!(
        matches!(error, MechanismError::Constraint(ConstraintError::NoPositionResidual { ref name }) if name == "user"),
        "{error}"
    );
}

/// Two identical ball joints declared as one joint of rank 6 have rows of rank 3: the reaction is not
/// determined, and the error names the joint.
#[test]
fn a_declared_rank_the_rows_do_not_have_is_rank_deficient() {
    let ball = || Arc::new(pinning::point::<Pga>("ball", Vector3::z(), Vector3::zeros())) as Arc<dyn Constraint<Pga>>;
    let mechanism = Mechanism::<Pga>::single(body())
        .with_constraint(Composite::new("double ball", vec![ball(), ball()], 6))
        .unwrap();
    let state = State::<Pga>::new(
        &body(),
        Vector3::new(0.0, 0.0, -1.0),
        &UnitQuaternion::identity(),
        Vector3::new(0.3, -0.2, 0.1),
        Vector3::zeros(),
    );
    let error = mechanism.rates_at(0.0, &[state]).unwrap_err();
    assert!(
        matches!(error, ConstraintError::RankDeficient { ref names, rank: 6, .. } if names.contains("double ball")),
        "{error}"
    );
}

/// A cuboid spinning at 300 rad/s stepped with dt = 1e-2 would turn 3 rad per step (RK4 doubled its energy in
/// 1 s, RKMK4-body overflowed its motor at dt = 1e6): every integrator refuses the step, leaving the state as
/// it was, and takes dt = 1e-3.
#[test]
fn a_step_that_turns_a_body_more_than_a_radian_is_refused() {
    let body = Body::cuboid(1.0, Vector3::new(0.1, 0.2, 0.3)).unwrap();
    let system = dynamics::FreeBody::<Pga>::new(body);
    let start = State::<Pga>::new(
        &body,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::new(0.0, 0.0, 300.0),
        Vector3::zeros(),
    );
    for integrator in dynamics::Integrator::ALL {
        let mut stepper = dynamics::Stepper::new(&system, integrator).unwrap();
        let mut states = [start];
        for dt in [1e-2, 1e6] {
            let error = stepper.step(0.0, &mut states, dt).unwrap_err();
            assert!(
                matches!(error, dynamics::StepError::StepTooLarge { body: 0, turn, .. } if (turn - 300.0 * dt).abs() < 1e-9 * turn),
                "{}: {error}",
                integrator.name()
            );
            assert_eq!(states[0], start);
        }
        let message = stepper.step(0.0, &mut states, 1e-2).unwrap_err().to_string();
        assert!(
            message.contains("body 0 turns 3.000 rad") && message.contains("take a step below 3.333e-3"),
            "{message}"
        );
        stepper.step(0.0, &mut states, 1e-3).unwrap();
    }
}

/// A state far beyond any physical scale (a body placed at 1e308 m once failed inside its first joint as a
/// "non-finite residual") is refused before the step, naming the body; NaN likewise.
#[test]
fn a_state_out_of_range_is_refused_before_the_step() {
    let mechanism = Mechanism::<Pga>::single(body());
    for position in [Vector3::new(1e308, 0.0, 0.0), Vector3::new(f64::NAN, 0.0, 0.0)] {
        let state = State::<Pga>::new(
            &body(),
            position,
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::zeros(),
        );
        let mut states = [state];
        let error = dynamics::Stepper::new(&mechanism, dynamics::Method::Rk4)
            .unwrap()
            .step(0.5, &mut states, 1e-3)
            .unwrap_err();
        assert!(
            matches!(error, dynamics::StepError::NonFiniteInput { t: 0.5, body: 0 }),
            "{error}"
        );
        assert!(error.to_string().contains("beyond 1e50"), "{error}");
    }
}

/// A joint between two bodies composes their relative motor only for constraints that say they read it
/// (`Constraint::uses_motor`); the others see a NaN motor. A constraint that reads it while saying it does not
/// therefore gets rows that are not finite: an error naming it, never a quiet wrong answer. Saying so makes it
/// work.
#[test]
fn a_constraint_reading_the_motor_it_said_it_would_not_is_an_error() {
    use dynamics::constraints::{Kinematics, RowBuffer};

    /// A ball joint whose biases are scaled by a factor computed from the relative motor (1 for any finite motor).
    struct ReadsTheMotor {
        ball: VirtualPower<Pga>,
        says_so: bool,
    }
    impl Constraint<Pga> for ReadsTheMotor {
        fn name(&self) -> &str {
            "reads the motor"
        }
        fn rank(&self) -> usize {
            3
        }
        fn row_count(&self) -> usize {
            3
        }
        fn has_position_residual(&self) -> bool {
            true
        }
        fn rows(&self, kinematics: &Kinematics<Pga>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
            let mut own = RowBuffer::new();
            self.ball.rows(kinematics, &mut own)?;
            let one = Pga::motor_coordinates(kinematics.motor).scalar * 0.0 + 1.0;
            for row in own.rows() {
                rows.push(dynamics::constraints::ConstraintRow {
                    bias: row.bias * one,
                    ..*row
                });
            }
            Ok(())
        }
        fn uses_motor(&self) -> bool {
            self.says_so
        }
    }
    let (top, bottom) = (Vector3::z() * 0.5, Vector3::z() * -0.5);
    let rod = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let hanging = |says_so: bool| {
        let mut chain = Mechanism::<Pga>::new();
        let upper = chain.add_body("upper", rod).unwrap();
        let lower = chain.add_body("lower", rod).unwrap();
        chain
            .add_joint(
                upper,
                Reference::World,
                VirtualPower::ball_joint("shoulder", top, Vector3::zeros()),
            )
            .unwrap();
        let elbow = ReadsTheMotor {
            ball: VirtualPower::ball_joint("elbow", top, bottom),
            says_so,
        };
        chain.add_joint(lower, upper, elbow).unwrap();
        let still = UnitQuaternion::identity();
        let swinging = [
            State::new(&rod, -top, &still, Vector3::x(), -Vector3::y() * 0.5),
            State::new(&rod, -top * 3.0, &still, Vector3::x(), -Vector3::y() * 1.5),
        ];
        chain.rates_at(0.0, &swinging)
    };
    let error = hanging(false).unwrap_err();
    assert!(
        matches!(error, ConstraintError::NonFinite { ref name, .. } if name == "reads the motor"),
        "{error}"
    );
    assert!(hanging(true).is_ok());
}

/// Solver thresholds outside their ranges (NaN, zero, negative, infinite, a relative residual above 1) are refused
/// when set, naming the setting: they once surfaced later as a joint's "rank deficiency", or, infinite, let a
/// contradiction pass.
#[test]
fn careless_solver_settings_are_refused() {
    use dynamics::SolverSettings;
    let mut system = Mechanism::<Pga>::new();
    let base = SolverSettings::default();
    for (settings, words) in [
        (
            SolverSettings {
                rank_tolerance: f64::NAN,
                ..base
            },
            "rank_tolerance",
        ),
        (
            SolverSettings {
                rank_tolerance: -1e-6,
                ..base
            },
            "rank_tolerance",
        ),
        (
            SolverSettings {
                rank_tolerance: 0.0,
                ..base
            },
            "rank_tolerance",
        ),
        (
            SolverSettings {
                rank_tolerance: 1.0,
                ..base
            },
            "rank_tolerance",
        ),
        (
            SolverSettings {
                consistency_tolerance: f64::INFINITY,
                ..base
            },
            "consistency_tolerance",
        ),
        (
            SolverSettings {
                consistency_tolerance: f64::NAN,
                ..base
            },
            "consistency_tolerance",
        ),
        (
            SolverSettings {
                consistency_tolerance: -0.5,
                ..base
            },
            "consistency_tolerance",
        ),
        (
            SolverSettings {
                consistency_tolerance: 2.0,
                ..base
            },
            "consistency_tolerance",
        ),
    ] {
        let error = system.set_settings(settings).unwrap_err().to_string();
        assert!(error.contains("solver settings") && error.contains(words), "{error}");
    }
    assert!(system.set_settings(base).is_ok());
    assert!(system
        .set_settings(SolverSettings {
            rank_tolerance: 1e-12,
            consistency_tolerance: 1.0
        })
        .is_ok());
}

/// An axis or normal is a direction: any finite nonzero length gives the same joint, 1e200 (whose squared norm
/// overflows) and 1e-200 (whose squared norm underflows) included, in every constructor that takes one; zero, NaN
/// and infinite lengths are refused naming the joint.
#[test]
fn axes_of_any_finite_length_are_directions() {
    use dynamics::{JointKind, JointModel, Method, Schedule};
    use nalgebra::Isometry3;
    type Build = fn(Vector3<f64>) -> Result<Arc<dyn Constraint<Pga>>, ConstraintError>;
    fn point() -> Vector3<f64> {
        Vector3::new(0.0, 0.0, 0.5) // the arm's top end, at the world origin
    }
    let builders: [(&str, Build); 5] = [
        ("virtual power hinge", |axis| {
            Ok(Arc::new(VirtualPower::hinge(
                "pivot",
                (point(), axis),
                (Vector3::zeros(), axis),
            )?))
        }),
        ("pinned hinge", |axis| {
            Ok(Arc::new(pinning::hinge::<Pga>(
                "pivot",
                (point(), axis),
                (Vector3::zeros(), axis),
            )?))
        }),
        ("pinned plane", |normal| {
            Ok(Arc::new(pinning::plane::<Pga>("pivot", (normal, 0.0), (normal, 0.0))?))
        }),
        ("virtual power prismatic", |axis| {
            Ok(Arc::new(VirtualPower::prismatic(
                "pivot",
                (point(), axis, Vector3::y()),
                (Vector3::zeros(), axis, Vector3::y()),
            )?))
        }),
        ("revolute joint model", |axis| {
            let model = JointModel::new(
                "pivot",
                JointKind::Revolute { axis },
                Isometry3::identity(),
                Isometry3::identity(),
            )?;
            Ok(model.virtual_power::<Pga>()?.expect("a revolute joint constrains"))
        }),
    ];
    let start = State::<Pga>::new(
        &body(),
        Vector3::new(0.0, 0.0, -0.5),
        &UnitQuaternion::identity(),
        Vector3::new(0.7, 0.0, 0.0),
        Vector3::new(0.0, 0.35, 0.0),
    );
    let run = |constraint: Arc<dyn Constraint<Pga>>| {
        let mut mechanism = Mechanism::<Pga>::new();
        let arm = mechanism.add_body("arm", body()).unwrap();
        mechanism.add_force(arm, dynamics::Force::gravity()).unwrap();
        mechanism.add_joint(arm, Reference::World, constraint).unwrap();
        let run = dynamics::simulate(&mechanism, &[start], Method::Rk4, &Schedule::new(1e-3, 0.01).unwrap()).unwrap();
        *run.body(0).last().unwrap()
    };
    for (label, build) in builders {
        let unit = run(build(Vector3::x()).unwrap());
        for length in [1e200, 1e-200, 3.0] {
            let end = run(build(Vector3::x() * length).unwrap_or_else(|error| panic!("{label} at {length}: {error}")));
            assert_eq!(end, unit, "{label} at {length}");
        }
        for bad in [
            Vector3::zeros(),
            Vector3::new(f64::NAN, 0.0, 0.0),
            Vector3::new(f64::INFINITY, 0.0, 0.0),
        ] {
            let error = build(bad).err().unwrap_or_else(|| panic!("{label} accepted {bad:?}"));
            assert!(error.to_string().contains("pivot"), "{label}: {error}");
        }
    }
}

/// A state written field by field whose motor is not a rigid motion (zero, or twice a unit motor) is refused before
/// the step, naming the body and the norm, by the stepper and by `simulate` (a zero motor was once blamed on the
/// step size).
#[test]
fn a_motor_that_is_not_a_rigid_motion_is_refused() {
    use dynamics::{MotorCoordinates, StepError};
    let mechanism = Mechanism::<Pga>::single(body());
    let unit = State::<Pga>::new(
        &body(),
        Vector3::new(1.0, 2.0, 3.0),
        &UnitQuaternion::identity(),
        Vector3::new(0.1, 0.0, 0.0),
        Vector3::zeros(),
    );
    let coordinates = Pga::motor_coordinates(unit.motor);
    for (scale, norm_squared) in [(0.0, 0.0), (2.0, 4.0), (1.0 + 1e-3, (1.0f64 + 1e-3).powi(2))] {
        let motor = Pga::motor(MotorCoordinates {
            scalar: coordinates.scalar * scale,
            l: coordinates.l * scale,
            t: coordinates.t * scale,
            pseudoscalar: coordinates.pseudoscalar * scale,
        });
        let mut states = [State { motor, ..unit }];
        let error = dynamics::Stepper::new(&mechanism, dynamics::Method::Rkmk6Body)
            .unwrap()
            .step(0.0, &mut states, 1e-3)
            .unwrap_err();
        assert_eq!(
            error,
            StepError::NotARigidMotion {
                t: 0.0,
                body: 0,
                norm_squared
            },
            "{error}"
        );
        let schedule = dynamics::Schedule::new(1e-3, 0.01).unwrap();
        let error = dynamics::simulate(&mechanism, &states, dynamics::Method::Rk4, &schedule).unwrap_err();
        assert!(error.to_string().contains("not a rigid motion"), "{error}");
    }
}

/// Far from the origin positions are resolved to ε |c|, so the body's own points lose their digits: beyond
/// `MAX_DISTANCE_IN_GYRATION_RADII` radii of gyration (1e-9 of the body's size) the step is refused with the reason;
/// just within it, the spin reads back to 1e-9 of the points' velocities (the state holds the momentum about the
/// centre of mass, so it reads back whole; while it held the momentum about the origin a free cuboid read its spin
/// back 1e-6 off at 1e8 m and lost it at 1e16 m).
#[test]
fn a_body_too_far_from_the_origin_is_refused_and_one_within_keeps_its_spin() {
    use dynamics::state::MAX_DISTANCE_IN_GYRATION_RADII;
    use dynamics::{FreeBody, Method, Schedule, StepError};
    let cuboid = Body::cuboid(2.0, Vector3::new(0.1, 0.2, 0.3)).unwrap();
    let radius = cuboid.smallest_gyration_radius();
    let limit = MAX_DISTANCE_IN_GYRATION_RADII * radius;
    let system = FreeBody::<Pga>::new(cuboid);
    let tilted = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.5));
    let (spin, velocity) = (Vector3::new(0.2, 1.0, 0.3), Vector3::new(1.0, -2.0, 0.5));
    let direction = Vector3::new(1.0, 0.3, 0.0).normalize();
    let at = |distance: f64| State::<Pga>::new(&cuboid, direction * distance, &tilted, spin, velocity);
    let second = Schedule::new(1e-2, 1.0).unwrap();
    for distance in [1.01 * limit, 1e8, 1e16, 1e30] {
        let error = dynamics::simulate(&system, &[at(distance)], Method::Rkmk8Body, &second)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("from the world origin") && error.contains("body 0"),
            "{distance}: {error}"
        );
        assert!(matches!(
            dynamics::Stepper::new(&system, Method::Rk4).unwrap().step(0.0, &mut [at(distance)], 1e-3),
            Err(StepError::TooFarFromOrigin { body: 0, distance: d, .. }) if (d - distance).abs() < 1e-9 * distance
        ));
    }
    let within = 0.99 * limit;
    let read_back = at(within).body_velocity(&cuboid);
    let spin_error = (Pga::screw_coordinates(read_back).l - spin).norm();
    let relative = spin_error * radius / velocity.norm();
    assert!(relative < 1e-9, "{relative:e}");
    assert!(dynamics::simulate(&system, &[at(within)], Method::Rkmk8Body, &second).is_ok());
}

/// Careless surfaces and held points are refused naming the parameter (surfaces) or the constraint (held points).
#[test]
fn careless_surfaces_and_held_points_are_refused() {
    use dynamics::constraints::SurfacePin;
    use dynamics::surfaces::{Sheets, Surface};
    use nalgebra::{Isometry3, Quaternion, Translation3, Unit, Vector2};

    let at = Isometry3::identity();
    let not_unit = Isometry3::from_parts(
        Translation3::identity(),
        Unit::new_unchecked(Quaternion::new(2.0, 0.0, 0.0, 0.0)),
    );
    let nan_turn = Isometry3::from_parts(
        Translation3::identity(),
        Unit::new_unchecked(Quaternion::new(f64::NAN, 0.0, 0.0, 0.0)),
    );
    let far = Isometry3::translation(2e6, 0.0, 0.0);
    let unit = Vector3::new(1.0, 1.0, 1.0);
    let cases: Vec<(&str, Result<Surface, dynamics::surfaces::SurfaceError>, &str)> = vec![
        (
            "NaN radius",
            Surface::ellipsoid(Vector3::new(f64::NAN, 1.0, 1.0), &at),
            "radii",
        ),
        (
            "zero radius",
            Surface::ellipsoid(Vector3::new(1.0, 0.0, 1.0), &at),
            "radii",
        ),
        (
            "negative radius",
            Surface::elliptic_cylinder(Vector2::new(-1.0, 1.0), &at),
            "radii",
        ),
        ("huge radius", Surface::cone(Vector2::new(1e7, 1.0), &at), "radii"),
        (
            "infinite radius",
            Surface::elliptic_paraboloid(Vector2::new(f64::INFINITY, 1.0), &at),
            "radii",
        ),
        (
            "radius whose 1/r² overflows",
            Surface::hyperbolic_paraboloid(Vector2::new(1e-200, 1.0), &at),
            "radii",
        ),
        (
            "centre beyond 1e6 m",
            Surface::hyperboloid(unit, Sheets::One, &far),
            "centre",
        ),
        (
            "orientation not unit",
            Surface::hyperboloid(unit, Sheets::Two, &not_unit),
            "orientation",
        ),
        ("orientation NaN", Surface::ellipsoid(unit, &nan_turn), "orientation"),
        ("zero normal", Surface::plane(Vector3::zeros(), 1.0), "normal"),
        (
            "NaN normal",
            Surface::plane(Vector3::new(f64::NAN, 0.0, 1.0), 1.0),
            "normal",
        ),
        ("offset beyond 1e6 m", Surface::plane(Vector3::z(), 1e7), "offset"),
        ("NaN offset", Surface::plane(Vector3::z(), f64::NAN), "offset"),
        (
            "no first- or second-order term",
            Surface::quadric([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]),
            "coefficients",
        ),
        (
            "NaN coefficient",
            Surface::quadric([f64::NAN, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]),
            "coefficients",
        ),
        (
            "huge coefficient",
            Surface::quadric([1e13, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]),
            "coefficients",
        ),
        (
            "torus axis zero",
            Surface::torus(Vector3::zeros(), Vector3::zeros(), 1.0, 0.5),
            "axis",
        ),
        (
            "torus centre NaN",
            Surface::torus(Vector3::new(f64::NAN, 0.0, 0.0), Vector3::z(), 1.0, 0.5),
            "centre",
        ),
        (
            "torus centre beyond 1e6 m",
            Surface::torus(Vector3::new(0.0, -3e6, 0.0), Vector3::z(), 1.0, 0.5),
            "centre",
        ),
        (
            "torus minor radius zero",
            Surface::torus(Vector3::zeros(), Vector3::z(), 1.0, 0.0),
            "minor_radius",
        ),
        (
            "torus major radius negative",
            Surface::torus(Vector3::zeros(), Vector3::z(), -1.0, 0.5),
            "major_radius",
        ),
        (
            "horn torus",
            Surface::torus(Vector3::zeros(), Vector3::z(), 1.0, 1.0),
            "minor_radius",
        ),
        (
            "spindle torus",
            Surface::torus(Vector3::zeros(), Vector3::z(), 1.0, 2.0),
            "minor_radius",
        ),
    ];
    for (label, result, parameter) in cases {
        match result {
            Err(error) => {
                assert_eq!(error.parameter, parameter, "{label}: {error}");
                assert!(
                    error.to_string().starts_with(&format!("surface {parameter}: ")),
                    "{label}: {error}"
                );
            }
            Ok(surface) => panic!("{label}: built {surface:?}"),
        }
    }
    let sphere = Surface::ellipsoid(unit, &at).unwrap();
    // A motor that is not a rigid motion: scaled, NaN, infinite.
    let along = dynamics::motor::translator::<Pga>(Vector3::x());
    for (label, motor) in [
        ("scaled motor", along * 2.0),
        ("NaN motor", along * f64::NAN),
        ("infinite motor", along * f64::INFINITY),
    ] {
        let error = sphere.moved::<Pga>(motor).unwrap_err();
        assert_eq!(error.parameter, "motor", "{label}: {error}");
        assert!(error.reason.contains("not a rigid motion"), "{label}: {error}");
    }
    for (label, body_point) in [
        ("NaN body point", Vector3::new(f64::NAN, 0.0, 0.0)),
        ("infinite body point", Vector3::new(0.0, f64::INFINITY, 0.0)),
        ("body point beyond 1e6 m", Vector3::new(0.0, 0.0, 2e6)),
    ] {
        for error in [
            SurfacePin::point_on_surface("bead", body_point, sphere).unwrap_err(),
            SurfacePin::point_on_curve("bead", body_point, [sphere, sphere]).unwrap_err(),
            VirtualPower::<Pga>::point_on_surface("bead", body_point, sphere).unwrap_err(),
            VirtualPower::<Pga>::point_on_curve("bead", body_point, [sphere, sphere]).unwrap_err(),
        ] {
            assert!(
                matches!(&error, ConstraintError::InvalidParameter { name, reason } if name == "bead" && reason.contains("body point")),
                "{label}: {error}"
            );
        }
    }
}
