//! Joint models: a joint between a child body and its parent (another body or the world) as robotics describes
//! it — a kind (revolute, prismatic, universal, …), the joint frame seen from each of the two bodies, an axis — with
//! its **coordinates**: the relative motion from joint positions and back, the motion subspace the articulated
//! solve works in, and the constraint rows the general solve uses (`docs/mechanisms.md` §M7).
//!
//! The joint frame is one frame seen from both sides: `parent_frame` places it in the parent's body frame (the
//! world for a joint to the world), `child_frame` in the child's. At zero joint positions the two coincide; in
//! general the child's joint frame sits at `J(q)` in the parent's, so the child body frame is at
//! `parent_frame · J(q) · child_frame⁻¹` in the parent's body frame.

use std::f64::consts::TAU;
use std::fmt;
use std::sync::Arc;

use arrayvec::ArrayVec;
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::paths::{MotorPoint, Path};
use crate::constraints::virtual_power::normals_to;
use crate::constraints::{Constraint, ConstraintError, Kinematics, RowBuffer, VirtualPower};
use crate::convert::direction_and_length;
use crate::limits::JointLimit;
use crate::motor;

/// What a joint lets the child do relative to its parent. Axes and normals are in the joint frame; they need not
/// be unit (they are normalised) but must have a direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// A turn by the angle q about `axis` (URDF `revolute` and `continuous`). One coordinate, rad.
    Revolute {
        /// The axis, joint frame.
        axis: Vector3<f64>,
    },
    /// A slide by q along `axis`. One coordinate, m.
    Prismatic {
        /// The axis, joint frame.
        axis: Vector3<f64>,
    },
    /// A turn about and a slide along `axis`: coordinates (angle rad, slide m).
    Cylindrical {
        /// The axis, joint frame.
        axis: Vector3<f64>,
    },
    /// A Cardan joint: a turn by q₁ about `first` (fixed in the parent's joint frame), then by q₂ about `second`
    /// (fixed in the child's); the two axes must be normal. Coordinates (q₁, q₂), rad.
    Universal {
        /// The first axis, fixed in the parent's joint frame.
        first: Vector3<f64>,
        /// The second axis, fixed in the child's joint frame.
        second: Vector3<f64>,
    },
    /// A ball joint: any rotation about the joint origin. Positions: the unit quaternion (w, x, y, z) of the child's
    /// joint frame in the parent's; velocities: the relative angular velocity in the child's joint axes (rad/s).
    Spherical,
    /// Motion in the plane normal to `normal`: coordinates (x, y, θ) — a slide of the child's joint origin along two
    /// in-plane directions of the parent's joint frame (m), then a turn about the normal (rad). The in-plane
    /// directions are `e₁ = normal × eₖ` (normalised; eₖ the coordinate axis least aligned with the normal) and
    /// `e₂ = normal × e₁` ([`JointModel::plane_directions`]).
    Planar {
        /// The plane's normal, joint frame.
        normal: Vector3<f64>,
    },
    /// No relative motion (URDF `fixed` between bodies kept apart, a weld). No coordinates.
    Weld,
    /// No constraint at all: the child moves freely (URDF `floating`). Positions: the child joint origin in the
    /// parent's joint frame (m) and the rotation (w, x, y, z); velocities: the child joint origin's velocity
    /// relative to the parent and the relative angular velocity, both in the child's joint axes (Pinocchio's
    /// free-flyer convention).
    Free,
}

impl JointKind {
    /// The number of position coordinates.
    pub fn position_count(&self) -> usize {
        match self {
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => 1,
            JointKind::Cylindrical { .. } | JointKind::Universal { .. } => 2,
            JointKind::Spherical => 4,
            JointKind::Planar { .. } => 3,
            JointKind::Weld => 0,
            JointKind::Free => 7,
        }
    }

    /// The number of velocity coordinates (the degrees of freedom).
    pub fn velocity_count(&self) -> usize {
        match self {
            JointKind::Spherical => 3,
            JointKind::Free => 6,
            other => other.position_count(),
        }
    }

