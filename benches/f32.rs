//! Our PGA at `scalar = f32` against the `geometric_algebra` crate (0.3, SIMD `Simd32x4` groups), in
//! one criterion run:
//! - PGA motor × motor: our `geometric_motor` against its `Motor::geometric_product(Motor)`;
//! - a PGA motor applied to a point: our `sandwich` (any motor) and `transform` (unit motors) against
//!   its `Motor::transformation(Point)` (a general sandwich, `m p ~m`).
//!
//! Each benchmark maps a batch of 1024 inputs into a reused output buffer (`black_box` on inputs and
//! outputs). The setup checks that both libraries compute the same rigid motions as nalgebra's
//! `Isometry3` (in f64), after mapping the blade conventions.
//!
//! ```sh
//! cargo bench --bench f32
//! ```

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use geometric_algebra::ppga3d as ga;
use geometric_algebra::{GeometricProduct, Transformation};
use nalgebra::{Isometry3, Point3};

#[allow(dead_code)] // `assert_close` is for f64 results; single precision uses `assert_near` below
mod common;
use common::{time_batch, Random, BATCH};

ga_macros::algebra! {
    /// PGA Cl(3,0,1), e0 first, in single precision.
    mod pga {
        scalar = f32;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Point = grades(3);
            Motor = grades(0, 2, 4);
            Multivector = all;
        }
        ops = [geometric, sandwich, transform];
    }
}

/// The unit PGA motor of an isometry, translator × rotor (the conventions of `benches/floor.rs`).
fn pga_motor(isometry: &Isometry3<f64>) -> pga::Motor {
    let q = isometry.rotation.quaternion();
    let rotor = pga::Motor {
        scalar: q.w as f32,
        e23: -q.i as f32,
        e13: q.j as f32,
        e12: -q.k as f32,
        ..pga::Motor::ZERO
    };
    let t = isometry.translation.vector;
    let translator = pga::Motor {
        scalar: 1.0,
        e01: (-t.x / 2.0) as f32,
        e02: (-t.y / 2.0) as f32,
        e03: (-t.z / 2.0) as f32,
        ..pga::Motor::ZERO
    };
    translator.geometric_motor(rotor)
}

/// x e032 + y e013 + z e021 + e123.
fn pga_point(p: &Point3<f64>) -> pga::Point {
    pga::Point {
        e012: -p.z as f32,
        e013: p.y as f32,
        e023: -p.x as f32,
        e123: 1.0,
    }
}

fn pga_coordinates(p: pga::Point) -> [f64; 3] {
    [-p.e023 / p.e123, p.e013 / p.e123, -p.e012 / p.e123].map(f64::from)
}

/// The same motor in `geometric_algebra`'s layout: `[1, e23, -e13, e12, e0123, e01, e02, e03]`
/// (the same blades, e0 first, except that its third element is the coefficient of e31 = −e13).
fn their_motor(m: pga::Motor) -> ga::Motor {
    ga::Motor::new(m.scalar, m.e23, -m.e13, m.e12, m.e0123, m.e01, m.e02, m.e03)
}

/// The same point in `geometric_algebra`'s layout: `[e123, -e023, e013, -e012]`.
fn their_point(p: pga::Point) -> ga::Point {
    ga::Point::new(p.e123, -p.e023, p.e013, -p.e012)
}

fn their_coordinates(p: ga::Point) -> [f64; 3] {
    [p[1] / p[0], p[2] / p[0], p[3] / p[0]].map(f64::from)
}

/// Fails the benchmark if two single-precision results differ by more than `tolerance`.
fn assert_near(got: &[f64], expected: &[f64], tolerance: f64, what: &str) {
    let error = got.iter().zip(expected).map(|(g, e)| (g - e).abs()).fold(0.0, f64::max);
    assert!(error < tolerance, "{what}: got {got:?}, expected {expected:?}");
}

