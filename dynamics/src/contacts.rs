//! Contacts: a body point kept on one side of a world plane, `n · p ≥ d` (docs/contacts.md). The same one-sided
//! machinery as [`crate::limits`], on a point instead of a joint coordinate; a mechanism enforces it exactly
//! ([`crate::Mechanism::add_contact`]):
//!
//! * while the point is above the plane [`crate::simulate()`] watches its height `n · p − d` as an event;
//! * where the height reaches zero (located to round-off) the point meets the plane in an **impact**: impulses
//!   along n through the kinetic metric, at that point and at every other point touching the plane and moving into
//!   it, that reverse their normal speeds times the restitution, pull on no point and change no held relation;
//! * a point that does not bounce away is **held** on the plane by a row `n · a_p = 0` of the articulated solve,
//!   whose multiplier is the plane's push; it is released where that push would pull.
//!
//! The point may be a sphere's centre ([`PlaneContact::sphere`]): the sphere stays above the plane, touching it at
//! its lowest point. With Coulomb friction ([`PlaneContact::with_friction`]) a held contact **slides**, the plane's
//! friction opposing the slip of the touching point with μ times the push, or **sticks**, two more rows holding the
//! slip at zero while the friction force stays inside the cone; the stop of a slide and the slip of a stick are
//! located transitions as the impacts are (docs/contacts.md "Friction").
//!
//! Between two bodies the plane may be fixed in the second body, a face of it
//! ([`crate::Mechanism::add_contact_on`]), or a sphere of one body kept outside a sphere of the other
//! ([`BallContact`]); the gap, its rate and the rows are then those of the relative motion (docs/contacts.md
//! "Between bodies"). Two convex polyhedra ([`Polyhedron`]) are kept apart by all their vertex–face pairs and edge
//! pairs ([`EdgeContact`]), each a contact only where its features meet ([`crate::Mechanism::add_polyhedron_contacts`],
//! docs/contacts.md "Edges").

use nalgebra::{Unit, Vector3};

use crate::constraints::ConstraintError;
pub use crate::state::LARGEST_COORDINATE;

/// A plane below a body point: the point `p` (body coordinates) is kept where `n · p ≥ offset` (world, m); or below
/// a sphere of radius r about that point, kept where `n · p ≥ offset + r`; or below the rim of a disk about that
/// point ([`PlaneContact::disk`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneContact {
    point: Vector3<f64>,
    radius: f64,
    rim: Option<Rim>,
    normal: Unit<Vector3<f64>>,
    offset: f64,
    restitution: f64,
    friction: Friction,
}

/// Coulomb's friction between a contact and its plane: the force opposing a slip has `kinetic` times the push, and a
/// contact at rest sticks while the force that holds it is at most `static` times the push (`static ≥ kinetic ≥
/// 0`). Isotropic: the same in every direction of the plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Friction {
    kinetic: f64,
    stiction: f64,
}

/// The largest friction coefficient accepted: beyond it a contact sticks for any push the simulation can represent.
pub const MAX_FRICTION: f64 = 1e6;

impl Friction {
    /// No friction: the plane pushes along its normal only.
    pub const NONE: Friction = Friction {
        kinetic: 0.0,
        stiction: 0.0,
    };

