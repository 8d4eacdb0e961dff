//! A mechanism's contacts (docs/contacts.md): body points or spheres kept above world planes, above planes fixed in
//! other bodies, or outside other bodies' spheres; their gaps, normals and relative velocities, their rows in joint
//! space, and the Newton projection that keeps a held contact touching.

use std::cell::OnceCell;

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::contacts::{BallContact, Friction, PlaneContact, FLAT_RIM, MAX_FACE_PLANES, OUTSIDE_FACE, TOUCHING};
use crate::mechanism::contact_frames::{edge_frame, sphere_edge_frame, BodyMotion, ContactFrame, RimPoint};
use crate::mechanism::error::listed;
use crate::mechanism::error::MechanismError;
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::mechanism::parts::{placed_plane, Against, BodyId, Contact, PointDirection};
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
    /// Keeps the point of `contact` (in `body`'s frame: the frame its joint models use, the principal frame unless the
    /// body was added with [`Mechanism::add_body_with_frame`]) above the contact's world plane, exactly and
    /// without friction ([`crate::contacts`]): [`crate::simulate()`] locates where it meets the plane, applies the
    /// impact, holds it there and releases it. Contacts need the articulated solve, as joint limits do: every joint a
    /// joint model, in a tree, and no Baumgarte stabilisation. Names are those of the transitions; a name must be new
    /// among the joints and contacts.
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Force, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let block = Body::cuboid(1.0, Vector3::new(0.2, 0.2, 0.2))?;
    /// let mut scene = Mechanism::<Pga>::new();
    /// let id = scene.add_body("block", block)?;
    /// scene.add_force(id, Force::gravity())?;
    /// for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)].into_iter().enumerate() {
    ///     let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.0)?; // above the floor z = 0
    ///     scene.add_contact(format!("corner {k}"), id, corner)?;
    /// }
    /// assert_eq!(scene.contact_names().count(), 4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_contact(
        &mut self,
        name: impl Into<String>,
        body: BodyId,
        contact: PlaneContact,
    ) -> Result<(), MechanismError> {
        let against = Against::World {
            normal: contact.normal(),
            offset: contact.offset(),
        };
        self.push_contact(name.into(), body, features(&contact), |_| Ok(against))
    }

    /// Keeps the point or sphere of `contact` (in `body`'s frame) above the contact's plane fixed in `surface`'s
    /// frame (normal and offset in that body's coordinates, as `body`'s point is in its own): a vertex or a sphere of
    /// one body on a face of another, exactly as [`Mechanism::add_contact`] keeps it on a world plane, the impacts,
    /// the push and the friction acting on both bodies (docs/contacts.md "Between bodies"). The plane is unbounded:
    /// the contact holds wherever the point meets it.
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Force, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// // A small block whose bottom corners rest on the top face (z = 0.1) of a larger one.
    /// let mut scene = Mechanism::<Pga>::new();
    /// let lower = scene.add_body("lower", Body::cuboid(4.0, Vector3::new(0.4, 0.4, 0.2))?)?;
    /// let upper = scene.add_body("upper", Body::cuboid(1.0, Vector3::new(0.2, 0.2, 0.2))?)?;
    /// scene.add_force(upper, Force::gravity())?;
    /// for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)].into_iter().enumerate() {
    ///     let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.1)?;
    ///     scene.add_contact_on(format!("corner {k}"), upper, lower, corner)?;
    /// }
    /// assert!(scene.add_contact_on("self", upper, upper, PlaneContact::new(Vector3::zeros(), Vector3::z(), 0.0)?).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_contact_on(
        &mut self,
        name: impl Into<String>,
        body: BodyId,
        surface: BodyId,
        contact: PlaneContact,
    ) -> Result<(), MechanismError> {
        let (normal, offset) = (contact.normal(), contact.offset());
        self.push_contact(name.into(), body, features(&contact), |mechanism| {
            let other = mechanism.other_body(body, surface)?;
            let (normal, offset) = placed_plane(&mechanism.bodies[other].frame, &normal, offset);
            Ok(Against::Face {
                body: other,
                normal,
                offset,
            })
        })
    }

    /// Keeps the sphere of `contact` fixed in `body` outside its sphere fixed in `other` (centres in each body's
    /// frame): two balls meeting, exactly, with Newton's restitution and Coulomb's friction at the point where they
    /// touch (docs/contacts.md "Between bodies").
    ///
    /// ```
    /// use dynamics::{contacts::BallContact, Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let ball = Body::new(0.17, Vector3::repeat(0.4 * 0.17 * 0.0285f64.powi(2)))?;
    /// let mut table = Mechanism::<Pga>::new();
    /// let (cue, red) = (table.add_body("cue", ball)?, table.add_body("red", ball)?);
    /// let touching = BallContact::new(Vector3::zeros(), 0.0285, Vector3::zeros(), 0.0285)?.with_restitution(1.0)?;
    /// table.add_ball_contact("cue on red", cue, red, touching)?;
    /// assert_eq!(table.contact_names().collect::<Vec<_>>(), ["cue on red"]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_ball_contact(
        &mut self,
        name: impl Into<String>,
        body: BodyId,
        other: BodyId,
        contact: BallContact,
    ) -> Result<(), MechanismError> {
        let (centre, other_centre) = contact.centres();
        let (radius, other_radius) = contact.radii();
        let parts = (centre, radius, None, contact.restitution(), contact.friction());
        self.push_contact(name.into(), body, parts, |mechanism| {
            let other = mechanism.other_body(body, other)?;
            Ok(Against::Ball {
                body: other,
                centre: mechanism.bodies[other]
                    .frame
                    .transform_point(&other_centre.into())
                    .coords,
                radius: other_radius,
            })
        })
    }

    /// The index of `other`, the second body of a contact of `body`: an error if it is unknown or the same body.
    pub(super) fn other_body(&self, body: BodyId, other: BodyId) -> Result<usize, MechanismError> {
        let index = self.check_body(other)?;
        if other == body {
            return Err(crate::ConstraintError::InvalidParameter {
                name: self.bodies[index].name.clone(),
                reason: "a contact between bodies needs two different bodies".to_owned(),
            }
            .into());
        }
        Ok(index)
    }

    /// A contact of `body` (its point, radius, rim, restitution and friction, the point and the rim's axis in the
    /// body's frame) kept outside what `against` gives, once the name and the solve are checked.
    pub(super) fn push_contact(
        &mut self,
        name: String,
        body: BodyId,
        (point, radius, rim, restitution, friction): ContactParts,
        against: impl FnOnce(&Self) -> Result<Against, MechanismError>,
    ) -> Result<(), MechanismError> {
        if name.is_empty() {
            return Err(MechanismError::EmptyName("contact"));
        }
        let index = self.check_body(body)?;
        if self.contacts.iter().any(|c| c.name == name) || self.joints.iter().any(|j| j.name() == name) {
            return Err(MechanismError::DuplicateContact(name));
        }
        if self.articulation.is_none() || self.coordinates().is_none() {
            return Err(crate::ConstraintError::InvalidParameter {
                name,
                reason: "contacts need the articulated solve: every joint a joint model, in a tree, no Baumgarte \
                         stabilisation"
                    .to_owned(),
            }
            .into());
        }
        let against = against(self)?;
        let frame = &self.bodies[index].frame;
        let point = frame.transform_point(&point.into()).coords;
        let rim = rim.map(|(axis, radius)| (frame.rotation * axis, radius));
        if friction.is_some() {
            self.frictional.push(self.contacts.len());
        }
        self.contacts.push(Contact {
            name,
            body: index,
            point,
            radius,
            rim,
            restitution,
            friction,
            against,
            face: Vec::new(),
            edge: None,
            switching: false,
            region_at_centre: false,
        });
        Ok(())
    }

    /// Bounds the plane of contact `name` to a face: its touching point must stay inside the convex solid `n_k · x ≤
    /// d_k` (the planes in the frame the contact's plane was given in: the world's, or the surface body's) while it
    /// touches, within [`OUTSIDE_FACE`]. The plane itself is unbounded; a contact that holds, or meets its plane,
    /// outside the face would be a silently wrong answer, so [`crate::simulate()`] stops there with an error naming the
    /// contact and how far outside it is. Each normal finite and not zero (of any size), each plane's distance from
    /// the origin (the offset over the normal's length) within [`crate::contacts::LARGEST_COORDINATE`]; at most
    /// [`MAX_FACE_PLANES`] planes. A ball contact has no face.
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// // A table top 1 m square at z = 0.8: a corner of a block may rest on it only within |x|, |y| ≤ 0.5.
    /// let mut scene = Mechanism::<Pga>::new();
    /// let block = scene.add_body("block", Body::cuboid(1.0, Vector3::repeat(0.1))?)?;
    /// scene.add_contact("corner", block, PlaneContact::new(Vector3::new(0.05, 0.05, -0.05), Vector3::z(), 0.8)?)?;
    /// let sides = [(Vector3::x(), 0.5), (-Vector3::x(), 0.5), (Vector3::y(), 0.5), (-Vector3::y(), 0.5)];
    /// scene.set_contact_face("corner", &sides)?;
    /// assert!(scene.set_contact_face("edge", &sides).is_err()); // no such contact
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_contact_face(&mut self, name: &str, solid: &[(Vector3<f64>, f64)]) -> Result<(), MechanismError> {
        self.bound_to_face(name, solid, false)
    }

    /// Contact `name` bounded to a face as [`Mechanism::set_contact_face`] bounds it, with `switching`: outside the
    /// face it lets go rather than stopping the run ([`Mechanism::set_contact_switching_face`]).
    pub(super) fn bound_to_face(
        &mut self,
        name: &str,
        solid: &[(Vector3<f64>, f64)],
        switching: bool,
    ) -> Result<(), MechanismError> {
        let refuse = |reason: String| {
            MechanismError::from(ConstraintError::InvalidParameter {
                name: name.to_owned(),
                reason,
            })
        };
        let Some(index) = self.contacts.iter().position(|c| c.name == name) else {
            return Err(refuse("no contact has this name".to_owned()));
        };
        if solid.len() > MAX_FACE_PLANES {
            return Err(refuse(format!(
                "a face is bounded by at most {MAX_FACE_PLANES} planes, got {}",
                solid.len()
            )));
        }
        let frame = match self.contacts[index].against {
            Against::World { .. } => nalgebra::Isometry3::identity(),
            Against::Face { body, .. } => self.bodies[body].frame,
            Against::Ball { .. } => return Err(refuse("a ball contact has no face".to_owned())),
            Against::Edge { .. } => return Err(refuse("an edge contact is bounded by its edges".to_owned())),
        };
        let within = |x: f64| x.is_finite() && x.abs() <= crate::contacts::LARGEST_COORDINATE;
        let mut face = Vec::with_capacity(solid.len());
        for (k, (normal, offset)) in solid.iter().enumerate() {
            // Scaled before its length is taken: a normal of huge or tiny numbers is a direction like any other.
            let scale = normal.amax();
            let length = (normal / scale).norm();
            let distance = offset / scale / length;
            if !(normal.iter().all(|x| x.is_finite()) && scale > 0.0 && within(distance)) {
                return Err(refuse(format!(
                    "the face's plane {} needs a finite, non-zero normal and a distance from the origin (the offset \
                     over the normal's length) within {:e} m, got {:?} and {offset}",
                    k + 1,
                    crate::contacts::LARGEST_COORDINATE,
                    normal.as_slice()
                )));
            }
            face.push(placed_plane(&frame, &(normal / scale / length), distance));
        }
        self.contacts[index].face = face;
        self.contacts[index].switching = switching;
        Ok(())
    }

    /// An error naming the first contact that touches its plane (held, or within [`TOUCHING`] of it) with its
    /// touching point outside its face by more than [`OUTSIDE_FACE`] ([`Mechanism::set_contact_face`]), or as a disk
    /// within [`FLAT_RIM`] of lying flat ([`PlaneContact::disk`]): what one touching point cannot answer for.
    pub(super) fn check_features(
        &self,
        t: f64,
        states: &[State<A>],
        held: &[Option<crate::limits::Bound>],
    ) -> Result<(), ConstraintError> {
        for (c, contact) in self.contacts.iter().enumerate() {
            if (contact.face.is_empty() || contact.switching) && contact.rim.is_none() {
                continue;
            }
            let frame = self.contact_frame(c, states);
            if held[self.limits.len() + c].is_none() && frame.gap > TOUCHING {
                continue;
            }
            let refuse = |reason: String| ConstraintError::InvalidParameter {
                name: contact.name.clone(),
                reason,
            };
            if frame.tilt < FLAT_RIM {
                return Err(refuse(format!(
                    "at t = {t} the disk lies flat on its plane (its axis {:.3e} rad from the normal), touching \
                     along its whole rim, which one rim point cannot hold (docs/contacts.md \"Rims\")",
                    frame.tilt.asin()
                )));
            }
            if !contact.switching && frame.outside > OUTSIDE_FACE.max(4.0 * f64::EPSILON * frame.touching.amax()) {
                let outside = frame.outside;
                return Err(refuse(format!(
                    "at t = {t} the contact touches its plane {outside:.3e} m outside its face: the plane holds only \
                     on the face, and a contact keeps the features it was given (docs/contacts.md \"Between bodies\")"
                )));
            }
        }
        Ok(())
    }

    /// Every contact's height above its plane (m, negative below it) at `states`, in the order they were added; an
    /// error unless there is one state per body. A switching contact ([`Mechanism::add_polyhedron_contacts`]) whose
    /// features do not meet there (its touching point outside its face or edges) has no height, +∞; where they meet,
    /// its height is the larger of its gap and how far outside its face or edges it is (within [`OUTSIDE_FACE`]):
    /// for a vertex inside the other solid, its distance from the solid's nearest face plane. An edge pair's lines
    /// pass each other behind a solid as often as through it: below [`TOUCHING`] it has no height either (two
    /// solids' overlap is a question for a collision library).
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::new(1.0, Vector3::repeat(0.004))?;
    /// let mut scene = Mechanism::<Pga>::new();
    /// let id = scene.add_body("ball", ball)?;
    /// scene.add_contact("bottom", id, PlaneContact::new(Vector3::new(0.0, 0.0, -0.1), Vector3::z(), 0.0)?)?;
    /// let at = State::<Pga>::from_world_twist(&ball, Vector3::z() * 0.5, &UnitQuaternion::identity(), Vector3::zeros(), Vector3::zeros());
    /// assert!((scene.contact_heights(&[at])?[0] - 0.4).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn contact_heights(&self, states: &[State<A>]) -> Result<Vec<f64>, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok((0..self.contacts.len())
            .map(|c| self.contact_height(c, states))
            .collect())
    }

    /// Contact `c`'s height at `states`, as [`Mechanism::contact_heights`] gives it.
    pub(super) fn contact_height(&self, c: usize, states: &[State<A>]) -> f64 {
        let frame = self.contact_frame(c, states);
        let contact = &self.contacts[c];
        match (contact.switching, contact.edge.is_some()) {
            (false, _) => frame.gap,
            (true, _) if !frame.defined || frame.outside > OUTSIDE_FACE => f64::INFINITY,
            // Two edges' lines pass each other far behind one solid as often as through it.
            (true, true) if frame.gap < -TOUCHING => f64::INFINITY,
            // Below the face's plane but at another face (a vertex on the top of a box, below its bottom face's
            // plane) is no deeper than that other face's plane: inside the solid, the deepest of them.
            (true, _) => frame.gap.max(frame.outside),
        }
    }

    /// The contacts' names, in the order they were added.
    pub fn contact_names(&self) -> impl Iterator<Item = &str> {
        self.contacts.iter().map(|c| c.name.as_str())
    }

    /// Contact `index`'s frame at `states` (docs/contacts.md "Between bodies").
    pub(super) fn contact_frame(&self, index: usize, states: &[State<A>]) -> ContactFrame {
        self.frame_of(index, &|b| self.body_motion(b, states))
    }

    /// Body `b`'s pose and velocity at `states` (world).
    fn body_motion(&self, b: usize, states: &[State<A>]) -> BodyMotion {
        let (position, rotation) = states[b].pose();
        let velocity = states[b].world_velocity(&self.bodies[b].body);
        BodyMotion {
            position,
            rotation: rotation.to_rotation_matrix().into_inner(),
            linear: velocity.linear,
            angular: velocity.angular,
        }
    }

    /// Contact `index`'s frame at `states`, each body's motion found at most once across the calls that share
    /// `motions` (one empty cell per body): the many contacts of a pair of polyhedra share two bodies.
    pub(super) fn frame_among(
        &self,
        index: usize,
        states: &[State<A>],
        motions: &[OnceCell<BodyMotion>],
    ) -> ContactFrame {
        self.frame_of(index, &|b| *motions[b].get_or_init(|| self.body_motion(b, states)))
    }

    /// Contact `index`'s frame at the kinematics the workspace holds (an evaluation's).
    pub(super) fn workspace_frame(&self, index: usize, workspace: &MechanismWorkspace<A>) -> ContactFrame {
        self.frame_of(index, &|b| {
            let kinematics = &workspace.bodies[b].kinematics;
            BodyMotion {
                position: kinematics.frame.position,
                rotation: *kinematics.frame.rotation.matrix(),
                linear: kinematics.linear_velocity,
                angular: kinematics.angular_velocity,
            }
        })
    }

    /// Contact `index`'s gap, normal, touching point and their rates with the bodies moving as `motion` gives
    /// (docs/contacts.md "Between bodies"): for a plane fixed in a body, n turns with it (`ṅ = ω × n`); for two
    /// balls n is along the line of centres d, `ṅ = (ḋ − n (n · ḋ)) / |d|`. The touching point is `c − r n` of the
    /// contact's sphere (its point c, for r = 0), moving at `ṗ = ċ − r ṅ`.
    fn frame_of(&self, index: usize, motion: &dyn Fn(usize) -> BodyMotion) -> ContactFrame {
        let contact = &self.contacts[index];
        let own = motion(contact.body);
        let centre = own.position + own.rotation * contact.point;
        let centre_velocity = own.velocity_at(&centre);
        let (other, gap_to_centre, normal, normal_rate) = match contact.against {
            Against::World { normal, offset } => (None, normal.dot(&centre) - offset, normal, Vector3::zeros()),
            Against::Face { body, normal, offset } => {
                let surface = motion(body);
                let normal = surface.rotation * normal;
                let height = normal.dot(&(centre - surface.position)) - offset;
                (Some(surface), height, normal, surface.angular.cross(&normal))
            }
            Against::Edge { body, start, edge } => {
                return match contact.edge {
                    Some(own_edge) => edge_frame((&own, centre, &own_edge), (&motion(body), start, &edge)),
                    None => sphere_edge_frame((&own, centre, contact.radius), (&motion(body), start, &edge)),
                };
            }
            Against::Ball {
                body,
                centre: other_centre,
                radius,
            } => {
                let ball = motion(body);
                let other_centre = ball.position + ball.rotation * other_centre;
                let between = centre - other_centre;
                let distance = between.norm();
                // Coincident centres have no line between them: any direction serves a gap of −(r₁ + r₂).
                let normal = if distance > 0.0 {
                    between / distance
                } else {
                    Vector3::z()
                };
                let rate = centre_velocity - ball.velocity_at(&other_centre);
                let normal_rate = if distance > 0.0 {
                    (rate - normal * normal.dot(&rate)) / distance
                } else {
                    Vector3::zeros()
                };
                (Some(ball), distance - radius, normal, normal_rate)
            }
        };
        let rim = contact.rim.map_or_else(RimPoint::default, |(axis, radius)| {
            RimPoint::towards(radius, &(own.rotation * axis), &own.angular, &normal, &normal_rate)
        });
        let touching = centre - rim.offset - normal * contact.radius;
        let surface_velocity = other.map_or_else(Vector3::zeros, |o| o.velocity_at(&touching));
        // How far the touching point is outside the contact's face, in the frame the face is fixed in, and how fast
        // it moves out across the farthest of the face's planes: y = Rᵀ(p − x), ẏ = Rᵀ(ṗ − v(p)).
        let touching_rate = centre_velocity - rim.rate - normal_rate * contact.radius;
        let (probe, probe_rate) = if contact.region_at_centre {
            (centre, centre_velocity)
        } else {
            (touching, touching_rate)
        };
        let (local, local_rate) = other.map_or((probe, probe_rate), |o| {
            let turn = o.rotation.transpose();
            (turn * (probe - o.position), turn * (probe_rate - o.velocity_at(&probe)))
        });
        let (outside, outside_rate) = (contact.face.iter()).fold((f64::NEG_INFINITY, 0.0), |m, (n, d)| {
            let distance = n.dot(&local) - d;
            if distance > m.0 {
                (distance, n.dot(&local_rate))
            } else {
                m
            }
        });
        ContactFrame {
            gap: gap_to_centre - normal.dot(&rim.offset) - contact.radius,
            normal,
            touching,
            relative: own.velocity_at(&touching) - surface_velocity,
            normal_rate,
            touching_rate,
            tilt: rim.tilt,
            outside,
            outside_rate,
            defined: true,
        }
    }

    /// Contact `index`'s height above its plane (m) and its point's speed along the normal (m/s), at `states`.
    pub(super) fn contact_motion(&self, index: usize, states: &[State<A>]) -> (f64, f64) {
        let frame = self.contact_frame(index, states);
        (frame.gap, frame.normal_speed())
    }

    /// The rows `c` of the contacts `indices` in joint space at `states`: `c · v` is the contact's normal speed at
    /// joint velocities v (the unit force along n through the touching point on its body and its opposite on the
    /// other, as a generalised force).
    pub(super) fn contact_rows(&self, states: &[State<A>], indices: &[usize]) -> Result<DMatrix<f64>, ConstraintError> {
        let points: Vec<PointDirection> = indices
            .iter()
            .map(|&i| {
                let frame = self.contact_frame(i, states);
                self.point_direction(i, frame.touching, frame.normal)
            })
            .collect();
        self.contact_jacobian(states, &points)
    }

    /// The joint-space rows of `points` (contacts' touching points along directions), with an error naming the
    /// contacts.
    pub(super) fn contact_jacobian(
        &self,
        states: &[State<A>],
        points: &[PointDirection],
    ) -> Result<DMatrix<f64>, ConstraintError> {
        self.point_jacobian(states, points)
            .map_err(|error| ConstraintError::InvalidParameter {
                name: listed(self.contact_names()),
                reason: error.to_string(),
            })
    }

    /// Contact `index`'s world point and direction, on its body and (negated) on the other.
    pub(super) fn point_direction(&self, index: usize, point: Vector3<f64>, direction: Vector3<f64>) -> PointDirection {
        let contact = &self.contacts[index];
        PointDirection {
            body: contact.body,
            other: contact.against.body(),
            point,
            direction,
        }
    }

    /// Contacts `indices` placed on their planes and, with `stop`, stopped there, the slips of the `sticking` ones
    /// with them, the `equalities` rows (joint space) kept (docs/contacts.md "Projection"): Newton steps
    /// `δ = M⁻¹Cᵀ(CM⁻¹Cᵀ)⁺(−h)` on the joint positions (retracted onto the quaternions) until the heights h are within
    /// [`ON_PLANE`], then the normal speeds and the sticking slips removed by the same map.
    pub(super) fn place_contacts(
        &self,
        t: f64,
        states: &mut [State<A>],
        (indices, sticking, stop): (&[usize], &[usize], bool),
        equalities: &DMatrix<f64>,
        previous: &mut Vec<f64>,
    ) -> Result<(), ConstraintError> {
        let space = self.limited_space()?;
        let layout = space.layout();
        let (mut q, mut v) = (vec![0.0; space.position_count()], vec![0.0; space.velocity_count()]);
        self.read_joints_into(states, &mut q, &mut v, previous)?;
        let mut residual = DVector::zeros(indices.len() + equalities.nrows());
        for _ in 0..NEWTON_STEPS {
            let heights: Vec<f64> = indices.iter().map(|&i| self.contact_motion(i, states).0).collect();
            // Far from the origin a height cannot be closer to zero than a few ulps of the point's coordinates.
            let within = |(&i, h): (&usize, &f64)| {
                let reach = self.contact_frame(i, states).touching.amax().abs();
                h.abs() <= ON_PLANE.max(4.0 * f64::EPSILON * reach)
            };
            if indices.iter().zip(&heights).all(within) {
                break;
            }
            residual.fill(0.0);
            heights.iter().enumerate().for_each(|(k, h)| residual[k] = -h);
            let rows = self.contact_rows(states, indices)?;
            let step = self.metric_correction(t, states, &rows, equalities, &residual)?;
            layout.retract(&mut q, step.as_slice());
            self.write_joints_into(t, &q, &v, states, &mut Vec::new())?;
        }
        if !stop {
            previous.clone_from(&q);
            return Ok(());
        }
        let rows = stack(&[&self.contact_rows(states, indices)?, &self.slip_rows(states, sticking)?]);
        let speeds = &rows * DVector::from_column_slice(&v);
        let mut residual = DVector::zeros(rows.nrows() + equalities.nrows());
        speeds.iter().enumerate().for_each(|(k, u)| residual[k] = -u);
        let change = self.metric_correction(t, states, &rows, equalities, &residual)?;
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        self.write_joints_into(t, &q, &v, states, &mut Vec::new())?;
        previous.clone_from(&q);
        Ok(())
    }
}

