//! Collision shapes against `[[plane]]`s, as contacts (docs/contacts.md "Shapes on planes"): every shape of every
//! body stays above every plane through the contacts that keep a convex shape above a plane exactly: its lowest point
//! is always one of them. A sphere is one sphere contact, a box its eight corners, a capsule the spheres at its
//! segment's ends, a cylinder the rims of its two caps, a convex hull its vertices. The expanded contacts are ordinary `[[contact]]` entries, so the
//! summary, the start check and the transitions treat them as any other.

use std::path::Path;

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};

use super::values::finite;
use crate::error::{invalid, SceneFileError};
use urdf_import::Geometry;

use crate::syntax::bodies::{CollisionShape, OrientationSpec};
use crate::syntax::contacts::{ContactSpec, DiskSpec, PlaneSpec, SphereSpec};

/// The largest size or coordinate of a collision shape (m), as for contact points.
const LARGEST: f64 = 1e6;

/// The most vertices a convex hull may bring (each is a contact with each plane, watched at every step).
pub const MAX_HULL_VERTICES: usize = 256;

/// A body's collision shapes: its name (`None` for the single `[body]`; a link's name for a robot's) and the shapes.
pub(crate) struct ShapedBody {
    pub name: Option<String>,
    pub shapes: Vec<CollisionShape>,
}

/// A robot's links' URDF `<collision>` shapes as the file's collision shapes (each in its link's frame, placed by its
/// origin), one [`ShapedBody`] per link that has any, and a warning for each that cannot be one: a mesh whose file
/// is not found or not STL. Meshes are looked up as written, relative to
/// the URDF's folder, and for `package://package/path` as `path` and `package/path` under the URDF's folder and each
/// folder above it.
pub(crate) fn urdf_shapes(
    collisions: &[(String, urdf_import::Collision)],
    urdf: &Path,
    warnings: &mut Vec<String>,
) -> Vec<ShapedBody> {
    let folder = urdf.parent().unwrap_or(Path::new("."));
    let mut bodies: Vec<ShapedBody> = Vec::new();
    for (link, collision) in collisions {
        let rotation = collision.origin.rotation;
        let orientation = Some(OrientationSpec {
            quaternion: Some([rotation.w, rotation.i, rotation.j, rotation.k]),
            ..OrientationSpec::default()
        });
        let position = Some(collision.origin.translation.vector.into());
        let shape = match &collision.geometry {
            Geometry::Sphere { radius } => CollisionShape::Sphere {
                radius: *radius,
                position,
                orientation,
            },
            Geometry::Box { size } => CollisionShape::Box {
                size: *size,
                position,
                orientation,
            },
            Geometry::Cylinder { radius, length } => CollisionShape::Cylinder {
                radius: *radius,
                length: *length,
                position,
                orientation,
            },
            Geometry::Mesh { filename, scale } => match mesh_file(folder, filename) {
                Some(path) => match mesh_vertices("mesh", &path) {
                    Ok(vertices) => CollisionShape::Convex {
                        points: Some(
                            (vertices.iter())
                                .map(|v| vec![v.x * scale[0], v.y * scale[1], v.z * scale[2]])
                                .collect(),
                        ),
                        mesh: None,
                        position,
                        orientation,
                    },
                    Err(error) => {
                        warnings.push(format!(
                            "link `{link}`: the mesh <collision> at line {} is skipped: {error}",
                            collision.line
                        ));
                        continue;
                    }
                },
                None => {
                    warnings.push(format!(
                        "link `{link}`: the mesh <collision> at line {} is skipped: {filename} is not found",
                        collision.line
                    ));
                    continue;
                }
            },
        };
        match bodies.iter_mut().find(|b| b.name.as_deref() == Some(link.as_str())) {
            Some(body) => body.shapes.push(shape),
            None => bodies.push(ShapedBody {
                name: Some(link.clone()),
                shapes: vec![shape],
            }),
        }
    }
    bodies
}

