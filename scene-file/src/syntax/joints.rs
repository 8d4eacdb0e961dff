//! `[[constraints]]` and `[[joint]]`: what each holds (its geometry), in which formulation, and a joint's `drive` and
//! `limit`.

use serde::Deserialize;

use super::arrays::{exactly, maybe_exactly};
use super::bodies::OrientationSpec;
use super::elements::DriveSpec;
use super::surfaces::SurfaceSpec;
use crate::names::FormulationName;

/// A `[[joint]]`: `between = [body, reference]`, the reference another body or `"world"`. The geometry is that
/// of a constraint, with the held body's points and axes in its body coordinates and the rest (`world_point`,
/// `world_axis`, also written `reference_point`, `reference_axis`; normals, offsets, centres) in the
/// reference's: its body coordinates, or the world's.
#[derive(Clone, Debug, Deserialize)]
pub struct JointSpec {
    /// Non-empty and unique among the file's and the robot's joints.
    pub name: String,
    /// The held body (a `[[body]]` entry), then its reference: another body, `"world"` or a robot link.
    #[serde(deserialize_with = "exactly")]
    pub between: [String; 2],
    /// By virtual power (the default) or by pinning.
    #[serde(default)]
    pub formulation: FormulationName,
    /// The prescribed coordinate of a hinge or prismatic joint.
    #[serde(default)]
    pub drive: Option<DriveSpec>,
    /// The range of a hinge's or prismatic joint's coordinate, enforced exactly.
    #[serde(default)]
    pub limit: Option<LimitSpec>,
    /// What it holds.
    #[serde(flatten)]
    pub geometry: Geometry,
}

/// One constraint: its geometry and formulation.
#[derive(Clone, Debug, Deserialize)]
pub struct ConstraintSpec {
    /// By virtual power (the default) or by pinning.
    #[serde(default)]
    pub formulation: FormulationName,
    /// What it holds.
    #[serde(flatten)]
    pub geometry: Geometry,
}

/// What a constraint holds. Body points and axes are in body coordinates, the rest in world coordinates;
/// lengths in metres. Axes and normals need not be unit.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Geometry {
    /// The body point stays at the world point (rank 3).
    BallJoint {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The reference's coordinates (m).
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
    },
    /// The body turns only about the world axis through the world point, where the body point stays
    /// (rank 5).
    Hinge(AxisJoint),
    /// The body point slides along and turns about the world axis (rank 4).
    Cylindrical(AxisJoint),
    /// The body slides along the world axis without turning: a cylindrical joint that also keeps the body
    /// normal (normal to the body axis) along the world normal (normal to the world axis) (rank 5).
    Prismatic {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// Body coordinates, any length.
        #[serde(deserialize_with = "exactly")]
        body_axis: [f64; 3],
        /// Body coordinates, any length.
        #[serde(deserialize_with = "exactly")]
        body_normal: [f64; 3],
        /// The reference's coordinates (m).
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        /// The reference's coordinates, any length.
        #[serde(alias = "reference_axis")]
        #[serde(deserialize_with = "exactly")]
        world_axis: [f64; 3],
        /// The reference's coordinates, any length.
        #[serde(alias = "reference_normal")]
        #[serde(deserialize_with = "exactly")]
        world_normal: [f64; 3],
    },
    /// The body plane through the body point normal to the body normal stays on the world plane through the
    /// world point normal to the world normal (rank 3).
    Planar {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// Body coordinates, any length.
        #[serde(deserialize_with = "exactly")]
        body_normal: [f64; 3],
        /// The reference's coordinates (m).
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        /// The reference's coordinates, any length.
        #[serde(alias = "reference_normal")]
        #[serde(deserialize_with = "exactly")]
        world_normal: [f64; 3],
    },
    /// A Cardan joint: the body point stays at the world point, the body axis normal to the world axis; the body
    /// turns about the world axis and about its own (rank 4).
    Universal(AxisJoint),
    /// A weld: the body keeps its pose in the reference's frame, `position` (its centre of mass, m) and
    /// `orientation` (body → reference, as `[initial] orientation`), each the pose at the start if not given
    /// (rank 6).
    Fixed {
        /// The body's centre of mass in the reference's frame (m).
        #[serde(default)]
        #[serde(deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        /// Body → reference.
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// The body point stays on the world plane `normal · x = offset` (rank 1).
    PointOnPlane {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The reference's coordinates, any length.
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
        /// `normal · x` on the plane (m times the normal's length).
        offset: f64,
    },
    /// The body point stays on the world line through the world point along the world axis (rank 2).
    PointOnLine {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The reference's coordinates (m).
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        /// The reference's coordinates, any length.
        #[serde(alias = "reference_axis")]
        #[serde(deserialize_with = "exactly")]
        world_axis: [f64; 3],
    },
    /// The body point stays on the sphere (rank 1).
    PointOnSphere {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The reference's coordinates (m).
        #[serde(deserialize_with = "exactly")]
        centre: [f64; 3],
        /// m.
        radius: f64,
    },
    /// The body point stays on a surface (rank 1).
    PointOnSurface {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The surface, in the reference's frame.
        surface: SurfaceSpec,
    },
    /// The body point stays on the curve where two surfaces meet (rank 2).
    PointOnCurve {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The two surfaces, in the reference's frame.
        surfaces: Vec<SurfaceSpec>,
    },
    /// The body point stays on the circle of the sphere in the plane through its centre normal to
    /// `normal` (rank 2).
    PointOnCircle {
        /// Body coordinates (m).
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        /// The sphere's and the circle's centre, the reference's coordinates (m).
        #[serde(deserialize_with = "exactly")]
        centre: [f64; 3],
        /// m.
        radius: f64,
        /// The circle's plane's normal, any length.
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
    },
}

