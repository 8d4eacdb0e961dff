//! `summary.md`: the setup, then per algebra the energy change, the largest violation and the CPU time, the steps,
//! the start's correction, the limits' and contacts' impacts, the work done against the energy change, the two
//! algebras' agreement, and the files written.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::constraints::Stabilisation;
use dynamics::integrate::Integrator;
use dynamics::limits::LimitTransition;
use scene_file::{CheckedScene, End};

use super::describe::{element_list, robot_summary, stepping};
use super::run::AlgebraRun;
use crate::csv;
use crate::markdown::{escape, scientific, TransitionCounts};
use crate::measure::agreement;

/// What `summary.md` says about the scene besides the runs.
pub(crate) struct Setup<'a> {
    pub(crate) scene: &'a CheckedScene,
    /// The scene file.
    pub(crate) path: &'a Path,
    pub(crate) title: &'a str,
    /// Whether the energy change is relative to |E₀| (else in J).
    pub(crate) relative_energy: bool,
}

/// Items joined by commas, or "none".
fn listed(items: Vec<String>) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join(", ")
    }
}

/// `summary.md`: the setup, then per algebra the energy change, the largest violation and the CPU time, the steps, the
/// start's correction and the impacts; what the numbers mean, the work done, the two algebras' agreement and the files.
pub(crate) fn summary(setup: &Setup, runs: &[AlgebraRun], files: &[String]) -> String {
    let scene = setup.scene;
    let mut out = String::new();
    let robot = scene.robot.as_ref().map(|robot| robot_summary(&robot.loaded));
    write_setup(&mut out, setup, robot.is_some());
    if let Some(robot) = &robot {
        let _ = writeln!(out, "{robot}");
    }
    write_contacts(&mut out, scene);
    write_elements(&mut out, &element_list(scene));
    // Joints to measure: the file's, or the robot's.
    let joints = !scene.layout.joints.is_empty() || robot.is_some();
    write_runs(&mut out, runs, joints);
    if joints {
        write_start_corrections(&mut out, scene, runs);
    }
    let limited = write_impacts(&mut out, scene, runs);
    write_meanings(&mut out, setup, limited, robot.is_some());
    if !scene.conservative {
        write_work(&mut out, scene, runs);
    }
    write_agreement(&mut out, runs);
    write_files(&mut out, scene, runs, files);
    out
}

/// The title and the setup: the file, the bodies, forces and constraints, the integrator, steps, duration, sampling
/// and stabilisation.
fn write_setup(out: &mut String, setup: &Setup, robot: bool) {
    let Setup { scene, path, title, .. } = *setup;
    let layout = &scene.layout;
    let body_name = |end: &End| match end {
        End::World => "the world".to_owned(),
        End::Body(i) => layout.bodies[*i].name.clone(),
        End::Link(link) => format!("the robot link {link}"),
    };
    let constraints: Vec<String> = layout
        .joints
        .iter()
        .map(|j| {
            let what = format!("{} by {}", j.kind, j.formulation.name());
            if layout.named {
                format!(
                    "{} ({what}, {} to {})",
                    escape(&j.name),
                    escape(&layout.bodies[j.body].name),
                    escape(&body_name(&j.reference))
                )
            } else {
                what
            }
        })
        .collect();
    let forces: Vec<String> = layout
        .bodies
        .iter()
        .flat_map(|b| {
            b.forces.iter().map(|f| {
                if layout.named {
                    format!("{} on {}", f.kind(), escape(&b.name))
                } else {
                    f.kind().to_owned()
                }
            })
        })
        .collect();
    let _ = writeln!(out, "# {}\n", escape(title));
    let _ = writeln!(
        out,
        "From {}: {}forces: {}; constraints: {}. {}, {}, {} s simulated, sampled every {} s{}.\n",
        escape(&path.display().to_string()),
        if layout.named {
            format!(
                "{}bodies: {}; ",
                if robot { "a robot (below); further " } else { "" },
                listed(layout.bodies.iter().map(|b| escape(&b.name)).collect())
            )
        } else {
            String::new()
        },
        listed(forces),
        listed(constraints),
        Integrator::from(scene.integrator).name(),
        stepping(scene),
        scene.duration,
        scene.sample_interval,
        match scene.stabilisation {
            _ if layout.joints.is_empty() && !robot => String::new(),
            Stabilisation::Projection { .. } => ", stabilised by projection".to_owned(),
            Stabilisation::Baumgarte { alpha, beta } => format!(", stabilised by Baumgarte (α = {alpha}, β = {beta})"),
            Stabilisation::None => ", without stabilisation".to_owned(),
        },
    );
}

