//! Each body-momentum method converges at its order, seen by self-convergence where no reference is accurate
//! enough: a tumbling cuboid thrown under gravity, 2 s, steps h, h/2, h/4; the observed order is
//! `log₂(|x_h − x_{h/2}| / |x_{h/2} − x_{h/4}|)` for the end orientation and position. RKMK8-body in particular:
//! on the reference scenes it is below the references' floor at the longest step their sample grid allows.
//!
//! Measured (`cargo test --release -p dynamics --test integration orders:: -- --nocapture`), PGA and CGA alike: RKMK4-body
//! 4.00 (h = 2e-2), RKMK6-body 5.99 (h = 4e-2), RKMK8-body 7.97 (h = 8e-2; differences 3.8e-7 and 1.5e-9).

use dynamics::{Algebra, Body, Cga, Force, FreeBody, Method, Pga, State, Stepper};
use nalgebra::{UnitQuaternion, Vector3};

/// The end pose after 2 s with steps of `dt`.
fn end_pose<A: Algebra>(method: Method, dt: f64) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let body = Body::cuboid(2.0, Vector3::new(0.3, 0.6, 1.1)).unwrap();
    let system = FreeBody::<A>::new(body).with_force(Force::gravity());
    let mut states = [State::<A>::new(
        &body,
        Vector3::new(0.4, -0.3, 0.2),
        &UnitQuaternion::from_euler_angles(0.3, -0.2, 0.9),
        Vector3::new(0.05, 4.0, 0.1),
        Vector3::new(1.0, 0.5, 3.0),
    )];
    let mut stepper = Stepper::new(&system, method).unwrap();
    let steps = (2.0 / dt).round() as usize;
    for k in 0..steps {
        stepper.step(k as f64 * dt, &mut states, dt).unwrap();
    }
    states[0].pose()
}

fn observed_order<A: Algebra>(method: Method, h: f64) -> f64 {
    let [coarse, middle, fine] = [h, h / 2.0, h / 4.0].map(|dt| end_pose::<A>(method, dt));
    let difference = |a: &(Vector3<f64>, UnitQuaternion<f64>), b: &(Vector3<f64>, UnitQuaternion<f64>)| {
        (a.0 - b.0).norm().max(a.1.angle_to(&b.1))
    };
    let (first, second) = (difference(&coarse, &middle), difference(&middle, &fine));
    let order = (first / second).log2();
    println!(
        "{} {}: differences {first:.2e}, {second:.2e}, order {order:.2}",
        A::NAME,
        method.name()
    );
    order
}

fn orders<A: Algebra>() {
    for (method, h) in [
        (Method::Rkmk4Body, 2e-2),
        (Method::Rkmk6Body, 4e-2),
        (Method::Rkmk8Body, 8e-2),
    ] {
        let order = observed_order::<A>(method, h);
        let expected = method.order() as f64;
        assert!(
            (order - expected).abs() < 0.3,
            "{}: observed order {order:.2}",
            method.name()
        );
    }
}

#[test]
fn body_momentum_methods_converge_at_their_order_pga() {
    orders::<Pga>();
}

#[test]
fn body_momentum_methods_converge_at_their_order_cga() {
    orders::<Cga>();
}
