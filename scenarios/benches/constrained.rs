//! CPU time of one constrained step (with projection) of each constrained reference scene (docs/scenes.md 2–4), per
//! algebra, formulation and general integrator, from a state one second into the scene. MuJoCo 4.0's RK4 step
//! on the same scenes and machine took 3.9–4.8 µs (recorded on 2026-11-22).
//!
//! `cargo bench -p scenarios --bench constrained [-- FILTER]`, e.g. `-- PGA` for PGA only.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::constraints::Stabilisation;
use dynamics::{Cga, Method, Pga, Stepper};
use reference::SceneId;
use scenarios::{build, Formulation, SceneAlgebra, SceneError};

const SCENES: [SceneId; 4] = [
    SceneId::Pendulum,
    SceneId::TopCusp,
    SceneId::RodOnSphere,
    SceneId::RodOnCircle,
];

fn bench_algebra<A: SceneAlgebra>(c: &mut Criterion) {
    let dt = 1e-3;
    for id in SCENES {
        for formulation in Formulation::ALL {
            let scene = match build::<A>(id, formulation, Stabilisation::PROJECTION) {
                Ok(scene) => scene,
                Err(SceneError::NotExpressible { .. }) => continue,
                Err(error) => panic!("scene {} does not build: {error}", id.label()),
            };
            let system = &scene.system;
            let mut state = [scene.initial];
            let mut stepper = Stepper::new(system, Method::Rk4).expect("a general method");
            for k in 0..1000 {
                stepper.step(k as f64 * dt, &mut state, dt).expect("the scene runs");
            }
            let mut group = c.benchmark_group(format!("{}/{}/{}", A::NAME, id.label(), formulation.name()));
            for method in Method::ALL {
                let mut stepper = Stepper::new(system, method).expect("a general method");
                group.bench_function(method.name(), |b| {
                    b.iter(|| {
                        let mut states = state;
                        stepper.step(black_box(1.0), &mut states, black_box(dt)).unwrap();
                        states
                    })
                });
            }
            group.finish();
        }
    }
}

fn steps(c: &mut Criterion) {
    bench_algebra::<Pga>(c);
    bench_algebra::<Cga>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    targets = steps
}
criterion_main!(benches);