    /// Kinetic coefficient `kinetic` and static coefficient `stiction`, each finite, in `[0, MAX_FRICTION]`, and
    /// `stiction ≥ kinetic`.
    ///
    /// ```
    /// use dynamics::contacts::Friction;
    ///
    /// let rubber = Friction::new(0.8, 1.0)?;
    /// assert_eq!((rubber.kinetic(), rubber.stiction()), (0.8, 1.0));
    /// assert!(Friction::new(0.5, 0.4).is_err()); // static below kinetic
    /// assert!(Friction::new(f64::NAN, 0.4).is_err());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(kinetic: f64, stiction: f64) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "friction".to_owned(),
            reason,
        };
        for (what, value) in [("kinetic", kinetic), ("static", stiction)] {
            if !(0.0..=MAX_FRICTION).contains(&value) {
                return Err(refuse(format!(
                    "the {what} coefficient must be finite and in [0, {MAX_FRICTION:e}], got {value}"
                )));
            }
        }
        if stiction < kinetic {
            return Err(refuse(format!(
                "the static coefficient {stiction} is below the kinetic one {kinetic}: a contact at rest would hold \
                 less than a sliding one pulls"
            )));
        }
        Ok(Friction { kinetic, stiction })
    }

    /// The same coefficient μ ≥ 0 for sliding and for sticking.
    ///
    /// ```
    /// use dynamics::contacts::Friction;
    ///
    /// let steel_on_steel = Friction::coulomb(0.6)?;
    /// assert_eq!((steel_on_steel.kinetic(), steel_on_steel.stiction()), (0.6, 0.6));
    /// assert!(Friction::coulomb(-0.1).is_err());
    /// assert!(!Friction::coulomb(0.0)?.is_some());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn coulomb(mu: f64) -> Result<Self, ConstraintError> {
        Friction::new(mu, mu)
    }

    /// The kinetic coefficient: a slide's friction force over the push.
    pub fn kinetic(&self) -> f64 {
        self.kinetic
    }

    /// The static coefficient: the largest friction force over the push a sticking contact holds.
    pub fn stiction(&self) -> f64 {
        self.stiction
    }

    /// Whether there is any friction.
    pub fn is_some(&self) -> bool {
        self.stiction > 0.0
    }
}

/// A contact's touching point may be this far (m) outside its face ([`crate::Mechanism::set_contact_face`]) before
/// the run stops: a point on the face's edge is outside by round-off.
pub const OUTSIDE_FACE: f64 = 1e-9;

/// The most planes a contact's face is bounded by (a convex hull's faces: at most twice its vertices).
pub const MAX_FACE_PLANES: usize = 1024;

/// A restitution coefficient, refused outside [0, 1] with an error naming `what`.
fn checked_restitution(what: &str, restitution: f64) -> Result<f64, ConstraintError> {
    if !(0.0..=1.0).contains(&restitution) {
        return Err(ConstraintError::InvalidParameter {
            name: what.to_owned(),
            reason: format!("a restitution coefficient is in [0, 1], got {restitution}"),
        });
    }
    Ok(restitution)
}

/// Contact points within this height (m) of their planes at an impact take part in it: a block landing flat meets
/// the floor with four corners at once, whose heights differ by round-off at the located time.
pub const TOUCHING: f64 = 1e-9;

