//! The multivectors a constraint can pin (`docs/theory.md` §7): points, lines and planes in both algebras, and in CGA
//! spheres and circles, as the types `algebra!` generated for PGA and CGA.
//!
//! Pinning is grade-agnostic (theory §7): it needs only to move an object between frames (`M X ~M`), to
//! commute it with a screw (`B × X`, which keeps its grade) and to read its coefficients. [`Pinnable`] is
//! that interface; [`PinningAlgebra`] names each algebra's point, line and plane types and builds them
//! from Euclidean data (theory §1.2, §1.3).

use std::fmt::Debug;
use std::ops::{Add, Mul, Sub};

use nalgebra::Vector3;

use crate::algebra::Algebra;
use crate::cga::{self, Cga};
use crate::pga::{self, Pga};

/// A value whose coefficients a constraint compares: residuals are differences of such values, one row
/// per coefficient.
pub trait Coefficients:
    Copy + Debug + Send + Sync + 'static + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// `[f64; n]` for an n-coefficient type.
    type Array: AsRef<[f64]>;
    /// The coefficients, in the type's blade order: one constraint row each.
    fn coefficients(self) -> Self::Array;
    /// The value with every coefficient zero.
    fn zero() -> Self;
}

/// A multivector that can be pinned: moved by a motor and commuted with a screw.
pub trait Pinnable<A: Algebra>: Coefficients {
    /// `M X ~M`. For CGA's 16-component even motor the generated sandwich may have a wider result type; its
    /// extra grades vanish for a unit motor and are dropped.
    fn transformed(self, motor: A::Motor) -> Self;
    /// `B × X` (commutator product, theory §1.1), which keeps the grade of X.
    fn screw_commutator(screw: A::Screw, object: Self) -> Self;
}

impl Coefficients for Vector3<f64> {
    type Array = [f64; 3];

    fn coefficients(self) -> [f64; 3] {
        self.into()
    }

    fn zero() -> Self {
        Vector3::zeros()
    }
}

macro_rules! generated_coefficients {
    ($($ty:ty),* $(,)?) => {$(
        impl Coefficients for $ty {
            type Array = [f64; <$ty>::BLADES.len()];

            #[inline]
            fn coefficients(self) -> Self::Array {
                self.to_array()
            }

            #[inline]
            fn zero() -> Self {
                <$ty>::ZERO
            }
        }
    )*};
}

generated_coefficients!(
    pga::generated::Point,
    pga::generated::Line,
    pga::generated::Plane,
    pga::generated::Pseudoscalar,
    cga::generated::Vector,
    cga::generated::FlatPoint,
    cga::generated::Bivector,
    cga::generated::Trivector,
    cga::generated::Quadvector,
    cga::generated::Pseudoscalar,
);

/// `Pinnable` from the generated sandwich and commutator; `$grade` projects the sandwich back onto the
/// object's grade where the generated result type is wider.
macro_rules! generated_pinnable {
    ($algebra:ty, $module:ident: $($ty:ident $(. $grade:ident)?),* $(,)?) => {$(
        impl Pinnable<$algebra> for $module::generated::$ty {
            #[inline]
            fn transformed(self, motor: <$algebra as Algebra>::Motor) -> Self {
                use $module::generated::Sandwich;
                motor.sandwich(self)$(.$grade())?
            }

            #[inline]
            fn screw_commutator(screw: <$algebra as Algebra>::Screw, object: Self) -> Self {
                use $module::generated::Commutator;
                screw.commutator(object)
            }
        }
    )*};
}

generated_pinnable!(Pga, pga: Point, Line, Plane);
generated_pinnable!(Cga, cga: Vector.grade_1, FlatPoint, Bivector, Trivector, Quadvector.grade_4);

/// An algebra in which points, lines and planes can be pinned (theory §7 table).
pub trait PinningAlgebra: Algebra {
    /// CGA: the null vector `up(x)`; PGA: the trivector `(1 + e₀x)I₃`.
    type PointObject: Pinnable<Self>;
    /// The object a point-to-point pin compares. PGA: its point. CGA: the flat point `up(x) ∧ n∞ = x∧n∞ + n0∧n∞`,
    /// whose coefficients are x and a constant weight, as PGA's point's are; the round point's fifth coefficient
    /// `½|x|²` would add a fourth non-zero row to a rank-3 joint and send it through the rank-truncated solve
    /// (`mechanism::reduce`), which made CGA's pinned top 3.2× slower than PGA's.
    type PinnedPoint: Pinnable<Self>;
    /// CGA: the OPNS trivector `up(a) ∧ up(a+d) ∧ n∞`; PGA: the bivector `d I₃ − (a∧d) I₃ e₀`.
    type LineObject: Pinnable<Self>;
    /// CGA: the OPNS 4-vector `(n + δ n∞) I₅`; PGA: the vector `n + δ e₀`.
    type PlaneObject: Pinnable<Self>;
    /// The value of `P ∧ X` for a point P and a plane X: a pseudoscalar, zero iff P is on X.
    type Incidence: Coefficients;
    /// The value of the incidence of a point and a line, zero iff the point is on the line (theory §9: CGA
    /// `P ∧ L`, a 4-vector; PGA `L × P`, a trivector).
    type LineIncidence: Coefficients;

