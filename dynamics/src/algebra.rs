//! The `Algebra` trait: what a rigid-body simulator needs from a geometric algebra (`docs/theory.md` §1).
//!
//! Both implementations ([`crate::Pga`], [`crate::Cga`]) are built from one `algebra!` invocation
//! each. The simulator is written once against this trait. Coordinates are the shared language of
//! the two algebras (theory §1.4): a screw (velocity, momentum, wrench, line) is `Σ aᵢ lᵢ + bᵢ tᵢ` with
//! `lᵢ = eᵢI₃` and `tᵢ = eᵢ ∧ N`, and a motor is `s + Σ aᵢlᵢ + Σ bᵢtᵢ + cΠ` with `Π = I₃ ∧ N`.

use core::fmt::Debug;
use core::ops::{Add, Mul, Neg, Sub};

use nalgebra::Vector3;

/// Coordinates of a screw `Σ aᵢ lᵢ + bᵢ tᵢ` (theory §1.4): `l` holds the aᵢ, `t` the bᵢ.
///
/// For a velocity, `l` is the angular velocity ω and `t` the linear velocity v; for a momentum `l`
/// is the linear momentum p and `t` the angular momentum L; for a wrench `l` is the force f and `t`
/// the moment (theory §3).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScrewCoordinates {
    /// The coefficients `aᵢ` of the rotation bivectors `lᵢ = eᵢI₃`.
    pub l: Vector3<f64>,
    /// The coefficients `bᵢ` of the translation bivectors `tᵢ = eᵢ ∧ N`.
    pub t: Vector3<f64>,
}

impl ScrewCoordinates {
    /// From `[a₁, a₂, a₃, b₁, b₂, b₃]`, the layout of the algebras' `const fn` coordinate maps.
    ///
    /// A force of 2 N along z acting through `(1, 0, 0)` m: the l-part is the force, the t-part its moment
    /// `a × f` about the origin (N m).
    ///
    /// ```
    /// use dynamics::{forces::force_line, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::Vector3;
    ///
    /// let wrench = ScrewCoordinates::from_array([0.0, 0.0, 2.0, 0.0, -2.0, 0.0]);
    /// assert_eq!(Pga::screw(wrench), force_line::<Pga>(Vector3::new(0.0, 0.0, 2.0), Vector3::x()));
    /// ```
    #[inline]
    pub fn from_array([a1, a2, a3, b1, b2, b3]: [f64; 6]) -> Self {
        ScrewCoordinates {
            l: Vector3::new(a1, a2, a3),
            t: Vector3::new(b1, b2, b3),
        }
    }

    /// `[a₁, a₂, a₃, b₁, b₂, b₃]`.
    #[inline]
    pub fn to_array(&self) -> [f64; 6] {
        [self.l.x, self.l.y, self.l.z, self.t.x, self.t.y, self.t.z]
    }
}

impl Add for ScrewCoordinates {
    type Output = ScrewCoordinates;

    #[inline]
    fn add(self, other: ScrewCoordinates) -> ScrewCoordinates {
        ScrewCoordinates {
            l: self.l + other.l,
            t: self.t + other.t,
        }
    }
}

/// Coordinates of a motor `s + Σ aᵢlᵢ + Σ bᵢtᵢ + cΠ` in the 8-dimensional motor subalgebra
/// (the dual quaternions, theory §2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotorCoordinates {
    /// The scalar part `s`.
    pub scalar: f64,
    /// The coefficients `aᵢ` of the rotation bivectors `lᵢ`.
    pub l: Vector3<f64>,
    /// The coefficients `bᵢ` of the translation bivectors `tᵢ`.
    pub t: Vector3<f64>,
    /// The coefficient `c` of `Π = I₃ ∧ N`.
    pub pseudoscalar: f64,
}

/// A geometric algebra that can host rigid-body dynamics: CGA Cl(4,1) or PGA Cl(3,0,1).
pub trait Algebra: Copy + Debug + Default + Send + Sync + 'static {
    /// A rigid transformation (even multivector in span{1, lᵢ, tᵢ, Π}).
    type Motor: Copy + Debug + PartialEq + Send + Sync + Add<Output = Self::Motor> + Mul<f64, Output = Self::Motor>;
    /// A screw: an element of span{lᵢ, tᵢ}.
    type Screw: Copy
        + Debug
        + PartialEq
        + Send
        + Sync
        + Add<Output = Self::Screw>
        + Sub<Output = Self::Screw>
        + Neg<Output = Self::Screw>
        + Mul<f64, Output = Self::Screw>;
    /// A Euclidean point (CGA: the null vector `up(x)`; PGA: the trivector `(1 + e₀x)I₃`).
    type Point: Copy + Debug + PartialEq + Send + Sync;

    /// "CGA" or "PGA".
    const NAME: &'static str;

    /// The screw with these coordinates.
    fn screw(coordinates: ScrewCoordinates) -> Self::Screw;
    /// The coordinates of a screw (blades outside span{lᵢ, tᵢ} are ignored).
    fn screw_coordinates(screw: Self::Screw) -> ScrewCoordinates;
    /// The motor with these coordinates.
    fn motor(coordinates: MotorCoordinates) -> Self::Motor;
    /// The coordinates of a motor (in both algebras a motor's blades are exactly {1, lᵢ, tᵢ, Π}, theory §1.4).
    fn motor_coordinates(motor: Self::Motor) -> MotorCoordinates;

    /// The geometric product of two motors.
    fn compose(first: Self::Motor, second: Self::Motor) -> Self::Motor;
    /// The geometric product `motor · screw` (an even element: a motor-shaped derivative).
    fn motor_times_screw(motor: Self::Motor, screw: Self::Screw) -> Self::Motor;
    /// The reverse `~M`.
    fn reverse(motor: Self::Motor) -> Self::Motor;
    /// `M X ~M` for a screw X (world view of a body screw).
    fn transform_screw(motor: Self::Motor, screw: Self::Screw) -> Self::Screw;
    /// The commutator product `(XY − YX)/2` of two screws (theory §1.1).
    fn commutator(first: Self::Screw, second: Self::Screw) -> Self::Screw;
    /// `⟨X ∧ Y⟩_Π`, the coefficient of Π in the outer product of two screws (theory §1.4): the
    /// reciprocal product that gives power and kinetic energy (theory §3, §4).
    fn wedge_pi(first: Self::Screw, second: Self::Screw) -> f64;

    /// The point at `x`.
    fn point(x: Vector3<f64>) -> Self::Point;
    /// The position of a point (normalised by its weight).
    fn position(point: Self::Point) -> Vector3<f64>;
    /// `M P ~M` for a point.
    fn transform_point(motor: Self::Motor, point: Self::Point) -> Self::Point;
}