/// A body axis through a body point, held on a world axis through a world point.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisJoint {
    /// Body coordinates (m).
    #[serde(deserialize_with = "exactly")]
    pub body_point: [f64; 3],
    /// Body coordinates, any length.
    #[serde(deserialize_with = "exactly")]
    pub body_axis: [f64; 3],
    /// The reference's coordinates (m).
    #[serde(alias = "reference_point")]
    #[serde(deserialize_with = "exactly")]
    pub world_point: [f64; 3],
    /// The reference's coordinates, any length.
    #[serde(alias = "reference_axis")]
    #[serde(deserialize_with = "exactly")]
    pub world_axis: [f64; 3],
}

impl Geometry {
    /// What it is, in messages and the summary: "hinge", "point on sphere", ….
    pub fn kind(&self) -> &'static str {
        match self {
            Geometry::BallJoint { .. } => "ball joint",
            Geometry::Hinge(_) => "hinge",
            Geometry::Cylindrical(_) => "cylindrical joint",
            Geometry::Prismatic { .. } => "prismatic joint",
            Geometry::Planar { .. } => "planar joint",
            Geometry::Universal(_) => "universal joint",
            Geometry::Fixed { .. } => "fixed joint",
            Geometry::PointOnLine { .. } => "point on line",
            Geometry::PointOnPlane { .. } => "point on plane",
            Geometry::PointOnSphere { .. } => "point on sphere",
            Geometry::PointOnCircle { .. } => "point on circle",
            Geometry::PointOnSurface { .. } => "point on surface",
            Geometry::PointOnCurve { .. } => "point on curve",
        }
    }
}

/// A joint's `limit = { lower = …, upper = …, restitution = … }` (rad or m; docs/limits.md): either bound may be left
/// out (no bound on that side), not both; the restitution defaults to 0 (the joint stops at its bound). Read as a
/// table only (serde's derived struct would also take an array, its entries by position).
#[derive(Clone, Copy, Debug)]
pub struct LimitSpec {
    pub(crate) lower: Option<f64>,
    pub(crate) upper: Option<f64>,
    pub(crate) restitution: Option<f64>,
}

const LIMIT_KEYS: &[&str] = &["lower", "upper", "restitution"];

impl<'de> Deserialize<'de> for LimitSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let table = std::collections::BTreeMap::<String, f64>::deserialize(deserializer)?;
        if let Some(key) = table.keys().find(|key| !LIMIT_KEYS.contains(&key.as_str())) {
            return Err(serde::de::Error::unknown_field(key, LIMIT_KEYS));
        }
        Ok(LimitSpec {
            lower: table.get("lower").copied(),
            upper: table.get("upper").copied(),
            restitution: table.get("restitution").copied(),
        })
    }
}
