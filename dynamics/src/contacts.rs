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
//! "Between bodies").

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
