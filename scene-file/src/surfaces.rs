//! The `surface = { kind = "…", … }` tables of the `point_on_surface` and `point_on_curve` constraints and joints
//! (docs/scene-files.md, "Surfaces"), built into [`dynamics::surfaces::Surface`] in the reference's frame.

use dynamics::surfaces::{Sheets, Surface};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};
use serde::Deserialize;

use super::{direction, exactly, finite, invalid, maybe_exactly, OrientationSpec, SceneFileError};

/// A surface: its kind and its parameters (lengths in metres).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// `x²/a² + y²/b² + z²/c² = 1`, `radii = [a, b, c]` along the local axes.
    Ellipsoid {
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 3],
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² = 1` about the local z.
    EllipticCylinder {
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² = z²`, apex at the centre.
    Cone {
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `z = x²/a² + y²/b²`, or `z = x²/a² − y²/b²` with `hyperbolic = true`.
    Paraboloid {
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        #[serde(default)]
        hyperbolic: bool,
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² − z²/c² = 1` (`sheets = 1`, the default) or `= −1` (`sheets = 2`).
    Hyperboloid {
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 3],
        #[serde(default = "one_sheet")]
        sheets: u8,
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `normal · x = offset`.
    Plane {
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
        offset: f64,
    },
    /// `a x² + b y² + c z² + d xy + e xz + f yz + g x + h y + i z + j = 0`.
    Quadric {
        #[serde(deserialize_with = "exactly")]
        coefficients: [f64; 10],
    },
    /// The ring torus about `axis` through `centre`.
    Torus {
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        #[serde(deserialize_with = "exactly")]
        axis: [f64; 3],
        major_radius: f64,
        minor_radius: f64,
    },
}

fn one_sheet() -> u8 {
    1
}

/// Where a posed quadric sits: its centre (default the origin) and its orientation (its local axes in the
/// reference's frame), given as `orientation` or as `axis` (its local z, turned there by the smallest rotation), not
/// both (default: the reference's axes). Messages name `what.centre`, `what.orientation` or `what.axis`.
fn pose(
    what: &str,
    centre: Option<[f64; 3]>,
    orientation: &Option<OrientationSpec>,
    axis: Option<[f64; 3]>,
) -> Result<Isometry3<f64>, SceneFileError> {
    let centre = match centre {
        Some(centre) => finite(&format!("{what}.centre"), centre)?,
        None => Vector3::zeros(),
    };
    let rotation = match (orientation, axis) {
        (Some(_), Some(_)) => return Err(invalid(what, "give `orientation` or `axis` (the local z), not both")),
        (Some(orientation), None) => orientation.rotation_of(&format!("{what}.orientation"))?,
        (None, Some(axis)) => {
            let axis = direction(&format!("{what}.axis"), axis)?;
            UnitQuaternion::rotation_between(&Vector3::z(), &axis)
                .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI))
        }
        (None, None) => UnitQuaternion::identity(),
    };
    Ok(Isometry3::from_parts(Translation3::from(centre), rotation))
}

impl SurfaceSpec {
    /// The surface, with messages naming `what` (e.g. `constraint bead: surface`) and the key at fault.
    pub fn surface(&self, what: &str) -> Result<Surface, SceneFileError> {
        let built = match self {
            SurfaceSpec::Ellipsoid {
                radii,
                centre,
                orientation,
                axis,
            } => Surface::ellipsoid(Vector3::from(*radii), &pose(what, *centre, orientation, *axis)?),
            SurfaceSpec::EllipticCylinder {
                radii,
                centre,
                orientation,
                axis,
            } => Surface::elliptic_cylinder(Vector2::from(*radii), &pose(what, *centre, orientation, *axis)?),
            SurfaceSpec::Cone {
                radii,
                centre,
                orientation,
                axis,
            } => Surface::cone(Vector2::from(*radii), &pose(what, *centre, orientation, *axis)?),
            SurfaceSpec::Paraboloid {
                radii,
                hyperbolic,
                centre,
                orientation,
                axis,
            } => {
                let pose = pose(what, *centre, orientation, *axis)?;
                if *hyperbolic {
                    Surface::hyperbolic_paraboloid(Vector2::from(*radii), &pose)
                } else {
                    Surface::elliptic_paraboloid(Vector2::from(*radii), &pose)
                }
            }
            SurfaceSpec::Hyperboloid {
                radii,
                sheets,
                centre,
                orientation,
                axis,
            } => {
                let sheets = match sheets {
                    1 => Sheets::One,
                    2 => Sheets::Two,
                    other => return Err(invalid(format!("{what}.sheets"), format!("{other} is not 1 or 2"))),
                };
                Surface::hyperboloid(Vector3::from(*radii), sheets, &pose(what, *centre, orientation, *axis)?)
            }
            SurfaceSpec::Plane { normal, offset } => Surface::plane(Vector3::from(*normal), *offset),
            SurfaceSpec::Quadric { coefficients } => Surface::quadric(*coefficients),
            SurfaceSpec::Torus {
                centre,
                axis,
                major_radius,
                minor_radius,
            } => Surface::torus(
                centre.map_or_else(Vector3::zeros, Vector3::from),
                Vector3::from(*axis),
                *major_radius,
                *minor_radius,
            ),
        };
        built.map_err(|error| invalid(format!("{what}.{}", error.parameter), error.reason))
    }
}