/// The contacts, each a body point, sphere or disk's rim above a world plane.
fn write_contacts(out: &mut String, scene: &CheckedScene) {
    if !scene.contacts.is_empty() {
        let _ = writeln!(
            out,
            "Contacts, each a body point, sphere or disk's rim kept above the world plane n · x = d (docs/contacts.md):\n"
        );
        for (k, contact) in scene.contacts.iter().enumerate() {
            let what = match (&contact.sphere, &contact.disk, contact.point) {
                (Some(sphere), ..) => format!(
                    "the sphere of radius {} m centred at {:?} m",
                    sphere.radius, sphere.centre
                ),
                (None, Some(disk), _) => format!(
                    "the rim of the disk of radius {} m centred at {:?} m, axis {:?},",
                    disk.radius, disk.centre, disk.axis
                ),
                (None, None, point) => format!("the point {:?} m", point.unwrap_or_default()),
            };
            let friction = match contact.static_friction {
                Some(stiction) if stiction != contact.friction => {
                    format!("friction {} (static {stiction})", contact.friction)
                }
                _ if contact.friction > 0.0 => format!("friction {}", contact.friction),
                _ => "no friction".to_owned(),
            };
            let _ = writeln!(
                out,
                "- {}: {what} of {}, n = {:?}, d = {} m, restitution {}, {friction}",
                escape(&contact.name(k)),
                escape(contact.body.as_deref().unwrap_or("the body")),
                contact.normal,
                contact.offset,
                contact.restitution
            );
        }
        let _ = writeln!(out);
    }
    if !scene.pairs.is_empty() {
        let _ = writeln!(
            out,
            "Pairs of bodies whose collision shapes stay apart (docs/contacts.md \"Between bodies\"):\n"
        );
        for pair in &scene.pairs {
            let friction = match (pair.friction.kinetic(), pair.friction.stiction()) {
                (_, 0.0) => "no friction".to_owned(),
                (kinetic, stiction) if kinetic == stiction => format!("friction {kinetic}"),
                (kinetic, stiction) => format!("friction {kinetic} (static {stiction})"),
            };
            let _ = writeln!(
                out,
                "- {}: `{}` and `{}`, restitution {}, {friction}",
                escape(&pair.name),
                escape(&pair.sides[0].body),
                escape(&pair.sides[1].body),
                pair.restitution
            );
        }
        let _ = writeln!(out);
    }
}

/// The force elements and drives, described.
fn write_elements(out: &mut String, elements: &[String]) {
    if !elements.is_empty() {
        let _ = writeln!(out, "Force elements and drives:\n");
        for element in elements {
            let _ = writeln!(out, "- {}", escape(element));
        }
        let _ = writeln!(out);
    }
}

/// Per algebra the energy change, the largest violation (with `joints` to measure) and the CPU time, and the steps.
fn write_runs(out: &mut String, runs: &[AlgebraRun], joints: bool) {
    let _ = writeln!(
        out,
        "| algebra | energy change at T | largest energy change | largest constraint violation (m) | CPU per \
         simulated second (s) | µs per step |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for run in runs {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {:.2} |",
            run.algebra.name(),
            scientific(run.energy_change.last().copied().unwrap_or(0.0)),
            scientific(run.max_energy_change()),
            if !joints {
                "–".to_owned()
            } else {
                scientific(run.max_violation())
            },
            scientific(run.cpu_per_simulated_second),
            run.time_per_step * 1e6,
        );
    }
    let _ = writeln!(out);
    for run in runs {
        let steps = run.statistics;
        let _ = writeln!(
            out,
            "Steps ({}): {} kept, {} refused, {} evaluations of the equations of motion, from {} s to {} s.",
            run.algebra.name(),
            steps.accepted,
            steps.rejected,
            steps.evaluations,
            scientific(steps.smallest_step),
            scientific(steps.largest_step),
        );
    }
    let _ = writeln!(out);
}