    /// The kind's name, as scene files write it.
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Revolute { .. } => "revolute",
            JointKind::Prismatic { .. } => "prismatic",
            JointKind::Cylindrical { .. } => "cylindrical",
            JointKind::Universal { .. } => "universal",
            JointKind::Spherical => "spherical",
            JointKind::Planar { .. } => "planar",
            JointKind::Weld => "weld",
            JointKind::Free => "free",
        }
    }

    /// The suffixes of the position coordinates' names (empty for a single coordinate).
    pub fn position_names(&self) -> &'static [&'static str] {
        match self {
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => &[""],
            JointKind::Cylindrical { .. } => &["angle", "slide"],
            JointKind::Universal { .. } => &["1", "2"],
            JointKind::Spherical => &["qw", "qx", "qy", "qz"],
            JointKind::Planar { .. } => &["x", "y", "theta"],
            JointKind::Weld => &[],
            JointKind::Free => &["x", "y", "z", "qw", "qx", "qy", "qz"],
        }
    }
}

/// Which body's joint frame an axis of motion is fixed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Side {
    Parent,
    Child,
}

/// A turn about, or a slide along, an axis through the child's joint origin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Motion {
    Rotation,
    Translation,
}

/// One velocity coordinate of a joint: the unit motion it produces (docs/mechanisms.md §M7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct JointAxis {
    pub side: Side,
    pub motion: Motion,
    /// The unit direction in the body frame of `side`.
    pub direction: Vector3<f64>,
}

/// A joint model: its kind, the joint frame seen from both bodies, and optionally a prescribed motion (see the
/// module docs).
#[derive(Clone)]
pub struct JointModel {
    name: String,
    kind: JointKind,
    parent_frame: Isometry3<f64>,
    child_frame: Isometry3<f64>,
    drive: Option<Arc<dyn Path<f64>>>,
    limit: Option<JointLimit>,
    axes: ArrayVec<JointAxis, 6>,
    /// `child_frame⁻¹`, kept for forward kinematics.
    child_inverse: Isometry3<f64>,
}

impl fmt::Debug for JointModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("JointModel")
            .field("name", &self.name)
            .field("kind", &self.kind)
            .field("parent_frame", &self.parent_frame)
            .field("child_frame", &self.child_frame)
            .field("driven", &self.drive.is_some())
            .field("limit", &self.limit)
            .finish()
    }
}

/// The largest coordinate of a joint frame's position (m) or a joint position: as [`crate::state::MAX_COORDINATE`].
const MAX_FRAME_COORDINATE: f64 = 1e50;
/// How far from normal a universal joint's two axes may be: `|a₁·a₂|` of the unit axes.
const NORMAL_AXES_TOLERANCE: f64 = 1e-9;

fn invalid(name: &str, reason: String) -> ConstraintError {
    ConstraintError::InvalidParameter {
        name: name.to_owned(),
        reason,
    }
}

fn unit_axis(name: &str, what: &str, v: Vector3<f64>) -> Result<Vector3<f64>, ConstraintError> {
    match direction_and_length(v) {
        Some((unit, _)) => Ok(unit),
        None => Err(invalid(name, format!("{what} {:?} has no direction", [v.x, v.y, v.z]))),
    }
}

fn check_frame(name: &str, what: &str, frame: &Isometry3<f64>) -> Result<(), ConstraintError> {
    let t = frame.translation.vector;
    let q = frame.rotation.quaternion();
    let finite =
        t.iter().all(|x| x.is_finite() && x.abs() <= MAX_FRAME_COORDINATE) && q.coords.iter().all(|x| x.is_finite());
    if !finite || (q.norm() - 1.0).abs() > 1e-9 {
        return Err(invalid(
            name,
            format!(
                "{what} must be finite with a unit rotation, got position {:?} and quaternion {:?}",
                [t.x, t.y, t.z],
                [q.w, q.i, q.j, q.k]
            ),
        ));
    }
    Ok(())
}

/// The angle of the turn about the unit `axis` in `rotation` (the twist of its swing–twist decomposition), in
/// (−π, π].
fn twist_angle(rotation: &UnitQuaternion<f64>, axis: &Vector3<f64>) -> f64 {
    let q = rotation.quaternion();
    let (w, along) = (q.w, q.imag().dot(axis));
    let (w, along) = if w < 0.0 { (-w, -along) } else { (w, along) };
    2.0 * along.atan2(w)
}

/// `angle + 2πk` nearest `previous` (continuous joints unwrapped across turns).
fn unwrapped(angle: f64, previous: Option<f64>) -> f64 {
    match previous {
        Some(p) if p.is_finite() => angle + TAU * ((p - angle) / TAU).round(),
        _ => angle,
    }
}

