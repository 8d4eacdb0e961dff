//! The `[[collision]]` pairs' contacts (docs/contacts.md "Between bodies"): for each shape of one body and each of
//! the other, the features that meet. Two spheres are one ball contact. Two polytopes (boxes, hulls) are every
//! vertex of each on every face of the other and every edge of each on every edge of the other, each pair watched
//! only where its features meet, so that they may tumble over each other (docs/contacts.md "Edges"). Otherwise
//! (a sphere, capsule or cylinder on a polytope) the features are chosen at the start: the face, of
//! either shape, that separates them most at the start (the largest least distance of the other's vertices, spheres
//! or rims; of faces separating as much, the largest) becomes a plane fixed in its body, and each vertex, sphere or
//! cap rim of the other shape is a contact on it: a box resting on a wider box rests on its corners on the
//! other's top face. A start where the shapes interpenetrate, or where no face separates a curved shape from a
//! polytope, is refused, naming the pair and the depth.

use dynamics::contacts::{BallContact, PlaneContact, Polyhedron, TOUCHING};
use dynamics::{Algebra, BodyId, Mechanism, Reference, State};
use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;

use super::assembly::Assembly;
use crate::check::collisions::{Face, Feature, ShapeGeometry, Solid};
use crate::check::pairs::CheckedPair;
use crate::error::{invalid, SceneFileError};

/// One body of a pair in the mechanism: its id, the maps from its shapes' frame (the body's or the link's) to the
/// body's reference frame (where contacts take their points), to its principal frame (where a state's pose puts it)
/// and to the world at the start.
struct Placed<'p> {
    name: &'p str,
    id: BodyId,
    to_body: Isometry3<f64>,
    to_principal: Isometry3<f64>,
    to_world: Isometry3<f64>,
}

/// A pair of shapes the contacts keep apart, as parry3d shapes for [`deepest_overlap`]: its name and, per side, the
/// body, the shape's frame in the body's principal frame (where a state's pose puts it), and the shape there.
pub(crate) struct ShapePair {
    name: String,
    sides: [(BodyId, Isometry3<f64>, SharedShape); 2],
}

/// Adds every pair's contacts to the mechanism, their features chosen with the bodies at `start` (on the joints);
/// returns the pairs of shapes, for [`deepest_overlap`].
pub(crate) fn add_pair_contacts<A: Algebra>(
    assembly: &mut Assembly<A>,
    start: &[State<A>],
) -> Result<Vec<ShapePair>, SceneFileError> {
    let scene = assembly.scene;
    let joined = joined_bodies(&assembly.mechanism);
    let mut shapes = Vec::new();
    for pair in &scene.pairs {
        let what = format!("collision {}", pair.name);
        let [first, second] = [0, 1].map(|k| place(assembly, start, &pair.sides[k].body, &what));
        let (first, second) = (first?, second?);
        if first.id == second.id || joined.contains(&(first.id, second.id)) || joined.contains(&(second.id, first.id)) {
            if pair.among_all {
                continue;
            }
            if first.id == second.id {
                return Err(invalid(
                    format!("{what}: bodies"),
                    format!(
                        "`{}` and `{}` are one body (joined by fixed joints)",
                        first.name, second.name
                    ),
                ));
            }
        }
        for a in &pair.sides[0].shapes {
            for b in &pair.sides[1].shapes {
                add_shape_pair(&mut assembly.mechanism, pair, (&first, a), (&second, b))?;
                let side = |placed: &Placed<'_>, shape: &ShapeGeometry| {
                    let shape = parry_shape(shape, &format!("{what}: {}", placed.name))?;
                    Ok::<_, SceneFileError>((placed.id, placed.to_principal, shape))
                };
                shapes.push(ShapePair {
                    name: format!(
                        "{}: {} {} and {} {}",
                        pair.name, first.name, a.label, second.name, b.label
                    ),
                    sides: [side(&first, a)?, side(&second, b)?],
                });
            }
        }
    }
    Ok(shapes)
}

