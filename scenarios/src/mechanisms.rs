//! The mechanisms of `docs/scenes.md` (built from the GA-independent [`reference::multibody`] parameters) as
//! [`Mechanism`]s with their initial states, per algebra and per joint formulation:
//!
//! | scene | virtual power (theory §6, §14.1) | pinning (theory §7, §14.1) |
//! |---|---|---|
//! | M1 double pendulum | two hinges: 3 forces + 2 couples each | two hinges: line + point each |
//! | M2 four-bar linkage | four hinges, 20 rows of rank 17 | the same by pinned lines and points |
//! | M3 N-link chain | N ball joints: 3 forces each | N pinned points |
//!
//! Initial states come from the scenes' joint coordinates (exact forward kinematics) and are projected onto
//! the joint manifold (theory §10), which moves them by round-off only.

use std::sync::Arc;

use nalgebra::Vector3;
use reference::multibody::{BodyState, Link, CHAIN, DOUBLE_PENDULUM, FOUR_BAR};

use dynamics::constraints::{pinning, Constraint, PinningAlgebra, Stabilisation, VirtualPower};
use dynamics::{Body, BodyId, Force, Mechanism, Reference, State};

use crate::single_body::{Formulation, SceneError};

/// Which mechanism.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MechanismId {
    /// M1: the 3D double pendulum.
    DoublePendulum,
    /// M2: the four-bar linkage.
    FourBar,
    /// M3: a chain of this many links joined by ball joints.
    Chain(usize),
}

impl MechanismId {
    /// Short name with the `docs/scenes.md` scene number, e.g. `"M3 chain of 8"`.
    pub fn label(self) -> String {
        match self {
            MechanismId::DoublePendulum => "M1 double pendulum".to_owned(),
            MechanismId::FourBar => "M2 four-bar linkage".to_owned(),
            MechanismId::Chain(n) => format!("M3 chain of {n}"),
        }
    }

    /// The number of bodies.
    pub fn bodies(self) -> usize {
        match self {
            MechanismId::DoublePendulum => 2,
            MechanismId::FourBar => 3,
            MechanismId::Chain(n) => n,
        }
    }

    /// The simulated time of `docs/scenes.md`.
    pub fn duration(self) -> f64 {
        match self {
            MechanismId::DoublePendulum => DOUBLE_PENDULUM.duration,
            MechanismId::FourBar => FOUR_BAR.duration,
            MechanismId::Chain(_) => CHAIN.duration,
        }
    }
}

/// A mechanism ready to run: the system and its initial state (one per body, projected onto the joints).
#[derive(Clone, Debug)]
pub struct MechanismScene<A: dynamics::Algebra> {
    /// Which mechanism this is.
    pub id: MechanismId,
    /// How its joints are written.
    pub formulation: Formulation,
    /// The bodies, joints, gravity and stabilisation.
    pub system: Mechanism<A>,
    /// Each body's initial state, in link order, projected onto the joint manifold.
    pub initial: Vec<State<A>>,
}

/// A body's state from its classical state.
pub fn state<A: dynamics::Algebra>(body: &Body, classical: &BodyState) -> State<A> {
    State::new(
        body,
        classical.position,
        &classical.orientation,
        classical
            .orientation
            .inverse_transform_vector(&classical.angular_velocity),
        classical.velocity,
    )
}

fn body(link: &Link) -> Result<Body, SceneError> {
    Ok(Body::new(link.mass, link.principal_moments())?)
}

/// A hinge of `body` to `reference` through the given points about the given axes, by either formulation.
fn hinge<A: PinningAlgebra>(
    formulation: Formulation,
    name: String,
    body: (Vector3<f64>, Vector3<f64>),
    reference: (Vector3<f64>, Vector3<f64>),
) -> Result<Arc<dyn Constraint<A>>, SceneError> {
    Ok(match formulation {
        Formulation::VirtualPower => Arc::new(VirtualPower::hinge(name, body, reference)?),
        Formulation::Pinning => Arc::new(pinning::hinge::<A>(name, body, reference)?),
    })
}

/// A ball joint of `body_point` to `reference_point`, by either formulation.
fn ball<A: PinningAlgebra>(
    formulation: Formulation,
    name: String,
    body_point: Vector3<f64>,
    reference_point: Vector3<f64>,
) -> Arc<dyn Constraint<A>> {
    match formulation {
        Formulation::VirtualPower => Arc::new(VirtualPower::ball_joint(name, body_point, reference_point)),
        Formulation::Pinning => Arc::new(pinning::point::<A>(name, body_point, reference_point)),
    }
}

/// Builds a mechanism from `docs/scenes.md` in algebra `A` with joints written by `formulation`, stabilised by
/// `stabilisation`; the initial state is projected onto the joint manifold.
pub fn build_mechanism<A: PinningAlgebra>(
    id: MechanismId,
    formulation: Formulation,
    stabilisation: Stabilisation,
) -> Result<MechanismScene<A>, SceneError> {
    build_mechanism_at(id, formulation, stabilisation, Vector3::zeros())
}

