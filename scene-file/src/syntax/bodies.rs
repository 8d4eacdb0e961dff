//! `[body]` or `[[body]]`: each body's mass and shape or principal moments, its state at t = 0 and its forces.

use serde::Deserialize;

use super::arrays::{exactly, maybe_exactly};

/// The `body` key: a table (`[body]`, one body) or an array of tables (`[[body]]`, named bodies). Deserialized
/// by peeking at which it is, so that toml's messages keep their line and column.
#[derive(Clone, Debug)]
pub enum Bodies {
    /// `[body]`: the single body, named "body".
    One(BodySpec),
    /// `[[body]]`: named bodies.
    Named(Vec<NamedBody>),
}

impl<'de> Deserialize<'de> for Bodies {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Bodies;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a [body] table or [[body]] entries")
            }

            fn visit_map<M: serde::de::MapAccess<'de>>(self, map: M) -> Result<Bodies, M::Error> {
                BodySpec::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(Bodies::One)
            }

            fn visit_seq<S: serde::de::SeqAccess<'de>>(self, seq: S) -> Result<Bodies, S::Error> {
                Vec::<NamedBody>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq)).map(Bodies::Named)
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// A `[[body]]` entry: a name, the body as in `[body]`, its initial state and its forces.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NamedBody {
    /// Letters, digits, `_` and `-` (it heads CSV columns and names the body in messages).
    pub name: String,
    /// kg.
    pub mass: f64,
    /// A solid of uniform density; give this or `principal_moments`.
    #[serde(default)]
    pub shape: Option<Shape>,
    /// About the centre of mass along the body axes (kg m²); give this or `shape`.
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub principal_moments: Option<[f64; 3]>,
    /// Collision shapes in the body's frame, which every `[[plane]]` keeps above it (docs/contacts.md).
    #[serde(default)]
    pub collision: Vec<CollisionShape>,
    /// Its state at t = 0; where absent, its joint places it.
    #[serde(default)]
    pub initial: Option<InitialSpec>,
    /// Its external forces.
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
}

/// The body: its mass (kg) and either a shape or its principal moments of inertia (kg m², about the centre
/// of mass along the body axes).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// kg.
    pub mass: f64,
    /// A solid of uniform density; give this or `principal_moments`.
    #[serde(default)]
    pub shape: Option<Shape>,
    /// About the centre of mass along the body axes (kg m²); give this or `shape`.
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub principal_moments: Option<[f64; 3]>,
    /// Collision shapes in the body's frame, which every `[[plane]]` keeps above it (docs/contacts.md).
    #[serde(default)]
    pub collision: Vec<CollisionShape>,
}

/// A solid of uniform density, centred on its centre of mass; lengths in metres.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// Side lengths along body x, y, z.
    Cuboid {
        /// Along body x, y, z (m).
        #[serde(deserialize_with = "exactly")]
        size: [f64; 3],
    },
    /// A thin rod along body z; its small axial moment (kg m²) keeps the inertia invertible.
    Rod {
        /// m.
        length: f64,
        /// kg m².
        axial_moment: f64,
    },
    /// Axis along body z, tip at body (0, 0, −3 height / 4).
    Cone {
        /// m.
        height: f64,
        /// Of the base (m).
        radius: f64,
    },
    /// A ball.
    Sphere {
        /// m.
        radius: f64,
    },
}

/// A collision shape in its body's frame (m): at `position`, turned by `orientation`; a capsule's and a cylinder's
/// axis along the shape's z (as URDF's cylinders). `[[plane]]`s keep each above them through contacts: a sphere's
/// own, a box's eight corners, a capsule's two end spheres, a cylinder's two cap rims, a convex hull's vertices.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CollisionShape {
    /// A ball of `radius`.
    Sphere {
        /// m.
        radius: f64,
        /// Its centre in the body's frame (m; default the origin).
        #[serde(default, deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body ← shape (default none).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// A box of edge lengths `size` along the shape's axes.
    Box {
        /// m.
        #[serde(deserialize_with = "exactly")]
        size: [f64; 3],
        /// Its centre in the body's frame (m; default the origin).
        #[serde(default, deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body ← shape (default none).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// The points within `radius` of a segment of `length` along the shape's z, centred.
    Capsule {
        /// m.
        radius: f64,
        /// Of the segment, between the end spheres' centres (m).
        length: f64,
        /// Its centre in the body's frame (m; default the origin).
        #[serde(default, deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body ← shape (default none).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// A solid cylinder of `radius` and `length` along the shape's z, centred.
    Cylinder {
        /// m.
        radius: f64,
        /// m.
        length: f64,
        /// Its centre in the body's frame (m; default the origin).
        #[serde(default, deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body ← shape (default none).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// The convex hull of `points` (m, the shape's frame), or of the vertices of the STL file `mesh` (relative to the
    /// scene file's folder).
    Convex {
        /// At least four points, not all in one plane.
        #[serde(default)]
        points: Option<Vec<Vec<f64>>>,
        /// An STL file (ASCII or binary).
        #[serde(default)]
        mesh: Option<String>,
        /// The shape's origin in the body's frame (m; default the body's origin).
        #[serde(default, deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body ← shape (default none).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
}

/// The state at t = 0. Constrained scenes are projected onto their constraints first (theory §10), so the
/// values need to satisfy them only approximately.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Centre of mass, world (m).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub position: [f64; 3],
    /// Body → world; the identity if absent.
    #[serde(default)]
    pub orientation: OrientationSpec,
    /// Angular velocity in body axes (rad/s).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub body_angular_velocity: [f64; 3],
    /// Centre-of-mass velocity, world (m/s).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub velocity: [f64; 3],
}

/// Body → world rotation: `axis` with `angle` (rad) or `degrees`, or a `quaternion` [w, x, y, z]
/// (normalised here); none of them is the identity.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationSpec {
    /// The rotation axis, of any length; with `angle` or `degrees`.
    #[serde(default, deserialize_with = "maybe_exactly")]
    pub axis: Option<[f64; 3]>,
    /// About `axis` (rad).
    pub angle: Option<f64>,
    /// About `axis` (°).
    pub degrees: Option<f64>,
    /// [w, x, y, z], of any length.
    #[serde(default, deserialize_with = "maybe_exactly")]
    pub quaternion: Option<[f64; 4]>,
}

/// An external force on the body (world frame).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceSpec {
    /// Uniform gravity at the centre of mass (m/s²; default 9.81 along −z).
    Gravity {
        /// m/s², world.
        #[serde(default = "standard_gravity")]
        #[serde(deserialize_with = "exactly")]
        acceleration: [f64; 3],
    },
    /// A constant force (N) along the fixed world line through `point` (m).
    Force {
        /// N, world.
        #[serde(deserialize_with = "exactly")]
        force: [f64; 3],
        /// A point of the force's line (m, world).
        #[serde(deserialize_with = "exactly")]
        point: [f64; 3],
    },
    /// A constant couple (N m).
    Couple {
        /// N m, world.
        #[serde(deserialize_with = "exactly")]
        moment: [f64; 3],
    },
}

pub(crate) fn standard_gravity() -> [f64; 3] {
    [0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY]
}