impl PlaneContact {
    /// The body point `point` (m, the body's frame) kept on the side of the plane `normal · x = offset` (world)
    /// that `normal` points to; inelastic (restitution 0). The normal need not be unit (the plane is scaled to a unit
    /// normal): finite and not zero, of any size. The point's coordinates finite and within [`LARGEST_COORDINATE`],
    /// and so the offset and the plane's distance from the origin (the offset over the normal's length).
    ///
    /// ```
    /// use dynamics::contacts::PlaneContact;
    /// use nalgebra::Vector3;
    ///
    /// // A block's corner 0.1 m below and beside its centre, above the floor z = 0, bouncing at half speed.
    /// let corner = PlaneContact::new(Vector3::new(0.1, 0.1, -0.1), Vector3::z(), 0.0)?.with_restitution(0.5)?;
    /// assert_eq!(corner.height(&Vector3::new(0.0, 0.0, 0.25)), 0.25);
    /// assert!(PlaneContact::new(Vector3::zeros(), Vector3::zeros(), 0.0).is_err()); // no normal
    /// let tiny = PlaneContact::new(Vector3::zeros(), Vector3::z() * 1e-300, 2e-300)?; // z = 2: a direction of any size
    /// assert_eq!((tiny.normal(), tiny.offset()), (Vector3::z(), 2.0));
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(point: Vector3<f64>, normal: Vector3<f64>, offset: f64) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "plane contact".to_owned(),
            reason,
        };
        let within = |x: f64| x.is_finite() && x.abs() <= LARGEST_COORDINATE;
        if !(point.iter().all(|&x| within(x)) && offset.is_finite()) {
            return Err(refuse(format!(
                "the body point {:?} and the offset {offset} must be finite and within {LARGEST_COORDINATE:e} m",
                point.as_slice()
            )));
        }
        // Scaled before its length is taken, so that a normal of huge or tiny numbers is still a direction.
        let scale = normal.amax();
        if !(normal.iter().all(|x| x.is_finite()) && scale > 0.0) {
            return Err(refuse(format!(
                "the normal {:?} must be finite and not zero",
                normal.as_slice()
            )));
        }
        let length = (normal / scale).norm();
        let offset = offset / scale / length;
        if !within(offset) {
            return Err(refuse(format!(
                "the plane's distance from the origin, {offset:e} m (the offset over the normal's length), must be \
                 finite and within {LARGEST_COORDINATE:e} m"
            )));
        }
        Ok(PlaneContact {
            point,
            radius: 0.0,
            rim: None,
            normal: Unit::new_unchecked(normal / scale / length),
            offset,
            restitution: 0.0,
            friction: Friction::NONE,
        })
    }

    /// A sphere of radius `radius` (m) about the body point `centre` (m, the body's frame), kept on the side of the
    /// plane `normal · x = offset` that `normal` points to: it touches the plane at its lowest point, `centre − r n`,
    /// where friction acts; the radius must be positive, finite and within [`LARGEST_COORDINATE`].
    ///
    /// ```
    /// use dynamics::contacts::{Friction, PlaneContact};
    /// use nalgebra::Vector3;
    ///
    /// // A foot: a 2 cm sphere at the end of a leg, on a floor with friction 0.8.
    /// let foot = PlaneContact::sphere(Vector3::new(0.0, 0.0, -0.16), 0.02, Vector3::z(), 0.0)?
    ///     .with_friction(Friction::coulomb(0.8)?);
    /// assert!((foot.height(&Vector3::new(0.0, 0.0, 0.05)) - 0.03).abs() < 1e-15); // the centre 5 cm up: 3 cm clear
    /// assert!(PlaneContact::sphere(Vector3::zeros(), -0.1, Vector3::z(), 0.0).is_err());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn sphere(
        centre: Vector3<f64>,
        radius: f64,
        normal: Vector3<f64>,
        offset: f64,
    ) -> Result<Self, ConstraintError> {
        if !(radius > 0.0 && radius <= LARGEST_COORDINATE) {
            return Err(ConstraintError::InvalidParameter {
                name: "plane contact".to_owned(),
                reason: format!(
                    "a sphere's radius must be positive, finite and within {LARGEST_COORDINATE:e} m, got {radius}"
                ),
            });
        }
        Ok(PlaneContact {
            radius,
            ..PlaneContact::new(centre, normal, offset)?
        })
    }

    /// The rim of a disk of radius `radius` (m) about the body point `centre`, in the plane through it normal to
    /// `axis` (the body's frame; any length), kept on the side of the plane `normal · x = offset` that `normal`
    /// points to: a cylinder's cap edge, a wheel or a coin. It touches the plane at its lowest point, `c − ρ û` with
    /// û the plane's normal projected on the disk and made unit, which runs along the rim as the disk turns; a
    /// cylinder on a plane is the disks of its two caps (docs/contacts.md "Rims"). A disk lying flat on its plane
    /// touches it along its whole rim, which one point cannot hold: [`crate::simulate()`] stops with an error naming
    /// the contact where a touching disk comes within [`FLAT_RIM`] of flat. The radius positive, finite and within
    /// [`LARGEST_COORDINATE`]; the axis finite and not zero (any length), the centre as [`PlaneContact::new`]'s point.
    ///
    /// ```
    /// use dynamics::contacts::PlaneContact;
    /// use nalgebra::Vector3;
    ///
    /// // A wheel of radius 0.3 m turning about the body's y axis, on the floor z = 0.
    /// let wheel = PlaneContact::disk(Vector3::zeros(), Vector3::y(), 0.3, Vector3::z(), 0.0)?;
    /// assert!((wheel.height(&Vector3::new(0.0, 0.0, 0.5)) - 0.5).abs() < 1e-15); // the centre's height
    /// assert!(PlaneContact::disk(Vector3::zeros(), Vector3::zeros(), 0.3, Vector3::z(), 0.0).is_err());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn disk(
        centre: Vector3<f64>,
        axis: Vector3<f64>,
        radius: f64,
        normal: Vector3<f64>,
        offset: f64,
    ) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "plane contact".to_owned(),
            reason,
        };
        if !(radius > 0.0 && radius <= LARGEST_COORDINATE) {
            return Err(refuse(format!(
                "a disk's radius must be positive, finite and within {LARGEST_COORDINATE:e} m, got {radius}"
            )));
        }
        // Scaled before its length is taken, so that a direction given by huge or tiny numbers is still one.
        let scale = axis.amax();
        if !(axis.iter().all(|x| x.is_finite()) && scale > 0.0) {
            return Err(refuse(format!(
                "a disk's axis must be finite and not zero, got {:?}",
                axis.as_slice()
            )));
        }
        Ok(PlaneContact {
            rim: Some(Rim {
                axis: Unit::new_normalize(axis / scale),
                radius,
            }),
            ..PlaneContact::new(centre, normal, offset)?
        })
    }

    /// The same contact with Newton's restitution coefficient `restitution` in [0, 1]: the point leaves the plane at
    /// `restitution` times the normal speed it met it with (1: elastic; 0: it stays).
    pub fn with_restitution(self, restitution: f64) -> Result<Self, ConstraintError> {
        let restitution = checked_restitution("plane contact", restitution)?;
        Ok(PlaneContact { restitution, ..self })
    }

    /// The same contact with Coulomb friction ([`Friction`]).
    pub fn with_friction(self, friction: Friction) -> Self {
        PlaneContact { friction, ..self }
    }

    /// The body point (m, the body's frame): the point kept above the plane, or the sphere's centre.
    pub fn point(&self) -> Vector3<f64> {
        self.point
    }

    /// The sphere's radius (m); zero for a point or a disk.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// A disk's unit axis (the body's frame) and radius (m), if the contact is a disk's rim.
    pub fn rim(&self) -> Option<(Vector3<f64>, f64)> {
        self.rim.map(|rim| (rim.axis.into_inner(), rim.radius))
    }

    /// The friction between the contact and its plane.
    pub fn friction(&self) -> Friction {
        self.friction
    }

    /// The plane's unit normal (world), pointing to the side the point is kept on.
    pub fn normal(&self) -> Vector3<f64> {
        self.normal.into_inner()
    }

    /// The plane's offset d in `n · x = d` (m, n unit).
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// The restitution coefficient.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The height (m) above the plane of the contact with its point at the world point `x`: `n · x − d` for a point
    /// (and a disk's centre), `n · x − d − r` for a sphere about x (its lowest point's); negative below it.
    pub fn height(&self, x: &Vector3<f64>) -> f64 {
        self.normal.dot(x) - self.offset - self.radius
    }
}