/// [`build_mechanism`] moved by `offset`: its world pivots and its bodies' initial positions, so that the same
/// motion runs `offset` away from the world origin. An offset that is not finite or has a coordinate beyond
/// [`dynamics::state::LARGEST_COORDINATE`] is [`SceneError::Offset`].
pub fn build_mechanism_at<A: PinningAlgebra>(
    id: MechanismId,
    formulation: Formulation,
    stabilisation: Stabilisation,
    offset: Vector3<f64>,
) -> Result<MechanismScene<A>, SceneError> {
    let largest = dynamics::state::LARGEST_COORDINATE;
    if !offset.iter().all(|x| x.abs() <= largest) {
        return Err(SceneError::Offset {
            offset: offset.into(),
            largest,
        });
    }
    let mut system = Mechanism::<A>::new();
    let gravity = Force::Gravity {
        acceleration: Vector3::new(0.0, 0.0, -reference::scenes::GRAVITY),
    };
    let add = |system: &mut Mechanism<A>, name: String, link: &Link| -> Result<(BodyId, Body), SceneError> {
        let body = body(link)?;
        let id = system.add_body(name, body)?;
        system.add_force(id, gravity.clone())?;
        Ok((id, body))
    };
    let classical: Vec<BodyState>;
    let mut bodies = Vec::new();
    match id {
        MechanismId::DoublePendulum => {
            let m1 = DOUBLE_PENDULUM;
            let (first, b1) = add(&mut system, "link 1".into(), &m1.links[0])?;
            let (second, b2) = add(&mut system, "link 2".into(), &m1.links[1])?;
            bodies.extend([b1, b2]);
            system.add_joint(
                first,
                Reference::World,
                hinge::<A>(
                    formulation,
                    "hinge 1".into(),
                    (m1.hinge_1_on_link_1, Vector3::x()),
                    (m1.pivot + offset, Vector3::x()),
                )?,
            )?;
            system.add_joint(
                second,
                first,
                hinge::<A>(
                    formulation,
                    "hinge 2".into(),
                    (m1.hinge_2_on_link_2, Vector3::y()),
                    (m1.hinge_2_on_link_1, Vector3::y()),
                )?,
            )?;
            classical = m1.initial_state().to_vec();
        }
        MechanismId::FourBar => {
            let m2 = FOUR_BAR;
            let links = m2.links();
            let [l1, l2, l3] = m2.lengths;
            let (crank, b1) = add(&mut system, "crank".into(), &links[0])?;
            let (coupler, b2) = add(&mut system, "coupler".into(), &links[1])?;
            let (rocker, b3) = add(&mut system, "rocker".into(), &links[2])?;
            bodies.extend([b1, b2, b3]);
            let end = |length: f64, sign: f64| Vector3::new(0.0, 0.0, sign * 0.5 * length);
            let y = Vector3::y();
            system.add_joint(
                crank,
                Reference::World,
                hinge::<A>(formulation, "A".into(), (end(l1, -1.0), y), (offset, y))?,
            )?;
            system.add_joint(
                coupler,
                crank,
                hinge::<A>(formulation, "B".into(), (end(l2, -1.0), y), (end(l1, 1.0), y))?,
            )?;
            system.add_joint(
                rocker,
                coupler,
                hinge::<A>(formulation, "C".into(), (end(l3, 1.0), y), (end(l2, 1.0), y))?,
            )?;
            system.add_joint(
                rocker,
                Reference::World,
                hinge::<A>(
                    formulation,
                    "D".into(),
                    (end(l3, -1.0), y),
                    (Vector3::new(m2.ground, 0.0, 0.0) + offset, y),
                )?,
            )?;
            classical = m2.initial_state().to_vec();
        }
        MechanismId::Chain(links) => {
            let half = CHAIN.half_length();
            let (top, bottom) = (Vector3::new(0.0, 0.0, half), Vector3::new(0.0, 0.0, -half));
            let mut previous: Option<BodyId> = None;
            for k in 0..links {
                let (link, b) = add(&mut system, format!("link {}", k + 1), &CHAIN.link)?;
                bodies.push(b);
                let (reference, reference_point) = match previous {
                    None => (Reference::World, offset),
                    Some(p) => (Reference::Body(p), bottom),
                };
                system.add_joint(
                    link,
                    reference,
                    ball::<A>(formulation, format!("ball {}", k + 1), top, reference_point),
                )?;
                previous = Some(link);
            }
            classical = CHAIN.initial_state(links);
        }
    }
    system.set_stabilisation(stabilisation)?;
    let mut initial: Vec<State<A>> = bodies
        .iter()
        .zip(&classical)
        .map(|(b, c)| {
            state(
                b,
                &BodyState {
                    position: c.position + offset,
                    ..*c
                },
            )
        })
        .collect();
    system.project(0.0, &mut initial)?;
    Ok(MechanismScene {
        id,
        formulation,
        system,
        initial,
    })
}
