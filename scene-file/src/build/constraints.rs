//! A joint that is no joint model as a `dynamics` constraint, by pinning or by virtual power, in an algebra with
//! [`RoundPins`] (only CGA has the spheres and circles that pinning a point to one needs).

use std::sync::Arc;

use dynamics::constraints::{linear, pinning, Constraint, MotorPoint, PinningAlgebra, SurfacePin, VirtualPower};
use dynamics::{motor, Cga, Pga, ScrewCoordinates};
use nalgebra::Vector3;

use crate::check::geometry::{AxisFreedom, CheckedGeometry};
use crate::error::{invalid, SceneFileError};

/// The pins of a body point on a sphere or a circle, where the algebra has them: only CGA has the spheres and circles
/// that pinning a point to one needs (theory §9, §13).
pub trait RoundPins: PinningAlgebra {
    /// The pin holding the body point (body coordinates) on the sphere (world, m); `None` without spheres.
    fn point_on_sphere_pin(
        name: String,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>>;
    /// The pin holding the body point on the circle (centre, radius, unit normal of its plane; world, m);
    /// `None` without circles.
    fn point_on_circle_pin(
        name: String,
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>>;
}

impl RoundPins for Pga {
    fn point_on_sphere_pin(_: String, _: Vector3<f64>, _: Vector3<f64>, _: f64) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }

    fn point_on_circle_pin(
        _: String,
        _: Vector3<f64>,
        _: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }
}

impl RoundPins for Cga {
    fn point_on_sphere_pin(
        name: String,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_sphere(name, body_point, centre, radius)))
    }

    fn point_on_circle_pin(
        name: String,
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_circle(name, body_point, circle)))
    }
}

/// The constraint of `geometry` (checked, its reference side in the reference body's frame, or the world's) in
/// algebra `A`, by pinning or by virtual power, called `name` in messages.
pub(crate) fn constraint_of<A: RoundPins>(
    name: String,
    geometry: CheckedGeometry,
    pinned: bool,
) -> Result<Arc<dyn Constraint<A>>, SceneFileError> {
    let not_expressible = |name, object| SceneFileError::NotExpressible {
        name,
        object,
        algebra: A::NAME,
    };
    Ok(match geometry {
        CheckedGeometry::Universal { body, world } => {
            if pinned {
                return Err(invalid(
                    format!("constraint {name}"),
                    "a universal joint has no pinned form (its two axes staying normal is not an incidence of \
                     pinned objects); write formulation = \"virtual_power\"",
                ));
            }
            Arc::new(VirtualPower::universal(name, body, world)?)
        }
        CheckedGeometry::Weld { position, orientation } => {
            let held = motor::from_pose::<A>(position, &orientation);
            if pinned {
                let zero = A::screw(ScrewCoordinates::default());
                let point = MotorPoint {
                    motor: held,
                    velocity: zero,
                    acceleration: zero,
                };
                Arc::new(pinning::motor_joint::<A>(name, move |_t: f64| point))
            } else {
                Arc::new(VirtualPower::weld(name, held))
            }
        }
        CheckedGeometry::Ball {
            body_point,
            world_point,
        } => {
            if pinned {
                Arc::new(pinning::point::<A>(name, body_point, world_point))
            } else {
                Arc::new(VirtualPower::ball_joint(name, body_point, world_point))
            }
        }
        CheckedGeometry::Axis { freedom, body, world } => match (freedom, pinned) {
            (AxisFreedom::Turn, true) => Arc::new(pinning::hinge::<A>(name, body, world)?),
            (AxisFreedom::Turn, false) => Arc::new(VirtualPower::hinge(name, body, world)?),
            (AxisFreedom::TurnAndSlide, true) => Arc::new(pinning::line::<A>(name, body, world)?),
            (AxisFreedom::TurnAndSlide, false) => Arc::new(VirtualPower::cylindrical(name, body, world)?),
            (
                AxisFreedom::Slide {
                    body_normal,
                    world_normal,
                },
                _,
            ) => {
                let body = (body.0, body.1, body_normal);
                let world = (world.0, world.1, world_normal);
                if pinned {
                    Arc::new(pinning::prismatic::<A>(name, body, world)?)
                } else {
                    Arc::new(VirtualPower::prismatic(name, body, world)?)
                }
            }
        },
        CheckedGeometry::Planar { body, world } => {
            if pinned {
                // The planes {x : n·x = n·p} of the unit normals (pinned planes need normals of one length).
                let plane = |(point, normal): (Vector3<f64>, Vector3<f64>)| (normal, normal.dot(&point));
                Arc::new(pinning::plane::<A>(name, plane(body), plane(world))?)
            } else {
                Arc::new(VirtualPower::planar(name, body, world)?)
            }
        }
        CheckedGeometry::Line { body_point, world } => {
            if pinned {
                Arc::new(linear::point_on_line::<A>(name, body_point, world))
            } else {
                Arc::new(VirtualPower::point_on_line(name, body_point, world)?)
            }
        }
        CheckedGeometry::Plane {
            body_point,
            normal,
            offset,
        } => {
            if pinned {
                Arc::new(linear::point_on_plane::<A>(name, body_point, (normal, offset)))
            } else {
                Arc::new(VirtualPower::point_on_plane(name, body_point, (normal, offset))?)
            }
        }
        CheckedGeometry::Surfaces {
            body_point,
            first,
            second,
        } => match (second, pinned) {
            (None, true) => Arc::new(SurfacePin::point_on_surface(name, body_point, first)?),
            (None, false) => Arc::new(VirtualPower::point_on_surface(name, body_point, first)?),
            (Some(second), true) => Arc::new(SurfacePin::point_on_curve(name, body_point, [first, second])?),
            (Some(second), false) => Arc::new(VirtualPower::point_on_curve(name, body_point, [first, second])?),
        },
        CheckedGeometry::Round {
            body_point,
            centre,
            radius,
            normal: None,
        } => {
            if pinned {
                A::point_on_sphere_pin(name.clone(), body_point, centre, radius)
                    .ok_or_else(|| not_expressible(name, "sphere"))?
            } else {
                Arc::new(VirtualPower::point_on_sphere(name, body_point, centre, radius)?)
            }
        }
        CheckedGeometry::Round {
            body_point,
            centre,
            radius,
            normal: Some(normal),
        } => {
            let circle = (centre, radius, normal);
            if pinned {
                A::point_on_circle_pin(name.clone(), body_point, circle)
                    .ok_or_else(|| not_expressible(name, "circle"))?
            } else {
                Arc::new(VirtualPower::point_on_circle(name, body_point, circle)?)
            }
        }
    })
}