/// The unit quaternion (w, x, y, z) of the coordinates `q`, normalised; `None` if it has no direction.
fn quaternion(q: &[f64]) -> Option<UnitQuaternion<f64>> {
    let raw = Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = raw.norm();
    (norm.is_finite() && norm > 0.0).then(|| UnitQuaternion::new_unchecked(raw / norm))
}

/// Writes `rotation` into `out` as (w, x, y, z), with the sign nearest `previous` (w ≥ 0 without one), so that
/// a sampled quaternion stays continuous.
fn write_quaternion(rotation: &UnitQuaternion<f64>, previous: Option<&[f64]>, out: &mut [f64]) {
    let q = rotation.quaternion();
    let mut c = [q.w, q.i, q.j, q.k];
    let flip = match previous {
        Some(p) if p.iter().all(|x| x.is_finite()) => c.iter().zip(p).map(|(a, b)| a * b).sum::<f64>() < 0.0,
        _ => c[0] < 0.0,
    };
    if flip {
        c.iter_mut().for_each(|x| *x = -*x);
    }
    out.copy_from_slice(&c);
}

impl JointModel {
    /// A joint named `name` of `kind`, whose joint frame is `parent_frame` in the parent's body frame (or the
    /// world) and `child_frame` in the child's. Errors name the joint: an empty name, an axis without a
    /// direction, frames that are not finite or whose rotation is not unit, universal axes that are not normal.
    ///
    /// The elbow of a double pendulum: the joint at the upper link's bottom end (0.5 m below its centre) and the
    /// lower link's top end (0.4 m above its centre), turning about y. At q = 0 the lower link hangs straight
    /// below the upper; at q = π/2 (a quarter turn about y, which takes z to x) its centre is 0.4 m from the elbow
    /// along −x:
    ///
    /// ```
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let elbow = JointModel::new(
    ///     "elbow",
    ///     JointKind::Revolute { axis: Vector3::y() * 2.0 }, // normalised
    ///     Isometry3::translation(0.0, 0.0, -0.5),
    ///     Isometry3::translation(0.0, 0.0, 0.4),
    /// )?;
    /// let straight = elbow.relative_pose(&[0.0])?;
    /// assert!((straight.translation.vector - Vector3::new(0.0, 0.0, -0.9)).norm() < 1e-15); // m
    /// let quarter = elbow.relative_pose(&[std::f64::consts::FRAC_PI_2])?;
    /// assert!((quarter.translation.vector - Vector3::new(-0.4, 0.0, -0.5)).norm() < 1e-15);
    /// assert!(JointModel::new("bad", JointKind::Revolute { axis: Vector3::zeros() }, Isometry3::identity(),
    ///     Isometry3::identity()).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(
        name: impl Into<String>,
        kind: JointKind,
        parent_frame: Isometry3<f64>,
        child_frame: Isometry3<f64>,
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        if name.is_empty() {
            return Err(invalid("joint", "a joint needs a non-empty name".to_owned()));
        }
        check_frame(&name, "the parent's joint frame", &parent_frame)?;
        check_frame(&name, "the child's joint frame", &child_frame)?;
        let kind = match kind {
            JointKind::Revolute { axis } => JointKind::Revolute {
                axis: unit_axis(&name, "axis", axis)?,
            },
            JointKind::Prismatic { axis } => JointKind::Prismatic {
                axis: unit_axis(&name, "axis", axis)?,
            },
            JointKind::Cylindrical { axis } => JointKind::Cylindrical {
                axis: unit_axis(&name, "axis", axis)?,
            },
            JointKind::Universal { first, second } => {
                let (first, second) = (
                    unit_axis(&name, "first axis", first)?,
                    unit_axis(&name, "second axis", second)?,
                );
                let cosine = first.dot(&second);
                if cosine.abs() > NORMAL_AXES_TOLERANCE {
                    return Err(invalid(
                        &name,
                        format!(
                            "a universal joint's axes must be normal, got {first:?} and {second:?} (cosine {cosine:e})"
                        ),
                    ));
                }
                JointKind::Universal { first, second }
            }
            JointKind::Planar { normal } => JointKind::Planar {
                normal: unit_axis(&name, "normal", normal)?,
            },
            other => other,
        };
        let mut model = JointModel {
            name,
            kind,
            parent_frame,
            child_frame,
            drive: None,
            limit: None,
            axes: ArrayVec::new(),
            child_inverse: child_frame.inverse(),
        };
        model.axes = model.joint_axes();
        Ok(model)
    }

