//! CPU time of one step of each integrator in each algebra, for the free cuboid of scene 1 (SCENES.md).
//!
//! `cargo bench -p dynamics --bench step`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::{
    step, step_free_body, step_splitting, Algebra, Body, Cga, FreeBody, Integrator, KineticSplitting, Method, Pga,
    State,
};
use nalgebra::{UnitQuaternion, Vector3};

/// Scene 1's body, and a state of it one second into its motion (a generic orientation and position, away
/// from the identity motor of t = 0).
fn scene_1<A: Algebra>() -> (FreeBody<A>, State<A>) {
    let body = Body::cuboid(1.0, Vector3::new(1.0, 2.0, 3.0)).expect("positive sides");
    let system = FreeBody::new(body);
    let mut state = State::<A>::new(
        &body,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::new(0.1, 10.0, 0.0),
        Vector3::new(1.0, 0.5, 0.0),
    );
    for k in 0..1000 {
        state = step(Method::Rk4, &system, k as f64 * 1e-3, &state, 1e-3);
    }
    (system, state)
}

fn bench_algebra<A: Algebra>(c: &mut Criterion) {
    let (system, state) = scene_1::<A>();
    let splitting = KineticSplitting::new(&system).expect("a free body splits");
    let mut group = c.benchmark_group(format!("step/{}", A::NAME));
    // The generic path of RKMK4-body, for any system (the free body's own path is `step_free_body`).
    group.bench_function("RKMK4-body (generic path)", |b| {
        b.iter(|| {
            step(
                Method::Rkmk4Body,
                &system,
                black_box(1.0),
                black_box(&state),
                black_box(1e-3),
            )
        })
    });
    for integrator in Integrator::ALL {
        group.bench_function(integrator.name(), |b| match integrator {
            Integrator::General(method) => {
                b.iter(|| step_free_body(method, &system, black_box(1.0), black_box(&state), black_box(1e-3)))
            }
            Integrator::Splitting(method) => {
                b.iter(|| step_splitting(method, &splitting, black_box(1.0), black_box(&state), black_box(1e-3)))
            }
        });
    }
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
