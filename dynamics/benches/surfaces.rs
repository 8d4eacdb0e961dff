//! A body point on a surface: one constraint row (the position residual F, the Jacobian from ∇F, the velocity
//! residual and the bias with ȧ·Hȧ) from the generated incidence and its derivatives (QCGA for a turned, off-centre
//! ellipsoid, DCGA for a tilted torus; `dynamics::constraints::SurfacePin`), beside the same row from the classical
//! implicit function written here: `F = dᵀA d + 2bᵀd + j`, `∇F = 2(A d + b)`, `H = 2A` with `d = x − c` for the
//! quadric, and `F = (|d|² + R² − r²)² − 4R²(|d|² − (n·d)²)` with its gradient and Hessian for the torus
//! (docs/surfaces.md §7).
//!
//! `cargo bench -p dynamics --bench surfaces`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::constraints::{Constraint, ConstraintRow, Kinematics, RowBuffer, SurfacePin};
use dynamics::surfaces::Surface;
use dynamics::{motor, Algebra, ConstraintError, Pga, ScrewCoordinates};
use nalgebra::{Isometry3, Matrix3, UnitQuaternion, Vector3};

/// A surface's classical implicit function: F, ∇F and the Hessian times v at x.
trait Classical {
    fn terms(&self, x: &Vector3<f64>, v: &Vector3<f64>) -> (f64, Vector3<f64>, Vector3<f64>);
}

/// `F = dᵀA d + 2bᵀd + j` with `d = x − c`.
struct Quadric {
    a: Matrix3<f64>,
    b: Vector3<f64>,
    j: f64,
    centre: Vector3<f64>,
}

impl Classical for Quadric {
    #[inline]
    fn terms(&self, x: &Vector3<f64>, v: &Vector3<f64>) -> (f64, Vector3<f64>, Vector3<f64>) {
        let d = x - self.centre;
        let ad = self.a * d;
        let value = d.dot(&(ad + 2.0 * self.b)) + self.j;
        (value, 2.0 * (ad + self.b), 2.0 * (self.a * v))
    }
}

/// The torus of radii R, r about the unit axis n through c.
struct Torus {
    centre: Vector3<f64>,
    axis: Vector3<f64>,
    major: f64,
    minor: f64,
}

impl Classical for Torus {
    #[inline]
    fn terms(&self, x: &Vector3<f64>, v: &Vector3<f64>) -> (f64, Vector3<f64>, Vector3<f64>) {
        let d = x - self.centre;
        let (r2, n) = (self.major * self.major, self.axis);
        let s = d.norm_squared() + r2 - self.minor * self.minor;
        let along = n.dot(&d);
        let across = d - n * along;
        let value = s * s - 4.0 * r2 * (d.norm_squared() - along * along);
        let gradient = 4.0 * s * d - 8.0 * r2 * across;
        let bending = 8.0 * d.dot(v) * d + 4.0 * s * v - 8.0 * r2 * (v - n * n.dot(v));
        (value, gradient, bending)
    }
}

/// The pinned row of the body point `p` on `surface`, as `SurfacePin` writes it (the same check that the gradient
/// has a direction, the same buffer), with the classical terms.
#[inline]
fn classical_row<A: Algebra>(
    surface: &impl Classical,
    p: &Vector3<f64>,
    kinematics: &Kinematics<A>,
    rows: &mut RowBuffer,
) -> Result<(), ConstraintError> {
    let a = kinematics.world_point(p);
    let a_rate = kinematics.world_point_velocity(p);
    let (value, gradient, bending) = surface.terms(&a, &a_rate);
    if gradient.norm() <= 1e-9 {
        return Err(ConstraintError::Singular {
            name: "held".to_owned(),
            reason: format!("no normal at {a:?}"),
        });
    }
    let g_body = kinematics.frame.rotation.inverse_transform_vector(&gradient);
    let moment = p.cross(&g_body);
    rows.push(ConstraintRow {
        jacobian: [moment.x, moment.y, moment.z, g_body.x, g_body.y, g_body.z],
        velocity_residual: gradient.dot(&a_rate),
        bias: gradient.dot(&kinematics.angular_velocity.cross(&a_rate)) + a_rate.dot(&bending),
        position_residual: Some(value),
    });
    Ok(())
}

