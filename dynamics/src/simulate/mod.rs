//! Running a system of rigid bodies over time: recording every body at chosen times, calling an observer after
//! every step, and locating events.
//!
//! A [`Schedule`] fixes the step and the sample times: a grid (by default every 0.01 s, the grid of the reference
//! scenes), which the step must divide so every sample falls on a step, or any list of times
//! ([`Schedule::at_times`]), any step size. A sample between two steps is taken by a partial step from the
//! last step's state — the method's own solution at that time, of its order and on the group (motors stay
//! motors) — which does not change the steps that follow.
//!
//! A [`Plan`] adds to a schedule an observer called after every step, which may stop the run, and [`Event`]s:
//! scalar functions of the state whose zero crossings are located to round-off by partial steps (a pendulum's
//! turning points, a body point reaching a plane), with a direction filter, and optionally terminal.
//!
//! A system with joint limits ([`crate::limits`], `docs/limits.md`) has each limit watched like an event: a step is
//! cut where a limit's gap closes or its reaction stops pushing, located to round-off, the impact, hold or release
//! made there ([`Simulation::transitions`]), and the run continues from it.
//!
//! [`simulate`] is the one entry point, for free bodies, constrained bodies and mechanisms, with any
//! [`Integrator`](crate::Integrator); it allocates once (the samples) and measures the CPU time of the stepping alone, for
//! work-precision comparisons.

mod error;
mod schedule;
mod events;
mod one_sided;
mod run;

pub use crate::limits::AT_BOUND;
pub use error::SimulationError;
pub use error::MAX_SAMPLES;
pub use events::{Crossing, Event, EventHit, Plan};
pub use one_sided::TRANSITIONS_IN_A_ROW;
pub use run::{simulate, Sample, Simulation, Stop};
pub use schedule::{Schedule, MAX_ADAPTIVE_STEPS, SAMPLE_INTERVAL};
