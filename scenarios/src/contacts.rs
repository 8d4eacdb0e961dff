//! Contact scenes (docs/contacts.md), as the report shows them: a cube dropped flat onto a floor, whose four bottom
//! corners land together at the free-fall time and bounce, and a cube dropped tumbling, its eight corners bouncing
//! until it rests on a face.

use dynamics::contacts::PlaneContact;
use dynamics::{Algebra, Body, Force, Mechanism, MechanismError, State};
use nalgebra::{Unit, UnitQuaternion, Vector3};

/// A 0.2 m cube of 1 kg above the floor z = 0, its corners kept above it with restitution 0.5.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactScene {
    /// Released at rest with its bottom face level, 0.5 m above the floor: it lands on four corners at once at
    /// `√(2h/g)` and bounces straight up at half the speed, again and again.
    FlatDrop,
    /// Released 0.4 m up (its centre 0.5 m), turned 30° about (1, 0.3, 0), spinning at (0, 2, 3) rad/s (body axes) and
    /// moving at 0.5 m/s along x: its corners bounce until it rests on a face, sliding and spinning on the frictionless
    /// floor.
    TumblingCube,
}

/// The cube's half side (m) and the flat drop's height (m, bottom face above the floor).
const HALF: f64 = 0.1;
const DROP: f64 = 0.5;

impl ContactScene {
    /// Every contact scene.
    pub const ALL: [ContactScene; 2] = [ContactScene::FlatDrop, ContactScene::TumblingCube];

    /// A short name for tables and figures.
    pub fn label(self) -> &'static str {
        match self {
            ContactScene::FlatDrop => "cube dropped flat",
            ContactScene::TumblingCube => "cube dropped tumbling",
        }
    }

    /// The simulated time (s).
    pub fn duration(self) -> f64 {
        match self {
            ContactScene::FlatDrop => 1.2,
            ContactScene::TumblingCube => 3.0,
        }
    }

    /// The cube's corners (body frame): the bottom four, then the top four.
    pub fn corners() -> [Vector3<f64>; 8] {
        let square = [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)];
        std::array::from_fn(|k| {
            let (x, y) = square[k % 4];
            Vector3::new(x, y, if k < 4 { -HALF } else { HALF })
        })
    }

    /// The cube, its contacts and its start.
    pub fn build<A: Algebra>(self) -> Result<(Mechanism<A>, Vec<State<A>>), MechanismError> {
        let cube = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).expect("a valid cube");
        let mut system = Mechanism::<A>::new();
        let id = system.add_body("cube", cube)?;
        system.add_force(id, Force::gravity())?;
        for (k, corner) in Self::corners().into_iter().enumerate() {
            let contact = PlaneContact::new(corner, Vector3::z(), 0.0)?.with_restitution(0.5)?;
            system.add_contact(format!("corner {}", k + 1), id, contact)?;
        }
        let start = match self {
            ContactScene::FlatDrop => State::from_world_twist(
                &cube,
                Vector3::new(0.0, 0.0, DROP + HALF),
                &UnitQuaternion::identity(),
                Vector3::zeros(),
                Vector3::zeros(),
            ),
            ContactScene::TumblingCube => {
                let turn = UnitQuaternion::from_axis_angle(
                    &Unit::new_normalize(Vector3::new(1.0, 0.3, 0.0)),
                    30f64.to_radians(),
                );
                State::from_world_twist(
                    &cube,
                    Vector3::new(0.0, 0.0, 0.5),
                    &turn,
                    turn * Vector3::new(0.0, 2.0, 3.0),
                    Vector3::new(0.5, 0.0, 0.0),
                )
            }
        };
        Ok((system, vec![start]))
    }

    /// The exact time of the first impact, where the scene has one in closed form: free fall from rest through the
    /// drop h, `√(2h/g)`.
    pub fn exact_first_impact(self) -> Option<f64> {
        match self {
            ContactScene::FlatDrop => Some((2.0 * DROP / dynamics::forces::STANDARD_GRAVITY).sqrt()),
            ContactScene::TumblingCube => None,
        }
    }
}
