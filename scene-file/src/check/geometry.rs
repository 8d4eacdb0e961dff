//! A constraint's geometry checked ([`CheckedGeometry`]): finite points, unit axes and normals, positive radii; moved into
//! the world from a reference body's frame, and how far a body is from satisfying it.

use dynamics::motor;
use dynamics::surfaces::{Surface, SurfaceError};
use dynamics::Pga;
use nalgebra::{Unit, UnitQuaternion, Vector3};

use super::bodies::Pose;
use super::values::{direction, finite, positive, rescaled};
use crate::error::{invalid, SceneFileError};
use crate::syntax::joints::Geometry;

/// What an axis joint leaves free.
#[derive(Clone, Copy, Debug)]
pub enum AxisFreedom {
    /// Turning about the axis: a hinge.
    Turn,
    /// Turning about and sliding along it: a cylindrical joint.
    TurnAndSlide,
    /// Sliding along it: a prismatic joint, whose body normal stays along the world normal (unit, normal to
    /// their axes).
    Slide {
        /// Body coordinates.
        body_normal: Vector3<f64>,
        /// The reference's coordinates.
        world_normal: Vector3<f64>,
    },
}

/// A constraint's geometry with every value checked: finite points, unit axes and normals, positive radii.
/// `body` values are in body coordinates, `world` values and the rest in the reference's (the world's, or a
/// reference body's until [`CheckedGeometry::in_world`]); points and lengths in metres.
// A surface holds its multivector and pose (about 200 bytes); a geometry is checked once per joint and read per
// sample for the violation, where a box would cost an indirection and the type its `Copy`.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug)]
pub enum CheckedGeometry {
    /// A body point held at a world point.
    Ball {
        /// The held point.
        body_point: Vector3<f64>,
        /// Where it is held.
        world_point: Vector3<f64>,
    },
    /// A body axis (point, unit direction) held on a world axis.
    Axis {
        /// Turning, sliding or both.
        freedom: AxisFreedom,
        /// The body axis.
        body: (Vector3<f64>, Vector3<f64>),
        /// The axis it is held on.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body plane (point, unit normal) held on a world plane.
    Planar {
        /// The body plane.
        body: (Vector3<f64>, Vector3<f64>),
        /// The plane it is held on.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body point held at a world point, the body axis (point, unit direction) kept normal to the world axis: a
    /// universal joint.
    Universal {
        /// The body point and axis.
        body: (Vector3<f64>, Vector3<f64>),
        /// The world point and axis.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// The body held at a pose: its centre of mass at `position`, turned by `orientation` (body → world).
    Weld {
        /// m.
        position: Vector3<f64>,
        /// Body → world.
        orientation: UnitQuaternion<f64>,
    },
    /// A body point held on a world line (point, unit direction).
    Line {
        /// The held point.
        body_point: Vector3<f64>,
        /// The line.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body point held on the plane `normal · x = offset`.
    Plane {
        /// The held point.
        body_point: Vector3<f64>,
        /// Unit.
        normal: Vector3<f64>,
        /// The plane's signed distance from the origin along `normal`.
        offset: f64,
    },
    /// A body point held on a surface, or on the curve where two meet.
    Surfaces {
        /// The held point.
        body_point: Vector3<f64>,
        /// The (first) surface.
        first: Surface,
        /// The second surface of a curve.
        second: Option<Surface>,
    },
    /// A body point held on a sphere, or on a circle of it.
    Round {
        /// The held point.
        body_point: Vector3<f64>,
        /// The sphere's and the circle's centre.
        centre: Vector3<f64>,
        /// Positive.
        radius: f64,
        /// The circle's plane normal; `None` for a sphere.
        normal: Option<Vector3<f64>>,
    },
}

/// A joint's geometry as checked: every value the file gives, and where a fixed joint is given no pose, the start's.
#[allow(clippy::large_enum_variant)] // as `CheckedGeometry`, which it mostly is
#[derive(Clone, Copy, Debug)]
pub enum HeldGeometry {
    /// Every value given.
    Given(CheckedGeometry),
    /// A fixed joint without a position or an orientation (or both): it keeps those the body starts in.
    WeldAtStart {
        /// The body's centre of mass in the reference's frame (m), if given.
        position: Option<Vector3<f64>>,
        /// Body → reference, if given.
        orientation: Option<UnitQuaternion<f64>>,
    },
}

impl HeldGeometry {
    /// The geometry; a fixed joint's missing position or orientation taken from `start`, the body's pose in its
    /// reference's frame at the start (asked for only then).
    pub fn at_start(self, start: impl FnOnce() -> Pose) -> CheckedGeometry {
        match self {
            HeldGeometry::Given(geometry) => geometry,
            HeldGeometry::WeldAtStart { position, orientation } => {
                let start = start();
                CheckedGeometry::Weld {
                    position: position.unwrap_or(start.0),
                    orientation: orientation.unwrap_or(start.1),
                }
            }
        }
    }
}

/// The values of the constraint `name`, checked with messages naming it and the key.
struct Fields<'a> {
    name: &'a str,
}

impl Fields<'_> {
    fn what(&self, field: &str) -> String {
        format!("constraint {}: {field}", self.name)
    }

    fn point(&self, field: &str, values: [f64; 3]) -> Result<Vector3<f64>, SceneFileError> {
        finite(&self.what(field), values)
    }

    fn unit(&self, field: &str, values: [f64; 3]) -> Result<Vector3<f64>, SceneFileError> {
        direction(&self.what(field), values).map(Unit::into_inner)
    }

    /// A point and a unit direction: an axis, or a plane by its normal.
    fn point_and_direction(
        &self,
        (point, direction): (&str, &str),
        values: ([f64; 3], [f64; 3]),
    ) -> Result<(Vector3<f64>, Vector3<f64>), SceneFileError> {
        Ok((self.point(point, values.0)?, self.unit(direction, values.1)?))
    }

    /// Normal to a unit axis: its component across the axis, which must not vanish (its length does not matter,
    /// so it is rescaled, lest the component overflow).
    fn across(&self, field: &str, axis: Vector3<f64>, values: [f64; 3]) -> Result<Vector3<f64>, SceneFileError> {
        let (_, normal) = rescaled(&self.what(field), values)?;
        let across = normal - axis * axis.dot(&normal);
        if across.norm() > 1e-9 * normal.norm() {
            Ok(across.normalize())
        } else {
            Err(invalid(self.what(field), "is zero or along the axis"))
        }
    }
}

impl Geometry {
    /// Every value checked, messages naming the constraint `name`.
    pub(crate) fn checked(&self, name: &str) -> Result<HeldGeometry, SceneFileError> {
        let fields = Fields { name };
        match self {
            Geometry::Fixed { position, orientation } => {
                let position = position.map(|p| fields.point("position", p)).transpose()?;
                let orientation = (orientation.as_ref())
                    .map(|o| o.rotation_of(&fields.what("orientation")))
                    .transpose()?;
                Ok(match (position, orientation) {
                    (Some(position), Some(orientation)) => {
                        HeldGeometry::Given(CheckedGeometry::Weld { position, orientation })
                    }
                    _ => HeldGeometry::WeldAtStart { position, orientation },
                })
            }
            Geometry::BallJoint { .. }
            | Geometry::Universal(_)
            | Geometry::Hinge(_)
            | Geometry::Cylindrical(_)
            | Geometry::Prismatic { .. }
            | Geometry::Planar { .. } => self.checked_joint(&fields).map(HeldGeometry::Given),
            _ => self.checked_point_on(&fields).map(HeldGeometry::Given),
        }
    }

    /// A joint between frames: a ball, universal, hinge, cylindrical, prismatic or planar joint.
    fn checked_joint(&self, fields: &Fields) -> Result<CheckedGeometry, SceneFileError> {
        let point = |field: &str, values| fields.point(field, values);
        let unit = |field: &str, values| fields.unit(field, values);
        Ok(match self {
            Geometry::BallJoint {
                body_point,
                world_point,
            } => CheckedGeometry::Ball {
                body_point: point("body_point", *body_point)?,
                world_point: point("world_point", *world_point)?,
            },
            Geometry::Universal(joint) => CheckedGeometry::Universal {
                body: fields.point_and_direction(("body_point", "body_axis"), (joint.body_point, joint.body_axis))?,
                world: fields
                    .point_and_direction(("world_point", "world_axis"), (joint.world_point, joint.world_axis))?,
            },
            Geometry::Hinge(joint) | Geometry::Cylindrical(joint) => CheckedGeometry::Axis {
                freedom: if matches!(self, Geometry::Hinge(_)) {
                    AxisFreedom::Turn
                } else {
                    AxisFreedom::TurnAndSlide
                },
                body: fields.point_and_direction(("body_point", "body_axis"), (joint.body_point, joint.body_axis))?,
                world: fields
                    .point_and_direction(("world_point", "world_axis"), (joint.world_point, joint.world_axis))?,
            },
            Geometry::Prismatic {
                body_point,
                body_axis,
                body_normal,
                world_point,
                world_axis,
                world_normal,
            } => {
                let (body_axis, world_axis) = (unit("body_axis", *body_axis)?, unit("world_axis", *world_axis)?);
                CheckedGeometry::Axis {
                    freedom: AxisFreedom::Slide {
                        body_normal: fields.across("body_normal", body_axis, *body_normal)?,
                        world_normal: fields.across("world_normal", world_axis, *world_normal)?,
                    },
                    body: (point("body_point", *body_point)?, body_axis),
                    world: (point("world_point", *world_point)?, world_axis),
                }
            }
            Geometry::Planar {
                body_point,
                body_normal,
                world_point,
                world_normal,
            } => CheckedGeometry::Planar {
                body: fields.point_and_direction(("body_point", "body_normal"), (*body_point, *body_normal))?,
                world: fields.point_and_direction(("world_point", "world_normal"), (*world_point, *world_normal))?,
            },
            _ => unreachable!("`checked` passes joints between frames only"),
        })
    }

    /// A body point on a line, plane, sphere, circle, surface or curve.
    fn checked_point_on(&self, fields: &Fields) -> Result<CheckedGeometry, SceneFileError> {
        let what = |field: &str| fields.what(field);
        let point = |field: &str, values| fields.point(field, values);
        let round = |body_point, centre, radius, normal| {
            Ok::<_, SceneFileError>(CheckedGeometry::Round {
                body_point: point("body_point", body_point)?,
                centre: point("centre", centre)?,
                radius: positive(&what("radius"), radius)?,
                normal,
            })
        };
        Ok(match self {
            Geometry::PointOnLine {
                body_point,
                world_point,
                world_axis,
            } => CheckedGeometry::Line {
                body_point: point("body_point", *body_point)?,
                world: fields.point_and_direction(("world_point", "world_axis"), (*world_point, *world_axis))?,
            },
            Geometry::PointOnPlane {
                body_point,
                normal,
                offset,
            } => {
                let (scale, scaled_normal) = rescaled(&what("normal"), *normal)?;
                if !offset.is_finite() {
                    return Err(invalid(what("offset"), format!("{offset} is not finite")));
                }
                // n·x = d is the unit normal's n/|n| · x = d/|n|.
                let unit_offset = offset / scale / scaled_normal.norm();
                if !unit_offset.is_finite() {
                    return Err(invalid(
                        what("offset"),
                        format!("{offset} over the normal's length {normal:?} is not finite"),
                    ));
                }
                CheckedGeometry::Plane {
                    body_point: point("body_point", *body_point)?,
                    normal: scaled_normal.normalize(),
                    offset: unit_offset,
                }
            }
            Geometry::PointOnSphere {
                body_point,
                centre,
                radius,
            } => round(*body_point, *centre, *radius, None)?,
            Geometry::PointOnCircle {
                body_point,
                centre,
                radius,
                normal,
            } => round(*body_point, *centre, *radius, Some(fields.unit("normal", *normal)?))?,
            Geometry::PointOnSurface { body_point, surface } => CheckedGeometry::Surfaces {
                body_point: point("body_point", *body_point)?,
                first: surface.surface(&what("surface"))?,
                second: None,
            },
            Geometry::PointOnCurve { body_point, surfaces } => match surfaces.as_slice() {
                [first, second] => CheckedGeometry::Surfaces {
                    body_point: point("body_point", *body_point)?,
                    first: first.surface(&what("surfaces[0]"))?,
                    second: Some(second.surface(&what("surfaces[1]"))?),
                },
                _ => {
                    return Err(invalid(
                        what("surfaces"),
                        format!("{} given: a curve is where exactly two surfaces meet", surfaces.len()),
                    ))
                }
            },
            _ => unreachable!("`checked` passes points on curves and surfaces only"),
        })
    }
}

impl CheckedGeometry {
    /// The geometry with its reference-side points, axes and planes moved from the reference body's frame (at
    /// its pose) into the world.
    pub fn in_world(&self, (position, orientation): &Pose) -> Result<CheckedGeometry, SceneFileError> {
        let point = |p: Vector3<f64>| position + orientation * p;
        let axis = |a: Vector3<f64>| orientation * a;
        Ok(match *self {
            CheckedGeometry::Ball {
                body_point,
                world_point,
            } => CheckedGeometry::Ball {
                body_point,
                world_point: point(world_point),
            },
            CheckedGeometry::Axis { freedom, body, world } => CheckedGeometry::Axis {
                freedom: match freedom {
                    AxisFreedom::Slide {
                        body_normal,
                        world_normal,
                    } => AxisFreedom::Slide {
                        body_normal,
                        world_normal: axis(world_normal),
                    },
                    other => other,
                },
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Planar { body, world } => CheckedGeometry::Planar {
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Universal { body, world } => CheckedGeometry::Universal {
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Weld {
                position: at,
                orientation: turn,
            } => CheckedGeometry::Weld {
                position: point(at),
                orientation: orientation * turn,
            },
            CheckedGeometry::Line { body_point, world } => CheckedGeometry::Line {
                body_point,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Plane {
                body_point,
                normal,
                offset,
            } => {
                // n·x = d in the reference frame is (Rn)·x_w = d + (Rn)·c in the world.
                let normal = axis(normal);
                CheckedGeometry::Plane {
                    body_point,
                    normal,
                    offset: offset + normal.dot(position),
                }
            }
            CheckedGeometry::Surfaces {
                body_point,
                first,
                second,
            } => {
                let carried = motor::from_pose::<Pga>(*position, orientation);
                let carried_away = |error: SurfaceError| invalid(format!("surface {}", error.parameter), error.reason);
                CheckedGeometry::Surfaces {
                    body_point,
                    first: first.moved::<Pga>(carried).map_err(carried_away)?,
                    second: second
                        .map(|surface| surface.moved::<Pga>(carried))
                        .transpose()
                        .map_err(carried_away)?,
                }
            }
            CheckedGeometry::Round {
                body_point,
                centre,
                radius,
                normal,
            } => CheckedGeometry::Round {
                body_point,
                centre: point(centre),
                radius,
                normal: normal.map(axis),
            },
        })
    }

    /// How far a body at `pose` is from satisfying the constraint (m): the body point's distance from where it
    /// must be; for axis joints also that of the point 1 m further along the body axis, for prismatic and
    /// planar joints that of the point 1 m along the body normal, for universal joints how far the point 1 m along
    /// the body axis is off the plane normal to the world axis, for welds the centre of mass's distance and the
    /// angle (rad) of the turn between the pose and the one held. World geometry (see [`CheckedGeometry::in_world`]
    /// for a body reference).
    pub fn violation(&self, (position, orientation): &Pose) -> f64 {
        let world = |body_point: Vector3<f64>| position + orientation * body_point;
        // Distance of a world point from a world line (point, unit direction).
        let off_line = |(on_line, direction): (Vector3<f64>, Vector3<f64>), p: Vector3<f64>| {
            (p - on_line).cross(&direction).norm()
        };
        match *self {
            CheckedGeometry::Ball {
                body_point,
                world_point,
            } => (world(body_point) - world_point).norm(),
            CheckedGeometry::Axis {
                freedom,
                body,
                world: line,
            } => {
                let along_axis = off_line(line, world(body.0 + body.1));
                let at_point = match freedom {
                    AxisFreedom::Turn => (world(body.0) - line.0).norm(),
                    AxisFreedom::TurnAndSlide => off_line(line, world(body.0)),
                    AxisFreedom::Slide {
                        body_normal,
                        world_normal,
                    } => {
                        // The point 1 m along the body normal stays in the plane of the axis and the world normal.
                        let off_plane = (world(body.0 + body_normal) - line.0).dot(&line.1.cross(&world_normal));
                        off_line(line, world(body.0)).max(off_plane.abs())
                    }
                };
                at_point.max(along_axis)
            }
            CheckedGeometry::Universal { body, world: line } => {
                // The point 1 m along the body axis off the plane normal to the world axis.
                let off_normal = (orientation * body.1).dot(&line.1).abs();
                (world(body.0) - line.0).norm().max(off_normal)
            }
            CheckedGeometry::Weld {
                position: at,
                orientation: turn,
            } => (position - at).norm().max(orientation.angle_to(&turn)),
            CheckedGeometry::Planar { body, world: plane } => {
                let off_plane = plane.1.dot(&(world(body.0) - plane.0)).abs();
                // The point 1 m along the body normal from the world normal through the body point.
                let tilt = (orientation * body.1).cross(&plane.1).norm();
                off_plane.max(tilt)
            }
            CheckedGeometry::Line {
                body_point,
                world: line,
            } => off_line(line, world(body_point)),
            CheckedGeometry::Plane {
                body_point,
                normal,
                offset,
            } => (normal.dot(&world(body_point)) - offset).abs(),
            CheckedGeometry::Surfaces {
                body_point,
                first,
                second,
            } => {
                // |F| / |∇F|: the distance from the surface to first order (exact for a plane).
                let at = world(body_point);
                let distance = |surface: &Surface| surface.value(&at).abs() / surface.gradient(&at).norm();
                distance(&first).max(second.as_ref().map_or(0.0, distance))
            }
            CheckedGeometry::Round {
                body_point,
                centre,
                radius,
                normal,
            } => {
                let offset = world(body_point) - centre;
                let off_plane = normal.map_or(0.0, |n| n.dot(&offset).abs());
                (offset.norm() - radius).abs().max(off_plane)
            }
        }
    }
}

/// The pose of a body at `body` (world) in the frame of a reference at `reference` (the world if `None`).
pub(crate) fn relative_pose(body: &Pose, reference: Option<&Pose>) -> Pose {
    match reference {
        None => *body,
        Some((position, orientation)) => (
            orientation.inverse() * (body.0 - position),
            orientation.inverse() * body.1,
        ),
    }
}

/// A joint's checked geometry, its body and its reference body (`None`: the world), by index.
pub type JointGeometry = (CheckedGeometry, usize, Option<usize>);

/// Each joint's violation (m) with the bodies at `poses` (by body index).
pub fn joint_violations<'a>(joints: &'a [JointGeometry], poses: &'a [Pose]) -> impl Iterator<Item = f64> + 'a {
    joints.iter().map(|(geometry, body, reference)| match reference {
        None => geometry.violation(&poses[*body]),
        // A reference pose that is not a rigid motion (never one from a run) has no violation to measure.
        Some(r) => geometry
            .in_world(&poses[*r])
            .map_or(f64::NAN, |g| g.violation(&poses[*body])),
    })
}
