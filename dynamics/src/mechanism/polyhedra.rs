//! Contacts among all the features of two convex solids (docs/contacts.md "Edges"): an edge of one body on an edge
//! of another, and contacts that switch, watched only where their features meet and letting go where they part, so
//! that a box may tumble over another as its vertices, faces and edges take turns.

use nalgebra::{Isometry3, Point3, Vector3};

use crate::algebra::Algebra;
use crate::contacts::{
    Edge, EdgeContact, Friction, PlaneContact, Polyhedron, MAX_POLYHEDRON_CONTACTS, OUTSIDE_FACE, TOUCHING,
};
use crate::mechanism::contact_frames::ContactFrame;
use crate::mechanism::error::MechanismError;
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::mechanism::parts::{placed_plane, Against, BodyId, EdgeFeature};
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
    /// Keeps an edge of `body` from passing through an edge of `other` (each in its body's frame): two convex solids
    /// meeting edge on edge, with the contact's restitution and friction at the point where the edges cross
    /// (docs/contacts.md "Edges"). The contact switches: it is watched only while its edges are apart, and where
    /// they cross outside either edge, or with their common normal outside either edge's faces, it is not a contact
    /// and lets go; the vertex and face contacts of the two solids
    /// ([`Mechanism::set_contact_switching_face`]) take over there.
    ///
    /// ```
    /// use dynamics::contacts::{Edge, EdgeContact};
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let mut scene = Mechanism::<Pga>::new();
    /// let cube = Body::cuboid(1.0, Vector3::repeat(0.2))?;
    /// let (upper, lower) = (scene.add_body("upper", cube)?, scene.add_body("lower", cube)?);
    /// let bottom = Edge::new(Vector3::new(-0.1, 0.1, -0.1), Vector3::new(0.1, 0.1, -0.1), [-Vector3::z(), Vector3::y()])?;
    /// let top = Edge::new(Vector3::new(0.1, -0.1, 0.1), Vector3::new(0.1, 0.1, 0.1), [Vector3::z(), Vector3::x()])?;
    /// scene.add_edge_contact("crossed", upper, lower, EdgeContact::new(bottom, top))?;
    /// assert_eq!(scene.contact_names().collect::<Vec<_>>(), ["crossed"]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_edge_contact(
        &mut self,
        name: impl Into<String>,
        body: BodyId,
        other: BodyId,
        contact: EdgeContact,
    ) -> Result<(), MechanismError> {
        let (own, theirs) = contact.edges();
        let index = self.check_body(body)?;
        let (_, edge) = principal(&self.bodies[index].frame, &own);
        let parts = (own.ends().0, 0.0, None, contact.restitution(), contact.friction());
        self.push_contact(name.into(), body, parts, |mechanism| {
            let other = mechanism.other_body(body, other)?;
            let (start, edge) = principal(&mechanism.bodies[other].frame, &theirs);
            Ok(Against::Edge {
                body: other,
                start,
                edge,
            })
        })?;
        let added = self.contacts.last_mut().expect("the contact just added");
        added.edge = Some(edge);
        added.switching = true;
        Ok(())
    }

    /// Keeps convex polyhedron `first` of body `a` and `second` of body `b` (each in its body's frame) from passing
    /// into each other, exactly (docs/contacts.md "Edges"): every vertex of each on every face of the other, bounded to
    /// the face ([`Mechanism::set_contact_switching_face`]), and every edge of each on every edge of the other
    /// ([`Mechanism::add_edge_contact`]), all with `friction` and `restitution`; each pair is watched only where its
    /// features meet, so that the solids may rest, slide, tip and tumble on each other as their features take
    /// turns. Contacts are named "`name`: `label_a` vertex i on `label_b` face j" (and the other way round) and
    /// "`name`: `label_a` edge i on `label_b` edge j", counting from 1. Returns how many were added: at most
    /// [`MAX_POLYHEDRON_CONTACTS`] per pair.
    ///
    /// ```
    /// use dynamics::contacts::{Friction, Polyhedron};
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let mut scene = Mechanism::<Pga>::new();
    /// let sides = Vector3::repeat(0.2);
    /// let (upper, lower) = (scene.add_body("upper", Body::cuboid(1.0, sides)?)?, scene.add_body("lower", Body::cuboid(1.0, sides)?)?);
    /// let cube = Polyhedron::cuboid(sides)?;
    /// let added = scene.add_polyhedron_contacts("stack", (upper, &cube, "upper"), (lower, &cube, "lower"), Friction::coulomb(0.5)?, 0.0)?;
    /// assert_eq!(added, 8 * 6 * 2 + 12 * 12);
    /// assert!(scene.contact_names().any(|n| n == "stack: upper edge 1 on lower edge 12"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_polyhedron_contacts(
        &mut self,
        name: &str,
        (a, first, label_a): (BodyId, &Polyhedron, &str),
        (b, second, label_b): (BodyId, &Polyhedron, &str),
        friction: Friction,
        restitution: f64,
    ) -> Result<usize, MechanismError> {
        let count = first.vertices().len() * second.faces().len()
            + second.vertices().len() * first.faces().len()
            + first.edges().len() * second.edges().len();
        if count > MAX_POLYHEDRON_CONTACTS {
            return Err(crate::ConstraintError::InvalidParameter {
                name: name.to_owned(),
                reason: format!(
                    "the two polyhedra make {count} feature pairs, more than {MAX_POLYHEDRON_CONTACTS}: give them fewer \
                     vertices"
                ),
            }
            .into());
        }
        let mut added = 0;
        for ((own, shape, label), (other, solid, other_label)) in [
            ((a, first, label_a), (b, second, label_b)),
            ((b, second, label_b), (a, first, label_a)),
        ] {
            for (i, vertex) in shape.vertices().iter().enumerate() {
                for (j, &(normal, offset)) in solid.faces().iter().enumerate() {
                    let contact_name = format!("{name}: {label} vertex {} on {other_label} face {}", i + 1, j + 1);
                    let contact = PlaneContact::new(*vertex, normal, offset)?
                        .with_restitution(restitution)?
                        .with_friction(friction);
                    self.add_contact_on(contact_name.as_str(), own, other, contact)?;
                    // The face is its plane within the solid's other planes.
                    let others: Vec<(Vector3<f64>, f64)> = (solid.faces().iter().enumerate())
                        .filter(|&(k, _)| k != j)
                        .map(|(_, plane)| *plane)
                        .collect();
                    self.set_contact_switching_face(&contact_name, &others)?;
                    added += 1;
                }
            }
        }
        for (i, edge) in first.edges().iter().enumerate() {
            for (j, other_edge) in second.edges().iter().enumerate() {
                let contact = EdgeContact::new(*edge, *other_edge)
                    .with_restitution(restitution)?
                    .with_friction(friction);
                self.add_edge_contact(
                    format!("{name}: {label_a} edge {} on {label_b} edge {}", i + 1, j + 1),
                    a,
                    b,
                    contact,
                )?;
                added += 1;
            }
        }
        Ok(added)
    }

    /// Keeps the sphere of `radius` about `centre` (the body `a`'s frame) outside convex polyhedron `solid` of body `b`,
    /// exactly, with all the features it may touch (docs/contacts.md "Spheres on polyhedra"): the sphere on each face
    /// (within the face), on each vertex (its centre where the vertex is nearest) and on each edge (its centre where
    /// the edge is nearest, between the edge's faces), each pair watched only where its feature is the nearest, so
    /// that a ball rolls off a box's face over its edge, or meets its corner. Contacts are named "`name`: `label_a` on
    /// `label_b` face j" (vertex i, edge k), counting from 1. Returns how many were added.
    ///
    /// ```
    /// use dynamics::contacts::{Friction, Polyhedron};
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let mut scene = Mechanism::<Pga>::new();
    /// let ball = scene.add_body("ball", Body::sphere(0.2, 0.03)?)?;
    /// let crate_ = scene.add_body("crate", Body::cuboid(5.0, Vector3::repeat(0.4))?)?;
    /// let shape = Polyhedron::cuboid(Vector3::repeat(0.4))?;
    /// let added = scene.add_sphere_polyhedron_contacts("ball on crate", (ball, Vector3::zeros(), 0.03, "ball"), (crate_, &shape, "crate"), Friction::NONE, 0.5)?;
    /// assert_eq!(added, 6 + 8 + 12);
    /// assert!(scene.add_sphere_polyhedron_contacts("again", (ball, Vector3::zeros(), -0.03, "ball"), (crate_, &shape, "crate"), Friction::NONE, 0.5).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_sphere_polyhedron_contacts(
        &mut self,
        name: &str,
        (a, centre, radius, label_a): (BodyId, Vector3<f64>, f64, &str),
        (b, solid, label_b): (BodyId, &Polyhedron, &str),
        friction: Friction,
        restitution: f64,
    ) -> Result<usize, MechanismError> {
        // Checked as a sphere on a plane is: the centre, the radius, the restitution.
        let on_face = |normal: Vector3<f64>, offset: f64| {
            PlaneContact::sphere(centre, radius, normal, offset)
                .and_then(|c| c.with_restitution(restitution))
                .map(|c| c.with_friction(friction))
        };
        for (j, &(normal, offset)) in solid.faces().iter().enumerate() {
            let contact_name = format!("{name}: {label_a} on {label_b} face {}", j + 1);
            self.add_contact_on(contact_name.as_str(), a, b, on_face(normal, offset)?)?;
            let others: Vec<(Vector3<f64>, f64)> = (solid.faces().iter().enumerate())
                .filter(|&(k, _)| k != j)
                .map(|(_, plane)| *plane)
                .collect();
            self.set_contact_switching_face(&contact_name, &others)?;
        }
        let parts = on_face(Vector3::z(), 0.0)?;
        let features = (centre, radius, None, parts.restitution(), parts.friction());
        for (i, vertex) in solid.vertices().iter().enumerate() {
            // The vertex is nearest where the centre lies behind it along every edge leaving it.
            let region: Vec<(Vector3<f64>, f64)> = (solid.edges().iter())
                .filter_map(|edge| {
                    let (start, end) = edge.ends();
                    let away = if start == *vertex {
                        end - start
                    } else if end == *vertex {
                        start - end
                    } else {
                        return None;
                    };
                    let away = away.normalize();
                    Some((away, away.dot(vertex)))
                })
                .collect();
            let contact_name = format!("{name}: {label_a} on {label_b} vertex {}", i + 1);
            self.push_contact(contact_name, a, features, |mechanism| {
                let other = mechanism.other_body(a, b)?;
                let frame = &mechanism.bodies[other].frame;
                Ok(Against::Ball {
                    body: other,
                    centre: frame.transform_point(&Point3::from(*vertex)).coords,
                    radius: 0.0,
                })
            })?;
            let index = self.contacts.len() - 1;
            let frame = self.bodies[b.index()].frame;
            self.contacts[index].face = region.iter().map(|(n, d)| placed_plane(&frame, n, *d)).collect();
            self.contacts[index].switching = true;
            self.contacts[index].region_at_centre = true;
        }
        for (k, edge) in solid.edges().iter().enumerate() {
            let contact_name = format!("{name}: {label_a} on {label_b} edge {}", k + 1);
            self.push_contact(contact_name, a, features, |mechanism| {
                let other = mechanism.other_body(a, b)?;
                let (start, edge) = principal(&mechanism.bodies[other].frame, edge);
                Ok(Against::Edge {
                    body: other,
                    start,
                    edge,
                })
            })?;
            let index = self.contacts.len() - 1;
            self.contacts[index].switching = true;
        }
        Ok(solid.faces().len() + solid.vertices().len() + solid.edges().len())
    }

    /// Bounds contact `name`'s plane to a face as [`Mechanism::set_contact_face`] does, for a contact that is one
    /// feature pair among all of two convex solids (docs/contacts.md "Edges"): a vertex of one on a face of the
    /// other, beside the other vertex–face pairs and the edge pairs ([`Mechanism::add_edge_contact`]). Outside the
    /// face the contact is not a contact: it is not watched there, and held, it lets go where its touching point
    /// leaves the face (a located transition), rather than stopping the run, since another pair takes over.
    ///
    /// ```
    /// use dynamics::contacts::PlaneContact;
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let mut scene = Mechanism::<Pga>::new();
    /// let cube = Body::cuboid(1.0, Vector3::repeat(0.2))?;
    /// let (upper, lower) = (scene.add_body("upper", cube)?, scene.add_body("lower", cube)?);
    /// let corner = PlaneContact::new(Vector3::new(0.1, 0.1, -0.1), Vector3::z(), 0.1)?; // on the lower's top face
    /// scene.add_contact_on("corner", upper, lower, corner)?;
    /// let sides = [(Vector3::x(), 0.1), (-Vector3::x(), 0.1), (Vector3::y(), 0.1), (-Vector3::y(), 0.1)];
    /// scene.set_contact_switching_face("corner", &sides)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_contact_switching_face(
        &mut self,
        name: &str,
        solid: &[(Vector3<f64>, f64)],
    ) -> Result<(), MechanismError> {
        self.bound_to_face(name, solid, true)
    }

    /// Whether switching contacts are watched, renewed from `states` (before every step, and at the run's start): a
    /// switching contact not held is watched once its gap is open beyond [`TOUCHING`], or where it touches inside
    /// its face or edges; it stops being watched where it closes outside them ([`Mechanism::lets_go`]), or where its
    /// gap has jumped below zero.
    pub(super) fn renew_switches(&self, states: &[State<A>], workspace: &mut MechanismWorkspace<A>) {
        workspace.switches_renewed = true;
        if !self.contacts.iter().any(|c| c.switching) {
            return;
        }
        let first = self.limits.len();
        let motions = vec![std::cell::OnceCell::new(); states.len()];
        for (c, contact) in self.contacts.iter().enumerate() {
            if !contact.switching || workspace.held[first + c].is_some() {
                continue;
            }
            let frame = self.frame_among(c, states, &motions);
            workspace.watched[c] = frame.defined
                && if workspace.watched[c] {
                    // A gap that jumped below zero (an edge pair's normal turning over) is no touch.
                    frame.gap >= -TOUCHING
                } else {
                    frame.gap > TOUCHING || (frame.gap.abs() <= TOUCHING && !outside(&frame))
                };
        }
    }

    /// Whether contact `c`, touching at `states`, is a switching contact whose features do not meet there: it is
    /// not a contact, and stops being watched.
    pub(super) fn lets_go(&self, c: usize, states: &[State<A>], workspace: &mut MechanismWorkspace<A>) -> bool {
        if !self.contacts[c].switching {
            return false;
        }
        // A gap that crossed zero by a jump (an edge pair's normal turning over far outside its faces) is no touch.
        let frame = self.contact_frame(c, states);
        if frame.defined && !outside(&frame) && frame.gap.abs() <= TOUCHING {
            return false;
        }
        workspace.watched[c] = false;
        true
    }
}

/// `edge` (a body's frame) in principal coordinates `x = F y`, F the body's `frame`: its start and the edge from it.
fn principal(frame: &Isometry3<f64>, edge: &Edge) -> (Vector3<f64>, EdgeFeature) {
    let (start, end) = edge.ends();
    let (start, end) = (frame * Point3::from(start), frame * Point3::from(end));
    let along = end - start;
    (
        start.coords,
        EdgeFeature {
            direction: along.normalize(),
            length: along.norm(),
            faces: edge.faces().map(|n| frame.rotation * n),
        },
    )
}

/// Whether a contact's touching point is outside its face or edges beyond [`OUTSIDE_FACE`], or on their boundary
/// (within it) and leaving: a corner that meets a face at its edge while moving off it is not on the face.
pub(super) fn outside(frame: &ContactFrame) -> bool {
    frame.outside > OUTSIDE_FACE || (frame.outside > -OUTSIDE_FACE && frame.outside_rate > 0.0)
}
