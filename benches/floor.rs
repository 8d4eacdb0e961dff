//! The compiler at the floor, in one criterion run:
//! - PGA motor × motor (48 multiplies): generated, in the canonical and in dual-quaternion field
//!   order, against a hand-written dual-quaternion kernel and nalgebra's `Isometry3 * Isometry3`;
//! - a unit PGA motor applied to a point: the generated `transform` and `sandwich` (their multiply counts are
//!   in their doc comments, asserted by ga-macros' doc tests) against nalgebra's `Isometry3 * Point3`;
//! - CGA on the null basis (n0 · ninf = −1), whose rigid motors have PGA's 8 coefficients: motor ×
//!   motor against PGA's.
//!
//! Each benchmark maps a batch of 1024 inputs into a reused output buffer (`black_box` on inputs and
//! outputs), so 1/throughput is the time per operation. The setup checks that the compared
//! implementations compute the same rigid motions.
//!
//! ```sh
//! cargo bench --bench floor
//! ```

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use nalgebra::{Isometry3, Point3};

mod common;
use common::{assert_close, time_batch, Random, BATCH};

ga_macros::algebra! {
    /// PGA Cl(3,0,1), e0 first.
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Point = grades(3);
            Motor = grades(0, 2, 4);
            Multivector = all;
        }
        ops = [geometric, sandwich, transform];
    }
}

ga_macros::algebra! {
    /// CGA on e1, e2, e3 and the null vectors n0, ninf.
    mod cga {
        scalar = f64;
        basis = [e1, e2, e3, n0, ninf];
        metric = [
            [1, 0, 0, 0, 0],
            [0, 1, 0, 0, 0],
            [0, 0, 1, 0, 0],
            [0, 0, 0, 0, -1],
            [0, 0, 0, -1, 0],
        ];
        types {
            Vector = grades(1);
            Motor = blades(scalar, e1_e2, e1_e3, e2_e3, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf);
            Multivector = all;
        }
        ops = [geometric, transform];
    }
}

ga_macros::algebra! {
    /// The same PGA with the motor in dual-quaternion order (real quaternion, then its e0123
    /// multiple): LLVM packs all 48 multiplies of this order into 24 two-lane `mulpd` (the canonical
    /// order gets 18 `mulpd` + 12 `mulsd`); the benchmark shows whether that pays.
    mod pga_lanes {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Point = blades(e123, e023, e013, e012);
            Motor = blades(scalar, e23, e13, e12, e0123, e01, e02, e03);
            Multivector = all;
        }
        ops = [geometric, sandwich, transform];
    }
}

/// The unit PGA motor of an isometry: translator × rotor. With e0 first, the quaternion units are
/// i = e23, j = e13, k = e12 (so i j k = −1), and a rotation q v q* of the point's ideal part is the
/// sandwich by w − x e23 − y e13 − z e12 (the reverse of the quaternion's image).
fn pga_motor(isometry: &Isometry3<f64>) -> pga::Motor {
    let q = isometry.rotation.quaternion();
    let rotor = pga::Motor {
        scalar: q.w,
        e23: -q.i,
        e13: q.j,
        e12: -q.k,
        ..pga::Motor::ZERO
    };
    let t = isometry.translation.vector;
    let translator = pga::Motor {
        scalar: 1.0,
        e01: -t.x / 2.0,
        e02: -t.y / 2.0,
        e03: -t.z / 2.0,
        ..pga::Motor::ZERO
    };
    translator.geometric_motor(rotor)
}

fn dual_quaternion_order(m: pga::Motor) -> pga_lanes::Motor {
    pga_lanes::Motor {
        scalar: m.scalar,
        e23: m.e23,
        e13: m.e13,
        e12: m.e12,
        e0123: m.e0123,
        e01: m.e01,
        e02: m.e02,
        e03: m.e03,
    }
}

/// x e032 + y e013 + z e021 + e123.
fn pga_point(p: &Point3<f64>) -> pga::Point {
    pga::Point {
        e012: -p.z,
        e013: p.y,
        e023: -p.x,
        e123: 1.0,
    }
}

fn pga_coordinates(p: pga::Point) -> [f64; 3] {
    [-p.e023 / p.e123, p.e013 / p.e123, -p.e012 / p.e123]
}

/// The hand-written kernel: a motor as the dual quaternion `real + ε dual`, each a `[w, i, j, k]`
/// array, multiplied as (a + ε b)(c + ε d) = ac + ε (ad + bc): three Hamilton products.
#[derive(Clone, Copy, Debug)]
struct DualQuaternion {
    real: [f64; 4],
    dual: [f64; 4],
}