fn surfaces(c: &mut Criterion) {
    let pose = Isometry3::new(Vector3::new(0.4, -0.3, 1.2), Vector3::new(0.3, -0.5, 0.8));
    let radii = Vector3::new(1.2, 0.8, 0.5);
    let ellipsoid = Surface::ellipsoid(radii, &pose).unwrap();
    let rotation = pose.rotation.to_rotation_matrix().into_inner();
    let quadric = Quadric {
        a: rotation * Matrix3::from_diagonal(&radii.map(|r| 1.0 / (r * r))) * rotation.transpose(),
        b: Vector3::zeros(),
        j: -1.0,
        centre: pose.translation.vector,
    };
    let axis = Vector3::new(0.3, 0.1, 1.0).normalize();
    let torus_surface = Surface::torus(Vector3::new(0.2, 0.1, 1.0), axis, 1.0, 0.3).unwrap();
    let torus = Torus {
        centre: Vector3::new(0.2, 0.1, 1.0),
        axis,
        major: 1.0,
        minor: 0.3,
    };
    // A body near each surface, turning and moving.
    let point = Vector3::new(0.0, 0.0, -0.4);
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.2, 0.6, -0.1));
    let twist = Pga::screw(ScrewCoordinates {
        l: Vector3::new(0.3, -1.1, 0.4),
        t: Vector3::new(0.5, 0.2, -0.7),
    });
    let near_ellipsoid =
        Kinematics::<Pga>::new(0.0, motor::from_pose::<Pga>(Vector3::new(1.1, 0.2, 1.9), &turn), twist);
    let near_torus = Kinematics::<Pga>::new(0.0, motor::from_pose::<Pga>(Vector3::new(1.3, 0.1, 1.2), &turn), twist);

    let mut group = c.benchmark_group("surfaces");
    let classical = |name: &str, kinematics: &Kinematics<Pga>| {
        let mut rows = RowBuffer::new();
        match name {
            "ellipsoid (QCGA)" => classical_row(&quadric, &point, kinematics, &mut rows),
            _ => classical_row(&torus, &point, kinematics, &mut rows),
        }
        .unwrap();
        rows.rows()[0]
    };
    for (name, surface, kinematics) in [
        ("ellipsoid (QCGA)", ellipsoid, &near_ellipsoid),
        ("torus (DCGA)", torus_surface, &near_torus),
    ] {
        let pin = SurfacePin::point_on_surface("held", point, surface).unwrap();
        // The two rows are one row: the baseline computes what the generated path does.
        let mut rows = RowBuffer::new();
        Constraint::<Pga>::rows(&pin, kinematics, &mut rows).unwrap();
        let (ours, theirs) = (rows.rows()[0], classical(name, kinematics));
        let scale = theirs.jacobian.iter().fold(theirs.bias.abs(), |m, a| m.max(a.abs()));
        for (a, b) in ours
            .jacobian
            .iter()
            .chain([&ours.bias, &ours.velocity_residual])
            .zip(theirs.jacobian.iter().chain([&theirs.bias, &theirs.velocity_residual]))
        {
            assert!((a - b).abs() < 1e-12 * scale, "{name}: {ours:?} vs {theirs:?}");
        }
        group.bench_function(format!("{name}: row, generated"), |b| {
            b.iter(|| {
                let mut rows = RowBuffer::new();
                Constraint::<Pga>::rows(&pin, black_box(kinematics), &mut rows).unwrap();
                rows.rows()[0]
            })
        });
        group.bench_function(format!("{name}: row, classical"), |b| {
            b.iter(|| classical(name, black_box(kinematics)))
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    targets = surfaces
}
criterion_main!(benches);