    /// The joint driven along `position` (its value, rate and acceleration over time): a revolute or prismatic
    /// joint whose coordinate is prescribed. The drive does work; the articulated solve finds the torque (or force)
    /// it takes, and the general solve holds the child on the motor path it implies.
    ///
    /// ```
    /// use dynamics::constraints::PathPoint;
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let spin = |t: f64| PathPoint { value: 2.0 * t, rate: 2.0, acceleration: 0.0 }; // rad, rad/s, rad/s²
    /// let axle = JointModel::new("axle", JointKind::Revolute { axis: Vector3::z() }, Isometry3::identity(),
    ///     Isometry3::identity())?.driven(spin)?;
    /// assert!(axle.is_driven());
    /// let ball = JointModel::new("ball", JointKind::Spherical, Isometry3::identity(), Isometry3::identity())?;
    /// assert!(ball.driven(spin).is_err()); // only one-coordinate joints are driven
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn driven(mut self, position: impl Path<f64> + 'static) -> Result<Self, ConstraintError> {
        self.one_coordinate("driven")?;
        if self.limit.is_some() {
            return Err(invalid(
                &self.name,
                "a limited joint cannot be driven: its drive decides where it is".to_owned(),
            ));
        }
        self.drive = Some(Arc::new(position));
        Ok(self)
    }

    /// The joint with its coordinate kept in `limit`'s range: a revolute or prismatic joint, not driven. A mechanism
    /// enforces it exactly ([`crate::limits`]): impacts at the bounds, held there while the bound pushes.
    ///
    /// ```
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::limits::JointLimit;
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let knee = JointModel::new("knee", JointKind::Revolute { axis: Vector3::y() }, Isometry3::identity(),
    ///     Isometry3::identity())?.with_limit(JointLimit::new(0.0, 2.6)?)?; // rad
    /// assert_eq!(knee.limit().map(|l| l.upper()), Some(2.6));
    /// let ball = JointModel::new("ball", JointKind::Spherical, Isometry3::identity(), Isometry3::identity())?;
    /// assert!(ball.with_limit(JointLimit::new(-1.0, 1.0)?).is_err()); // one coordinate only
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_limit(mut self, limit: JointLimit) -> Result<Self, ConstraintError> {
        self.one_coordinate("limited")?;
        if self.drive.is_some() {
            return Err(invalid(
                &self.name,
                "a driven joint cannot be limited: its drive decides where it is".to_owned(),
            ));
        }
        self.limit = Some(limit);
        Ok(self)
    }

    /// The joint's limit, if it has one.
    pub fn limit(&self) -> Option<&JointLimit> {
        self.limit.as_ref()
    }

    /// An error unless the joint is revolute or prismatic (what it would be: "driven", "limited").
    fn one_coordinate(&self, what: &str) -> Result<(), ConstraintError> {
        if matches!(self.kind, JointKind::Revolute { .. } | JointKind::Prismatic { .. }) {
            return Ok(());
        }
        Err(invalid(
            &self.name,
            format!(
                "only revolute and prismatic joints can be {what}, this one is {}",
                self.kind.name()
            ),
        ))
    }

    /// The joint's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The joint's kind, with unit axes.
    #[inline]
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }

    /// The joint frame in the parent's body frame (or the world).
    #[inline]
    pub fn parent_frame(&self) -> &Isometry3<f64> {
        &self.parent_frame
    }

    /// The joint frame in the child's body frame.
    #[inline]
    pub fn child_frame(&self) -> &Isometry3<f64> {
        &self.child_frame
    }

    /// Whether the joint's coordinate is prescribed ([`JointModel::driven`]).
    pub fn is_driven(&self) -> bool {
        self.drive.is_some()
    }

    /// The prescribed coordinate at time `t` (value, rate, acceleration), for a driven joint.
    #[inline]
    pub fn drive_at(&self, t: f64) -> Option<crate::constraints::PathPoint<f64>> {
        self.drive.as_ref().map(|path| path.at(t))
    }

