//! The joints and incidences by virtual power (`docs/theory.md` §6, §14): ball, hinge, universal, cylindrical,
//! prismatic, planar, weld and motor joints, and a body point on a plane, line, sphere, circle or surface, each as the
//! constraint wrenches it can exert — forces at the constrained body point and couples along directions that follow
//! the body (see [`crate::constraints::virtual_power`]).

use std::sync::Arc;

use arrayvec::ArrayVec;
use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::on_surfaces::{check_curve, check_held_point};
use crate::constraints::paths::{Fixed, MotorPath, MotorPoint, Path};
use crate::constraints::virtual_power::{coordinate_axes, normals_to, unit, Alignment, VirtualPower, Wrenches};
use crate::constraints::{Composite, ConstraintError};
use crate::surfaces::Surface;

impl<A: Algebra> VirtualPower<A> {
    fn point_joint(
        name: String,
        body_point: Vector3<f64>,
        point: Arc<dyn Path<Vector3<f64>>>,
        forces: impl IntoIterator<Item = Vector3<f64>>,
        alignments: impl IntoIterator<Item = (Vector3<f64>, Vector3<f64>)>,
    ) -> Self {
        let forces: ArrayVec<Vector3<f64>, 3> = forces.into_iter().collect();
        VirtualPower {
            name,
            wrenches: Wrenches::Point {
                body_point,
                fixed: point.is_fixed().then(|| point.at(0.0).value),
                point,
                along_axes: forces == coordinate_axes(),
                forces,
                alignments: alignments
                    .into_iter()
                    .map(|(body_direction, normal)| Alignment { body_direction, normal })
                    .collect(),
            },
        }
    }