/// A disk's rim: its unit axis (body frame) and radius (m).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rim {
    axis: Unit<Vector3<f64>>,
    radius: f64,
}

/// A disk touching its plane (or within [`TOUCHING`] of it) whose axis is this close to the plane's normal (the sine
/// of the angle between them) lies flat, touching along its whole rim: [`crate::simulate()`] stops there with an
/// error naming the contact, as one point cannot hold it.
pub const FLAT_RIM: f64 = 1e-6;

/// A sphere fixed in one body kept outside a sphere fixed in another ([`crate::Mechanism::add_ball_contact`]):
/// their centres stay at least the sum of the radii apart. They touch on the line between the centres, where the
/// impact, the push and the friction act.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallContact {
    centre: Vector3<f64>,
    radius: f64,
    other_centre: Vector3<f64>,
    other_radius: f64,
    restitution: f64,
    friction: Friction,
}

impl BallContact {
    /// The sphere of radius `radius` about `centre` (m, the first body's frame) outside the sphere of radius
    /// `other_radius` about `other_centre` (m, the second body's frame); inelastic and frictionless. Centres finite
    /// and within [`LARGEST_COORDINATE`], radii positive and within it.
    ///
    /// ```
    /// use dynamics::contacts::{BallContact, Friction};
    /// use nalgebra::Vector3;
    ///
    /// // Two billiard balls of 28.5 mm radius about their centres of mass, elastic.
    /// let balls = BallContact::new(Vector3::zeros(), 0.0285, Vector3::zeros(), 0.0285)?
    ///     .with_restitution(1.0)?
    ///     .with_friction(Friction::coulomb(0.05)?);
    /// assert_eq!(balls.radii(), (0.0285, 0.0285));
    /// assert!(BallContact::new(Vector3::zeros(), 0.0, Vector3::zeros(), 0.1).is_err());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(
        centre: Vector3<f64>,
        radius: f64,
        other_centre: Vector3<f64>,
        other_radius: f64,
    ) -> Result<Self, ConstraintError> {
        let within = |x: f64| x.is_finite() && x.abs() <= LARGEST_COORDINATE;
        if !(centre.iter().chain(other_centre.iter()).all(|&x| within(x))) {
            return Err(ConstraintError::InvalidParameter {
                name: "ball contact".to_owned(),
                reason: format!(
                    "the centres {:?} and {:?} must be finite and within {LARGEST_COORDINATE:e} m",
                    centre.as_slice(),
                    other_centre.as_slice()
                ),
            });
        }
        for value in [radius, other_radius] {
            if !(value > 0.0 && value <= LARGEST_COORDINATE) {
                return Err(ConstraintError::InvalidParameter {
                    name: "ball contact".to_owned(),
                    reason: format!(
                        "a sphere's radius must be positive, finite and within {LARGEST_COORDINATE:e} m, got {value}"
                    ),
                });
            }
        }
        Ok(BallContact {
            centre,
            radius,
            other_centre,
            other_radius,
            restitution: 0.0,
            friction: Friction::NONE,
        })
    }

    /// The same contact with Newton's restitution coefficient in [0, 1] (1: elastic; 0: the spheres stay touching).
    pub fn with_restitution(self, restitution: f64) -> Result<Self, ConstraintError> {
        let restitution = checked_restitution("ball contact", restitution)?;
        Ok(BallContact { restitution, ..self })
    }

    /// The same contact with Coulomb friction between the spheres.
    pub fn with_friction(self, friction: Friction) -> Self {
        BallContact { friction, ..self }
    }

    /// The centres (m), each in its body's frame.
    pub fn centres(&self) -> (Vector3<f64>, Vector3<f64>) {
        (self.centre, self.other_centre)
    }

    /// The radii (m).
    pub fn radii(&self) -> (f64, f64) {
        (self.radius, self.other_radius)
    }

    /// The restitution coefficient.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The friction between the spheres.
    pub fn friction(&self) -> Friction {
        self.friction
    }
}