/// Where a URDF mesh address points: as written relative to `folder`, or a `package://package/path` as `path` or
/// `package/path` under `folder` and each folder above it; `None` if no such file exists.
fn mesh_file(folder: &Path, filename: &str) -> Option<std::path::PathBuf> {
    let address = filename.strip_prefix("file://").unwrap_or(filename);
    let Some(packaged) = address.strip_prefix("package://") else {
        let path = folder.join(address);
        return path.is_file().then_some(path);
    };
    let inside = packaged.split_once('/').map_or(packaged, |(_, rest)| rest);
    folder
        .ancestors()
        .flat_map(|dir| [dir.join(inside), dir.join(packaged)])
        .find(|path| path.is_file())
}

/// One point, sphere or disk rim of a shape, in its body's frame, with the feature's name (" corner 3"): about
/// `centre`, a sphere of `radius` (zero: a point) or the rim of a disk (its unit axis and radius).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Feature {
    pub name: String,
    pub centre: Vector3<f64>,
    pub radius: f64,
    pub rim: Option<(Vector3<f64>, f64)>,
}

impl Feature {
    /// The least height of the feature, its body placed by `place`, above the plane `normal · x = offset` (in the
    /// frame `place` maps to): `n · c − d − r`, less `ρ |n − (n · a) a|` for a rim of axis a.
    pub fn height(&self, place: &Isometry3<f64>, normal: &Vector3<f64>, offset: f64) -> f64 {
        let rim = self.rim.map_or(0.0, |(axis, radius)| {
            let axis = place.rotation * axis;
            radius * (normal - axis * normal.dot(&axis)).norm()
        });
        normal.dot(&(place * Point3::from(self.centre)).coords) - offset - self.radius - rim
    }
}

/// A face's plane `normal · x = offset` (its body's frame, normal unit and outward) and its area (m²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Face {
    pub normal: Vector3<f64>,
    pub offset: f64,
    pub area: f64,
}

impl Face {
    /// The face's plane in the frame `place` maps its body's frame to: `(R n) · x = d + (R n) · t`.
    pub fn placed(&self, place: &Isometry3<f64>) -> (Vector3<f64>, f64) {
        let normal = place.rotation * self.normal;
        (normal, self.offset + normal.dot(&place.translation.vector))
    }
}

/// What a shape is against another shape (docs/contacts.md "Between bodies").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Solid {
    /// A sphere: one feature, its centre and radius.
    Ball,
    /// A capsule: the spheres at its segment's ends, which are its lowest points against a plane only.
    Capsule,
    /// A cylinder: its caps' rims, which are its lowest points against a plane only.
    Cylinder,
    /// A box or convex hull: its vertices and its faces.
    Polytope,
}

/// A collision shape, checked: its label ("box 2"), what it is, the features that keep it above a plane, and (for a
/// polytope) its faces, all in its body's frame.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ShapeGeometry {
    pub label: String,
    pub solid: Solid,
    pub features: Vec<Feature>,
    pub faces: Vec<Face>,
}

