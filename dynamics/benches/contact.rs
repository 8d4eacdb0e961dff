//! CPU per simulated second of a box held on a floor by its four bottom corners with friction (sticking: twelve rows
//! held exactly), against the same box without contact (falling freely), both by DOP853-body at the same tolerance,
//! and of a box sliding on the floor (four held corners, friction tilting their rows). The ratio is what holding a
//! resting body exactly costs over moving it freely.
//!
//! `cargo bench -p dynamics --bench contact`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::contacts::{Friction, PlaneContact};
use dynamics::{simulate, Body, Force, Mechanism, Method, Pga, Schedule, State, Tolerance};
use nalgebra::{UnitQuaternion, Vector3};

/// A 0.2 m cube of 1 kg under gravity, with its four bottom corners on the floor z = 0 (friction 0.5) if `held`.
fn cube(held: bool) -> (Mechanism<Pga>, Body) {
    let body = Body::cuboid(1.0, Vector3::repeat(0.2)).expect("positive sides");
    let mut system = Mechanism::<Pga>::new();
    let id = system.add_body("cube", body).expect("a new name");
    system.add_force(id, Force::gravity()).expect("a body");
    if held {
        for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]
            .into_iter()
            .enumerate()
        {
            let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.0)
                .expect("a plane")
                .with_friction(Friction::coulomb(0.5).expect("a coefficient"));
            system
                .add_contact(format!("corner {k}"), id, corner)
                .expect("a contact");
        }
    }
    (system, body)
}

fn contact(c: &mut Criterion) {
    let schedule =
        Schedule::adaptive(Tolerance::new(1e-10, 1e-10).expect("a tolerance"), 1.0, 0.1).expect("a schedule");
    let mut group = c.benchmark_group("contact/one simulated second, DOP853-body 1e-10");
    group.sample_size(20).measurement_time(Duration::from_secs(5));
    for (name, held, velocity) in [
        ("free fall (no contact)", false, Vector3::zeros()),
        ("resting on four sticking corners", true, Vector3::zeros()),
        ("sliding on four corners", true, Vector3::x() * 3.0),
    ] {
        let (system, body) = cube(held);
        let start = [State::<Pga>::from_world_twist(
            &body,
            Vector3::z() * 0.1,
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            velocity,
        )];
        group.bench_function(name, |b| {
            b.iter(|| simulate(black_box(&system), &start, Method::Dop853Body, &schedule).expect("the cube runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, contact);
criterion_main!(benches);