/// Edges closer to parallel than this sine leave their contact to the vertex contacts at their ends: their common
/// normal turns ever faster as they align (docs/contacts.md "Edges").
pub const PARALLEL_EDGES: f64 = 1e-3;

/// A straight edge of a convex polyhedron in its body's frame: its two ends and the outward normals of the two faces
/// that meet along it (docs/contacts.md "Edges").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    start: Vector3<f64>,
    end: Vector3<f64>,
    faces: [Unit<Vector3<f64>>; 2],
}

impl Edge {
    /// The edge from `start` to `end` (m, the body's frame) between the faces of outward normals `faces` (any
    /// length). The ends finite, within [`LARGEST_COORDINATE`] and apart; each normal finite, not zero, and normal to
    /// the edge (within a sine of 1e-6); the two faces not parallel (an edge where the solid turns).
    ///
    /// ```
    /// use dynamics::contacts::Edge;
    /// use nalgebra::Vector3;
    ///
    /// // The top front edge of a 0.2 m cube: between its top face (+z) and its front face (+y).
    /// let edge = Edge::new(Vector3::new(-0.1, 0.1, 0.1), Vector3::new(0.1, 0.1, 0.1), [Vector3::z(), Vector3::y()])?;
    /// assert_eq!(edge.length(), 0.2);
    /// assert!(Edge::new(Vector3::zeros(), Vector3::x(), [Vector3::z(), Vector3::x()]).is_err()); // a face along it
    /// assert!(Edge::new(Vector3::zeros(), Vector3::x(), [Vector3::z(), Vector3::z() * 2.0]).is_err()); // flat
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(start: Vector3<f64>, end: Vector3<f64>, faces: [Vector3<f64>; 2]) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "edge".to_owned(),
            reason,
        };
        let within = |x: &f64| x.is_finite() && x.abs() <= LARGEST_COORDINATE;
        if !(start.iter().all(within) && end.iter().all(within)) {
            return Err(refuse(format!(
                "the ends {:?} and {:?} must be finite and within {LARGEST_COORDINATE:e} m",
                start.as_slice(),
                end.as_slice()
            )));
        }
        let along = end - start;
        let length = along.norm();
        if length <= 1e-9 * start.amax().max(end.amax()).max(1.0) {
            return Err(refuse(format!(
                "the ends {:?} and {:?} must be apart",
                start.as_slice(),
                end.as_slice()
            )));
        }
        let direction = along / length;
        let mut units = [Unit::new_unchecked(Vector3::z()); 2];
        for (unit, normal) in units.iter_mut().zip(faces) {
            let scale = normal.amax();
            if !(normal.iter().all(|x| x.is_finite()) && scale > 0.0) {
                return Err(refuse(format!(
                    "a face's normal {:?} must be finite and not zero",
                    normal.as_slice()
                )));
            }
            *unit = Unit::new_normalize(normal / scale);
            if unit.dot(&direction).abs() > 1e-6 {
                return Err(refuse(format!(
                    "a face's normal {:?} must be normal to the edge {:?}: the face contains it",
                    normal.as_slice(),
                    direction.as_slice()
                )));
            }
        }
        if units[0].cross(&units[1]).norm() <= 1e-6 {
            return Err(refuse(format!(
                "the faces' normals {:?} and {:?} are parallel: the solid does not turn at this edge",
                faces[0].as_slice(),
                faces[1].as_slice()
            )));
        }
        Ok(Edge {
            start,
            end,
            faces: units,
        })
    }

    /// The ends (m, the body's frame).
    pub fn ends(&self) -> (Vector3<f64>, Vector3<f64>) {
        (self.start, self.end)
    }

    /// The length (m).
    pub fn length(&self) -> f64 {
        (self.end - self.start).norm()
    }

    /// The unit outward normals of the two faces meeting along it (the body's frame).
    pub fn faces(&self) -> [Vector3<f64>; 2] {
        self.faces.map(Unit::into_inner)
    }
}

