//! The file's contacts added to the mechanism, each point in its body's (or link's) frame, and a start below a contact's
//! plane refused.

use dynamics::contacts::PlaneContact;
use dynamics::{Algebra, Dynamics, Mechanism, Reference, State};
use nalgebra::Vector3;

use super::system::Place;
use crate::check::layout::{end_of, Layout};
use crate::error::{invalid, SceneFileError};
use crate::syntax::file::SceneFile;

impl SceneFile {
    /// Adds the file's contacts to `system`, each point in its body's (or link's) frame.
    pub(super) fn add_contacts<A: Algebra>(
        &self,
        layout: &Layout,
        system: &mut Mechanism<A>,
        place: &Place<'_>,
    ) -> Result<(), SceneFileError> {
        for (k, spec) in self.contact.iter().enumerate() {
            let what = format!("contact {}", spec.name(k));
            let body = match (&spec.body, layout.bodies.as_slice(), &self.robot) {
                (Some(name), ..) => name.clone(),
                (None, [only], None) => only.name.clone(),
                (None, ..) => return Err(invalid(format!("{what}: body"), "name the body whose point it is")),
            };
            let end = end_of(
                &layout.bodies,
                self.robot()?.map(|(_, l)| l),
                &format!("{what}: body"),
                &body,
            )?;
            let (Reference::Body(id), frame) = place(&end)? else {
                return Err(invalid(
                    format!("{what}: body"),
                    "the world has no point to keep above a plane",
                ));
            };
            let point = frame.transform_point(&Vector3::from(spec.point).into()).coords;
            let contact = PlaneContact::new(point, Vector3::from(spec.normal), spec.offset)
                .and_then(|contact| contact.with_restitution(spec.restitution))
                .map_err(|error| invalid(what.clone(), error.to_string()))?;
            system
                .add_contact(spec.name(k), id, contact)
                .map_err(|error| invalid(what.clone(), error.to_string()))?;
        }
        Ok(())
    }

    /// Refuses a start that puts a contact point below its plane, naming the contact and the depth.
    pub(super) fn check_contact_start<A: Algebra>(
        &self,
        system: &Mechanism<A>,
        initial: &[State<A>],
    ) -> Result<(), SceneFileError> {
        if self.contact.is_empty() {
            return Ok(());
        }
        let mut values = vec![0.0; system.limit_count()];
        system.limit_values(0.0, initial, &mut system.workspace(), &mut values)?;
        let first = values.len() - self.contact.len();
        for (k, spec) in self.contact.iter().enumerate() {
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
}
