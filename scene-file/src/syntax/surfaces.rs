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
        /// The semi-axes a, b (and c) along the local x, y (and z) (m).
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 3],
        /// The local origin in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The local axes in the reference's frame; give this or `axis`, or neither (the reference's axes).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        /// The local z in the reference's frame (any length), turned there by the smallest rotation.
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² = 1` about the local z.
    EllipticCylinder {
        /// The semi-axes a, b (and c) along the local x, y (and z) (m).
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        /// The local origin in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The local axes in the reference's frame; give this or `axis`, or neither (the reference's axes).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        /// The local z in the reference's frame (any length), turned there by the smallest rotation.
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² = z²`, apex at the centre.
    Cone {
        /// The semi-axes a, b (and c) along the local x, y (and z) (m).
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        /// The local origin in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The local axes in the reference's frame; give this or `axis`, or neither (the reference's axes).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        /// The local z in the reference's frame (any length), turned there by the smallest rotation.
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `z = x²/a² + y²/b²`, or `z = x²/a² − y²/b²` with `hyperbolic = true`.
    Paraboloid {
        /// The semi-axes a, b (and c) along the local x, y (and z) (m).
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 2],
        /// The saddle `z = x²/a² − y²/b²` in place of the bowl.
        #[serde(default)]
        hyperbolic: bool,
        /// The local origin in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The local axes in the reference's frame; give this or `axis`, or neither (the reference's axes).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        /// The local z in the reference's frame (any length), turned there by the smallest rotation.
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `x²/a² + y²/b² − z²/c² = 1` (`sheets = 1`, the default) or `= −1` (`sheets = 2`).
    Hyperboloid {
        /// The semi-axes a, b (and c) along the local x, y (and z) (m).
        #[serde(deserialize_with = "exactly")]
        radii: [f64; 3],
        /// 1 or 2.
        #[serde(default = "one_sheet")]
        sheets: u8,
        /// The local origin in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The local axes in the reference's frame; give this or `axis`, or neither (the reference's axes).
        #[serde(default)]
        orientation: Option<OrientationSpec>,
        /// The local z in the reference's frame (any length), turned there by the smallest rotation.
        #[serde(default, deserialize_with = "maybe_exactly")]
        axis: Option<[f64; 3]>,
    },
    /// `normal · x = offset`.
    Plane {
        /// The plane's normal (any length).
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
        /// `normal · x` on the plane (m times the normal's length).
        offset: f64,
    },
    /// `a x² + b y² + c z² + d xy + e xz + f yz + g x + h y + i z + j = 0`.
    Quadric {
        /// a, b, …, j.
        #[serde(deserialize_with = "exactly")]
        coefficients: [f64; 10],
    },
    /// The ring torus about `axis` through `centre`.
    Torus {
        /// The torus's centre in the reference's frame (m); the origin if absent.
        #[serde(default, deserialize_with = "maybe_exactly")]
        centre: Option<[f64; 3]>,
        /// The axis the tube's centre circle turns about (any length).
        #[serde(deserialize_with = "exactly")]
        axis: [f64; 3],
        /// From the centre to the tube's centre circle (m).
        major_radius: f64,
        /// The tube's radius (m), below the major radius.
        minor_radius: f64,
    },
}

fn one_sheet() -> u8 {
    1
}
