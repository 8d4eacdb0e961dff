//! Scene-file joints as joint models (`dynamics::joints`): the joint frames chosen from a joint's geometry, so that
//! its coordinates exist and the articulated solve applies, and the joint's rows in the chosen formulation.
//!
//! The frames (docs/scene-files.md): the joint frame's origin is the reference point in the reference's frame
//! (the world, a body's frame, or a robot link's frame) and the body point in the body's; its axes are the
//! reference's axes on the reference side, and on the body side those axes turned by the smallest rotation taking
//! the reference axis (or normal) to the body axis (or normal). So each coordinate is zero when the body is turned
//! relative to its reference by the smallest rotation taking its axis onto the reference axis, with the body point
//! on the reference point:
//!
//! * hinge: the angle (rad) about the reference axis, right-handed;
//! * cylindrical: that angle, then the slide (m) of the body point along the reference axis;
//! * prismatic: the slide along the reference axis (the frames are aligned axis to axis and normal to normal);
//! * planar: the slides along `e₁ = n × eₖ` and `e₂ = n × e₁` of the reference normal n (eₖ the coordinate axis
//!   least aligned with n), then the turn about n;
//! * ball: the quaternion of the body's turn relative to the reference;
//! * universal: the turn q₁ about the reference axis, then q₂ about the body axis; zero when the body is turned by
//!   the smallest rotation taking its axis into the plane normal to the reference axis (no turn when the two axes
//!   are written normal to each other);
//! * fixed: none.
//!
//! Antiparallel axes have no smallest rotation: a half turn about the first normal `e₁` of the reference axis is
//! taken.

use std::sync::Arc;

use dynamics::constraints::{pinning, Constraint, MotorPoint, PinningAlgebra};
use dynamics::{motor, JointKind, JointModel, ScrewCoordinates};
use nalgebra::{Isometry3, Matrix3, Quaternion, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::check::geometry::{AxisFreedom, CheckedGeometry};
use crate::error::{invalid, SceneFileError};
use crate::syntax::elements::DriveSpec;

/// The smallest rotation taking the unit vector `from` to the unit vector `to`; exactly the identity when they are
/// equal, a half turn about `from`'s first normal when they are opposite.
pub(crate) fn smallest_rotation(from: &Vector3<f64>, to: &Vector3<f64>) -> UnitQuaternion<f64> {
    if from == to {
        return UnitQuaternion::identity();
    }
    // The half-way quaternion (1 + a·b, a × b), normalised: accurate except for exactly opposite vectors.
    let (w, v) = (1.0 + from.dot(to), from.cross(to));
    let norm = (w * w + v.norm_squared()).sqrt();
    if norm > 1e-150 {
        UnitQuaternion::new_unchecked(Quaternion::new(w / norm, v.x / norm, v.y / norm, v.z / norm))
    } else {
        let normal = JointModel::plane_directions(from)[0];
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(normal), std::f64::consts::PI)
    }
}

/// The rotation taking the orthonormal pair (a₁, n₁) to (a₂, n₂); the identity when they are equal.
fn frame_rotation(from: (Vector3<f64>, Vector3<f64>), to: (Vector3<f64>, Vector3<f64>)) -> UnitQuaternion<f64> {
    if from == to {
        return UnitQuaternion::identity();
    }
    let frame = |(a, n): (Vector3<f64>, Vector3<f64>)| Matrix3::from_columns(&[a, n, a.cross(&n)]);
    let matrix = frame(to) * frame(from).transpose();
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&matrix))
}

/// Whether a joint of this geometry becomes a joint model (ball, hinge, cylindrical, prismatic, planar, universal,
/// fixed); the others (points on lines, planes, spheres, circles) stay constraints.
pub(crate) fn has_model(geometry: &CheckedGeometry) -> bool {
    matches!(
        geometry,
        CheckedGeometry::Ball { .. }
            | CheckedGeometry::Axis { .. }
            | CheckedGeometry::Planar { .. }
            | CheckedGeometry::Universal { .. }
            | CheckedGeometry::Weld { .. }
    )
}