    /// A planar joint's in-plane directions e₁, e₂ (joint frame), along which its x and y slide.
    pub fn plane_directions(normal: &Vector3<f64>) -> [Vector3<f64>; 2] {
        normals_to(*normal)
    }

    /// The velocity coordinates as unit motions, in the order of the joint's velocity coordinates.
    fn joint_axes(&self) -> ArrayVec<JointAxis, 6> {
        let in_parent = |d: Vector3<f64>| self.parent_frame.rotation * d;
        let in_child = |d: Vector3<f64>| self.child_frame.rotation * d;
        let axis = |side: Side, motion: Motion, d: Vector3<f64>| JointAxis {
            side,
            motion,
            direction: match side {
                Side::Parent => in_parent(d),
                Side::Child => in_child(d),
            },
        };
        let frame = [Vector3::x(), Vector3::y(), Vector3::z()];
        let mut axes = ArrayVec::new();
        match self.kind {
            JointKind::Revolute { axis: a } => axes.push(axis(Side::Child, Motion::Rotation, a)),
            JointKind::Prismatic { axis: a } => axes.push(axis(Side::Child, Motion::Translation, a)),
            JointKind::Cylindrical { axis: a } => {
                axes.push(axis(Side::Child, Motion::Rotation, a));
                axes.push(axis(Side::Child, Motion::Translation, a));
            }
            JointKind::Universal { first, second } => {
                axes.push(axis(Side::Parent, Motion::Rotation, first));
                axes.push(axis(Side::Child, Motion::Rotation, second));
            }
            JointKind::Spherical => frame
                .iter()
                .for_each(|&d| axes.push(axis(Side::Child, Motion::Rotation, d))),
            JointKind::Planar { normal } => {
                let [e1, e2] = normals_to(normal);
                axes.push(axis(Side::Parent, Motion::Translation, e1));
                axes.push(axis(Side::Parent, Motion::Translation, e2));
                axes.push(axis(Side::Child, Motion::Rotation, normal));
            }
            JointKind::Weld => {}
            JointKind::Free => {
                frame
                    .iter()
                    .for_each(|&d| axes.push(axis(Side::Child, Motion::Translation, d)));
                frame
                    .iter()
                    .for_each(|&d| axes.push(axis(Side::Child, Motion::Rotation, d)));
            }
        }
        axes
    }

    #[inline]
    pub(crate) fn axes(&self) -> &[JointAxis] {
        &self.axes
    }

