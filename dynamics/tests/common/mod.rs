//! Shared by the integration tests: scene 1 set up from the reference crate, conversion of a run to a
//! reference trajectory, a deterministic random source, and a macro that instantiates generic tests for
//! both algebras.
#![allow(dead_code)] // each test binary uses a different subset

use dynamics::simulate::Simulation;
use dynamics::{Algebra, Body, FreeBody, State};
use reference::{SceneId, SceneParameters, Trajectory};

/// Instantiates generic test functions `fn name<A: Algebra>()` as `pga::name` and `cga::name`.
#[macro_export]
macro_rules! for_both_algebras {
    ($($test:ident),* $(,)?) => {
        mod pga { $( #[test] fn $test() { super::$test::<dynamics::Pga>(); } )* }
        mod cga { $( #[test] fn $test() { super::$test::<dynamics::Cga>(); } )* }
    };
}

/// Scene 1 (SCENES.md): the free Dzhanibekov cuboid, its body and initial state.
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

/// A run's samples as a reference trajectory, for the reference crate's metrics.
pub fn trajectory<A: Algebra>(run: &Simulation<A>) -> Trajectory {
    run.trajectory().expect("a run records samples with increasing times")
}

/// A deterministic xorshift source of numbers in [−1, 1).
pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Self {
        Random(seed.max(1))
    }

    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    pub fn vector(&mut self, scale: f64) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.next(), self.next(), self.next()) * scale
    }

    pub fn rotation(&mut self) -> nalgebra::UnitQuaternion<f64> {
        // A uniformly spread axis-angle up to π.
        nalgebra::UnitQuaternion::from_scaled_axis(self.vector(std::f64::consts::PI / 3f64.sqrt()))
    }
}