/// The joint model of `geometry` (its reference side in the reference's frame, which sits at `frame` in the
/// reference body's frame: a robot link's frame, else the identity), driven by `drive` if given; `None` for a
/// geometry without one ([`has_model`]).
pub(crate) fn joint_model(
    name: &str,
    geometry: &CheckedGeometry,
    frame: &Isometry3<f64>,
    drive: Option<DriveSpec>,
) -> Result<Option<JointModel>, SceneFileError> {
    let at =
        |point: Vector3<f64>, rotation: UnitQuaternion<f64>| Isometry3::from_parts(Translation3::from(point), rotation);
    let parent_at = |point: Vector3<f64>| frame * at(point, UnitQuaternion::identity());
    let (kind, parent, child) = match *geometry {
        CheckedGeometry::Ball {
            body_point,
            world_point,
        } => (
            JointKind::Spherical,
            parent_at(world_point),
            at(body_point, UnitQuaternion::identity()),
        ),
        CheckedGeometry::Axis { freedom, body, world } => {
            let (kind, rotation) = match freedom {
                AxisFreedom::Turn => (
                    JointKind::Revolute { axis: world.1 },
                    smallest_rotation(&world.1, &body.1),
                ),
                AxisFreedom::TurnAndSlide => (
                    JointKind::Cylindrical { axis: world.1 },
                    smallest_rotation(&world.1, &body.1),
                ),
                AxisFreedom::Slide {
                    body_normal,
                    world_normal,
                } => (
                    JointKind::Prismatic { axis: world.1 },
                    frame_rotation((world.1, world_normal), (body.1, body_normal)),
                ),
            };
            (kind, parent_at(world.0), at(body.0, rotation))
        }
        CheckedGeometry::Planar { body, world } => (
            JointKind::Planar { normal: world.1 },
            parent_at(world.0),
            at(body.0, smallest_rotation(&world.1, &body.1)),
        ),
        CheckedGeometry::Universal { body, world } => {
            // The body axis turned into the plane normal to the reference axis, by the smallest rotation.
            let across = body.1 - world.1 * world.1.dot(&body.1);
            if across.norm() <= 1e-9 {
                return Err(invalid(
                    format!("joint {name}: body_axis"),
                    "is along the reference axis: a universal joint's two axes must be normal",
                ));
            }
            let second = if across == body.1 { body.1 } else { across.normalize() };
            (
                JointKind::Universal { first: world.1, second },
                parent_at(world.0),
                at(body.0, smallest_rotation(&second, &body.1)),
            )
        }
        CheckedGeometry::Weld { position, orientation } => (
            JointKind::Weld,
            frame * at(position, orientation),
            Isometry3::identity(),
        ),
        CheckedGeometry::Line { .. }
        | CheckedGeometry::Plane { .. }
        | CheckedGeometry::Round { .. }
        | CheckedGeometry::Surfaces { .. } => return Ok(None),
    };
    let model = JointModel::new(name, kind, parent, child)?;
    Ok(Some(match drive {
        None => model,
        Some(drive) => {
            if !matches!(kind, JointKind::Revolute { .. } | JointKind::Prismatic { .. }) {
                return Err(invalid(
                    format!("joint {name}: drive"),
                    format!(
                        "only hinge and prismatic joints are driven, this one is a {}",
                        geometry_kind(geometry)
                    ),
                ));
            }
            model.driven(move |t: f64| drive.at(t))?
        }
    }))
}

fn geometry_kind(geometry: &CheckedGeometry) -> &'static str {
    match geometry {
        CheckedGeometry::Ball { .. } => "ball joint",
        CheckedGeometry::Axis {
            freedom: AxisFreedom::TurnAndSlide,
            ..
        } => "cylindrical joint",
        CheckedGeometry::Axis { .. } => "hinge or prismatic joint",
        CheckedGeometry::Planar { .. } => "planar joint",
        CheckedGeometry::Universal { .. } => "universal joint",
        CheckedGeometry::Weld { .. } => "fixed joint",
        _ => "constraint",
    }
}