/// An edge of one body kept from passing through an edge of another: two convex polyhedra meeting edge on edge, where
/// no vertex touches a face (docs/contacts.md "Edges"). The gap is the distance between the two edges' lines along
/// their common normal, which points out of the second body's solid at its edge; the contact holds only while the
/// nearest points lie on both edges and the normal lies between each edge's faces, and lets go where they leave:
/// the other features of the two solids take over there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeContact {
    edge: Edge,
    other: Edge,
    restitution: f64,
    friction: Friction,
}

impl EdgeContact {
    /// `edge` of the contact's body against `other` of the second body (each in its body's frame); inelastic and
    /// without friction.
    ///
    /// ```
    /// use dynamics::contacts::{Edge, EdgeContact, Friction};
    /// use nalgebra::Vector3;
    ///
    /// let bottom = Edge::new(Vector3::new(-0.1, 0.0, -0.1), Vector3::new(0.1, 0.0, -0.1), [-Vector3::z(), Vector3::y()])?;
    /// let top = Edge::new(Vector3::new(0.0, -0.1, 0.1), Vector3::new(0.0, 0.1, 0.1), [Vector3::z(), Vector3::x()])?;
    /// let crossed = EdgeContact::new(bottom, top).with_restitution(0.5)?.with_friction(Friction::coulomb(0.3)?);
    /// assert_eq!(crossed.edges(), (bottom, top));
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(edge: Edge, other: Edge) -> Self {
        EdgeContact {
            edge,
            other,
            restitution: 0.0,
            friction: Friction::NONE,
        }
    }

