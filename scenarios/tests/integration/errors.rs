//! The reference scenes' own errors are reached (every error variant has a test): a scene asked for
//! in a formulation its algebra cannot write, and a run measured at a time the reference does not have.

use dynamics::constraints::Stabilisation;
use dynamics::simulate::Sample;
use dynamics::{Cga, Pga};
use nalgebra::{UnitQuaternion, Vector3};
use reference::SceneId;
use scenarios::mechanism_measures::{measure, MeasureError};
use scenarios::{build, Formulation, MechanismId, SceneError};

#[test]
fn a_sphere_pin_is_not_expressible_in_pga() {
    let Err(error) = build::<Pga>(SceneId::RodOnSphere, Formulation::Pinning, Stabilisation::None) else {
        panic!("PGA has no spheres to pin");
    };
    assert!(
        matches!(error, SceneError::NotExpressible { algebra: "PGA", .. }),
        "{error}"
    );
    // The same scene in CGA builds.
    assert!(build::<Cga>(SceneId::RodOnSphere, Formulation::Pinning, Stabilisation::None).is_ok());
}

#[test]
fn a_run_off_the_reference_grid_cannot_be_measured() {
    let sample = |t: f64| Sample {
        t,
        position: Vector3::zeros(),
        orientation: UnitQuaternion::identity(),
        velocity: Vector3::zeros(),
        angular_velocity: Vector3::zeros(),
        energy: 0.0,
        work: 0.0,
    };
    let bodies = vec![vec![sample(0.0), sample(0.005)]; MechanismId::DoublePendulum.bodies()];
    let error = measure(MechanismId::DoublePendulum, &bodies).unwrap_err();
    assert!(matches!(error, MeasureError::NoReferenceAt(t) if t == 0.005), "{error}");
}

/// A step too large for a mechanism is named as such, with a step that works, never as a joint's rank deficiency
/// or a constraint that "cannot hold together": the four-bar at dt = 0.1 and 0.5 (its reference step is 2e-3),
/// stiff Baumgarte gains, a body spinning at 1e6 rad/s.
#[test]
fn a_step_too_large_for_a_mechanism_is_named_with_a_step_that_works() {
    use dynamics::{Dynamics, Method, StepError, Stepper};
    for method in [Method::Rk4, Method::Rkmk6Body] {
        for dt in [0.1, 0.5] {
            let scene = scenarios::build_mechanism::<Pga>(
                MechanismId::FourBar,
                Formulation::VirtualPower,
                Stabilisation::PROJECTION,
            )
            .unwrap();
            let mut states = scene.initial.clone();
            let mut stepper = Stepper::new(&scene.system, method).unwrap();
            let outcome = (0..200).try_for_each(|k| stepper.step(k as f64 * dt, &mut states, dt));
            match outcome {
                Err(StepError::ConstraintStepTooLarge { dt: refused, works, .. }) => {
                    assert_eq!(refused, dt);
                    assert!(works < dt);
                    let mut retried = states.clone();
                    stepper.step(0.0, &mut retried, works).unwrap();
                }
                Err(StepError::StepTooLarge { .. }) => {}
                other => panic!("{method:?} at dt = {dt}: {other:?}"),
            }
        }
    }

    let stiff = Stabilisation::Baumgarte { alpha: 1e4, beta: 1e4 };
    let scene = scenarios::build_mechanism::<Pga>(MechanismId::FourBar, Formulation::VirtualPower, stiff).unwrap();
    let mut states = scene.initial.clone();
    let mut stepper = Stepper::new(&scene.system, Method::Rkmk6Body).unwrap();
    let error = stepper.step(0.0, &mut states, 2e-3).unwrap_err();
    assert!(
        matches!(error, StepError::FeedbackStepTooLarge { rate, .. } if rate == 1e4),
        "{error}"
    );
    assert!(error.to_string().contains("take a step below 2.500e-4"), "{error}");
    stepper.step(0.0, &mut states, 2e-4).unwrap();
    let mut system = scene.system.clone();
    for gain in [1e7, 1e300, f64::INFINITY] {
        let refused = system
            .set_stabilisation(Stabilisation::Baumgarte {
                alpha: 10.0,
                beta: gain,
            })
            .unwrap_err();
        assert!(refused.to_string().contains("at most 1e6"), "{refused}");
    }

    let scene = scenarios::build_mechanism::<Pga>(
        MechanismId::DoublePendulum,
        Formulation::VirtualPower,
        Stabilisation::PROJECTION,
    )
    .unwrap();
    let mut states = scene.initial.clone();
    let body = *scene.system.body(0);
    let (position, orientation) = states[0].pose();
    let spin = orientation.inverse_transform_vector(&Vector3::new(1e6, 0.0, 0.0));
    states[0] = dynamics::State::new(&body, position, &orientation, spin, Vector3::zeros());
    let error = Stepper::new(&scene.system, Method::Rkmk6Body)
        .unwrap()
        .step(0.0, &mut states, 1e-3)
        .unwrap_err();
    assert!(matches!(error, StepError::StepTooLarge { body: 0, .. }), "{error}");
}

/// Careless offsets for a moved mechanism (`scenarios::build_mechanism_at`): a non-finite one, or one beyond
/// `dynamics::state::LARGEST_COORDINATE`, is refused as an offset (not as a joint that cannot hold), never a panic; a
/// finite one within reach builds, wrong length being impossible by type.
#[test]
fn careless_mechanism_offsets_are_refused_naming_the_cause() {
    use scenarios::build_mechanism_at;
    for id in [MechanismId::DoublePendulum, MechanismId::FourBar, MechanismId::Chain(2)] {
        let build =
            |offset| build_mechanism_at::<Pga>(id, Formulation::VirtualPower, Stabilisation::PROJECTION, offset);
        for value in [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e300, -1e300, 1.5e6] {
            for offset in [Vector3::new(value, 0.0, 0.0), Vector3::new(0.0, 0.0, value)] {
                let error = build(offset).map(drop).unwrap_err();
                assert!(
                    matches!(error, SceneError::Offset { .. }) && error.to_string().contains("must be finite"),
                    "{id:?} at {offset:?}: {error}"
                );
            }
        }
        for value in [0.0, -1e3, 1e4, 1e6] {
            let offset = Vector3::new(value, -value, 0.0);
            assert!(build(offset).is_ok(), "{id:?} at {value}");
        }
    }
}