    /// The point at `x`.
    fn point_object(x: Vector3<f64>) -> Self::PointObject;
    /// The pinned point at `x` ([`PinningAlgebra::PinnedPoint`]).
    fn pinned_point(x: Vector3<f64>) -> Self::PinnedPoint;
    /// The line through `point` along `direction`; with a unit direction it has unit weight.
    fn line_object(point: Vector3<f64>, direction: Vector3<f64>) -> Self::LineObject;
    /// The plane `{x : normal·x = offset}`.
    fn plane_object(normal: Vector3<f64>, offset: f64) -> Self::PlaneObject;
    /// `P ∧ X` (theory §9 table: body point on plane).
    fn point_plane_incidence(point: Self::PointObject, plane: Self::PlaneObject) -> Self::Incidence;
    /// The point–line incidence (theory §9 table: body point on line; §1.3: a PGA point X is on the line L iff
    /// `L × X = 0`).
    fn point_line_incidence(point: Self::PointObject, line: Self::LineObject) -> Self::LineIncidence;
}

impl PinningAlgebra for Pga {
    type PointObject = pga::generated::Point;
    type PinnedPoint = pga::generated::Point;
    type LineObject = pga::generated::Line;
    type PlaneObject = pga::generated::Plane;
    type Incidence = pga::generated::Pseudoscalar;
    type LineIncidence = pga::generated::Point;

    fn point_object(x: Vector3<f64>) -> Self::PointObject {
        Pga::point(x)
    }

    fn pinned_point(x: Vector3<f64>) -> Self::PinnedPoint {
        Pga::point(x)
    }

    fn line_object(point: Vector3<f64>, direction: Vector3<f64>) -> Self::LineObject {
        // theory §1.3: L = d I₃ + (a⨯d)∧e₀, i.e. lᵢ-coordinates d and tᵢ-coordinates a⨯d.
        let moment = point.cross(&direction);
        pga::line_from_coordinates([direction.x, direction.y, direction.z, moment.x, moment.y, moment.z])
    }

    fn plane_object(normal: Vector3<f64>, offset: f64) -> Self::PlaneObject {
        pga::generated::Plane {
            e1: normal.x,
            e2: normal.y,
            e3: normal.z,
            e0: offset,
        }
    }

    fn point_plane_incidence(point: Self::PointObject, plane: Self::PlaneObject) -> Self::Incidence {
        point ^ plane
    }

    fn point_line_incidence(point: Self::PointObject, line: Self::LineObject) -> Self::LineIncidence {
        use pga::generated::Commutator;
        line.commutator(point)
    }
}

/// `n∞` (theory §1.2).
const INFINITY: cga::generated::Vector = cga::generated::Vector {
    ninf: 1.0,
    ..cga::generated::Vector::ZERO
};

/// `I₅ = e12345`, which takes IPNS (vector, bivector) objects to OPNS ones (theory §1.2). With `e4 = ½n∞ − n0` and
/// `e5 = ½n∞ + n0`, `e4∧e5 = −n0∧n∞`, so I₅ is minus the null basis' blade `e1_e2_e3_n0_ninf`.
const UNIT_PSEUDOSCALAR: cga::generated::Pseudoscalar = cga::generated::Pseudoscalar { e1_e2_e3_n0_ninf: -1.0 };

/// The IPNS plane `n + δ n∞` (theory §1.2).
fn cga_dual_plane(normal: Vector3<f64>, offset: f64) -> cga::generated::Vector {
    cga::generated::Vector {
        e1: normal.x,
        e2: normal.y,
        e3: normal.z,
        n0: 0.0,
        ninf: offset,
    }
}

/// The IPNS sphere `up(c) − ½ρ² n∞` (theory §1.2).
fn cga_dual_sphere(centre: Vector3<f64>, radius: f64) -> cga::generated::Vector {
    Cga::point(centre) - INFINITY * (0.5 * radius * radius)
}

/// The OPNS sphere `(up(c) − ½ρ² n∞) I₅` (CGA only).
pub fn cga_sphere(centre: Vector3<f64>, radius: f64) -> cga::generated::Quadvector {
    cga_dual_sphere(centre, radius) * UNIT_PSEUDOSCALAR
}

/// The OPNS circle of radius ρ about `centre` in the plane through it with `normal`: the meet of the sphere
/// and the plane, `(σ ∧ π) I₅` (CGA only).
pub fn cga_circle(centre: Vector3<f64>, radius: f64, normal: Vector3<f64>) -> cga::generated::Trivector {
    (cga_dual_sphere(centre, radius) ^ cga_dual_plane(normal, normal.dot(&centre))) * UNIT_PSEUDOSCALAR
}

impl PinningAlgebra for Cga {
    type PointObject = cga::generated::Vector;
    type PinnedPoint = cga::generated::FlatPoint;
    type LineObject = cga::generated::Trivector;
    type PlaneObject = cga::generated::Quadvector;
    type Incidence = cga::generated::Pseudoscalar;
    type LineIncidence = cga::generated::Quadvector;

    fn point_object(x: Vector3<f64>) -> Self::PointObject {
        Cga::point(x)
    }

    fn pinned_point(x: Vector3<f64>) -> Self::PinnedPoint {
        // up(x) ∧ n∞ = (x + n0 + ½|x|² n∞) ∧ n∞ = x∧n∞ + n0∧n∞.
        cga::generated::FlatPoint {
            e1_ninf: x.x,
            e2_ninf: x.y,
            e3_ninf: x.z,
            n0_ninf: 1.0,
        }
    }

    fn line_object(point: Vector3<f64>, direction: Vector3<f64>) -> Self::LineObject {
        Cga::point(point) ^ Cga::point(point + direction) ^ INFINITY
    }

    fn plane_object(normal: Vector3<f64>, offset: f64) -> Self::PlaneObject {
        cga_dual_plane(normal, offset) * UNIT_PSEUDOSCALAR
    }

    fn point_plane_incidence(point: Self::PointObject, plane: Self::PlaneObject) -> Self::Incidence {
        point ^ plane
    }

    fn point_line_incidence(point: Self::PointObject, line: Self::LineObject) -> Self::LineIncidence {
        point ^ line
    }
}
