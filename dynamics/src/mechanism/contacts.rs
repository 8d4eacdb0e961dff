//! A mechanism's contacts (docs/contacts.md): body points kept above world planes, their heights and normal
//! speeds, their rows in joint space, and the Newton projection that keeps a held contact on its plane.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::contacts::PlaneContact;
use crate::mechanism::error::MechanismError;
use crate::mechanism::model::Mechanism;
use crate::mechanism::parts::{BodyId, Contact};
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
    /// Keeps the point of `contact` (in `body`'s frame: the frame its joint models use, the principal frame unless the
    /// body was added with [`Mechanism::add_body_with_frame`]) above the contact's world plane, exactly and
    /// without friction ([`crate::contacts`]): [`crate::simulate()`] locates where it meets the plane, applies the
    /// impact, holds it there and releases it. Contacts need the articulated solve, as joint limits do: every joint a
    /// joint model, in a tree, and no Baumgarte stabilisation. Names are those of the transitions; a name must be new
    /// among the joints and contacts.
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Force, Mechanism, Pga};
    /// use nalgebra::Vector3;
    ///
    /// let block = Body::cuboid(1.0, Vector3::new(0.2, 0.2, 0.2))?;
    /// let mut scene = Mechanism::<Pga>::new();
    /// let id = scene.add_body("block", block)?;
    /// scene.add_force(id, Force::gravity())?;
    /// for (k, (x, y)) in [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)].into_iter().enumerate() {
    ///     let corner = PlaneContact::new(Vector3::new(x, y, -0.1), Vector3::z(), 0.0)?; // above the floor z = 0
    ///     scene.add_contact(format!("corner {k}"), id, corner)?;
    /// }
    /// assert_eq!(scene.contact_names().count(), 4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_contact(
        &mut self,
        name: impl Into<String>,
        body: BodyId,
        contact: PlaneContact,
    ) -> Result<(), MechanismError> {
        let name = name.into();
        if name.is_empty() {
            return Err(MechanismError::EmptyName("contact"));
        }
        let index = self.check_body(body)?;
        if self.contacts.iter().any(|c| c.name == name) || self.joints.iter().any(|j| j.name() == name) {
            return Err(MechanismError::DuplicateContact(name));
        }
        if self.articulation.is_none() || self.coordinates().is_none() {
            return Err(crate::ConstraintError::InvalidParameter {
                name,
                reason: "contacts need the articulated solve: every joint a joint model, in a tree, no Baumgarte \
                         stabilisation"
                    .to_owned(),
            }
            .into());
        }
        let point = self.bodies[index].frame.transform_point(&contact.point().into()).coords;
        if contact.friction().is_some() {
            self.frictional.push(self.contacts.len());
        }
        self.contacts.push(Contact {
            name,
            body: index,
            point,
            contact,
        });
        Ok(())
    }

    /// Every contact's height above its plane (m, negative below it) at `states`, in the order they were added; an
    /// error unless there is one state per body.
    ///
    /// ```
    /// use dynamics::{contacts::PlaneContact, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::new(1.0, Vector3::repeat(0.004))?;
    /// let mut scene = Mechanism::<Pga>::new();
    /// let id = scene.add_body("ball", ball)?;
    /// scene.add_contact("bottom", id, PlaneContact::new(Vector3::new(0.0, 0.0, -0.1), Vector3::z(), 0.0)?)?;
    /// let at = State::<Pga>::from_world_twist(&ball, Vector3::z() * 0.5, &UnitQuaternion::identity(), Vector3::zeros(), Vector3::zeros());
    /// assert!((scene.contact_heights(&[at])?[0] - 0.4).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn contact_heights(&self, states: &[State<A>]) -> Result<Vec<f64>, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok((0..self.contacts.len())
            .map(|c| self.contact_motion(c, states).0)
            .collect())
    }

    /// The contacts' names, in the order they were added.
    pub fn contact_names(&self) -> impl Iterator<Item = &str> {
        self.contacts.iter().map(|c| c.name.as_str())
    }

    /// Contact `index`'s point (world) in `state`, its body's.
    fn contact_point(&self, contact: &Contact, state: &State<A>) -> Vector3<f64> {
        let (position, rotation) = state.pose();
        position + rotation * contact.point
    }

    /// Contact `index`'s height above its plane (m) and its point's speed along the normal (m/s), at `states`.
    pub(super) fn contact_motion(&self, index: usize, states: &[State<A>]) -> (f64, f64) {
        let contact = &self.contacts[index];
        let state = &states[contact.body];
        let (position, rotation) = state.pose();
        let offset = rotation * contact.point;
        let point = position + offset;
        let velocity = state.world_velocity(&self.bodies[contact.body].body);
        let speed = velocity.linear + velocity.angular.cross(&offset);
        (contact.contact.height(&point), contact.contact.normal().dot(&speed))
    }

    /// The rows `c` of the contacts `indices` in joint space at `states`: `c · v` is the contact's normal speed at
    /// joint velocities v (the unit force along n through the point, as a generalised force).
    pub(super) fn contact_rows(&self, states: &[State<A>], indices: &[usize]) -> Result<DMatrix<f64>, ConstraintError> {
        let points: Vec<(usize, Vector3<f64>, Vector3<f64>)> = indices
            .iter()
            .map(|&i| {
                let contact = &self.contacts[i];
                let point = self.contact_point(contact, &states[contact.body]);
                (contact.body, point, contact.contact.normal())
            })
            .collect();
        self.point_jacobian(states, &points)
            .map_err(|error| ConstraintError::InvalidParameter {
                name: self.contact_names().collect::<Vec<_>>().join(" + "),
                reason: error.to_string(),
            })
    }

    /// Contacts `indices` placed on their planes and, with `stop`, stopped there, the slips of the `sticking` ones
    /// with them, the `equalities` rows (joint space) kept (docs/contacts.md "Projection"): Newton steps
    /// `δ = M⁻¹Cᵀ(CM⁻¹Cᵀ)⁺(−h)` on the joint positions (retracted onto the quaternions) until the heights h are within
    /// [`ON_PLANE`], then the normal speeds and the sticking slips removed by the same map.
    pub(super) fn place_contacts(
        &self,
        t: f64,
        states: &mut [State<A>],
        (indices, sticking, stop): (&[usize], &[usize], bool),
        equalities: &DMatrix<f64>,
        previous: &mut Vec<f64>,
    ) -> Result<(), ConstraintError> {
        let space = self.limited_space()?;
        let layout = space.layout();
        let (mut q, mut v) = (vec![0.0; space.position_count()], vec![0.0; space.velocity_count()]);
        self.read_joints_into(states, &mut q, &mut v, previous)?;
        let mut residual = DVector::zeros(indices.len() + equalities.nrows());
        for _ in 0..NEWTON_STEPS {
            let heights: Vec<f64> = indices.iter().map(|&i| self.contact_motion(i, states).0).collect();
            // Far from the origin a height cannot be closer to zero than a few ulps of the point's coordinates.
            let within = |(&i, h): (&usize, &f64)| {
                let contact = &self.contacts[i];
                let reach = self.contact_point(contact, &states[contact.body]).amax().abs();
                h.abs() <= ON_PLANE.max(4.0 * f64::EPSILON * reach)
            };
            if indices.iter().zip(&heights).all(within) {
                break;
            }
            residual.fill(0.0);
            heights.iter().enumerate().for_each(|(k, h)| residual[k] = -h);
            let rows = self.contact_rows(states, indices)?;
            let step = self.metric_correction(t, states, &rows, equalities, &residual)?;
            layout.retract(&mut q, step.as_slice());
            self.write_joints_into(t, &q, &v, states, &mut Vec::new())?;
        }
        if !stop {
            previous.clone_from(&q);
            return Ok(());
        }
        let rows = stack(&[&self.contact_rows(states, indices)?, &self.slip_rows(states, sticking)?]);
        let speeds = &rows * DVector::from_column_slice(&v);
        let mut residual = DVector::zeros(rows.nrows() + equalities.nrows());
        speeds.iter().enumerate().for_each(|(k, u)| residual[k] = -u);
        let change = self.metric_correction(t, states, &rows, equalities, &residual)?;
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        self.write_joints_into(t, &q, &v, states, &mut Vec::new())?;
        previous.clone_from(&q);
        Ok(())
    }
}

/// The Newton steps [`Mechanism::place_contacts`] takes at most (one is enough but for round-off: each squares the
/// height).
const NEWTON_STEPS: usize = 4;

/// Heights (m) within this of the plane count as on it (or within a few ulps of the point's coordinates, if more).
const ON_PLANE: f64 = 1e-14;

/// Rows stacked one matrix above the next (all with the same columns).
pub(super) fn stack(blocks: &[&DMatrix<f64>]) -> DMatrix<f64> {
    let columns = blocks.iter().map(|b| b.ncols()).max().unwrap_or(0);
    let total = blocks.iter().map(|b| b.nrows()).sum();
    let mut stacked = DMatrix::zeros(total, columns);
    let mut at = 0;
    for block in blocks {
        if block.nrows() > 0 {
            stacked
                .view_mut((at, 0), (block.nrows(), block.ncols()))
                .copy_from(block);
        }
        at += block.nrows();
    }
    stacked
}