/// How far putting the start on the joints moved the body it moved most, per algebra.
fn write_start_corrections(out: &mut String, scene: &CheckedScene, runs: &[AlgebraRun]) {
    let corrections: Vec<String> = runs
        .iter()
        .filter_map(|run| {
            let (body, _) = run.start_correction.largest()?;
            Some(format!(
                "{} moved `{}` by {} m and turned it by {} rad",
                run.algebra.name(),
                escape(&run.names[body]),
                scientific(run.start_correction.moved[body]),
                scientific(run.start_correction.turned[body]),
            ))
        })
        .collect();
    let _ = writeln!(
        out,
        "Putting the start on the joints (at most max_start_correction = {} m and rad) {}.\n",
        scene.max_start_correction,
        corrections.join("; ")
    );
}

/// The limits' and contacts' transitions per algebra, and whether there were any.
fn write_impacts(out: &mut String, scene: &CheckedScene, runs: &[AlgebraRun]) -> bool {
    let limited = runs.iter().any(|run| !run.transitions.is_empty());
    let frictional =
        scene.contacts.iter().any(|c| c.friction > 0.0) || scene.pairs.iter().any(|p| p.friction.is_some());
    for run in runs.iter().filter(|run| !run.transitions.is_empty()) {
        let counts = TransitionCounts::of(&run.transitions);
        let taken = run.impact_energy();
        let _ = writeln!(
            out,
            "{} ({}): {} bounces, {} holds, {} releases, {} sticks, {} slips, the first at t = {} s; the impacts \
             changed the energy by {} J{}{}.",
            {
                let contacts: Vec<String> = (scene.contacts.iter().enumerate()).map(|(k, c)| c.name(k)).collect();
                let on_contact = |t: &LimitTransition| {
                    contacts.contains(&t.constraint) || scene.pairs.iter().any(|pair| pair.owns(&t.constraint))
                };
                match (
                    run.transitions.iter().any(on_contact),
                    run.transitions.iter().all(on_contact),
                ) {
                    (false, _) => "Joint limits",
                    (true, true) => "Contacts",
                    (true, false) => "Joint limits and contacts",
                }
            },
            run.algebra.name(),
            counts.bounces,
            counts.holds,
            counts.releases,
            counts.sticks,
            counts.slips,
            run.transitions[0].t,
            scientific(taken),
            if frictional {
                format!(
                    ", sliding friction and the force elements by {} J in all",
                    scientific(run.total_energy_change() - taken)
                )
            } else {
                String::new()
            },
            if scene.contacts.is_empty() && scene.pairs.is_empty() {
                String::new()
            } else {
                format!(
                    "; the deepest a contact point went below its plane, or two shapes into each other, at the \
                     samples: {} m",
                    scientific(run.deepest)
                )
            },
        );
    }
    if !scene.pairs.is_empty() {
        for run in runs {
            let deepest = match &run.overlap {
                Some((t, shapes, depth)) => format!("{} m ({}, t = {t} s)", scientific(*depth), escape(shapes)),
                None => "none".to_owned(),
            };
            let _ = writeln!(
                out,
                "{}: the deepest two `[[collision]]` shapes went into each other at the samples, by parry3d's query \
                 rather than the contacts (it sees shapes meet where no contact watches them, as a sphere past the \
                 face it is held on; its tolerance for polytopes is some 1e-8 m): {deepest}.",
                run.algebra.name()
            );
        }
        let _ = writeln!(out);
    }
    if limited {
        let _ = writeln!(out);
    }
    limited
}

/// What the energy change and the violation mean, with `limited` impacts and a `robot`.
fn write_meanings(out: &mut String, setup: &Setup, limited: bool, robot: bool) {
    let _ = writeln!(
        out,
        "Energy change: {}{}.",
        if setup.relative_energy {
            "|E(t) − E₀| / |E₀|"
        } else {
            "|E(t) − E₀| in J (|E₀| < 1e-6 J, where a relative change means nothing)"
        },
        if limited {
            ", less what the impacts at limits and contacts changed it by up to t (recorded at each impact)"
        } else {
            ""
        }
    );
    if setup.scene.conservative {
        let _ = writeln!(
            out,
            "Every force has a potential, so the energy change is the integrator's drift."
        );
    } else {
        let _ = writeln!(
            out,
            "Forces without a potential (constant forces or couples, dampers, torques, controllers, drives, sliding \
             friction) do work, so the energy change is physical, not only drift."
        );
    }
    let _ = writeln!(
        out,
        "The violation is the largest distance of a constrained body point from where it must be (for axis \
         joints also of the point 1 m along the body axis, for prismatic and planar joints of the point 1 m along \
         the body normal, for universal joints how far the point 1 m along the body axis is off the plane normal to \
         the reference axis, for fixed joints the turn's angle in rad{}). CPU time is the stepping alone.\n",
        if robot {
            "; for the robot's joints the distance of each child's joint origin from where its joint coordinates \
             put it, and the angle of the turn between them"
        } else {
            ""
        }
    );
}

