//! Scene files' contacts (docs/scene-files.md): `[[contact]]`, a body point or sphere kept above a world plane,
//! exactly, with Coulomb friction (`dynamics::contacts`); `[[plane]]`, a world plane every collision shape stays
//! above; `[[collision]]`, two bodies whose shapes stay apart.

use serde::Deserialize;

use super::arrays::{exactly, maybe_exactly};

/// `[[contact]]`: `point` (m) of `body` (a named body or robot link; the only body may go unnamed), or the sphere
/// `sphere = { centre, radius }`, or the rim of the disk `disk = { centre, axis, radius }` in its frame, kept on the side of the plane `normal · x = offset` (world) that the
/// normal points to, meeting it with `restitution`, rubbing it with Coulomb `friction` (and `static_friction`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// The contact's name in messages and the summary (default "contact k").
    #[serde(default)]
    pub name: Option<String>,
    /// A named body or robot link; the only body of a scene may go unnamed.
    #[serde(default)]
    pub body: Option<String>,
    /// In the body's (or link's) coordinates (m); or `sphere`, or `disk`.
    #[serde(default, deserialize_with = "maybe_exactly")]
    pub point: Option<[f64; 3]>,
    /// A sphere fixed in the body (centre in its coordinates, m) that rolls and slides on the plane; or `point`.
    #[serde(default)]
    pub sphere: Option<SphereSpec>,
    /// A disk fixed in the body whose rim rolls and slides on the plane (a wheel, a cylinder's cap); or `point`.
    #[serde(default)]
    pub disk: Option<DiskSpec>,
    /// The plane's normal, world, any length (default +z, a floor).
    #[serde(default = "up", deserialize_with = "exactly")]
    pub normal: [f64; 3],
    /// `normal · x` on the plane (m times the normal's length).
    #[serde(default)]
    pub offset: f64,
    /// Newton's coefficient, in [0, 1] (default 0: the point stays on the plane).
    #[serde(default)]
    pub restitution: f64,
    /// Coulomb's kinetic coefficient μ ≥ 0 (default 0: no friction).
    #[serde(default)]
    pub friction: f64,
    /// Coulomb's static coefficient μ_s ≥ μ, which a sticking contact's force stays within (default μ).
    #[serde(default)]
    pub static_friction: Option<f64>,
}

/// `sphere = { centre = [x, y, z], radius = r }` of a contact (m, body coordinates).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// The centre in the body's coordinates.
    #[serde(deserialize_with = "exactly")]
    pub centre: [f64; 3],
    /// The radius, positive.
    pub radius: f64,
}

/// `disk = { centre = [x, y, z], axis = [x, y, z], radius = r }` of a contact (m, body coordinates): the circle of
/// radius r about the centre, normal to the axis.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiskSpec {
    /// The centre in the body's coordinates.
    #[serde(deserialize_with = "exactly")]
    pub centre: [f64; 3],
    /// Normal to the disk, any length.
    #[serde(deserialize_with = "exactly")]
    pub axis: [f64; 3],
    /// The radius, positive.
    pub radius: f64,
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

/// `[[plane]]`: a world half-space `normal · x ≥ offset` that every collision shape stays above (as `[[contact]]`s of
/// its sphere, corners or vertices), with Coulomb `friction` and Newton's `restitution`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// The plane's name, which heads its contacts' names (default "plane k").
    #[serde(default)]
    pub name: Option<String>,
    /// World, any length (default +z, a floor).
    #[serde(default = "up", deserialize_with = "exactly")]
    pub normal: [f64; 3],
    /// `normal · x` on the plane (m times the normal's length).
    #[serde(default)]
    pub offset: f64,
    /// Coulomb's kinetic coefficient μ ≥ 0 (default 0).
    #[serde(default)]
    pub friction: f64,
    /// Coulomb's static coefficient μ_s ≥ μ (default μ).
    #[serde(default)]
    pub static_friction: Option<f64>,
    /// Newton's coefficient, in [0, 1] (default 0).
    #[serde(default)]
    pub restitution: f64,
}

impl PlaneSpec {
    /// The plane's name: as written, else "plane k" (1-based).
    pub fn name(&self, index: usize) -> String {
        self.name.clone().unwrap_or_else(|| format!("plane {}", index + 1))
    }
}

/// `[[collision]]`: the collision shapes of two bodies (or robot links) never interpenetrate, meeting with
/// `restitution` and rubbing with Coulomb `friction` (and `static_friction`); `bodies = "all"` for every pair of bodies
/// with shapes, but for links joined by a joint.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionSpec {
    /// The pair's name, which heads its contacts' names (default "`a` / `b`").
    #[serde(default)]
    pub name: Option<String>,
    /// Two body or link names, or `"all"`.
    pub bodies: PairBodies,
    /// With `"all"`: pairs left out, each two names.
    #[serde(default)]
    pub except: Vec<Vec<String>>,
    /// Coulomb's kinetic coefficient μ ≥ 0 (default 0).
    #[serde(default)]
    pub friction: f64,
    /// Coulomb's static coefficient μ_s ≥ μ (default μ).
    #[serde(default)]
    pub static_friction: Option<f64>,
    /// Newton's coefficient, in [0, 1] (default 0).
    #[serde(default)]
    pub restitution: f64,
}

/// The bodies of a `[[collision]]`: two names, or `"all"`.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum PairBodies {
    /// Two bodies or links by name.
    Named(Vec<String>),
    /// `"all"`: every pair of bodies with collision shapes.
    Every(String),
}
