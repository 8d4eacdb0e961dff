//! The file's contacts added to the mechanism, each point in its body's (or link's) frame, and a start below a contact's
//! plane refused.

use dynamics::contacts::PlaneContact;
use dynamics::{Algebra, Dynamics, Mechanism, Reference, State};
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
        let point = frame.transform_point(&Vector3::from(spec.point).into()).coords;
        let contact = PlaneContact::new(point, Vector3::from(spec.normal), spec.offset)
            .and_then(|contact| contact.with_restitution(spec.restitution))
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
    let mut values = vec![0.0; mechanism.limit_count()];
    mechanism.limit_values(0.0, initial, &mut mechanism.workspace(), &mut values)?;
    let first = values.len() - scene.contacts.len();
    for (k, spec) in scene.contacts.iter().enumerate() {
        let height = values[first + k];
        if height < -dynamics::simulate::AT_BOUND {
            return Err(invalid(
                format!("contact {}", spec.name(k)),
                format!("the start puts its point {height:e} m below its plane"),
            ));
        }
    }
    Ok(())
}
