//! A four-bar linkage carried through near-toggle configurations: M2's layout (planar in x–z, hinges about y, under
//! gravity) with links chosen so that the coupler and the rocker come within 6.4° of collinear once per revolution,
//! its crank started at 2π rad/s. Near toggle the coupler's and rocker's rates grow like `1/sin μ'` (μ' the
//! supplement of the transmission angle), their accelerations like `1/sin³ μ'` and their higher derivatives faster
//! still, so the motion's speed varies sharply within each revolution: the case where steps chosen by the error
//! should pay.
//!
//! The linkage has one degree of freedom and no forces without a potential: the error of a run is its largest
//! energy drift (J), as for the chain.

use dynamics::constraints::{Stabilisation, VirtualPower};
use dynamics::joint_models::{JointKind, JointModel};
use dynamics::{Algebra, Body, Force, Mechanism, Reference, State};
use nalgebra::{Isometry3, Vector3};
use reference::multibody::FourBar;

use crate::mechanisms::state;
use crate::SceneError;

/// The near-toggle four-bar: ground 1 m, crank 0.3 m, coupler 0.7 m, rocker 0.602 m (so coupler + rocker exceeds
/// ground + crank by 2 mm: the crank turns fully, and at φ = π the transmission angle is 173.6°), M2's widths and
/// masses, started at φ = 0 turning at 2π rad/s, for 2 s.
pub const NEAR_TOGGLE: FourBar = FourBar {
    ground: 1.0,
    lengths: [0.3, 0.7, 0.602],
    width: 0.05,
    masses: [0.5, 1.0, 0.8],
    initial_angle: 0.0,
    initial_rate: std::f64::consts::TAU,
    duration: 2.0,
    revolution_period: 1.0,
};

/// The linkage under gravity and its start on the loop: the crank a joint model to the world at A, the coupler one
/// to the crank's end B, the rocker one to the ground pivot D, and the loop closed at C by a hinge (virtual power),
/// which puts the mechanism on the general solve; stabilised by projection.
pub fn build<A: Algebra>() -> Result<(Mechanism<A>, Vec<State<A>>), SceneError> {
    let four_bar = NEAR_TOGGLE;
    let [l1, l2, l3] = four_bar.lengths;
    let mut system = Mechanism::<A>::new();
    let mut bodies = Vec::new();
    let mut ids = Vec::new();
    for (name, link) in ["crank", "coupler", "rocker"].into_iter().zip(&four_bar.links()) {
        let body = Body::new(link.mass, link.principal_moments())?;
        let id = system.add_body(name, body)?;
        system.add_force(id, Force::gravity())?;
        ids.push(id);
        bodies.push(body);
    }
    let end = |length: f64, sign: f64| Isometry3::translation(0.0, 0.0, sign * 0.5 * length);
    let hinge = |name: &str, parent: Isometry3<f64>, child: Isometry3<f64>| {
        JointModel::new(name, JointKind::Revolute { axis: Vector3::y() }, parent, child)
    };
    system.connect(
        ids[0],
        Reference::World,
        hinge("A", Isometry3::identity(), end(l1, -1.0))?,
    )?;
    system.connect(ids[1], ids[0], hinge("B", end(l1, 1.0), end(l2, -1.0))?)?;
    let ground = Isometry3::translation(four_bar.ground, 0.0, 0.0);
    system.connect(ids[2], Reference::World, hinge("D", ground, end(l3, -1.0))?)?;
    let y = Vector3::y();
    let closing = VirtualPower::hinge(
        "C",
        (Vector3::new(0.0, 0.0, 0.5 * l3), y),
        (Vector3::new(0.0, 0.0, 0.5 * l2), y),
    )?;
    system.add_joint(ids[2], ids[1], closing)?;
    system.set_stabilisation(Stabilisation::PROJECTION)?;
    let classical = four_bar.state(four_bar.initial_angle, four_bar.initial_rate);
    let mut initial: Vec<State<A>> = bodies.iter().zip(&classical).map(|(b, c)| state(b, c)).collect();
    system.project(0.0, &mut initial)?;
    Ok((system, initial))
}