    /// `J(q)`: the child's joint frame in the parent's joint frame at joint positions `q`. Errors: a wrong count,
    /// a coordinate that is not finite or beyond 1e50, a quaternion of zero length.
    pub fn joint_pose(&self, q: &[f64]) -> Result<Isometry3<f64>, ConstraintError> {
        let expected = self.kind.position_count();
        if q.len() != expected {
            return Err(invalid(
                &self.name,
                format!("takes {expected} position coordinates, got {}", q.len()),
            ));
        }
        if !q.iter().all(|x| x.is_finite() && x.abs() <= MAX_FRAME_COORDINATE) {
            return Err(invalid(
                &self.name,
                format!("joint positions must be finite and at most 1e50, got {q:?}"),
            ));
        }
        let turn = |axis: &Vector3<f64>, angle: f64| {
            UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_unchecked(*axis), angle)
        };
        let no_direction = || invalid(&self.name, format!("the quaternion {q:?} has no direction"));
        Ok(match self.kind {
            JointKind::Revolute { axis } => Isometry3::from_parts(Translation3::identity(), turn(&axis, q[0])),
            JointKind::Prismatic { axis } => Isometry3::from_parts((axis * q[0]).into(), UnitQuaternion::identity()),
            JointKind::Cylindrical { axis } => Isometry3::from_parts((axis * q[1]).into(), turn(&axis, q[0])),
            JointKind::Universal { first, second } => {
                Isometry3::from_parts(Translation3::identity(), turn(&first, q[0]) * turn(&second, q[1]))
            }
            JointKind::Spherical => {
                Isometry3::from_parts(Translation3::identity(), quaternion(q).ok_or_else(no_direction)?)
            }
            JointKind::Planar { normal } => {
                let [e1, e2] = normals_to(normal);
                Isometry3::from_parts((e1 * q[0] + e2 * q[1]).into(), turn(&normal, q[2]))
            }
            JointKind::Weld => Isometry3::identity(),
            JointKind::Free => Isometry3::from_parts(
                Translation3::new(q[0], q[1], q[2]),
                quaternion(&q[3..7]).ok_or_else(no_direction)?,
            ),
        })
    }

    /// The child's body frame in the parent's body frame at joint positions `q`:
    /// `parent_frame · J(q) · child_frame⁻¹`.
    pub fn relative_pose(&self, q: &[f64]) -> Result<Isometry3<f64>, ConstraintError> {
        if let (JointKind::Revolute { axis }, [angle]) = (&self.kind, q) {
            // The common case without the checks' and the general turn's detours: (cos ½q, sin ½q a).
            if angle.is_finite() && angle.abs() <= MAX_FRAME_COORDINATE {
                let (sin, cos) = (0.5 * angle).sin_cos();
                let turn = UnitQuaternion::new_unchecked(Quaternion::from_parts(cos, axis * sin));
                return Ok(self.parent_frame
                    * Isometry3::from_parts(Translation3::identity(), turn)
                    * self.child_inverse);
            }
        }
        Ok(self.parent_frame * self.joint_pose(q)? * self.child_inverse)
    }

    /// The joint positions of a relative pose `J` (the child's joint frame in the parent's joint frame), the
    /// inverse of [`JointModel::joint_pose`] on the joint's motions; off them (a pose the joint cannot reach, by
    /// drift) the nearest coordinates in the joint's own terms (a revolute joint's twist about its axis). Angles are
    /// taken nearest `previous` (continuous joints unwrapped across turns; quaternions kept continuous).
    pub(crate) fn coordinates_of(&self, joint_pose: &Isometry3<f64>, previous: Option<&[f64]>, out: &mut [f64]) {
        let r = &joint_pose.rotation;
        let t = joint_pose.translation.vector;
        let before = |k: usize| previous.map(|p| p[k]);
        match self.kind {
            JointKind::Revolute { axis } => out[0] = unwrapped(twist_angle(r, &axis), before(0)),
            JointKind::Prismatic { axis } => out[0] = axis.dot(&t),
            JointKind::Cylindrical { axis } => {
                out[0] = unwrapped(twist_angle(r, &axis), before(0));
                out[1] = axis.dot(&t);
            }
            JointKind::Universal { first, second } => {
                // R = Rot(a₁, q₁) Rot(a₂, q₂): R a₂ = cos q₁ a₂ + sin q₁ a₃ and Rᵀ a₁ = cos q₂ a₁ + sin q₂ a₃, a₃ = a₁ × a₂.
                let third = first.cross(&second);
                let (moved_second, moved_first) = (r * second, r.inverse() * first);
                out[0] = unwrapped(third.dot(&moved_second).atan2(second.dot(&moved_second)), before(0));
                out[1] = unwrapped(third.dot(&moved_first).atan2(first.dot(&moved_first)), before(1));
            }
            JointKind::Spherical => write_quaternion(r, previous, out),
            JointKind::Planar { normal } => {
                let [e1, e2] = normals_to(normal);
                out[0] = e1.dot(&t);
                out[1] = e2.dot(&t);
                out[2] = unwrapped(twist_angle(r, &normal), before(2));
            }
            JointKind::Weld => {}
            JointKind::Free => {
                out[..3].copy_from_slice(t.as_slice());
                write_quaternion(r, previous.map(|p| &p[3..7]), &mut out[3..7]);
            }
        }
    }

    /// The child's body velocity relative to the parent, in the child's body frame, per unit rate of a one-coordinate
    /// joint: a turn about the axis through the joint origin `p` is `(d; p × d)`, a slide `(0; d)`.
    fn unit_child_velocity(&self) -> ScrewCoordinates {
        let axis = self.axes[0];
        let origin = self.child_frame.translation.vector;
        match axis.motion {
            Motion::Rotation => ScrewCoordinates {
                l: axis.direction,
                t: origin.cross(&axis.direction),
            },
            Motion::Translation => ScrewCoordinates {
                l: Vector3::zeros(),
                t: axis.direction,
            },
        }
    }

    /// The joint's constraint rows by virtual power (`docs/theory.md` §6), in the child's and the parent's body
    /// frames; `None` for a free joint, which constrains nothing. A driven joint is a motor joint along the path its
    /// coordinate implies.
    pub fn virtual_power<A: Algebra>(&self) -> Result<Option<Arc<dyn Constraint<A>>>, ConstraintError> {
        let name = self.name.clone();
        let (parent_origin, child_origin) = (
            self.parent_frame.translation.vector,
            self.child_frame.translation.vector,
        );
        let in_parent = |d: &Vector3<f64>| self.parent_frame.rotation * d;
        let in_child = |d: &Vector3<f64>| self.child_frame.rotation * d;
        if let Some(drive) = &self.drive {
            let path = JointPath::<A> {
                model: self.clone(),
                drive: drive.clone(),
                unit: A::screw(self.unit_child_velocity()),
            };
            return Ok(Some(Arc::new(VirtualPower::motor_joint(name, path))));
        }
        let rows: Arc<dyn Constraint<A>> = match &self.kind {
            JointKind::Revolute { axis } => Arc::new(VirtualPower::hinge(
                name,
                (child_origin, in_child(axis)),
                (parent_origin, in_parent(axis)),
            )?),
            JointKind::Prismatic { axis } => {
                let normal = normals_to(*axis)[0];
                Arc::new(VirtualPower::prismatic(
                    name,
                    (child_origin, in_child(axis), in_child(&normal)),
                    (parent_origin, in_parent(axis), in_parent(&normal)),
                )?)
            }
            JointKind::Cylindrical { axis } => Arc::new(VirtualPower::cylindrical(
                name,
                (child_origin, in_child(axis)),
                (parent_origin, in_parent(axis)),
            )?),
            JointKind::Universal { first, second } => Arc::new(VirtualPower::universal(
                name,
                (child_origin, in_child(second)),
                (parent_origin, in_parent(first)),
            )?),
            JointKind::Spherical => Arc::new(VirtualPower::ball_joint(name, child_origin, parent_origin)),
            JointKind::Planar { normal } => Arc::new(VirtualPower::planar(
                name,
                (child_origin, in_child(normal)),
                (parent_origin, in_parent(normal)),
            )?),
            JointKind::Weld => {
                let at_rest = self.parent_frame * self.child_frame.inverse();
                Arc::new(VirtualPower::weld(name, pose_motor::<A>(&at_rest)))
            }
            JointKind::Free => return Ok(None),
        };
        Ok(Some(rows))
    }
}

