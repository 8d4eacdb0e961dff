//! # ga-codegen: a geometric algebra compiler
//!
//! Turns an algebra (basis vectors with their squares, or any symmetric bilinear form) and a set of
//! declared sparse types (Motor, Line, Point, …) into fully unrolled Rust code: one function per
//! operation and type pair, only the non-zero terms, cancellations found symbolically with exact
//! rational coefficients.
//!
//! ```
//! use ga_codegen::{AlgebraDeclaration, BasisVectorDeclaration, Evaluator, Layout, Operation};
//! use ga_codegen::{ScalarType, TypeDeclaration};
//!
//! // The plane (e1² = e2² = 1) with vectors and rotors (grades 0 and 2).
//! let basis = ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 });
//! let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
//! let declaration = AlgebraDeclaration {
//!     scalar: ScalarType::F32,
//!     basis: basis.to_vec(),
//!     metric: None,
//!     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
//!     operations: None,
//!     lowering: vec![],
//!     expressions: vec![],
//! };
//! let code = ga_codegen::pretty(&ga_codegen::generate(&declaration)?)?;
//! assert!(code.contains("pub struct Rotor"));
//!
//! // The same rules on dense multivectors (blade masks 1, e1, e2, e12): e1 e2 = e12.
//! let e1e2 = Evaluator::new(&[1, 1])?.binary(Operation::Geometric, &[0., 1., 0., 0.], &[0., 0., 1., 0.])?;
//! assert_eq!(e1e2, [0., 0., 0., 1.]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The pipeline, one module per stage:
//! 1. [`declaration`] → [`algebra`]: the validated algebra model ([`blade`] masks and names, [`metric`]);
//! 2. [`product`]: product rules computed per blade pair (never a dense 2ⁿ×2ⁿ table), a single
//!    signed blade on an orthogonal basis and an exact sum of blades for a general bilinear form
//!    (Chevalley's recursion);
//! 3. [`expand`]: symbolic expansion of an operation on two sparse types into polynomials; for the
//!    unit-versor `transform`, the two-stage form `x + a (x ~a − ~a x)`, equal to the sandwich when
//!    `a ~a = 1`;
//! 4. [`program`]: lowering to straight-line code (shared products, doubling), with the [`Cost`]
//!    model (exact multiply and add counts), or, for a product too big to unroll, [`table`]: constant
//!    tables and a loop; [`functions`] catalogues every emitted function and chooses between the two;
//! 5. [`emit`]: Rust tokens via `quote`; [`features`] emits the opt-in impls of ecosystem traits
//!    (`Display`, `approx`, `mint`).
//!
//! Declared formulas ([`expression`], e.g. `m * l * ~m`) take the same path as a whole: [`fuse`] expands
//! each exactly into one polynomial per output blade of any degree, lowers them together to one program
//! (and, for a formula linear in a parameter, to the matrix of that linear map), which [`emit`] prints as
//! a `const fn`.
//!
//! [`evaluator`] applies the same rules to dense coefficient vectors at run time: the oracle the
//! tests compare emitted code against, and a tool for exploring large algebras.
//!
//! Each module refers only to modules before it in the order declared below (`tests/integration/module_order.rs`
//! checks it; docs/architecture.md).
//!
//! Most users call it through the `algebra!` macro of `ga-macros`; [`generate`] is the library entry.

#![deny(missing_docs)]
// The declaration: blade masks, operations, the syntax tree of declared expressions, the declaration, its errors.
pub mod blade;
pub mod operation;
pub mod expression;
pub mod declaration;
pub mod error;
// The validated algebra model: the metric, the names of emitted items, the algebra.
pub mod metric;
mod naming;
pub mod algebra;
// Product rules per blade pair, and the evaluator applying them to dense multivectors.
pub mod product;
pub mod evaluator;
// Symbolic expansion of a product and its lowering to straight-line code or tables, one function each.
pub mod expand;
pub mod program;
pub mod table;
pub mod functions;
// Declared expressions expanded as a whole: fused into one function, or in closed form.
pub mod fuse;
pub mod transcendental;
// Emission: the opt-in trait impls, the Rust tokens.
pub mod features;
pub mod emit;

pub use algebra::{Algebra, Field, SparseType};
pub use declaration::{AlgebraDeclaration, BasisVectorDeclaration, Layout, Lowering, ScalarType, TypeDeclaration};
pub use error::{Error, EvaluatorError, Location, NameProblem};
pub use evaluator::Evaluator;
pub use expression::{Expression, ExpressionDeclaration, ExpressionKind, Parameter};
pub use features::Feature;
/// Exact rational numbers: metric entries and every coefficient of the expansion.
pub use num_rational::Rational64;
pub use operation::Operation;
pub use program::Cost;

/// Compiles a declaration into the items of a module (types, traits, impls); the caller wraps them
/// in `mod name { … }`.
pub fn generate(declaration: &AlgebraDeclaration) -> Result<proc_macro2::TokenStream, Error> {
    emit::emit(&Algebra::new(declaration)?)
}

/// [`generate`], followed by the impls of `features` for every declared type (see [`features`]).
/// The items [`generate`] emits are the same with or without features.
pub fn generate_with_features(
    declaration: &AlgebraDeclaration,
    features: &[Feature],
) -> Result<proc_macro2::TokenStream, Error> {
    let algebra = Algebra::new(declaration)?;
    let mut items = emit::emit(&algebra)?;
    items.extend(features::emit(&algebra, features));
    Ok(items)
}

/// Formats emitted tokens as readable Rust source (prettyplease), e.g. to inspect or snapshot them.
pub fn pretty(tokens: &proc_macro2::TokenStream) -> Result<String, syn::Error> {
    Ok(prettyplease::unparse(&syn::parse2::<syn::File>(tokens.clone())?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn features_only_add_items() {
        let declaration = AlgebraDeclaration {
            scalar: ScalarType::F64,
            basis: [("e1", 1), ("e2", 1)]
                .map(|(name, square)| BasisVectorDeclaration {
                    name: name.to_string(),
                    square,
                })
                .to_vec(),
            metric: None,
            types: vec![TypeDeclaration {
                name: "Vector".to_string(),
                layout: Layout::Grades(vec![1]),
            }],
            operations: Some(vec![Operation::Reverse]),
            lowering: vec![],
            expressions: vec![],
        };
        let plain = generate(&declaration).unwrap().to_string();
        assert_eq!(generate_with_features(&declaration, &[]).unwrap().to_string(), plain);
        let featured = generate_with_features(&declaration, &Feature::ALL).unwrap().to_string();
        assert!(featured.starts_with(&plain) && featured.len() > plain.len());
        assert!(featured.contains(":: mint :: Vector2"), "{featured}");
    }
}
