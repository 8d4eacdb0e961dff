//! Shared by the integration tests: scene 1 set up from the reference crate, conversion of a run to a reference
//! trajectory, and (from `dynamics`' test support) the random source and the both-algebras macro.

#[macro_use]
#[path = "../../../../dynamics/tests/integration/common/mod.rs"]
mod support;

pub use support::Random;

use dynamics::simulate::Simulation;
use dynamics::{Algebra, Body, FreeBody, State};
use reference::{SceneId, SceneParameters, Trajectory};

/// Scene 1 (docs/scenes.md): the free Dzhanibekov cuboid, its body and initial state.
pub struct Cuboid<A: Algebra> {
    pub scene: SceneParameters,
    pub body: Body,
    pub system: FreeBody<A>,
    pub initial: State<A>,
}

pub fn cuboid<A: Algebra>() -> Cuboid<A> {
    let scene = SceneId::Cuboid.parameters();
    let body = Body::new(scene.mass, scene.principal_moments).expect("scene 1 body is physical");
    let initial = State::<A>::new(
        &body,
        scene.initial_com,
        &scene.initial_orientation,
        scene.initial_body_angular_velocity,
        scene.initial_com_velocity,
    );
    Cuboid {
        scene,
        body,
        system: FreeBody::new(body),
        initial,
    }
}

/// A single-body run's samples as a reference trajectory, for the reference crate's metrics.
pub fn trajectory<A: Algebra>(run: &Simulation<A>) -> Trajectory {
    scenarios::trajectory(run.body(0)).expect("a run records samples with increasing times")
}