/// Every plane's contacts with every body's shapes: named "`plane`: `body` `kind` `j` `feature`", with the plane's
/// normal, offset, friction and restitution. Relative mesh paths are read from `folder`.
pub(crate) fn plane_contacts(
    planes: &[PlaneSpec],
    bodies: &[ShapedBody],
    folder: &Path,
) -> Result<Vec<ContactSpec>, SceneFileError> {
    let mut features = Vec::new();
    for body in bodies {
        let label = body.name.as_deref().unwrap_or("body");
        for shape in body_geometry(body, folder)? {
            for feature in shape.features {
                let name = format!("{label} {}{}", shape.label, feature.name);
                features.push((body.name.as_deref(), name, feature));
            }
        }
    }
    let mut contacts = Vec::new();
    for (k, plane) in planes.iter().enumerate() {
        for (body, name, feature) in &features {
            let centre: [f64; 3] = feature.centre.into();
            let (point, sphere, disk) = match feature.rim {
                Some((axis, radius)) => (
                    None,
                    None,
                    Some(DiskSpec {
                        centre,
                        axis: axis.into(),
                        radius,
                    }),
                ),
                None if feature.radius > 0.0 => (
                    None,
                    Some(SphereSpec {
                        centre,
                        radius: feature.radius,
                    }),
                    None,
                ),
                None => (Some(centre), None, None),
            };
            contacts.push(ContactSpec {
                name: Some(format!("{}: {name}", plane.name(k))),
                body: body.map(str::to_owned),
                point,
                sphere,
                disk,
                normal: plane.normal,
                offset: plane.offset,
                restitution: plane.restitution,
                friction: plane.friction,
                static_friction: plane.static_friction,
            });
        }
    }
    Ok(contacts)
}

/// The shape's kind as its key names it.
fn kind(shape: &CollisionShape) -> &'static str {
    match shape {
        CollisionShape::Sphere { .. } => "sphere",
        CollisionShape::Box { .. } => "box",
        CollisionShape::Capsule { .. } => "capsule",
        CollisionShape::Cylinder { .. } => "cylinder",
        CollisionShape::Convex { .. } => "convex",
    }
}

/// A size: positive, finite and at most [`LARGEST`].
fn size(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value > 0.0 && value <= LARGEST {
        Ok(value)
    } else {
        Err(invalid(
            what,
            format!("must be positive and at most 1e6 m, got {value}"),
        ))
    }
}

/// Every shape of `body` checked, in order (relative mesh paths read from `folder`).
pub(crate) fn body_geometry(body: &ShapedBody, folder: &Path) -> Result<Vec<ShapeGeometry>, SceneFileError> {
    let label = body.name.as_deref().unwrap_or("body");
    (body.shapes.iter().enumerate())
        .map(|(j, shape)| shape_geometry(shape, &format!("body {label}: collision {}", j + 1), j, folder))
        .collect()
}

