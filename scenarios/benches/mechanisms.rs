//! CPU time of one step of the mechanisms of docs/scenes.md, per algebra, joint formulation and integrator, with
//! projection onto the joints after each step: M1 (double pendulum), M2 (four-bar linkage, a redundant loop) and
//! M3 (chains of N ball-jointed links, N = 1 … 64, with projection and with Baumgarte stabilisation), from a state
//! 0.2 s into the motion. MuJoCo's RK4 steps on the same scenes are measured beside these with
//! `tools/anchors/measure` (see docs/benchmarks.md).
//!
//! `cargo bench -p scenarios --bench mechanisms [-- FILTER]`, e.g. `-- M3` for the chains only.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dynamics::constraints::{PinningAlgebra, Stabilisation};
use dynamics::{Cga, Method, Pga, State, Stepper};
use reference::multibody::CHAIN_LENGTHS;
use scenarios::{build_mechanism, Formulation, MechanismId, MechanismScene};

/// The scene advanced 0.2 s with RK4 at dt = 1e-3 (away from the symmetric start).
fn advanced<A: PinningAlgebra>(scene: &MechanismScene<A>) -> Vec<State<A>> {
    let mut state = scene.initial.clone();
    let mut stepper = Stepper::new(&scene.system, Method::Rk4).expect("a general method");
    for k in 0..200 {
        stepper.step(k as f64 * 1e-3, &mut state, 1e-3).expect("the scene runs");
    }
    state
}

/// One step of `method` from `state`, per iteration.
fn bench_step<A: PinningAlgebra>(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: impl Into<String>,
    scene: &MechanismScene<A>,
    method: Method,
    dt: f64,
) {
    let state = advanced(scene);
    let mut stepper = Stepper::new(&scene.system, method).expect("a general method");
    c.bench_function(id.into(), |b| {
        b.iter(|| {
            let mut states = state.clone();
            stepper.step(black_box(0.2), &mut states, black_box(dt)).unwrap();
            states
        })
    });
}

fn scenes<A: PinningAlgebra>(c: &mut Criterion) {
    for (id, dt) in [(MechanismId::DoublePendulum, 2e-3), (MechanismId::FourBar, 2e-3)] {
        let mut group = c.benchmark_group(format!("{}/{}", A::NAME, id.label()));
        for formulation in Formulation::ALL {
            let scene = build_mechanism::<A>(id, formulation, Stabilisation::PROJECTION).expect("the scene builds");
            for method in [Method::Rk4, Method::Rkmk4Body, Method::Rkmk6Body, Method::Rkmk8Body] {
                bench_step(
                    &mut group,
                    format!("{}/{}", formulation.name(), method.name()),
                    &scene,
                    method,
                    dt,
                );
            }
            // The eighth-order method at the step where it meets MuJoCo's M1 accuracy (about 2.6e-2, the main
            // job's sweep): a longer step leaves the stages further from the joint manifold, so it may cost more.
            if id == MechanismId::DoublePendulum {
                let name = format!("{}/{} at dt = 2.5e-2", formulation.name(), Method::Rkmk8Body.name());
                bench_step(&mut group, name, &scene, Method::Rkmk8Body, 2.5e-2);
            }
        }
        group.finish();
    }
}

fn chains<A: PinningAlgebra>(c: &mut Criterion) {
    for (name, stabilisation) in [
        ("projection", Stabilisation::PROJECTION),
        (
            "baumgarte",
            Stabilisation::Baumgarte {
                alpha: 10.0,
                beta: 10.0,
            },
        ),
    ] {
        let mut group = c.benchmark_group(format!("{}/M3 chain, RK4, {name}", A::NAME));
        for n in CHAIN_LENGTHS {
            let scene = build_mechanism::<A>(MechanismId::Chain(n), Formulation::VirtualPower, stabilisation)
                .expect("the chain builds");
            let state = advanced(&scene);
            let mut stepper = Stepper::new(&scene.system, Method::Rk4).expect("a general method");
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| {
                    let mut states = state.clone();
                    stepper.step(black_box(0.2), &mut states, black_box(1e-3)).unwrap();
                    states
                })
            });
        }
        group.finish();
    }
}

fn all(c: &mut Criterion) {
    scenes::<Pga>(c);
    scenes::<Cga>(c);
    chains::<Pga>(c);
    chains::<Cga>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    targets = all
}
criterion_main!(benches);
