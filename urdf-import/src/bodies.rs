//! Stage 4: the merged bodies checked, and the body-level repairs ([`crate::ImportOptions::bound_mass`],
//! [`crate::ImportOptions::bound_inertia`]). [`check_bodies`] runs after [`crate::merge`]: each body a moving joint
//! carries must have a positive mass and positive principal moments, because the dynamics keeps every body's own mass
//! and inertia invertible (unlike Pinocchio, which only needs the articulated inertia and returns NaN when a whole
//! subtree is massless).

use crate::error::{ImportError, Moments, Names};
use crate::merge::RobotModel;
use crate::validate::{inertia_scale, principal_axes, rebuild, ImportOptions, Repair, ROUND_OFF};

/// Whether a mass and ascending principal moments describe an invertible body: a positive mass, and no moment
/// zero up to round-off ([`ROUND_OFF`] × [`inertia_scale`]).
pub fn invertible(mass: f64, moments: &[f64; 3]) -> bool {
    mass > 0.0 && moments[0] > ROUND_OFF * inertia_scale(moments, mass)
}

/// Checks the merged bodies (stage 4, after [`crate::merge::merge`]) and applies the body bounds the options ask
/// for: every body a moving joint carries must have a positive mass and positive principal moments. Also sets
/// [`RobotModel::root_fixed_only`]. The model is one [`crate::merge::merge`] built (its joints' body indices in
/// range); a model without bodies has nothing to check.
pub fn check_bodies(model: &mut RobotModel, options: &ImportOptions) -> Result<(), ImportError> {
    options.check()?;
    let Some(root) = model.bodies.first() else {
        return Ok(());
    };
    let root_moments = root.principal_moments().unwrap_or([f64::NAN; 3]);
    model.root_fixed_only = !invertible(root.mass, &root_moments);
    if model.root_fixed_only {
        let names: Vec<String> = root.links.iter().map(|l| l.name.clone()).collect();
        model.warnings.push(format!(
            "the root body (links {}) has mass {} kg and principal moments {} kg m²: it can only be fixed to the world",
            Names(&names),
            root.mass,
            Moments(&root_moments)
        ));
    }

    // Mass below each body, the body included (children come after their parents in `bodies`).
    let mut parent_body = vec![None; model.bodies.len()];
    for joint in &model.joints {
        parent_body[joint.child] = Some(joint.parent);
    }
    let mut subtree_mass: Vec<f64> = model.bodies.iter().map(|b| b.mass).collect();
    for b in (1..model.bodies.len()).rev() {
        if let Some(p) = parent_body[b] {
            subtree_mass[p] += subtree_mass[b];
        }
    }

    for joint in &model.joints {
        let body = &mut model.bodies[joint.child];
        if let Some(bound) = options.bound_mass {
            if body.mass < bound {
                model.repairs.push(Repair::MassRaised {
                    body: body.name.clone(),
                    old: body.mass,
                    new: bound,
                });
                body.mass = bound;
            }
        }
        let principal = principal_axes(&body.inertia);
        if let (Some(bound), Some((moments, axes))) = (options.bound_inertia, principal) {
            if moments.iter().any(|&m| m < bound) {
                let new = moments.map(|m| m.max(bound));
                body.inertia = rebuild(&axes, new);
                model.repairs.push(Repair::InertiaRaised {
                    body: body.name.clone(),
                    old: moments,
                    new,
                });
            }
        }
        let moments = body.principal_moments().unwrap_or([f64::NAN; 3]);
        if !invertible(body.mass, &moments) {
            return Err(ImportError::SingularBody {
                joint: joint.name.clone(),
                line: joint.line,
                links: body.links.iter().map(|l| l.name.clone()).collect(),
                mass: body.mass,
                moments,
                massless_subtree: subtree_mass[joint.child] == 0.0,
            });
        }
    }
    Ok(())
}