/// The rows of `model` in the chosen formulation: by virtual power its own ([`JointModel::virtual_power`]); by
/// pinning the pinned objects of its frames (a point, a line and a point, a line, a line and a plane, a plane; a
/// driven joint's and a weld's motor by two pinned lines). A universal joint has no pinned form.
pub(crate) fn rows<A: PinningAlgebra>(
    model: &JointModel,
    pinned: bool,
    drive: Option<DriveSpec>,
) -> Result<Arc<dyn Constraint<A>>, SceneFileError> {
    let name = model.name().to_owned();
    if !pinned {
        return model
            .virtual_power::<A>()?
            .ok_or_else(|| invalid(format!("joint {name}"), "a free joint has no rows"));
    }
    let (child, parent) = (model.child_frame(), model.parent_frame());
    let (c, p) = (child.translation.vector, parent.translation.vector);
    let in_child = |d: &Vector3<f64>| child.rotation * d;
    let in_parent = |d: &Vector3<f64>| parent.rotation * d;
    if let Some(drive) = drive {
        // The motor of the prescribed coordinate, U = parent_frame · J(q(t)) · child_frame⁻¹, with the child's body
        // velocity u q̇ (u: a turn about the axis through the child's joint origin, or a slide along it).
        let (unit, turns) = match *model.kind() {
            JointKind::Revolute { axis } => (in_child(&axis), true),
            JointKind::Prismatic { axis } => (in_child(&axis), false),
            _ => unreachable!("only revolute and prismatic joints are driven"),
        };
        let unit = if turns {
            ScrewCoordinates {
                l: unit,
                t: c.cross(&unit),
            }
        } else {
            ScrewCoordinates {
                l: Vector3::zeros(),
                t: unit,
            }
        };
        let held = model.clone();
        let scaled = move |s: f64| {
            A::screw(ScrewCoordinates {
                l: unit.l * s,
                t: unit.t * s,
            })
        };
        let path = move |t: f64| {
            let q = drive.at(t);
            let pose = held.relative_pose(&[q.value]).unwrap_or_else(|_| {
                Isometry3::from_parts(
                    Translation3::new(f64::NAN, f64::NAN, f64::NAN),
                    UnitQuaternion::identity(),
                )
            });
            MotorPoint {
                motor: motor::from_pose::<A>(pose.translation.vector, &pose.rotation),
                velocity: scaled(q.rate),
                acceleration: scaled(q.acceleration),
            }
        };
        return Ok(Arc::new(pinning::motor_joint::<A>(name, path)));
    }
    Ok(match *model.kind() {
        JointKind::Spherical => Arc::new(pinning::point::<A>(name, c, p)),
        JointKind::Revolute { axis } => {
            Arc::new(pinning::hinge::<A>(name, (c, in_child(&axis)), (p, in_parent(&axis)))?)
        }
        JointKind::Cylindrical { axis } => {
            Arc::new(pinning::line::<A>(name, (c, in_child(&axis)), (p, in_parent(&axis)))?)
        }
        JointKind::Prismatic { axis } => {
            let normal = JointModel::plane_directions(&axis)[0];
            Arc::new(pinning::prismatic::<A>(
                name,
                (c, in_child(&axis), in_child(&normal)),
                (p, in_parent(&axis), in_parent(&normal)),
            )?)
        }
        JointKind::Planar { normal } => {
            let (body, world) = (in_child(&normal), in_parent(&normal));
            Arc::new(pinning::plane::<A>(name, (body, body.dot(&c)), (world, world.dot(&p)))?)
        }
        JointKind::Weld => {
            let rest = parent * child.inverse();
            let zero = A::screw(ScrewCoordinates::default());
            let held = MotorPoint {
                motor: motor::from_pose::<A>(rest.translation.vector, &rest.rotation),
                velocity: zero,
                acceleration: zero,
            };
            Arc::new(pinning::motor_joint::<A>(name, move |_t: f64| held))
        }
        JointKind::Universal { .. } => {
            return Err(invalid(
                format!("joint {name}"),
                "a universal joint has no pinned form (its two axes staying normal is not an incidence of pinned \
                 objects); write formulation = \"virtual_power\"",
            ))
        }
        JointKind::Free => return Err(invalid(format!("joint {name}"), "a free joint has no rows")),
    })
}