/// `shape` (the `index`th of its body) checked: the points and spheres that keep it above a plane and its faces, in
/// its body's frame.
fn shape_geometry(
    shape: &CollisionShape,
    what: &str,
    index: usize,
    folder: &Path,
) -> Result<ShapeGeometry, SceneFileError> {
    let (position, orientation) = match shape {
        CollisionShape::Sphere {
            position, orientation, ..
        }
        | CollisionShape::Box {
            position, orientation, ..
        }
        | CollisionShape::Capsule {
            position, orientation, ..
        }
        | CollisionShape::Cylinder {
            position, orientation, ..
        }
        | CollisionShape::Convex {
            position, orientation, ..
        } => (position, orientation),
    };
    let origin = finite(&format!("{what}: position"), position.unwrap_or_default())?;
    if origin.amax() > LARGEST {
        return Err(invalid(
            format!("{what}: position"),
            "must be within 1e6 m of the body's origin",
        ));
    }
    let turn = match orientation {
        Some(spec) => spec.rotation_of(&format!("{what}: orientation"))?,
        None => UnitQuaternion::identity(),
    };
    let place = |local: Vector3<f64>| origin + turn * local;
    let feature = |name: String, local: Vector3<f64>, radius: f64| Feature {
        name,
        centre: place(local),
        radius,
        rim: None,
    };
    // A face of the shape's own frame, placed: `n · x = d` becomes `(R n) · x = d + (R n) · o`.
    let face = |normal: Vector3<f64>, offset: f64, area: f64| {
        let normal = turn * normal;
        Face {
            normal,
            offset: offset + normal.dot(&origin),
            area,
        }
    };
    let label = format!("{} {}", kind(shape), index + 1);
    let (solid, features, faces) = match shape {
        CollisionShape::Sphere { radius, .. } => {
            let radius = size(&format!("{what}: radius"), *radius)?;
            (
                Solid::Ball,
                vec![feature(String::new(), Vector3::zeros(), radius)],
                Vec::new(),
            )
        }
        CollisionShape::Box { size: edges, .. } => {
            let half: Vec<f64> = (0..3)
                .map(|k| size(&format!("{what}: size"), edges[k]).map(|e| 0.5 * e))
                .collect::<Result<_, _>>()?;
            let corners = (0..8)
                .map(|c| {
                    let sign = |bit: usize| if c & (1 << bit) == 0 { -1.0 } else { 1.0 };
                    let corner = Vector3::new(sign(0) * half[0], sign(1) * half[1], sign(2) * half[2]);
                    feature(format!(" corner {}", c + 1), corner, 0.0)
                })
                .collect();
            let faces = (0..6)
                .map(|f| {
                    let sign = if f % 2 == 0 { -1.0 } else { 1.0 };
                    let (j, k) = ((f / 2 + 1) % 3, (f / 2 + 2) % 3);
                    face(Vector3::ith(f / 2, sign), half[f / 2], 4.0 * half[j] * half[k])
                })
                .collect();
            (Solid::Polytope, corners, faces)
        }
        CollisionShape::Capsule { radius, length, .. } => {
            let radius = size(&format!("{what}: radius"), *radius)?;
            let half = 0.5 * size(&format!("{what}: length"), *length)?;
            let ends = vec![
                feature(" end 1".to_owned(), Vector3::z() * -half, radius),
                feature(" end 2".to_owned(), Vector3::z() * half, radius),
            ];
            (Solid::Capsule, ends, Vec::new())
        }
        CollisionShape::Cylinder { radius, length, .. } => {
            let radius = size(&format!("{what}: radius"), *radius)?;
            let half = 0.5 * size(&format!("{what}: length"), *length)?;
            let cap = |k: usize, sign: f64| Feature {
                rim: Some((turn * Vector3::z(), radius)),
                ..feature(format!(" cap {k}"), Vector3::z() * sign * half, 0.0)
            };
            (Solid::Cylinder, vec![cap(1, -1.0), cap(2, 1.0)], Vec::new())
        }
        CollisionShape::Convex { points, mesh, .. } => {
            let vertices = match (points, mesh) {
                (Some(points), None) => listed_points(&format!("{what}: points"), points)?,
                (None, Some(file)) => mesh_vertices(&format!("{what}: mesh"), &folder.join(file))?,
                (Some(_), Some(_)) => return Err(invalid(what, "give `points` or `mesh`, not both")),
                (None, None) => return Err(invalid(what, "give the hull's `points` or a `mesh` file")),
            };
            let (vertices, planes) = hull(what, &vertices)?;
            let features = (vertices.into_iter().enumerate())
                .map(|(k, vertex)| feature(format!(" vertex {}", k + 1), vertex, 0.0))
                .collect();
            let faces = planes.into_iter().map(|(n, d, area)| face(n, d, area)).collect();
            (Solid::Polytope, features, faces)
        }
    };
    Ok(ShapeGeometry {
        label,
        solid,
        features,
        faces,
    })
}

/// The listed points, each of three finite coordinates within [`LARGEST`].
fn listed_points(what: &str, points: &[Vec<f64>]) -> Result<Vec<Vector3<f64>>, SceneFileError> {
    points
        .iter()
        .enumerate()
        .map(|(k, point)| {
            let &[x, y, z] = point.as_slice() else {
                return Err(invalid(
                    what,
                    format!("point {} has {} numbers, not 3", k + 1, point.len()),
                ));
            };
            let point = finite(what, [x, y, z])?;
            if point.amax() > LARGEST {
                return Err(invalid(what, format!("point {} is beyond 1e6 m", k + 1)));
            }
            Ok(point)
        })
        .collect()
}

