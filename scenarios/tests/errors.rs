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