/// The motor of a pose (body → reference).
pub(crate) fn pose_motor<A: Algebra>(pose: &Isometry3<f64>) -> A::Motor {
    motor::from_pose::<A>(pose.translation.vector, &pose.rotation)
}

/// A driven one-coordinate joint's motor path: `U = parent_frame · J(q(t)) · child_frame⁻¹`, with the child's body
/// velocity `ξ = u q̇` and `ξ̇ = u q̈` (the unit velocity u is fixed in the child's frame).
struct JointPath<A: Algebra> {
    model: JointModel,
    drive: Arc<dyn Path<f64>>,
    unit: A::Screw,
}

impl<A: Algebra> crate::constraints::MotorPath<A> for JointPath<A> {
    fn at(&self, t: f64) -> MotorPoint<A> {
        let q = self.drive.at(t);
        // A non-finite prescribed value gives a non-finite motor, which the joint's rows report as an error.
        let pose = self.model.relative_pose(&[q.value]).unwrap_or_else(|_| {
            Isometry3::from_parts(
                Translation3::new(f64::NAN, f64::NAN, f64::NAN),
                UnitQuaternion::identity(),
            )
        });
        MotorPoint {
            motor: pose_motor::<A>(&pose),
            velocity: self.unit * q.rate,
            acceleration: self.unit * q.acceleration,
        }
    }
}

/// A joint that constrains nothing (a free joint's rows): rank 0, no rows.
pub(crate) struct Unconstrained {
    pub name: String,
}

impl<A: Algebra> Constraint<A> for Unconstrained {
    fn name(&self) -> &str {
        &self.name
    }

    fn rank(&self) -> usize {
        0
    }

    fn row_count(&self) -> usize {
        0
    }

    fn has_position_residual(&self) -> bool {
        true
    }

    fn rows(&self, _kinematics: &Kinematics<A>, _rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        Ok(())
    }

    fn uses_motor(&self) -> bool {
        false
    }
}
