//! Emission: Rust tokens for the declared types and every operation between them.
//!
//! Per declared type: a `#[repr(C)]` struct with one pub field per blade, constructors and unary
//! methods (`const fn`). Binary operations are traits (`Geometric<Rhs>`, `Outer<Rhs>`, …) implemented
//! for every type pair, with `core::ops` sugar (`*` geometric, `^` outer, `&` regressive, `|` left
//! contraction); each is also an inherent `const fn` named after the operation and the right-hand
//! type (`a.geometric_motor(b)`), so products can be evaluated in constants and const assertions.
//! The code uses only `core`, but for the closed forms (`exp`, `log`, `sqrt`, `normalized`), which call `std`'s float
//! functions; each function's doc comment states its exact cost.
//!
//! One file per kind of item, declared in the order each builds on the ones before it: `emitter` (the state and the
//! small pieces: literals, identifiers, doc lines) → `code` (a function's body from its program or tables) → `types`
//! (the structs and their arithmetic) → `operations` (the operation traits, methods and impls) → `fused` (declared
//! expressions as one fused `const fn`, and linear maps) → `closed_form` (`exp`, `log`, `sqrt`, `normalized`) → `items`
//! (all of them in the module's order).

mod emitter;
mod code;
mod types;
mod operations;
mod fused;
mod closed_form;
mod items;

pub use items::{emit, emit_within, fused_function};
pub use operations::binary_function;
pub use types::DERIVED_TRAITS;
