//! The `surface = { kind = "…", … }` tables of the `point_on_surface` and `point_on_curve` constraints and joints
//! (docs/scene-files.md, "Surfaces").

use serde::Deserialize;

use super::arrays::{exactly, maybe_exactly};
use super::bodies::OrientationSpec;

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
