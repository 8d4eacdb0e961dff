//! Generated PGA and CGA products against a hand-unrolled dual-quaternion baseline and nalgebra.
//!
//! Each benchmark maps a batch of 1024 random inputs into a preallocated output buffer; the
//! throughput is in operations, so 1/throughput is the time per operation. `black_box` hides the
//! inputs from the optimiser on every iteration (nothing is constant-folded or hoisted out of the
//! timing loop) and publishes the outputs (nothing is dead code).
//!
//! Before timing, the setup checks that the three implementations compute the same rigid motions,
//! so every row of a group measures the same work.
//!
//! ```sh
//! cargo bench --bench products
//! ```

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

mod common;
use common::{assert_close, time_batch, Random, BATCH};
use nalgebra::{Isometry3, Point3};

ga_macros::algebra! {
    /// PGA Cl(3,0,1), e0 first.
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Plane = grades(1);
            Line = grades(2);
            Point = grades(3);
            Motor = grades(0, 2, 4);
            Translator = blades(scalar, e01, e02, e03);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    /// CGA Cl(4,1).
    mod cga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1];
        types {
            Vector = grades(1);
            Even = grades(0, 2, 4);
            Multivector = all;
        }
    }
}

use pga::Sandwich;

/// The PGA motor of an isometry: translator × rotor (rotate first, then translate).
fn motor_of(isometry: &Isometry3<f64>) -> pga::Motor {
    let q = isometry.rotation.quaternion();
    // q = w + x i + y j + z k with i = e32, j = e13, k = e21 (so that i j k = −1).
    let rotor = pga::Motor {
        scalar: q.w,
        e23: -q.i,
        e13: q.j,
        e12: -q.k,
        ..pga::Motor::ZERO
    };
    let t = isometry.translation.vector;
    let translator = pga::Translator {
        scalar: 1.0,
        e01: -t.x / 2.0,
        e02: -t.y / 2.0,
        e03: -t.z / 2.0,
    };
    translator * rotor
}

/// The PGA point (x, y, z) = x e032 + y e013 + z e021 + e123.
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

/// The baseline's 4-float quaternion `w + x i + y j + z k`.
#[derive(Clone, Copy, Debug)]
struct Quat {
    w: f64,
    x: f64,
    y: f64,
    z: f64,
}

impl Quat {
    /// The Hamilton product, written out: 16 multiplies, 12 adds.
    #[inline(always)]
    fn mul(self, r: Quat) -> Quat {
        Quat {
            w: self.w * r.w - self.x * r.x - self.y * r.y - self.z * r.z,
            x: self.w * r.x + self.x * r.w + self.y * r.z - self.z * r.y,
            y: self.w * r.y - self.x * r.z + self.y * r.w + self.z * r.x,
            z: self.w * r.z + self.x * r.y - self.y * r.x + self.z * r.w,
        }
    }

    #[inline(always)]
    fn add(self, r: Quat) -> Quat {
        Quat {
            w: self.w + r.w,
            x: self.x + r.x,
            y: self.y + r.y,
            z: self.z + r.z,
        }
    }

    #[inline(always)]
    fn conjugate(self) -> Quat {
        Quat {
            w: self.w,
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }
}

/// The hand-written baseline: a rigid motion as the 8-float dual quaternion `real + ε dual`, the
/// representation a hand-written PGA motor product amounts to.
#[derive(Clone, Copy, Debug)]
struct DualQuaternion {
    real: Quat,
    dual: Quat,
}

impl DualQuaternion {
    /// The isomorphic image of a PGA motor: e0123 ↔ −ε, and e0 ∧ (the vector dual to a rotor
    /// bivector) ↔ −ε times that quaternion unit.
    fn from_motor(m: pga::Motor) -> DualQuaternion {
        DualQuaternion {
            real: Quat {
                w: m.scalar,
                x: -m.e23,
                y: m.e13,
                z: -m.e12,
            },
            dual: Quat {
                w: -m.e0123,
                x: -m.e01,
                y: -m.e02,
                z: -m.e03,
            },
        }
    }

    /// The point (x, y, z) as 1 + ε (x i + y j + z k).
    fn point(p: &Point3<f64>) -> DualQuaternion {
        DualQuaternion {
            real: Quat {
                w: 1.0,
                x: 0.0,
                y: 0.0,
                z: 0.0,
            },
            dual: Quat {
                w: 0.0,
                x: p.x,
                y: p.y,
                z: p.z,
            },
        }
    }

    /// (a + ε b)(c + ε d) = ac + ε (ad + bc): three quaternion products, 48 multiplies, 40 adds.
    #[inline(always)]
    fn mul(self, r: DualQuaternion) -> DualQuaternion {
        DualQuaternion {
            real: self.real.mul(r.real),
            dual: self.real.mul(r.dual).add(self.dual.mul(r.real)),
        }
    }

    /// Quaternion and dual conjugation together: (a + ε b)* = a* − ε b*.
    #[inline(always)]
    fn full_conjugate(self) -> DualQuaternion {
        let dual = self.dual.conjugate();
        DualQuaternion {
            real: self.real.conjugate(),
            dual: Quat {
                w: -dual.w,
                x: -dual.x,
                y: -dual.y,
                z: -dual.z,
            },
        }
    }

