//! The main job: every reference scene in both algebras with each integrator over a sweep of step
//! sizes; work-precision tables (`report.md`), PNG plots and trajectories as CSV.

pub mod plot;