    /// The same contact with Newton's restitution coefficient in [0, 1].
    pub fn with_restitution(self, restitution: f64) -> Result<Self, ConstraintError> {
        let restitution = checked_restitution("edge contact", restitution)?;
        Ok(EdgeContact { restitution, ..self })
    }

    /// The same contact with Coulomb friction between the edges.
    pub fn with_friction(self, friction: Friction) -> Self {
        EdgeContact { friction, ..self }
    }

    /// The contact body's edge and the second body's.
    pub fn edges(&self) -> (Edge, Edge) {
        (self.edge, self.other)
    }

    /// The restitution coefficient.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The friction between the edges.
    pub fn friction(&self) -> Friction {
        self.friction
    }
}

/// The most contacts [`crate::Mechanism::add_polyhedron_contacts`] adds for one pair of polyhedra: each is watched
/// at every step.
pub const MAX_POLYHEDRON_CONTACTS: usize = 10_000;

/// The most faces a [`Polyhedron`] may have (each a plane its vertex contacts are bounded by).
pub const MAX_POLYHEDRON_FACES: usize = 512;

/// A convex polyhedron in a body's frame: its vertices, its faces' planes and its edges, for
/// [`crate::Mechanism::add_polyhedron_contacts`].
#[derive(Clone, Debug, PartialEq)]
pub struct Polyhedron {
    vertices: Vec<Vector3<f64>>,
    faces: Vec<(Vector3<f64>, f64)>,
    edges: Vec<Edge>,
}