/// The work done by the forces without a potential against the energy change, less what the impacts took, per
/// algebra.
fn write_work(out: &mut String, scene: &CheckedScene, runs: &[AlgebraRun]) {
    let impacts = runs.iter().any(|run| !run.transitions.is_empty());
    let (minus, taken) = if impacts {
        (" − L(T)", " L(T) (J) |")
    } else {
        ("", "")
    };
    let _ = writeln!(
        out,
        "| algebra | E(T) − E₀ (J) |{taken} work W(T) (J) | E(T) − E₀{minus} − W(T) (J) |"
    );
    let _ = writeln!(out, "|---|---|---|---|{}", if impacts { "---|" } else { "" });
    for run in runs {
        let _ = writeln!(
            out,
            "| {} | {} |{} {} | {} |",
            run.algebra.name(),
            scientific(run.total_energy_change()),
            if impacts {
                format!(" {} |", scientific(run.impact_energy()))
            } else {
                String::new()
            },
            scientific(run.work.last().copied().unwrap_or(0.0)),
            scientific(run.unexplained_energy())
        );
    }
    let _ = writeln!(
        out,
        "\nW is the work of the forces without a potential (force elements, drives, constant forces and couples, \
         sliding friction at contacts) from the start, integrated with the method's own weights{}, so \
         E(T) − E₀{minus} − W(T) is the integration error.{}\n",
        if impacts {
            ", and L(T) what the impacts at limits and contacts changed the energy by"
        } else {
            ""
        },
        if matches!(Integrator::from(scene.integrator), Integrator::Splitting(_)) {
            " The splitting methods integrate no power: here W stays 0."
        } else {
            ""
        }
    );
}

/// How far the two algebras' runs are apart, if both ran.
fn write_agreement(out: &mut String, runs: &[AlgebraRun]) {
    if let [first, second] = runs {
        let (angle, distance) = first
            .bodies
            .iter()
            .zip(&second.bodies)
            .map(|(a, b)| agreement(a, b))
            .fold((0.0f64, 0.0f64), |(a, d), (x, y)| (a.max(x), d.max(y)));
        let _ = writeln!(
            out,
            "{} vs {}: largest orientation difference {} rad, largest position difference {} m.\n",
            first.algebra.name(),
            second.algebra.name(),
            scientific(angle),
            scientific(distance)
        );
    }
}

/// The files written, each with its columns.
fn write_files(out: &mut String, scene: &CheckedScene, runs: &[AlgebraRun], files: &[String]) {
    for file in files {
        if file.ends_with(".png") {
            let _ = writeln!(out, "![{file}]({file})\n");
        } else if file.contains("_joints_") {
            let _ = writeln!(
                out,
                "Joint coordinates: [{file}]({file}) (columns: t, every non-fixed joint in URDF file order (rad or m, \
                 continuous joints unwrapped){}, then the energy of the whole system (J)).\n",
                if file_has_base(runs) {
                    ", base.x, base.y, base.z, base.qw, base.qx, base.qy, base.qz (the root link frame, world ← root)"
                } else {
                    ""
                }
            );
        } else {
            let columns = if scene.layout.named {
                "t, then per body NAME.x, NAME.y, NAME.z (centre of mass, world, m), NAME.qw, NAME.qx, NAME.qy, \
                 NAME.qz (orientation body → world), then the energy of the whole system (J)"
                    .to_owned()
            } else {
                csv::HEADER.to_owned()
            };
            let _ = writeln!(out, "Trajectory: [{file}]({file}) (columns: {columns}).\n");
        }
    }
}

/// Whether the joints CSV has the floating base's columns.
fn file_has_base(runs: &[AlgebraRun]) -> bool {
    runs.iter().any(|r| {
        r.joints
            .as_ref()
            .is_some_and(|(headers, _)| headers.iter().any(|h| h == "base.x"))
    })
}
