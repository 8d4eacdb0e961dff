//! CPU time of one step of each integrator in each algebra, for the free cuboid of scene 1 (docs/scenes.md), and of
//! the same body as a one-body `Mechanism` without joints (the general path every mechanism takes).
//!
//! `cargo bench -p dynamics --bench step`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::{Algebra, Body, Cga, FreeBody, Integrator, Mechanism, Method, Pga, State, Stepper};
use nalgebra::{UnitQuaternion, Vector3};

/// Scene 1's body, and a state of it one second into its motion (a generic orientation and position, away
/// from the identity motor of t = 0).
fn scene_1<A: Algebra>() -> (Body, State<A>) {
    let body = Body::cuboid(1.0, Vector3::new(1.0, 2.0, 3.0)).expect("positive sides");
    let system = FreeBody::new(body);
    let mut state = [State::<A>::new(
        &body,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::new(0.1, 10.0, 0.0),
        Vector3::new(1.0, 0.5, 0.0),
    )];
    let mut stepper = Stepper::new(&system, Method::Rk4).expect("a general method");
    for k in 0..1000 {
        stepper
            .step(k as f64 * 1e-3, &mut state, 1e-3)
            .expect("a free body steps");
    }
    (body, state[0])
}

fn bench_algebra<A: Algebra>(c: &mut Criterion) {
    let (body, state) = scene_1::<A>();
    let system = FreeBody::<A>::new(body);
    let mechanism = Mechanism::<A>::single(body);
    let mut group = c.benchmark_group(format!("step/{}", A::NAME));
    for integrator in Integrator::ALL {
        let mut stepper = Stepper::new(&system, integrator).expect("every integrator applies to a free body");
        group.bench_function(integrator.name(), |b| {
            b.iter(|| {
                let mut states = [state];
                stepper.step(black_box(1.0), &mut states, black_box(1e-3)).unwrap();
                states
            })
        });
    }
    let mut stepper = Stepper::new(&mechanism, Method::Rkmk4Body).expect("a general method");
    group.bench_function("RKMK4-body (one-body mechanism)", |b| {
        b.iter(|| {
            let mut states = [state];
            stepper.step(black_box(1.0), &mut states, black_box(1e-3)).unwrap();
            states
        })
    });
    group.finish();
}

fn steps(c: &mut Criterion) {
    bench_algebra::<Pga>(c);
    bench_algebra::<Cga>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    targets = steps
}
criterion_main!(benches);