#[inline(always)]
fn hamilton(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

impl DualQuaternion {
    /// The motor s + r + t + p I as a dual quaternion: I = e0123 is ε, and e01 = −I i, e02 = I j,
    /// e03 = −I k.
    fn from_motor(m: pga::Motor) -> Self {
        DualQuaternion {
            real: [m.scalar, m.e23, m.e13, m.e12],
            dual: [m.e0123, -m.e01, m.e02, -m.e03],
        }
    }

    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        let (a, b) = (hamilton(self.real, other.dual), hamilton(self.dual, other.real));
        DualQuaternion {
            real: hamilton(self.real, other.real),
            dual: [a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]],
        }
    }
}

fn motor_times_motor(c: &mut Criterion) {
    let mut random = Random(11);
    let isometries: Vec<(Isometry3<f64>, Isometry3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.isometry())).collect();
    let motors: Vec<(pga::Motor, pga::Motor)> = isometries.iter().map(|(a, b)| (pga_motor(a), pga_motor(b))).collect();
    let kernels: Vec<(DualQuaternion, DualQuaternion)> = motors
        .iter()
        .map(|&(a, b)| (DualQuaternion::from_motor(a), DualQuaternion::from_motor(b)))
        .collect();
    let probe = Point3::new(0.3, -1.7, 2.9);
    for ((&(a, b), &(x, y)), (i, j)) in motors.iter().zip(&kernels).zip(&isometries) {
        let product = a.geometric_motor(b);
        let (mapped, kernel) = (DualQuaternion::from_motor(product), x.mul(y));
        assert_close(&mapped.real, &kernel.real, "the kernel's real part");
        assert_close(&mapped.dual, &kernel.dual, "the kernel's dual part");
        let expected = i * j * probe;
        let moved = pga_coordinates(product.transform_point(pga_point(&probe)));
        assert_close(
            &moved,
            &[expected.x, expected.y, expected.z],
            "motor product = isometry product",
        );
    }

    let reordered: Vec<(pga_lanes::Motor, pga_lanes::Motor)> = motors
        .iter()
        .map(|&(a, b)| (dual_quaternion_order(a), dual_quaternion_order(b)))
        .collect();
    for (&(a, b), &(x, y)) in motors.iter().zip(&reordered) {
        let (product, reordered_product) = (a.geometric_motor(b), x.geometric_motor(y));
        assert_close(
            &dual_quaternion_order(product).to_array(),
            &reordered_product.to_array(),
            "field order",
        );
    }

    let mut group = c.benchmark_group("floor_pga_motor_times_motor");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated", &motors, |(a, b)| a.geometric_motor(b));
    time_batch(&mut group, "generated_dual_quaternion_order", &reordered, |(a, b)| {
        a.geometric_motor(b)
    });
    time_batch(&mut group, "hand_written_dual_quaternion", &kernels, |(a, b)| a.mul(b));
    time_batch(&mut group, "nalgebra_isometry", &isometries, |(a, b)| a * b);
    group.finish();
}

fn motor_on_point(c: &mut Criterion) {
    let mut random = Random(12);
    let isometries: Vec<(Isometry3<f64>, Point3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.point())).collect();
    let generated: Vec<(pga::Motor, pga::Point)> =
        isometries.iter().map(|(m, p)| (pga_motor(m), pga_point(p))).collect();
    for (&(m, p), (isometry, point)) in generated.iter().zip(&isometries) {
        let expected = isometry * point;
        let expected = [expected.x, expected.y, expected.z];
        assert_close(&pga_coordinates(m.transform_point(p)), &expected, "transform");
        assert_close(&pga_coordinates(m.sandwich_point(p)), &expected, "sandwich");
    }

    let mut group = c.benchmark_group("floor_pga_motor_on_point");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated_transform", &generated, |(m, p)| {
        m.transform_point(p)
    });
    time_batch(&mut group, "generated_sandwich", &generated, |(m, p)| {
        m.sandwich_point(p)
    });
    time_batch(&mut group, "nalgebra_isometry", &isometries, |(m, p)| m * p);
    group.finish();
}

fn null_cga_against_pga(c: &mut Criterion) {
    let mut random = Random(13);
    let mut array = || random.array();
    let pga_motors: Vec<(pga::Motor, pga::Motor)> = (0..BATCH)
        .map(|_| (pga::Motor::from_array(array()), pga::Motor::from_array(array())))
        .collect();
    let cga_motors: Vec<(cga::Motor, cga::Motor)> = (0..BATCH)
        .map(|_| (cga::Motor::from_array(array()), cga::Motor::from_array(array())))
        .collect();

    let mut group = c.benchmark_group("floor_motor_times_motor_null_cga_vs_pga");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "pga", &pga_motors, |(a, b)| a.geometric_motor(b));
    time_batch(&mut group, "null_basis_cga", &cga_motors, |(a, b)| a.geometric_motor(b));
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = floor;
    config = config();
    targets = motor_times_motor, motor_on_point, null_cga_against_pga
}
criterion_main!(floor);