impl Polyhedron {
    /// A box of sides `sides` (m) about the body's origin, along its axes: 8 vertices, 6 faces, 12 edges.
    ///
    /// ```
    /// use dynamics::contacts::Polyhedron;
    /// use nalgebra::Vector3;
    ///
    /// let crate_ = Polyhedron::cuboid(Vector3::new(0.4, 0.3, 0.2))?;
    /// assert_eq!((crate_.vertices().len(), crate_.faces().len(), crate_.edges().len()), (8, 6, 12));
    /// assert!(Polyhedron::cuboid(Vector3::new(0.4, 0.0, 0.2)).is_err());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn cuboid(sides: Vector3<f64>) -> Result<Self, ConstraintError> {
        if !sides.iter().all(|&s| s > 0.0 && s <= LARGEST_COORDINATE) {
            return Err(ConstraintError::InvalidParameter {
                name: "polyhedron".to_owned(),
                reason: format!(
                    "a box's sides must be positive, finite and within {LARGEST_COORDINATE:e} m, got {:?}",
                    sides.as_slice()
                ),
            });
        }
        let half = sides / 2.0;
        let vertices = (0..8)
            .map(|c| {
                let sign = |bit: usize| if c & (1 << bit) == 0 { -1.0 } else { 1.0 };
                Vector3::new(sign(0) * half.x, sign(1) * half.y, sign(2) * half.z)
            })
            .collect();
        let faces = (0..6)
            .map(|f| {
                let sign = if f % 2 == 0 { -1.0 } else { 1.0 };
                (Vector3::ith(f / 2, sign), half[f / 2])
            })
            .collect();
        Polyhedron::new(vertices, faces)
    }

    /// The convex polyhedron of `vertices` (m, the body's frame) bounded by the planes `faces`, `n · x ≤ d` with n
    /// outward (any length): every vertex inside every plane and on at least three, every plane through at least
    /// three vertices, at least four planes and at most [`MAX_POLYHEDRON_FACES`]. Its edges are where two faces
    /// share two vertices.
    ///
    /// ```
    /// use dynamics::contacts::Polyhedron;
    /// use nalgebra::Vector3;
    ///
    /// // A tetrahedron: the corner of a cube at the origin cut off by x + y + z = 1.
    /// let vertices = vec![Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z()];
    /// let faces = vec![(-Vector3::x(), 0.0), (-Vector3::y(), 0.0), (-Vector3::z(), 0.0), (Vector3::repeat(1.0), 1.0)];
    /// assert_eq!(Polyhedron::new(vertices.clone(), faces.clone())?.edges().len(), 6);
    /// assert!(Polyhedron::new(vertices[..3].to_vec(), faces).is_err()); // a face through no third vertex
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(vertices: Vec<Vector3<f64>>, faces: Vec<(Vector3<f64>, f64)>) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "polyhedron".to_owned(),
            reason,
        };
        if !(4..=MAX_POLYHEDRON_FACES).contains(&faces.len()) {
            return Err(refuse(format!(
                "a polyhedron has 4 to {MAX_POLYHEDRON_FACES} faces, got {}",
                faces.len()
            )));
        }
        let within = |x: &f64| x.is_finite() && x.abs() <= LARGEST_COORDINATE;
        if let Some(v) = vertices.iter().find(|v| !v.iter().all(within)) {
            return Err(refuse(format!(
                "a vertex {:?} is not finite or beyond {LARGEST_COORDINATE:e} m",
                v.as_slice()
            )));
        }
        let extent = vertices.iter().fold(0.0f64, |m, v| m.max(v.amax()));
        let on = 1e-9 * extent.max(1e-3);
        let mut planes = Vec::with_capacity(faces.len());
        for (k, (normal, offset)) in faces.iter().enumerate() {
            let scale = normal.amax();
            if !(normal.iter().all(|x| x.is_finite()) && scale > 0.0 && offset.is_finite()) {
                return Err(refuse(format!(
                    "face {} needs a finite, non-zero normal and a finite offset, got {:?} and {offset}",
                    k + 1,
                    normal.as_slice()
                )));
            }
            let length = (normal / scale).norm();
            let (normal, offset) = (normal / scale / length, offset / scale / length);
            let touching = vertices.iter().filter(|v| (normal.dot(v) - offset).abs() <= on).count();
            if let Some(v) = vertices.iter().find(|v| normal.dot(v) - offset > on) {
                return Err(refuse(format!(
                    "the vertex {:?} is outside face {} ({:?} · x ≤ {offset}): the polyhedron is not convex",
                    v.as_slice(),
                    k + 1,
                    normal.as_slice()
                )));
            }
            if touching < 3 {
                return Err(refuse(format!(
                    "face {} passes through {touching} vertices: a face has at least three",
                    k + 1
                )));
            }
            planes.push((normal, offset));
        }
        if let Some(v) =
            (vertices.iter()).find(|v| planes.iter().filter(|(n, d)| (n.dot(v) - d).abs() <= on).count() < 3)
        {
            return Err(refuse(format!(
                "the vertex {:?} lies on fewer than three faces: not a corner of the polyhedron",
                v.as_slice()
            )));
        }
        let mut edges = Vec::new();
        for (k, (n1, d1)) in planes.iter().enumerate() {
            for (n2, d2) in &planes[k + 1..] {
                let along = n1.cross(n2);
                if along.norm() <= 1e-9 {
                    continue;
                }
                let shared: Vec<&Vector3<f64>> = (vertices.iter())
                    .filter(|v| (n1.dot(v) - d1).abs() <= on && (n2.dot(v) - d2).abs() <= on)
                    .collect();
                let extreme =
                    |sign: f64| (shared.iter()).max_by(|a, b| (sign * along.dot(a)).total_cmp(&(sign * along.dot(b))));
                if let (Some(start), Some(end)) = (extreme(-1.0), extreme(1.0)) {
                    if shared.len() >= 2 {
                        edges.push(Edge::new(**start, **end, [*n1, *n2])?);
                    }
                }
            }
        }
        Ok(Polyhedron {
            vertices,
            faces: planes,
            edges,
        })
    }

    /// The vertices (m, the body's frame).
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The faces' planes `n · x ≤ d`, n unit and outward.
    pub fn faces(&self) -> &[(Vector3<f64>, f64)] {
        &self.faces
    }

    /// The edges, each between two faces.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }
}
