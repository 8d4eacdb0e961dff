//! Scene files' contacts (docs/scene-files.md): `[[contact]]`, a body point kept above a world plane, exactly
//! (`dynamics::contacts`).

use serde::Deserialize;

use super::arrays::exactly;

/// `[[contact]]`: `point` (m) of `body` (a named body or robot link; the only body may go unnamed) kept on the side
/// of the plane `normal · x = offset` (world) that the normal points to, meeting it with `restitution`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub body: Option<String>,
    #[serde(deserialize_with = "exactly")]
    pub point: [f64; 3],
    #[serde(default = "up", deserialize_with = "exactly")]
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