/// The vertices of an STL file (ASCII or binary).
fn mesh_vertices(what: &str, path: &Path) -> Result<Vec<Vector3<f64>>, SceneFileError> {
    let mut file = std::fs::File::open(path)
        .map_err(|error| invalid(what, format!("cannot read the mesh {}: {error}", path.display())))?;
    let mesh = stl_io::read_stl(&mut file)
        .map_err(|error| invalid(what, format!("{} is not an STL mesh: {error}", path.display())))?;
    let points: Vec<Vec<f64>> = mesh
        .vertices
        .iter()
        .map(|v| v.0.iter().map(|&x| f64::from(x)).collect())
        .collect();
    listed_points(what, &points)
}

/// The vertices of the convex hull of `points` (parry3d's quickhull) and its faces' planes and areas `(n, d, A)` (n
/// unit and outward, coplanar triangles merged), refused if the points span no volume (fewer than four, or all in one plane: a
/// hull of no thickness would let the plane through between its vertices only by round-off, and is more likely a
/// typo) or bring more than [`MAX_HULL_VERTICES`].
#[allow(clippy::type_complexity)]
fn hull(
    what: &str,
    points: &[Vector3<f64>],
) -> Result<(Vec<Vector3<f64>>, Vec<(Vector3<f64>, f64, f64)>), SceneFileError> {
    let extent = points.iter().fold(0.0f64, |m, p| m.max(p.amax()));
    let centre = points.iter().sum::<Vector3<f64>>() / points.len().max(1) as f64;
    let flat = || {
        invalid(
            what,
            format!(
                "the {} points span no volume (fewer than four, or all in one plane or line)",
                points.len()
            ),
        )
    };
    if points.len() < 4 {
        return Err(flat());
    }
    let input: Vec<parry3d_f64::math::Vector3> = (points.iter())
        .map(|p| parry3d_f64::math::Vector3::new(p.x, p.y, p.z))
        .collect();
    let (vertices, triangles) = parry3d_f64::transformation::try_convex_hull(&input).map_err(|_| flat())?;
    let at = |i: u32| {
        let v = vertices[i as usize];
        Vector3::new(v.x, v.y, v.z) - centre
    };
    let volume: f64 = (triangles.iter())
        .map(|t| at(t[0]).dot(&at(t[1]).cross(&at(t[2]))) / 6.0)
        .sum();
    // NaN (a degenerate hull) counts as no volume.
    let thick = volume.abs() > 1e-12 * extent.max(f64::MIN_POSITIVE).powi(3);
    if !thick {
        return Err(flat());
    }
    let mut used: Vec<u32> = triangles.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    if used.len() > MAX_HULL_VERTICES {
        return Err(invalid(
            what,
            format!(
                "the hull has {} vertices, more than {MAX_HULL_VERTICES} contacts per plane: simplify the mesh",
                used.len()
            ),
        ));
    }
    let mut planes: Vec<(Vector3<f64>, f64, f64)> = Vec::new();
    for t in &triangles {
        let (a, b, c) = (at(t[0]), at(t[1]), at(t[2]));
        let normal = (b - a).cross(&(c - a));
        if normal.norm() <= f64::EPSILON * extent * extent {
            continue;
        }
        // Outward: away from the centre of the points, which is inside the hull.
        let normal = normal.normalize() * if normal.dot(&a) < 0.0 { -1.0 } else { 1.0 };
        let offset = normal.dot(&(a + centre));
        let area = 0.5 * (b - a).cross(&(c - a)).norm();
        let same = |(n, d, _): &&mut (Vector3<f64>, f64, f64)| {
            (*n - normal).norm() < 1e-9 && (*d - offset).abs() < 1e-9 * extent
        };
        match planes.iter_mut().find(same) {
            Some(plane) => plane.2 += area,
            None => planes.push((normal, offset, area)),
        }
    }
    Ok((used.into_iter().map(|i| at(i) + centre).collect(), planes))
}