    /// Moves a point 1 + ε v by two plain products: σ (1 + ε v) σ̄*.
    #[inline(always)]
    fn transform(self, point: DualQuaternion) -> DualQuaternion {
        self.mul(point).mul(self.full_conjugate())
    }
}

fn quat_array(q: Quat) -> [f64; 4] {
    [q.w, q.x, q.y, q.z]
}

fn motor_product(c: &mut Criterion) {
    let mut random = Random(1);
    let isometries: Vec<(Isometry3<f64>, Isometry3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.isometry())).collect();
    let motors: Vec<(pga::Motor, pga::Motor)> = isometries.iter().map(|(a, b)| (motor_of(a), motor_of(b))).collect();
    let dual_quaternions: Vec<(DualQuaternion, DualQuaternion)> = motors
        .iter()
        .map(|&(a, b)| (DualQuaternion::from_motor(a), DualQuaternion::from_motor(b)))
        .collect();

    let probe = Point3::new(0.3, -1.7, 2.9);
    for ((&(ma, mb), &(da, db)), (ia, ib)) in motors.iter().zip(&dual_quaternions).zip(&isometries) {
        let generated = ma * mb;
        let baseline = da.mul(db);
        let mapped = DualQuaternion::from_motor(generated);
        assert_close(
            &quat_array(baseline.real),
            &quat_array(mapped.real),
            "baseline real part",
        );
        assert_close(
            &quat_array(baseline.dual),
            &quat_array(mapped.dual),
            "baseline dual part",
        );
        let expected = ia * ib * probe;
        assert_close(
            &pga_coordinates(generated.sandwich(pga_point(&probe))),
            &[expected.x, expected.y, expected.z],
            "composed motor against composed isometry",
        );
    }

    let mut group = c.benchmark_group("pga_motor_times_motor");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated", &motors, |(a, b)| a * b);
    time_batch(
        &mut group,
        "hand_unrolled_dual_quaternion",
        &dual_quaternions,
        |(a, b)| a.mul(b),
    );
    time_batch(&mut group, "nalgebra_isometry", &isometries, |(a, b)| a * b);
    group.finish();
}

fn point_transform(c: &mut Criterion) {
    let mut random = Random(2);
    let isometries: Vec<(Isometry3<f64>, Point3<f64>)> =
        (0..BATCH).map(|_| (random.isometry(), random.point())).collect();
    let generated: Vec<(pga::Motor, pga::Point)> =
        isometries.iter().map(|(m, p)| (motor_of(m), pga_point(p))).collect();
    let baseline: Vec<(DualQuaternion, DualQuaternion)> = generated
        .iter()
        .zip(&isometries)
        .map(|(&(m, _), (_, p))| (DualQuaternion::from_motor(m), DualQuaternion::point(p)))
        .collect();

    for ((&(m, p), &(d, q)), (isometry, point)) in generated.iter().zip(&baseline).zip(&isometries) {
        let expected = isometry * point;
        let expected = [expected.x, expected.y, expected.z];
        assert_close(&pga_coordinates(m.sandwich(p)), &expected, "generated sandwich");
        let moved = d.transform(q);
        assert_close(
            &[moved.dual.x, moved.dual.y, moved.dual.z],
            &expected,
            "baseline transform",
        );
    }

    let mut group = c.benchmark_group("pga_motor_moves_point");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "generated_fused_sandwich", &generated, |(m, p)| {
        m.sandwich(p)
    });
    time_batch(
        &mut group,
        "hand_unrolled_dual_quaternion_two_products",
        &baseline,
        |(d, q)| d.transform(q),
    );
    time_batch(&mut group, "nalgebra_isometry", &isometries, |(m, p)| m * p);
    group.finish();
}

fn full_products(c: &mut Criterion) {
    let mut random = Random(3);
    let cga_even: Vec<(cga::Even, cga::Even)> = (0..BATCH)
        .map(|_| {
            (
                cga::Even::from_array(random.array()),
                cga::Even::from_array(random.array()),
            )
        })
        .collect();
    let pga_multivectors: Vec<(pga::Multivector, pga::Multivector)> = (0..BATCH)
        .map(|_| {
            (
                pga::Multivector::from_array(random.array()),
                pga::Multivector::from_array(random.array()),
            )
        })
        .collect();
    let cga_multivectors: Vec<(cga::Multivector, cga::Multivector)> = (0..BATCH)
        .map(|_| {
            (
                cga::Multivector::from_array(random.array()),
                cga::Multivector::from_array(random.array()),
            )
        })
        .collect();

    let mut group = c.benchmark_group("geometric_product");
    group.throughput(Throughput::Elements(BATCH as u64));
    time_batch(&mut group, "cga_even_times_even", &cga_even, |(a, b)| a * b);
    time_batch(
        &mut group,
        "pga_multivector_times_multivector",
        &pga_multivectors,
        |(a, b)| a * b,
    );
    time_batch(
        &mut group,
        "cga_multivector_times_multivector",
        &cga_multivectors,
        |(a, b)| a * b,
    );
    group.finish();
}

/// Short enough that the whole run takes under a minute (41 s measured on two shared cores).
fn config() -> Criterion {
    Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

criterion_group! {
    name = benches;
    config = config();
    targets = motor_product, point_transform, full_products
}
criterion_main!(benches);
