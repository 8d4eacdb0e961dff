//! `[[collision]]`s checked: the pairs of bodies (or robot links) whose collision shapes stay apart, each with its
//! friction and restitution and both bodies' shapes (docs/contacts.md "Between bodies", docs/scene-files.md). Which
//! features of the shapes meet is chosen where the start is known, when the system is built.

use std::path::Path;

use dynamics::contacts::Friction;

use super::collisions::{body_geometry, ShapeGeometry, ShapedBody, Solid};
use crate::error::{invalid, SceneFileError};
use crate::syntax::contacts::{CollisionSpec, PairBodies};

/// A `[[collision]]`'s pair of bodies, checked.
#[derive(Clone, Debug)]
pub struct CheckedPair {
    /// The pair's name, heading its contacts' names: as written, else "`a` / `b`".
    pub name: String,
    /// The two bodies and their shapes.
    pub sides: [PairSide; 2],
    pub friction: Friction,
    pub restitution: f64,
    /// Whether the pair came from `bodies = "all"`: then links joined by a joint, or merged into one body, are
    /// skipped rather than refused.
    pub among_all: bool,
}

/// One body of a pair: its name ("body" for the single `[body]`) and its shapes.
#[derive(Clone, Debug)]
pub struct PairSide {
    pub body: String,
    pub(crate) shapes: Vec<ShapeGeometry>,
}

impl CheckedPair {
    /// Whether a transition's constraint name is one of this pair's contacts.
    pub fn owns(&self, constraint: &str) -> bool {
        constraint
            .strip_prefix(self.name.as_str())
            .is_some_and(|rest| rest.starts_with(": "))
    }
}

/// The file's `[[collision]]`s, each between two of `bodies` (those with shapes; relative mesh paths from `folder`):
/// the names known and different, friction and restitution in range, and no capsule or cylinder against a sphere, a
/// capsule or a cylinder (their touching point runs over the curved side, which the contacts, fixed features, do not
/// model).
pub(crate) fn collision_pairs(
    specs: &[CollisionSpec],
    bodies: &[ShapedBody],
    folder: &Path,
) -> Result<Vec<CheckedPair>, SceneFileError> {
    let shaped: Vec<(String, Vec<ShapeGeometry>)> = (bodies.iter())
        .filter(|b| !b.shapes.is_empty())
        .map(|b| {
            Ok((
                b.name.clone().unwrap_or_else(|| "body".to_owned()),
                body_geometry(b, folder)?,
            ))
        })
        .collect::<Result<_, SceneFileError>>()?;
    let mut pairs = Vec::new();
    for (k, spec) in specs.iter().enumerate() {
        let what = spec.name.clone().unwrap_or_else(|| format!("collision {}", k + 1));
        // A body's index among those with shapes.
        let index = |name: &str| {
            (shaped.iter()).position(|(n, _)| n == name).ok_or_else(|| {
                invalid(
                    format!("{what}: bodies"),
                    format!("no body or robot link named `{name}` has collision shapes"),
                )
            })
        };
        if !spec.except.is_empty() && matches!(spec.bodies, PairBodies::Named(_)) {
            return Err(invalid(
                format!("{what}: except"),
                "leaves pairs out of `bodies = \"all\"`; a pair named by its two bodies has none to leave out",
            ));
        }
        let friction = Friction::new(spec.friction, spec.static_friction.unwrap_or(spec.friction))
            .map_err(|error| invalid(format!("{what}: friction"), error.to_string()))?;
        if !(0.0..=1.0).contains(&spec.restitution) {
            return Err(invalid(
                format!("{what}: restitution"),
                format!("must be in [0, 1], got {}", spec.restitution),
            ));
        }
        let chosen: Vec<[usize; 2]> = match &spec.bodies {
            PairBodies::Named(names) => {
                let [first, second] = names.as_slice() else {
                    return Err(invalid(
                        format!("{what}: bodies"),
                        format!("name two bodies, or give \"all\"; got {} names", names.len()),
                    ));
                };
                if first == second {
                    return Err(invalid(
                        format!("{what}: bodies"),
                        format!("`{first}` twice: a body's shapes do not collide with each other"),
                    ));
                }
                vec![[index(first)?, index(second)?]]
            }
            PairBodies::Every(all) if all == "all" => {
                if shaped.len() < 2 {
                    return Err(invalid(
                        format!("{what}: bodies"),
                        format!(
                            "\"all\" pairs the bodies with collision shapes, and {} has them",
                            shaped.len()
                        ),
                    ));
                }
                let mut left_out = Vec::new();
                for names in &spec.except {
                    let [first, second] = names.as_slice() else {
                        return Err(invalid(
                            format!("{what}: except"),
                            format!("each pair left out is two names; got {} names", names.len()),
                        ));
                    };
                    let (a, b) = (index(first)?, index(second)?);
                    left_out.push([a.min(b), a.max(b)]);
                }
                (0..shaped.len())
                    .flat_map(|a| (a + 1..shaped.len()).map(move |b| [a, b]))
                    .filter(|pair| !left_out.contains(pair))
                    .collect()
            }
            PairBodies::Every(other) => {
                return Err(invalid(
                    format!("{what}: bodies"),
                    format!("give two names, `bodies = [\"a\", \"b\"]`, or \"all\"; got \"{other}\""),
                ))
            }
        };
        for [a, b] in chosen {
            let sides = [a, b].map(|i| PairSide {
                body: shaped[i].0.clone(),
                shapes: shaped[i].1.clone(),
            });
            for first in &sides[0].shapes {
                for second in &sides[1].shapes {
                    let curved = |s: &ShapeGeometry| s.solid != Solid::Polytope;
                    let either = |kind: Solid| first.solid == kind || second.solid == kind;
                    let refuse = |what_meets: &str| {
                        invalid(
                            format!("{what}: bodies"),
                            format!(
                                "`{}` {} against `{}` {}: {what_meets}; use spheres, boxes or convex hulls",
                                sides[0].body, first.label, sides[1].body, second.label
                            ),
                        )
                    };
                    if either(Solid::Cylinder) && curved(first) && curved(second) {
                        return Err(refuse(
                            "a cylinder against a sphere, a capsule or a cylinder is not modelled (their touching \
                             point runs over the curved side); a cylinder's rims rest on faces",
                        ));
                    }
                    if either(Solid::Capsule) && curved(first) && curved(second) {
                        return Err(refuse(
                            "a capsule against a sphere or a capsule is not modelled (their touching point runs along \
                             the segment)",
                        ));
                    }
                }
            }
            let name = match (&spec.name, &spec.bodies) {
                (Some(name), PairBodies::Named(_)) => name.clone(),
                (Some(name), PairBodies::Every(_)) => format!("{name}: {} / {}", sides[0].body, sides[1].body),
                (None, _) => format!("{} / {}", sides[0].body, sides[1].body),
            };
            pairs.push(CheckedPair {
                name,
                sides,
                friction,
                restitution: spec.restitution,
                among_all: matches!(spec.bodies, PairBodies::Every(_)),
            });
        }
    }
    Ok(pairs)
}