/// A rotation by π/2 about z then a translation by (1, 2, 3): (1, 0, 0) goes to (1, 3, 3) in both.
fn check_known_motion() {
    let isometry = Isometry3::new(
        nalgebra::Vector3::new(1.0, 2.0, 3.0),
        nalgebra::Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2),
    );
    let (motor, point) = (pga_motor(&isometry), pga_point(&Point3::new(1.0, 0.0, 0.0)));
    let expected = [1.0, 3.0, 3.0];
    assert_near(
        &pga_coordinates(motor.sandwich_point(point)),
        &expected,
        1e-5,
        "ours, known motion",
    );
    let theirs = their_motor(motor).transformation(their_point(point));
    assert_near(
        &their_coordinates(theirs),
        &expected,
        1e-5,
        "geometric_algebra, known motion",
    );
}

fn motor_times_motor(c: &mut Criterion) {
    check_known_motion();
    let mut random = Random(21);
    let isometries: Vec<(Isometry3<f64>, Isometry3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.isometry())).collect();
    let ours: Vec<(pga::Motor, pga::Motor)> = isometries.iter().map(|(a, b)| (pga_motor(a), pga_motor(b))).collect();
    let theirs: Vec<(ga::Motor, ga::Motor)> = ours.iter().map(|&(a, b)| (their_motor(a), their_motor(b))).collect();
    let probe = Point3::new(0.3, -1.7, 2.9);
    for ((&(a, b), &(x, y)), (i, j)) in ours.iter().zip(&theirs).zip(&isometries) {
        let (product, their_product) = (a.geometric_motor(b), x.geometric_product(y));
        let mapped: [f32; 8] = their_motor(product).into();
        let their_product: [f32; 8] = their_product.into();
        assert_near(
            &mapped.map(f64::from),
            &their_product.map(f64::from),
            1e-4,
            "motor product, ours = geometric_algebra",
        );
        let expected = i * j * probe;
        let expected = [expected.x, expected.y, expected.z];
        let moved = pga_coordinates(product.sandwich_point(pga_point(&probe)));
        assert_near(&moved, &expected, 1e-3, "our motor product = isometry product");
        let moved = their_coordinates(x.geometric_product(y).transformation(their_point(pga_point(&probe))));
        assert_near(
            &moved,
            &expected,
            1e-3,
            "geometric_algebra's motor product = isometry product",
        );
    }

    let mut group = c.benchmark_group("f32_pga_motor_times_motor");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated", &ours, |(a, b)| a.geometric_motor(b));
    time_batch(&mut group, "geometric_algebra", &theirs, |(a, b)| {
        a.geometric_product(b)
    });
    group.finish();
}

fn motor_on_point(c: &mut Criterion) {
    let mut random = Random(22);
    let isometries: Vec<(Isometry3<f64>, Point3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.point())).collect();
    let ours: Vec<(pga::Motor, pga::Point)> = isometries.iter().map(|(m, p)| (pga_motor(m), pga_point(p))).collect();
    let theirs: Vec<(ga::Motor, ga::Point)> = ours.iter().map(|&(m, p)| (their_motor(m), their_point(p))).collect();
    for ((&(m, p), &(x, q)), (isometry, point)) in ours.iter().zip(&theirs).zip(&isometries) {
        let expected = isometry * point;
        let expected = [expected.x, expected.y, expected.z];
        assert_near(&pga_coordinates(m.transform_point(p)), &expected, 1e-3, "transform");
        assert_near(&pga_coordinates(m.sandwich_point(p)), &expected, 1e-3, "sandwich");
        assert_near(
            &their_coordinates(x.transformation(q)),
            &expected,
            1e-3,
            "geometric_algebra",
        );
    }

    let mut group = c.benchmark_group("f32_pga_motor_on_point");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated_transform", &ours, |(m, p)| m.transform_point(p));
    time_batch(&mut group, "generated_sandwich", &ours, |(m, p)| m.sandwich_point(p));
    time_batch(&mut group, "geometric_algebra_transformation", &theirs, |(m, p)| {
        m.transformation(p)
    });
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = f32_against_geometric_algebra;
    config = config();
    targets = motor_times_motor, motor_on_point
}
criterion_main!(f32_against_geometric_algebra);