    /// Ball joint: the body point `body_point` (body coordinates) stays at `world_point`. Rank 3.
    ///
    /// A rod's top end held at the origin: a state swinging about the pivot keeps it; one moved 1 cm off breaks it
    /// by 1 cm (the force rows' residuals are distances).
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?; // 1 kg, 1 m along body z
    /// let top = Vector3::new(0.0, 0.0, 0.5); // body point, m
    /// let ball = VirtualPower::<Pga>::ball_joint("pivot", top, Vector3::zeros());
    /// assert_eq!(ball.rank(), 3);
    /// let pendulum = Mechanism::single(rod).with_constraint(ball)?;
    /// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, -0.3, 0.0));
    /// let (centre, spin) = (-(tilt * top), Vector3::new(1.0, 0.5, 2.0)); // m, rad/s
    /// let swinging = State::from_world_twist(&rod, centre, &tilt, spin, spin.cross(&centre));
    /// let on = pendulum.violation(0.0, &[swinging])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// let off = State::from_world_twist(&rod, centre + Vector3::y() * 0.01, &tilt, spin, spin.cross(&centre));
    /// assert!((pendulum.violation(0.0, &[off])?.position - 0.01).abs() < 1e-15); // m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn ball_joint(name: impl Into<String>, body_point: Vector3<f64>, world_point: Vector3<f64>) -> Self {
        Self::point_joint(
            name.into(),
            body_point,
            Arc::new(Fixed(world_point)),
            coordinate_axes(),
            [],
        )
    }

    /// A driven ball joint: the body point stays at a pivot moving along `pivot(t)` (value, velocity,
    /// acceleration, world or reference frame). The pivot's motion does work: force k's velocity condition is
    /// `⟨Ḃ ∧ T_bk⟩_Π = ṗₖ`, the prescribed power of the driven motion (theory §14.1). Rank 3.
    ///
    /// A pivot raised at 0.5 m/s: a rod hanging from it and rising with it is on the joint, velocities included;
    /// the same rod at rest is not.
    ///
    /// ```
    /// use dynamics::constraints::{PathPoint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let lift = |t: f64| PathPoint {
    ///     value: Vector3::z() * (0.5 * t),
    ///     rate: Vector3::z() * 0.5,
    ///     acceleration: Vector3::zeros(),
    /// };
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let top = Vector3::new(0.0, 0.0, 0.5);
    /// let lifted = Mechanism::<Pga>::single(rod).with_constraint(VirtualPower::driven_ball_joint("hook", top, lift))?;
    /// let still = UnitQuaternion::identity();
    /// let at = |v: f64| State::new(&rod, Vector3::zeros(), &still, Vector3::zeros(), Vector3::z() * v);
    /// let rising = lifted.violation(1.0, &[at(0.5)])?; // at t = 1 s the hook is at z = 0.5 m
    /// assert!(rising.position < 1e-15 && rising.velocity < 1e-15);
    /// assert!((lifted.violation(1.0, &[at(0.0)])?.velocity - 0.5).abs() < 1e-15); // m/s behind the hook
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn driven_ball_joint(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        pivot: impl Path<Vector3<f64>> + 'static,
    ) -> Self {
        Self::point_joint(name.into(), body_point, Arc::new(pivot), coordinate_axes(), [])
    }

    /// Hinge: a ball joint at the point plus two couples normal to the axis, so the body turns only about
    /// the world axis through `world_point`; `body_axis` is the axis in body coordinates. Rank 5.
    ///
    /// A door hinged about the world z axis at its edge: swinging about the axis keeps the hinge, a tilt about x
    /// breaks it.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let door = Body::cuboid(20.0, Vector3::new(0.8, 0.04, 2.0))?; // kg; m
    /// let edge = Vector3::new(-0.4, 0.0, 0.0); // body point on the hinge line, m
    /// let hinge = VirtualPower::<Pga>::hinge("hinge", (edge, Vector3::z()), (Vector3::zeros(), Vector3::z()))?;
    /// assert_eq!(hinge.rank(), 5);
    /// let system = Mechanism::single(door).with_constraint(hinge)?;
    /// let state = |turn: Vector3<f64>, spin: Vector3<f64>| {
    ///     let rotation = UnitQuaternion::from_scaled_axis(turn);
    ///     let centre = -(rotation * edge);
    ///     State::from_world_twist(&door, centre, &rotation, spin, spin.cross(&centre))
    /// };
    /// let open = system.violation(0.0, &[state(Vector3::z() * 1.2, Vector3::z() * 0.5)])?; // rad, rad/s
    /// assert!(open.position < 1e-15 && open.velocity < 1e-15);
    /// assert!(system.violation(0.0, &[state(Vector3::x() * 0.1, Vector3::zeros())])?.position > 0.09);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn hinge(
        name: impl Into<String>,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let (body_axis, world_axis) = (
            unit(&name, "body axis", body_axis)?,
            unit(&name, "world axis", world_axis)?,
        );
        let normals = normals_to(world_axis);
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(world_point)),
            coordinate_axes(),
            normals.map(|n| (body_axis, n)),
        ))
    }

    /// Universal joint (Cardan): a ball joint at the point plus one couple keeping the body axis normal to the
    /// world axis, so the body turns about the world axis and about its own axis (two degrees of freedom). The
    /// axes must be normal to each other (within 1e-9 of their lengths) when the joint is assembled. Rank 4.
    ///
    /// A shaft coupled to a driving shaft along world x, its own axis along body y: turning about either axis
    /// keeps the joint, a turn about the third direction breaks it.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let shaft = Body::cylinder(1.0, 0.02, 0.4)?;
    /// let cross = Vector3::new(0.0, 0.0, 0.2); // body point at the cross, m
    /// let joint = VirtualPower::<Pga>::universal("cardan", (cross, Vector3::y()), (Vector3::zeros(), Vector3::x()))?;
    /// assert_eq!(joint.rank(), 4);
    /// let system = Mechanism::single(shaft).with_constraint(joint)?;
    /// let at = |turn: UnitQuaternion<f64>| State::new(&shaft, -(turn * cross), &turn, Vector3::zeros(), Vector3::zeros());
    /// let both = UnitQuaternion::from_scaled_axis(Vector3::x() * 0.4) * UnitQuaternion::from_scaled_axis(Vector3::y() * 0.7);
    /// assert!(system.violation(0.0, &[at(both)])?.position < 1e-15);
    /// let twisted = UnitQuaternion::from_scaled_axis(Vector3::z() * 0.1);
    /// assert!((system.violation(0.0, &[at(twisted)])?.position - 0.1f64.sin()).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn universal(
        name: impl Into<String>,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let (body_axis, world_axis) = (
            unit(&name, "body axis", body_axis)?,
            unit(&name, "world axis", world_axis)?,
        );
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(world_point)),
            coordinate_axes(),
            [(body_axis, world_axis)],
        ))
    }

    /// Cylindrical joint: two forces normal to the axis at the body point plus two couples normal to the axis,
    /// so the body slides along and turns about the world axis. Rank 4.
    ///
    /// A sleeve on the vertical line through (1, 0, 0): it may slide along and turn about it.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let sleeve = Body::cylinder(1.0, 0.05, 0.3)?;
    /// let (on_body, on_world) = ((Vector3::zeros(), Vector3::z()), (Vector3::x(), Vector3::z())); // (point, axis)
    /// let joint = VirtualPower::<Pga>::cylindrical("sleeve", on_body, on_world)?;
    /// assert_eq!(joint.rank(), 4);
    /// let system = Mechanism::single(sleeve).with_constraint(joint)?;
    /// let turned = UnitQuaternion::from_scaled_axis(Vector3::z() * 2.0);
    /// // 0.7 m up the line, turning at 3 rad/s and sliding at 1 m/s.
    /// let (centre, spin) = (Vector3::new(1.0, 0.0, 0.7), Vector3::z() * 3.0);
    /// let state = State::from_world_twist(&sleeve, centre, &turned, spin, Vector3::z());
    /// let on = system.violation(0.0, &[state])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn cylindrical(
        name: impl Into<String>,
        (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
        (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let (body_axis, world_axis) = (
            unit(&name, "body axis", body_axis)?,
            unit(&name, "world axis", world_axis)?,
        );
        let normals = normals_to(world_axis);
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(world_point)),
            normals,
            normals.map(|n| (body_axis, n)),
        ))
    }

    /// Prismatic joint (slider): the body slides along the world axis without turning. The cylindrical joint's
    /// two forces and two couples, plus a couple about the axis keeping the body direction `body_normal`
    /// (normal to the body axis) along the world direction `world_normal` (normal to the world axis). Rank 5.
    ///
    /// A carriage on a rail along world x: it slides, but a turn about the rail breaks the joint.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let carriage = Body::cuboid(2.0, Vector3::new(0.3, 0.2, 0.1))?;
    /// let (x, z) = (Vector3::x(), Vector3::z());
    /// let rail = VirtualPower::<Pga>::prismatic("rail", (Vector3::zeros(), x, z), (Vector3::zeros(), x, z))?;
    /// assert_eq!(rail.rank(), 5);
    /// let system = Mechanism::single(carriage).with_constraint(rail)?;
    /// let still = UnitQuaternion::identity();
    /// let sliding = State::new(&carriage, x * 1.5, &still, Vector3::zeros(), x * 2.0); // m, m/s
    /// let on = system.violation(0.0, &[sliding])?;
    /// assert!(on.position == 0.0 && on.velocity == 0.0);
    /// let rolled = UnitQuaternion::from_scaled_axis(x * 0.2);
    /// let off = State::new(&carriage, x * 1.5, &rolled, Vector3::zeros(), Vector3::zeros());
    /// assert!((system.violation(0.0, &[off])?.position - 0.2f64.sin()).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn prismatic(
        name: impl Into<String>,
        (body_point, body_axis, body_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
        (world_point, world_axis, world_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let (body_axis, world_axis) = (
            unit(&name, "body axis", body_axis)?,
            unit(&name, "world axis", world_axis)?,
        );
        let body_normal = unit(
            &name,
            "body normal",
            body_normal - body_axis * body_axis.dot(&body_normal),
        )?;
        let world_normal = unit(
            &name,
            "world normal",
            world_normal - world_axis * world_axis.dot(&world_normal),
        )?;
        // The joint frame: the world normal and the axis's second normal; the body normal must not tilt
        // towards the second.
        let second = world_axis.cross(&world_normal);
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(world_point)),
            [world_normal, second],
            [(body_axis, world_normal), (body_axis, second), (body_normal, second)],
        ))
    }

    /// Planar joint: the body plane through `body_point` with normal `body_normal` stays on the world plane
    /// through `world_point` with normal `world_normal`: a force along the normal and two couples keeping the
    /// normals aligned. Rank 3.
    ///
    /// A puck whose bottom face (body plane through `(0, 0, −0.02)`, normal z) stays on the floor z = 0: it slides
    /// and turns about the vertical.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let puck = Body::cylinder(0.2, 0.04, 0.04)?;
    /// let bottom = (Vector3::new(0.0, 0.0, -0.02), Vector3::z());
    /// let floor = VirtualPower::<Pga>::planar("floor", bottom, (Vector3::zeros(), Vector3::z()))?;
    /// assert_eq!(floor.rank(), 3);
    /// let system = Mechanism::single(puck).with_constraint(floor)?;
    /// let turned = UnitQuaternion::from_scaled_axis(Vector3::z() * 2.0);
    /// let (centre, spin) = (Vector3::new(1.0, -2.0, 0.02), Vector3::z() * 5.0); // m, rad/s
    /// let gliding = State::from_world_twist(&puck, centre, &turned, spin, Vector3::x());
    /// let on = system.violation(0.0, &[gliding])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-13); // m, m/s: round-off
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn planar(
        name: impl Into<String>,
        (body_point, body_normal): (Vector3<f64>, Vector3<f64>),
        (world_point, world_normal): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let (body_normal, world_normal) = (
            unit(&name, "body normal", body_normal)?,
            unit(&name, "world normal", world_normal)?,
        );
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(world_point)),
            [world_normal],
            normals_to(world_normal).map(|n| (body_normal, n)),
        ))
    }

    /// The body point stays on the world plane `{x : normal·x = offset}`. Rank 1.
    ///
    /// The normal need not be unit: `(0, 0, 2)·x = 1` is the plane z = 0.5 m.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let foot = Vector3::new(0.0, 0.0, -0.5); // body point, m
    /// let on_plane = VirtualPower::<Pga>::point_on_plane("foot", foot, (Vector3::new(0.0, 0.0, 2.0), 1.0))?;
    /// assert_eq!(on_plane.rank(), 1);
    /// let system = Mechanism::single(rod).with_constraint(on_plane)?;
    /// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.2, 0.0));
    /// let centre = Vector3::new(3.0, -1.0, 0.5) - tilt * foot; // the foot anywhere on z = 0.5
    /// let on = system.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), Vector3::x())])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_plane(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        (normal, offset): (Vector3<f64>, f64),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let length = normal.norm();
        let normal = unit(&name, "plane normal", normal)?;
        if !offset.is_finite() {
            return Err(ConstraintError::InvalidParameter {
                name,
                reason: format!("plane offset {offset} is not finite"),
            });
        }
        let on_plane = normal * (offset / length);
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(on_plane)),
            [normal],
            [],
        ))
    }

    /// The body point stays on the world line through `line_point` along `direction`: two forces normal to the
    /// line. Rank 2.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let end = Vector3::new(0.0, 0.0, 0.5); // body point, m
    /// // The end on the line through (0, 0, 1) along (1, 1, 0): two rows, rank 2.
    /// let on_line = VirtualPower::<Pga>::point_on_line("end", end, (Vector3::z(), Vector3::new(1.0, 1.0, 0.0)))?;
    /// assert_eq!(on_line.rank(), 2);
    /// let system = Mechanism::single(rod).with_constraint(on_line)?;
    /// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.6, 0.1));
    /// let centre = Vector3::new(0.4, 0.4, 1.0) - tilt * end; // the end 0.4√2 m along the line
    /// let on = system.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), Vector3::zeros())])?;
    /// assert!(on.position < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_line(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        (line_point, direction): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        let direction = unit(&name, "line direction", direction)?;
        Ok(Self::point_joint(
            name,
            body_point,
            Arc::new(Fixed(line_point)),
            normals_to(direction),
            [],
        ))
    }

    /// The body point stays on the sphere `|a − centre| = radius`. Rank 1.
    ///
    /// A spherical pendulum's bob as a point on a sphere: one row, whose residual `½(ρ² − |a − c|²)` vanishes
    /// anywhere on the sphere.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let bob = Body::sphere(1.0, 0.05)?;
    /// let on_sphere = VirtualPower::<Pga>::point_on_sphere("string", Vector3::zeros(), Vector3::z() * 2.0, 1.5)?;
    /// assert_eq!(on_sphere.rank(), 1);
    /// let system = Mechanism::single(bob).with_constraint(on_sphere)?;
    /// let direction = Vector3::new(0.3, -0.4, -1.0).normalize();
    /// let at = Vector3::z() * 2.0 + direction * 1.5; // m
    /// let velocity = direction.cross(&Vector3::z()); // tangent, m/s
    /// let state = State::new(&bob, at, &UnitQuaternion::identity(), Vector3::zeros(), velocity);
    /// let on = system.violation(0.0, &[state])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// assert!(VirtualPower::<Pga>::point_on_sphere("string", Vector3::zeros(), Vector3::z(), 0.0).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_sphere(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Result<Self, ConstraintError> {
        Self::point_on_moving_sphere(name, body_point, Fixed(centre), radius)
    }

    /// The body point stays on a sphere whose centre follows `centre` (value, velocity, acceleration). Rank 1.
    ///
    /// A bob on a string of 1.5 m whose top is carried along x at 1 m/s: a bob straight below it and moving with
    /// it keeps the constraint.
    ///
    /// ```
    /// use dynamics::constraints::{PathPoint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let carried = |t: f64| PathPoint {
    ///     value: Vector3::new(t, 0.0, 2.0),
    ///     rate: Vector3::x(),
    ///     acceleration: Vector3::zeros(),
    /// };
    /// let bob = Body::sphere(1.0, 0.05)?;
    /// let string = VirtualPower::<Pga>::point_on_moving_sphere("string", Vector3::zeros(), carried, 1.5)?;
    /// let system = Mechanism::single(bob).with_constraint(string)?;
    /// let still = UnitQuaternion::identity();
    /// let below = State::new(&bob, Vector3::new(0.7, 0.0, 0.5), &still, Vector3::zeros(), Vector3::x());
    /// let on = system.violation(0.7, &[below])?; // t = 0.7 s
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_moving_sphere(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        centre: impl Path<Vector3<f64>> + 'static,
        radius: f64,
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        if !(radius.is_finite() && radius > 0.0) {
            return Err(ConstraintError::InvalidParameter {
                name,
                reason: format!("sphere radius {radius} is not positive"),
            });
        }
        Ok(VirtualPower {
            name,
            wrenches: Wrenches::Sphere {
                body_point,
                centre: Arc::new(centre),
                radius,
            },
        })
    }

    /// The body point `body_point` (body coordinates, m) stays on `surface` (reference frame): a unit force along the
    /// surface normal, from the same algebra as the pinned form ([`crate::constraints::SurfacePin`]), through the
    /// point. Its position residual is `F/|∇F|`, the distance from the surface to first order. Rank 1.
    ///
    /// A rod's end on an ellipsoid of radii 2, 1, 1 m: at the end of its long axis, sliding across it, the residuals
    /// vanish; 1 cm further out the residual is 1 cm.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::surfaces::Surface;
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{Isometry3, UnitQuaternion, Vector3};
    ///
    /// let egg = Surface::ellipsoid(Vector3::new(2.0, 1.0, 1.0), &Isometry3::identity())?;
    /// let end = Vector3::new(0.0, 0.0, -0.5); // body point, m
    /// let on_egg = VirtualPower::<Pga>::point_on_surface("end", end, egg)?;
    /// assert_eq!(on_egg.rank(), 1);
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let system = Mechanism::single(rod).with_constraint(on_egg)?;
    /// let still = UnitQuaternion::identity();
    /// let at = State::new(&rod, Vector3::new(2.0, 0.0, 0.5), &still, Vector3::zeros(), Vector3::y());
    /// let on = system.violation(0.0, &[at])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// let out = State::new(&rod, Vector3::new(2.01, 0.0, 0.5), &still, Vector3::zeros(), Vector3::y());
    /// assert!((system.violation(0.0, &[out])?.position - 0.01).abs() < 1e-4); // m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_surface(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        surface: Surface,
    ) -> Result<Self, ConstraintError> {
        Self::on_surfaces(name.into(), body_point, &[surface])
    }

    /// The body point stays on the curve where `surfaces` meet (reference frame): unit forces along both normals.
    /// Rank 2; where the surfaces are tangent the rows lose rank, an error naming the constraint.
    ///
    /// An ellipse as an ellipsoid of radii 2, 1, 1 m cut by the plane z = 0: a bead on it moving along it.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::surfaces::Surface;
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{Isometry3, UnitQuaternion, Vector3};
    ///
    /// let egg = Surface::ellipsoid(Vector3::new(2.0, 1.0, 1.0), &Isometry3::identity())?;
    /// let ellipse = VirtualPower::<Pga>::point_on_curve("ellipse", Vector3::zeros(), [egg, Surface::plane(Vector3::z(), 0.0)?])?;
    /// assert_eq!((ellipse.rank(), ellipse.row_count()), (2, 2));
    /// let bead = Body::sphere(0.1, 0.01)?;
    /// let system = Mechanism::single(bead).with_constraint(ellipse)?;
    /// let phi = 0.7f64;
    /// let at = Vector3::new(2.0 * phi.cos(), phi.sin(), 0.0); // m
    /// let along = Vector3::new(-2.0 * phi.sin(), phi.cos(), 0.0); // m/s
    /// let state = State::new(&bead, at, &UnitQuaternion::identity(), Vector3::zeros(), along);
    /// let on = system.violation(0.0, &[state])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_curve(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        surfaces: [Surface; 2],
    ) -> Result<Self, ConstraintError> {
        Self::on_surfaces(name.into(), body_point, &surfaces)
    }

    fn on_surfaces(name: String, body_point: Vector3<f64>, surfaces: &[Surface]) -> Result<Self, ConstraintError> {
        check_held_point(&name, &body_point)?;
        check_curve(&name, surfaces)?;
        Ok(VirtualPower {
            name,
            wrenches: Wrenches::Surfaces {
                body_point,
                surfaces: surfaces.iter().copied().collect(),
            },
        })
    }

    /// The body point stays on the circle of `radius` about `centre` in the plane with `normal`: a sphere plus
    /// a plane through its centre (theory §6). Rank 2.
    ///
    /// A bead on a ring of radius 0.5 m about (0, 0, 1) in a horizontal plane: two rows, rank 2. A bead going round
    /// the ring is on it; 0.1 m above the ring it is 0.1 m off the plane (the sphere's residual `½(ρ² − |a − c|²)` is
    /// only −0.005 m² there). The radius must be positive.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ring = VirtualPower::<Pga>::point_on_circle("ring", Vector3::zeros(), (Vector3::z(), 0.5, Vector3::z()))?;
    /// assert_eq!((ring.rank(), ring.row_count()), (2, 2));
    /// let bead = Body::sphere(0.1, 0.01)?;
    /// let system = Mechanism::single(bead).with_constraint(ring)?;
    /// let (phi, still) = (0.8f64, UnitQuaternion::identity());
    /// let at = Vector3::z() + Vector3::new(phi.cos(), phi.sin(), 0.0) * 0.5; // m
    /// let along = Vector3::new(-phi.sin(), phi.cos(), 0.0) * 2.0; // tangent, m/s
    /// let on = system.violation(0.0, &[State::new(&bead, at, &still, Vector3::zeros(), along)])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// let above = State::new(&bead, at + Vector3::z() * 0.1, &still, Vector3::zeros(), Vector3::zeros());
    /// assert!((system.violation(0.0, &[above])?.position - 0.1).abs() < 1e-15); // m
    /// let flat = (Vector3::z(), 0.0, Vector3::z()); // radius 0
    /// assert!(VirtualPower::<Pga>::point_on_circle("ring", Vector3::zeros(), flat).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn point_on_circle(
        name: impl Into<String>,
        body_point: Vector3<f64>,
        (centre, radius, normal): (Vector3<f64>, f64, Vector3<f64>),
    ) -> Result<Composite<A>, ConstraintError> {
        let name = name.into();
        let sphere = Self::point_on_sphere(format!("{name}: sphere"), body_point, centre, radius)?;
        let plane = Self::point_on_plane(format!("{name}: plane"), body_point, (normal, normal.dot(&centre)))?;
        Ok(Composite::new(name, vec![Arc::new(sphere), Arc::new(plane)], 2))
    }

    /// A motor joint: the body's motor relative to the reference follows `path` (U(t) with its body-frame
    /// velocity ξ and ξ̇). The six unit wrenches of the body frame, each with the prescribed power of the
    /// driven motion: velocity conditions `x = ξ(t)` on the relative body velocity x, position residuals the
    /// coordinates of `−2 log(~U M)` (the screw that carries the path's motor U to the relative motor M for unit
    /// time, zero on the path; its rate is `x − ξ` to first order). Rank 6.
    ///
    /// A turntable: the body's motor follows a turn about z at 1 rad/s. A body on the path, turning with it, has
    /// zero violation; all six degrees of freedom are prescribed.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, PathPoint, ScrewMotion, VirtualPower};
    /// use dynamics::{motor, Algebra, Body, Mechanism, Pga, ScrewCoordinates, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let about_z = Pga::screw(ScrewCoordinates { l: Vector3::z(), t: Vector3::zeros() });
    /// let theta = |t: f64| PathPoint { value: t, rate: 1.0, acceleration: 0.0 }; // rad
    /// let path = ScrewMotion::<Pga, _>::new(motor::identity::<Pga>(), about_z, theta);
    /// let turntable = VirtualPower::motor_joint("turntable", path);
    /// assert_eq!(turntable.rank(), 6);
    /// let disc = Body::cylinder(1.0, 0.3, 0.02)?;
    /// let system = Mechanism::single(disc).with_constraint(turntable)?;
    /// let turned = UnitQuaternion::from_scaled_axis(Vector3::z() * 0.5);
    /// let on_path = State::from_body_twist(&disc, Vector3::zeros(), &turned, Vector3::z(), Vector3::zeros());
    /// let on = system.violation(0.5, &[on_path])?; // t = 0.5 s: turned by 0.5 rad at 1 rad/s
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn motor_joint(name: impl Into<String>, path: impl MotorPath<A> + 'static) -> Self {
        VirtualPower {
            name: name.into(),
            wrenches: Wrenches::Motor(Arc::new(path)),
        }
    }

    /// A weld: the body's motor relative to the reference stays `relative` (body → reference), a motor joint on a
    /// fixed path (all six degrees of freedom held, position residual `−2 log(~U M)`). Rank 6.
    ///
    /// A bracket welded 0.3 m below its reference, turned a quarter turn about z: a state at that pose is on the
    /// weld, the same state 1 mm lower is 1 mm off.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, VirtualPower};
    /// use dynamics::{motor, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let bracket = Body::cuboid(0.5, Vector3::new(0.1, 0.1, 0.05))?;
    /// let turn = UnitQuaternion::from_scaled_axis(Vector3::z() * std::f64::consts::FRAC_PI_2);
    /// let at = Vector3::new(0.0, 0.0, -0.3); // m
    /// let weld = VirtualPower::<Pga>::weld("bolted", motor::from_pose::<Pga>(at, &turn));
    /// assert_eq!(weld.rank(), 6);
    /// let system = Mechanism::single(bracket).with_constraint(weld)?;
    /// let on = system.violation(0.0, &[State::new(&bracket, at, &turn, Vector3::zeros(), Vector3::zeros())])?;
    /// assert!(on.position < 1e-15 && on.velocity == 0.0);
    /// let lower = State::new(&bracket, at - Vector3::z() * 1e-3, &turn, Vector3::zeros(), Vector3::zeros());
    /// assert!((system.violation(0.0, &[lower])?.position - 1e-3).abs() < 1e-15); // m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn weld(name: impl Into<String>, relative: A::Motor) -> Self {
        let zero = A::screw(ScrewCoordinates::default());
        let held = MotorPoint {
            motor: relative,
            velocity: zero,
            acceleration: zero,
        };
        Self::motor_joint(name, move |_t: f64| held)
    }
}
