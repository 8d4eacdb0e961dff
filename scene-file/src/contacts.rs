//! Scene files' contacts (docs/scene-files.md): `[[contact]]`, a body point kept above a world plane, exactly
//! (`dynamics::contacts`).

use dynamics::contacts::PlaneContact;
use dynamics::{Algebra, Dynamics, Mechanism, Reference, State};
use nalgebra::Vector3;
use serde::Deserialize;

use super::{invalid, Layout, Place, SceneFile, SceneFileError};

/// `[[contact]]`: `point` (m) of `body` (a named body or robot link; the only body may go unnamed) kept on the side
/// of the plane `normal · x = offset` (world) that the normal points to, meeting it with `restitution`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub body: Option<String>,
    #[serde(deserialize_with = "super::exactly")]
    pub point: [f64; 3],
    #[serde(default = "up", deserialize_with = "super::exactly")]
    pub normal: [f64; 3],
    #[serde(default)]
    pub offset: f64,
    #[serde(default)]
    pub restitution: f64,
}

/// The default normal: world z, a floor.
fn up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

impl ContactSpec {
    /// The contact's name: as written, else "contact k" (1-based).
    pub fn name(&self, index: usize) -> String {
        self.name.clone().unwrap_or_else(|| format!("contact {}", index + 1))
    }
}

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
            let end = super::end_of(
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
