//! CPU per simulated second of a box held on a floor by its four bottom corners with friction (sticking: twelve rows
//! held exactly), against the same box without contact (falling freely), both by DOP853-body at the same tolerance,
//! and of a box sliding on the floor (four held corners, friction tilting their rows). The ratio is what holding a
//! resting body exactly costs over moving it freely; the resting box with each corner listed 100 times, what repeated
//! contacts cost (docs/contacts.md "Repeated and dependent contacts"). A cube resting on a heavy box by its four corners on the box's
//! face, against the same cube kept on it by all 240 feature pairs of the two boxes: what the pairs that switch cost.
//!
//! `cargo bench -p dynamics --bench contact`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::contacts::{Friction, PlaneContact, Polyhedron};
use dynamics::{simulate, Body, Force, Mechanism, Method, Pga, Schedule, State, Tolerance};
use nalgebra::{UnitQuaternion, Vector3};

/// A 0.2 m cube of 1 kg under gravity, with its four bottom corners on the floor z = 0 (friction 0.5), each listed
/// `copies` times (none: no contact).
fn cube(copies: usize) -> (Mechanism<Pga>, Body) {
    let body = Body::cuboid(1.0, Vector3::repeat(0.2)).expect("positive sides");
    let mut system = Mechanism::<Pga>::new();
    let id = system.add_body("cube", body).expect("a new name");
    system.add_force(id, Force::gravity()).expect("a body");
    for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]
        .into_iter()
        .enumerate()
    {
        let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.0)
            .expect("a plane")
            .with_friction(Friction::coulomb(0.5).expect("a coefficient"));
        for copy in 0..copies {
            system
                .add_contact(format!("corner {k} copy {copy}"), id, corner)
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
    for (name, copies, velocity) in [
        ("free fall (no contact)", 0, Vector3::zeros()),
        ("resting on four sticking corners", 1, Vector3::zeros()),
        (
            "resting on four sticking corners, each listed 100 times",
            100,
            Vector3::zeros(),
        ),
        ("sliding on four corners", 1, Vector3::x() * 3.0),
    ] {
        let (system, body) = cube(copies);
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
    let mut group = c.benchmark_group("contact/a cube resting on a heavy box, one simulated second, DOP853-body 1e-10");
    group.sample_size(20).measurement_time(Duration::from_secs(5));
    for (name, every_pair) in [
        ("its four bottom corners on the box's top face", false),
        ("all 240 vertex-face and edge-edge pairs", true),
    ] {
        let (system, start) = cube_on_a_box(every_pair);
        group.bench_function(name, |b| {
            b.iter(|| simulate(black_box(&system), &start, Method::Dop853Body, &schedule).expect("the cube runs"))
        });
    }
    group.finish();
}

/// The cube of [`cube`] (friction 0.5) resting on the middle of a 0.6 m × 0.6 m × 0.2 m box of 1e15 kg without
/// gravity, by its four bottom corners on the box's top face, or by every feature pair of the two
/// (`Mechanism::add_polyhedron_contacts`): what watching the pairs that do not touch costs.
fn cube_on_a_box(every_pair: bool) -> (Mechanism<Pga>, [State<Pga>; 2]) {
    let (cube, ledge) = (Vector3::repeat(0.2), Vector3::new(0.6, 0.6, 0.2));
    let mut system = Mechanism::<Pga>::new();
    let top = system
        .add_body("cube", Body::cuboid(1.0, cube).expect("sides"))
        .expect("a name");
    let below = system
        .add_body("box", Body::cuboid(1e15, ledge).expect("sides"))
        .expect("a name");
    system.add_force(top, Force::gravity()).expect("a body");
    let friction = Friction::coulomb(0.5).expect("a coefficient");
    if every_pair {
        let shapes = (
            Polyhedron::cuboid(cube).expect("sides"),
            Polyhedron::cuboid(ledge).expect("sides"),
        );
        system
            .add_polyhedron_contacts(
                "pair",
                (top, &shapes.0, "cube"),
                (below, &shapes.1, "box"),
                friction,
                0.0,
            )
            .expect("two boxes");
    } else {
        for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]
            .into_iter()
            .enumerate()
        {
            let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.1)
                .expect("a plane")
                .with_friction(friction);
            system
                .add_contact_on(format!("corner {k}"), top, below, corner)
                .expect("a contact");
        }
    }
    let at = |body: Body, z: f64| {
        State::<Pga>::from_world_twist(
            &body,
            Vector3::z() * z,
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::zeros(),
        )
    };
    let start = [
        at(Body::cuboid(1.0, cube).expect("sides"), 0.2),
        at(Body::cuboid(1e15, ledge).expect("sides"), 0.0),
    ];
    (system, start)
}

criterion_group!(benches, contact);
criterion_main!(benches);