/// A contact's point, sphere radius, rim (axis and radius), restitution and friction, in its body's frame.
pub(super) type ContactParts = (Vector3<f64>, f64, Option<(Vector3<f64>, f64)>, f64, Friction);

/// A plane contact's parts.
fn features(contact: &PlaneContact) -> ContactParts {
    (
        contact.point(),
        contact.radius(),
        contact.rim(),
        contact.restitution(),
        contact.friction(),
    )
}

/// The Newton steps [`Mechanism::place_contacts`] takes at most (one is enough but for round-off: each squares the
/// height).
const NEWTON_STEPS: usize = 4;

/// Heights (m) within this of the plane count as on it (or within a few ulps of the point's coordinates, if more).
const ON_PLANE: f64 = 1e-14;

/// Rows stacked one matrix above the next (all with the same columns).
pub(super) fn stack(blocks: &[&DMatrix<f64>]) -> DMatrix<f64> {
    let columns = blocks.iter().map(|b| b.ncols()).max().unwrap_or(0);
    let total = blocks.iter().map(|b| b.nrows()).sum();
    let mut stacked = DMatrix::zeros(total, columns);
    let mut at = 0;
    for block in blocks {
        if block.nrows() > 0 {
            stacked
                .view_mut((at, 0), (block.nrows(), block.ncols()))
                .copy_from(block);
        }
        at += block.nrows();
    }
    stacked
}
