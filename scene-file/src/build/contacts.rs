//! The file's contacts added to the mechanism, each point or sphere in its body's (or link's) frame, and a start below
//! a contact's plane refused.

use dynamics::contacts::{Friction, PlaneContact};
use dynamics::{Algebra, Mechanism, Reference, State};
use nalgebra::Vector3;

use super::assembly::Assembly;
use crate::check::scene::CheckedScene;
use crate::error::{invalid, SceneFileError};

/// Adds the file's contacts to the mechanism, each point in its body's (or link's) frame.
pub(crate) fn add_contacts<A: Algebra>(assembly: &mut Assembly<A>) -> Result<(), SceneFileError> {
    let scene = assembly.scene;
    let layout = &scene.layout;
    for (k, spec) in scene.contacts.iter().enumerate() {
        let what = format!("contact {}", spec.name(k));
        let body = match (&spec.body, layout.bodies.as_slice(), &scene.robot) {
            (Some(name), ..) => name.clone(),
            (None, [only], None) => only.name.clone(),
            (None, ..) => return Err(invalid(format!("{what}: body"), "name the body whose point it is")),
        };
        let robot = scene.robot.as_ref().map(|robot| &robot.loaded);
        let end = layout.end(robot, &format!("{what}: body"), &body)?;
        let (Reference::Body(id), frame) = assembly.places.place(&end)? else {
            return Err(invalid(
                format!("{what}: body"),
                "the world has no point to keep above a plane",
            ));
        };
        // The end's frame in the body's reference frame, the frame `Mechanism::add_contact` takes points in (a robot
        // link's pose in its body's first link's frame; the place is in principal coordinates).
        let frame = assembly.mechanism.reference_frame(id)?.inverse() * frame;
        let in_frame = |point: [f64; 3]| frame.transform_point(&Vector3::from(point).into()).coords;
        let normal = Vector3::from(spec.normal);
        let contact = match (spec.point, &spec.sphere, &spec.disk) {
            (Some(point), None, None) => PlaneContact::new(in_frame(point), normal, spec.offset),
            (None, Some(sphere), None) => {
                PlaneContact::sphere(in_frame(sphere.centre), sphere.radius, normal, spec.offset)
            }
            (None, None, Some(disk)) => {
                // Turned only if finite (and scaled first, so that huge numbers stay finite), else passed on for
                // the contact to refuse as given.
                let axis = Vector3::from(disk.axis);
                let axis = if axis.iter().all(|x| x.is_finite()) && axis.amax() > 0.0 {
                    frame.rotation * (axis / axis.amax())
                } else {
                    axis
                };
                PlaneContact::disk(in_frame(disk.centre), axis, disk.radius, normal, spec.offset)
            }
            (None, None, None) => {
                return Err(invalid(
                    what,
                    "give the `point = [x, y, z]`, the `sphere = { centre = [x, y, z], radius = r }` or the \
                     `disk = { centre = [x, y, z], axis = [x, y, z], radius = r }` kept above the plane",
                ))
            }
            _ => return Err(invalid(what, "give one of `point`, `sphere` and `disk`")),
        };
        let friction = Friction::new(spec.friction, spec.static_friction.unwrap_or(spec.friction));
        let contact = contact
            .and_then(|contact| contact.with_restitution(spec.restitution))
            .and_then(|contact| Ok(contact.with_friction(friction?)))
            .map_err(|error| invalid(what.clone(), error.to_string()))?;
        (assembly.mechanism)
            .add_contact(spec.name(k), id, contact)
            .map_err(|error| invalid(what.clone(), error.to_string()))?;
    }
    Ok(())
}

/// Refuses a start that puts a contact point below its plane, naming the contact and the depth.
pub(crate) fn check_contact_start<A: Algebra>(
    scene: &CheckedScene,
    mechanism: &Mechanism<A>,
    initial: &[State<A>],
) -> Result<(), SceneFileError> {
    if scene.contacts.is_empty() {
        return Ok(());
    }
    let heights = mechanism.contact_heights(initial)?;
    for (k, (spec, height)) in scene.contacts.iter().zip(heights).enumerate() {
        if height < -dynamics::simulate::AT_BOUND {
            let what = match (&spec.sphere, &spec.disk) {
                (Some(_), _) => "sphere",
                (_, Some(_)) => "disk",
                _ => "point",
            };
            return Err(invalid(
                format!("contact {}", spec.name(k)),
                format!("the start puts its {what} {:e} m below its plane", -height),
            ));
        }
    }
    Ok(())
}