/// A shape as parry3d's: a ball about its centre, a capsule between its end spheres' centres, a cylinder between its
/// caps' centres, a polytope as the hull of its vertices (all in the shape's body or link frame). parry3d refuses
/// hulls it deems degenerate, which a valid polytope can be to it: a box of 1000 × 0.6 × 0.3 m is; that is an error
/// naming `what` and the shape.
fn parry_shape(shape: &ShapeGeometry, what: &str) -> Result<SharedShape, SceneFileError> {
    let at = |v: &nalgebra::Vector3<f64>| Vector::new(v.x, v.y, v.z);
    match shape.solid {
        // A ball as a capsule of no length, so that its centre need not be the frame's origin.
        Solid::Ball | Solid::Capsule => {
            let (first, last) = (&shape.features[0], &shape.features[shape.features.len() - 1]);
            Ok(SharedShape::capsule(at(&first.centre), at(&last.centre), first.radius))
        }
        Solid::Cylinder => {
            // parry3d's cylinder stands on its own y axis, centred: turned onto the caps' axis, between their centres.
            let (first, last) = (&shape.features[0], &shape.features[1]);
            let (axis, radius) = first.rim.expect("a cylinder's features are its rims");
            let turn = UnitQuaternion::rotation_between(&Vector3::y(), &axis)
                .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
            let middle = Isometry3::from_parts(((first.centre + last.centre) / 2.0).into(), turn);
            let half = (last.centre - first.centre).norm() / 2.0;
            Ok(SharedShape::compound(vec![(
                parry_pose(&middle),
                SharedShape::cylinder(half, radius),
            )]))
        }
        Solid::Polytope => {
            let vertices: Vec<Vector> = shape.features.iter().map(|f| at(&f.centre)).collect();
            SharedShape::convex_hull(&vertices).ok_or_else(|| {
                let extent = |axis: usize| {
                    let values = shape.features.iter().map(|f| f.centre[axis]);
                    values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
                };
                let sides = [0, 1, 2].map(extent);
                invalid(
                    what,
                    format!(
                        "parry3d, which measures how deep shapes meet, cannot build the hull of {} (its extents {:.3e}, \
                         {:.3e} and {:.3e} m are too unequal for it); a floor or a wall is a [[plane]]",
                        shape.label, sides[0], sides[1], sides[2]
                    ),
                )
            })
        }
    }
}

/// An isometry as parry3d's pose.
fn parry_pose(isometry: &Isometry3<f64>) -> Pose {
    let (t, q) = (isometry.translation.vector, isometry.rotation);
    Pose::from_parts(Vector::new(t.x, t.y, t.z), Rotation::from_xyzw(q.i, q.j, q.k, q.w))
}

/// The pair of shapes that go deepest into each other with the bodies at `states` (their names and the depth, m), if
/// any overlaps at all: parry3d's contact query, independent of the contacts, so that shapes that meet where no
/// contact watches them (a sphere past the face it is held on) are seen.
pub(crate) fn deepest_overlap<A: Algebra>(pairs: &[ShapePair], states: &[State<A>]) -> Option<(String, f64)> {
    let pose = |(body, frame, _): &(BodyId, Isometry3<f64>, SharedShape)| {
        let (position, rotation) = states[body.index()].pose();
        parry_pose(&(Isometry3::from_parts(position.into(), rotation) * frame))
    };
    (pairs.iter())
        .filter_map(|pair| {
            let [a, b] = &pair.sides;
            let contact = query::contact(&pose(a), a.2.as_ref(), &pose(b), b.2.as_ref(), 0.0).ok()??;
            (contact.dist < 0.0).then(|| (pair.name.clone(), -contact.dist))
        })
        .max_by(|x, y| x.1.total_cmp(&y.1))
}

/// Every pair of bodies a joint model joins (child, parent), which `"all"` skips: a link's shapes touch its
/// neighbours' at the joint by design.
fn joined_bodies<A: Algebra>(mechanism: &Mechanism<A>) -> Vec<(BodyId, BodyId)> {
    mechanism.joint_space().map_or_else(
        |_| Vec::new(),
        |space| {
            (space.groups().iter())
                .filter_map(|group| Some((group.body(), group.parent()?)))
                .collect()
        },
    )
}

/// Where the body or link `name` is: its id, its frame in the body's reference frame, and its pose at `start`.
fn place<'p, A: Algebra>(
    assembly: &Assembly<A>,
    start: &[State<A>],
    name: &'p str,
    what: &str,
) -> Result<Placed<'p>, SceneFileError> {
    let scene = assembly.scene;
    let robot = scene.robot.as_ref().map(|robot| &robot.loaded);
    let end = scene.layout.end(robot, &format!("{what}: bodies"), name)?;
    let (Reference::Body(id), to_body) = assembly.places.place(&end)? else {
        return Err(invalid(
            format!("{what}: bodies"),
            "the world has no shapes: use a [[plane]]",
        ));
    };
    // The place is in principal coordinates; contacts take points in the body's reference frame.
    let reference = assembly.mechanism.reference_frame(id)?;
    let state = &start[id.index()];
    let (position, rotation) = state.pose();
    let pose = Isometry3::from_parts(position.into(), rotation);
    Ok(Placed {
        name,
        id,
        to_body: reference.inverse() * to_body,
        to_principal: to_body,
        to_world: pose * to_body,
    })
}

