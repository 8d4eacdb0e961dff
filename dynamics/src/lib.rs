//! Rigid-body dynamics in CGA and PGA.
