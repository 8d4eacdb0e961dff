//! MuJoCo 4.0's measured points on the same scenes and machine (RK4; from the project's issue tracker,
//! measured by the team): orientation error at T (rad; the circle scene: m, reduced coordinates) for
//! dt = 1e-2, 1e-3, 1e-4, and the CPU time per step. Drawn as reference markers on the work-precision
//! plots: CPU per simulated second = time per step / dt.

use reference::SceneId;

/// (dt, error) points and the time per step (s).
pub struct Anchor {
    pub points: [(f64, f64); 3],
    pub time_per_step: f64,
}

pub fn anchor(scene: SceneId) -> Option<Anchor> {
    let points = |errors: [f64; 3]| [(1e-2, errors[0]), (1e-3, errors[1]), (1e-4, errors[2])];
    match scene {
        SceneId::Cuboid => Some(Anchor {
            points: points([3e-6, 2e-10, 4e-12]),
            time_per_step: 4.3e-6,
        }),
        SceneId::Pendulum => Some(Anchor {
            points: points([2e-7, 4e-11, 2e-15]),
            time_per_step: 3.9e-6,
        }),
        SceneId::TopCusp => Some(Anchor {
            points: points([2e-4, 2e-8, 1e-12]),
            time_per_step: 4.3e-6,
        }),
        SceneId::RodOnCircle => Some(Anchor {
            points: points([8e-7, 8e-11, 8e-14]),
            time_per_step: 4.8e-6,
        }),
        SceneId::TopSteady | SceneId::RodOnSphere => None,
    }
}

/// The anchor as (CPU per simulated second, error) points.
pub fn work_precision_points(scene: SceneId) -> Option<Vec<(f64, f64)>> {
    anchor(scene).map(|a| {
        a.points
            .iter()
            .map(|&(dt, error)| (a.time_per_step / dt, error))
            .collect()
    })
}