/// The contacts between shape `a` of one body and shape `b` of the other (module docs), named "`pair`: `body` `shape`
/// `feature` on `body` `shape` `face k`".
fn add_shape_pair<A: Algebra>(
    mechanism: &mut Mechanism<A>,
    pair: &CheckedPair,
    (first, a): (&Placed<'_>, &ShapeGeometry),
    (second, b): (&Placed<'_>, &ShapeGeometry),
) -> Result<(), SceneFileError> {
    let what = format!(
        "collision {}: `{}` {} and `{}` {}",
        pair.name, first.name, a.label, second.name, b.label
    );
    let failed = |error: &dyn std::fmt::Display| invalid(what.clone(), error.to_string());
    let refuse_depth = |depth: f64| {
        invalid(
            what.clone(),
            format!("the start puts the two shapes {depth:.3e} m into each other (no face of either separates them)"),
        )
    };
    if a.solid == Solid::Ball && b.solid == Solid::Ball {
        let (centre, other) = (&a.features[0], &b.features[0]);
        let gap = (first.to_world * Point3::from(centre.centre) - second.to_world * Point3::from(other.centre)).norm()
            - centre.radius
            - other.radius;
        if gap < -TOUCHING {
            return Err(refuse_depth(-gap));
        }
        let contact = BallContact::new(
            first.to_body * centre.centre,
            centre.radius,
            second.to_body * other.centre,
            other.radius,
        )
        .and_then(|c| c.with_restitution(pair.restitution))
        .map_err(|e| failed(&e))?
        .with_friction(pair.friction);
        let name = format!(
            "{}: {} {} on {} {}",
            pair.name, first.name, a.label, second.name, b.label
        );
        return mechanism
            .add_ball_contact(name, first.id, second.id, contact)
            .map_err(|e| failed(&e));
    }
    let polytope_or_ball = |shape: &ShapeGeometry| matches!(shape.solid, Solid::Polytope | Solid::Ball);
    if polytope_or_ball(a) && polytope_or_ball(b) {
        return add_polyhedra(mechanism, pair, [(first, a), (second, b)], &what);
    }
    // The face that separates most: of b against a's features, or of a against b's; of faces that separate as much
    // (within round-off: a box resting on a wider one, whose top face and the box's bottom face are one plane) the
    // largest, so that the smaller shape's vertices rest on it.
    let mut candidates = Vec::new();
    for (faces_of_b, (faced, shape), (other, features)) in
        [(true, (second, b), (first, a)), (false, (first, a), (second, b))]
    {
        for (k, face) in shape.faces.iter().enumerate() {
            let separation = least_distance(faced, face, other, &features.features);
            candidates.push((separation, face.area, faces_of_b, k));
        }
    }
    let most = candidates.iter().fold(f64::NEG_INFINITY, |m, c| m.max(c.0));
    let Some(&(separation, _, faces_of_b, k)) = (candidates.iter())
        .filter(|c| c.0 >= most - TOUCHING)
        .max_by(|x, y| x.1.total_cmp(&y.1))
    else {
        unreachable!("a pair of shapes not both balls has a polytope, with faces")
    };
    if separation < -TOUCHING {
        // No face separates them: they overlap, or they are apart only across the polytope's edge or vertex, which
        // the contacts (a sphere, capsule end or rim on a face) cannot hold apart; parry3d's distance tells which.
        let (shape_a, shape_b) = (parry_shape(a, &what)?, parry_shape(b, &what)?);
        let (pose_a, pose_b) = (parry_pose(&first.to_world), parry_pose(&second.to_world));
        let distance =
            query::distance(&pose_a, shape_a.as_ref(), &pose_b, shape_b.as_ref()).map_or(0.0, |d| d.distance);
        if distance > TOUCHING {
            return Err(invalid(
                what,
                format!(
                    "the start has the two shapes {distance:.3e} m apart with no face between them (an edge or a \
                     vertex faces the curved shape): a sphere, capsule or cylinder is held on a polytope's faces only \
                     (docs/contacts.md \"Between bodies\"); turn or move them so that a face lies between them"
                ),
            ));
        }
        return Err(refuse_depth(-separation));
    }
    let ((faced, shape), (other, features)) = if faces_of_b {
        ((second, b), (first, a))
    } else {
        ((first, a), (second, b))
    };
    let face = shape.faces[k];
    // A plane of the shape in its body's reference frame.
    let placed = |face: &Face| face.placed(&faced.to_body);
    let (normal, offset) = placed(&face);
    // The contacts hold on this face only: inside the shape's other faces.
    let solid: Vec<_> = shape.faces.iter().map(placed).collect();
    for feature in &features.features {
        let point = other.to_body * Point3::from(feature.centre);
        let contact = match feature.rim {
            Some((axis, radius)) => {
                PlaneContact::disk(point.coords, other.to_body.rotation * axis, radius, normal, offset)
            }
            None if feature.radius > 0.0 => PlaneContact::sphere(point.coords, feature.radius, normal, offset),
            None => PlaneContact::new(point.coords, normal, offset),
        }
        .and_then(|c| c.with_restitution(pair.restitution))
        .map_err(|e| failed(&e))?
        .with_friction(pair.friction);
        let name = format!(
            "{}: {} {}{} on {} {} face {}",
            pair.name,
            other.name,
            features.label,
            feature.name,
            faced.name,
            shape.label,
            k + 1
        );
        mechanism
            .add_contact_on(name.as_str(), other.id, faced.id, contact)
            .and_then(|()| mechanism.set_contact_face(&name, &solid))
            .map_err(|e| failed(&e))?;
    }
    Ok(())
}

/// A polytope and a polytope, or a ball and a polytope, kept apart by all their feature pairs
/// (`Mechanism::add_polyhedron_contacts`, `Mechanism::add_sphere_polyhedron_contacts`, docs/contacts.md "Edges",
/// "Spheres on polyhedra"): refused if the start puts them into each other (parry3d's contact query); errors name
/// `what`.
fn add_polyhedra<A: Algebra>(
    mechanism: &mut Mechanism<A>,
    pair: &CheckedPair,
    [(first, a), (second, b)]: [(&Placed<'_>, &ShapeGeometry); 2],
    what: &str,
) -> Result<(), SceneFileError> {
    let (shape_a, shape_b) = (parry_shape(a, what)?, parry_shape(b, what)?);
    let (pose_a, pose_b) = (parry_pose(&first.to_world), parry_pose(&second.to_world));
    if let Ok(Some(contact)) = query::contact(&pose_a, shape_a.as_ref(), &pose_b, shape_b.as_ref(), 0.0) {
        if contact.dist < -TOUCHING {
            return Err(invalid(
                what,
                format!("the start puts the two shapes {:.3e} m into each other", -contact.dist),
            ));
        }
    }
    // A shape in its body's reference frame, where contacts take their points and planes.
    let polyhedron = |placed: &Placed<'_>, shape: &ShapeGeometry| {
        let vertices = (shape.features.iter())
            .map(|f| (placed.to_body * Point3::from(f.centre)).coords)
            .collect();
        let faces = shape.faces.iter().map(|face| face.placed(&placed.to_body)).collect();
        Polyhedron::new(vertices, faces).map_err(|e| invalid(what, e.to_string()))
    };
    let label = |placed: &Placed<'_>, shape: &ShapeGeometry| format!("{} {}", placed.name, shape.label);
    let added = match (a.solid, b.solid) {
        (Solid::Ball, _) | (_, Solid::Ball) => {
            let ((ball, sphere), (faced, solid)) = if a.solid == Solid::Ball {
                ((first, a), (second, b))
            } else {
                ((second, b), (first, a))
            };
            let feature = &sphere.features[0];
            mechanism.add_sphere_polyhedron_contacts(
                &pair.name,
                (
                    ball.id,
                    (ball.to_body * Point3::from(feature.centre)).coords,
                    feature.radius,
                    &label(ball, sphere),
                ),
                (faced.id, &polyhedron(faced, solid)?, &label(faced, solid)),
                pair.friction,
                pair.restitution,
            )
        }
        _ => mechanism.add_polyhedron_contacts(
            &pair.name,
            (first.id, &polyhedron(first, a)?, &label(first, a)),
            (second.id, &polyhedron(second, b)?, &label(second, b)),
            pair.friction,
            pair.restitution,
        ),
    };
    added.map_err(|e| invalid(what, e.to_string()))?;
    Ok(())
}

/// The least height, at the start, of `features` of the body `other` above `face` of the body `faced` (each
/// feature's lowest point: less its radius, and for a rim its reach towards the face).
fn least_distance(faced: &Placed<'_>, face: &Face, other: &Placed<'_>, features: &[Feature]) -> f64 {
    let (normal, offset) = face.placed(&faced.to_world);
    (features.iter())
        .map(|f| f.height(&other.to_world, &normal, offset))
        .fold(f64::INFINITY, f64::min)
}
