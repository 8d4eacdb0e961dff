//! The surfaces of `point_on_surface` and `point_on_curve`, built into [`dynamics::surfaces::Surface`] in the
//! reference's frame.

use dynamics::surfaces::{Sheets, Surface};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};

use super::values::{direction, finite};
use crate::error::{invalid, SceneFileError};
use crate::syntax::bodies::OrientationSpec;
use crate::syntax::surfaces::SurfaceSpec;

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
    pub(crate) fn surface(&self, what: &str) -> Result<Surface, SceneFileError> {
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
