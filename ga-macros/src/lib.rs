//! # ga-macros: the `algebra!` macro
//!
//! Declares a geometric algebra and its sparse types in a module; the module receives fully unrolled
//! Rust code for them, compiled by [`ga_codegen`].
//!
//! ```ignore
//! ga_macros::algebra! {
//!     /// 3D projective geometric algebra.
//!     pub mod pga {
//!         scalar = f64;                                   // or f32
//!         basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];       // names and squares, in bit order
//!         types {
//!             Plane = grades(1);
//!             Line = grades(2);
//!             Point = grades(3);
//!             /// A rigid motion.
//!             Motor = grades(0, 2, 4);
//!             Translator = blades(scalar, e01, e02, e03);
//!             Multivector = all;
//!         }
//!         ops = [geometric, outer, reverse];              // optional: emit only these operations
//!     }
//! }
//! ```
//!
//! - Attributes and doc comments on the module are kept on the emitted module, and so is its
//!   visibility. Doc comments on a type are kept on its struct; other attributes on a type are refused.
//! - The settings may come in any order, each at most once. `scalar`, `basis` and `types` are
//!   required; `metric` and `ops` are optional (all operations are emitted without `ops`).
//! - `scalar` is `f32` or `f64`.
//! - `basis` lists the basis vectors in bit order, each with its square: `1`, `-1` or `0`.
//! - `metric` declares any symmetric bilinear form instead: `metric[i][j]` = B(eᵢ, eⱼ), rational
//!   entries (`1`, `-1`, `1/2`, `-1/2`), and then `basis` lists names only. CGA on a null basis, whose
//!   rigid motors have PGA's 8 coefficients:
//!
//!   ```ignore
//!   basis = [e1, e2, e3, n0, ninf];
//!   metric = [[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1, 0, 0], [0, 0, 0, 0, -1], [0, 0, 0, -1, 0]];
//!   types { Motor = blades(scalar, e1_e2, e1_e3, e2_e3, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf); }
//!   ```
//!
//!   Blades are outer products of basis vectors (`e1_ninf` = e1 ∧ ninf), so grades keep their
//!   meaning. The complements and the regressive product stay metric-free, relative to the basis
//!   pseudoscalar `I = e1 ∧ … ∧ en`; the polarity is `a I⁻¹` and uses the metric.
//! - A type is `grades(…)` (every blade of those grades, in canonical order), `blades(…)` (exactly
//!   those blades in that order; `scalar` is the grade-0 blade, and a permuted name such as `e31`
//!   stores −`e13`) or `all` (the full multivector, for small algebras only).
//! - `ops` takes the method names of [`ga_codegen::Operation`], e.g. `geometric`, `outer`,
//!   `left_contraction`, `reverse`, `transform`.
//! - `transform` is the sandwich `a x ~a` for unit versors (`a ~a = 1`), using that identity to do
//!   less work: a unit PGA motor moves a point in 22 multiplies instead of the sandwich's 35.
//!
//! Limits, so that every accepted declaration builds in reasonable time and memory:
//! - At most 32 basis vectors (blades are 32-bit masks), and `all` only up to 10 dimensions: its
//!   products have 4ⁿ terms.
//! - At most 1024 fields in any type (2¹⁰, the size of `all` in 10 dimensions), since a product of two
//!   types has up to fields² terms. The count is checked before any blade is listed, so `grades(16)`
//!   in 32 dimensions (601 080 390 fields) is refused at once.
//!
//! Names are Rust identifiers, Unicode included (`basis = [α = 1, β = 1]`); raw identifiers and
//! keywords are refused. Type names must differ in snake case (they name the `const fn` products, as
//! in `geometric_motor`) and must not be a name the module defines or uses: the trait of an emitted
//! binary operation (`Geometric`, `Sandwich`, …), `From`, `core`, `str` or the scalar type. When blade
//! names join basis vector names with `_` (`n0_ninf`), basis vector names must not contain `_`, and no
//! blade may be named `scalar` or a keyword (as `f` + `o` + `r` would be).
//!
//! Mistakes are compile errors at the offending token (the square `2`, the blade `e05`, the unknown
//! setting, the metric entry `0.5` or the entry that breaks its symmetry), all of them at once where
//! they are independent.

mod diagnostics;
mod expand;
mod parse;
mod validate;

use proc_macro::TokenStream;

/// Declares a geometric algebra module; see the [crate documentation](crate) for the syntax.
#[proc_macro]
pub fn algebra(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as parse::AlgebraInput);
    validate::validate(&input)
        .and_then(|declaration| expand::expand(&input, &declaration))
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
