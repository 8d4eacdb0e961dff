//! # ga-macros: the `algebra!` macro
//!
//! Declares a geometric algebra and its sparse types in a module; the module receives fully unrolled
//! Rust code for them, compiled by [`ga_codegen`].
//!
//! ```
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
//!         ops = [geometric, outer, reverse, transform];   // optional: emit only these operations
//!         features = [display];                           // optional: impls of ecosystem traits
//!     }
//! }
//!
//! use pga::Transform as _;
//!
//! fn main() {
//!     // The point (1, 2, 3) is e123 + 1 e032 + 2 e013 + 3 e021; the stored blades are canonical.
//!     assert_eq!(pga::Point::BLADES, ["e012", "e013", "e023", "e123"]);
//!     let point = pga::Point::from_array([-3.0, 2.0, -1.0, 1.0]);
//!     // A translation by (10, 0, 0), and its composition with itself.
//!     let step = pga::Translator { scalar: 1.0, e01: -5.0, e02: 0.0, e03: 0.0 };
//!     let twice: pga::Motor = (step * step).into();
//!     assert_eq!(twice, pga::Motor { scalar: 1.0, e01: -10.0, ..pga::Motor::ZERO });
//!     assert_eq!(twice.transform(point), pga::Point::from_array([-3.0, 2.0, -21.0, 1.0]));
//!     assert_eq!(twice.to_string(), "1 - 10*e01");
//!     assert_eq!(pga::Plane { e1: 1.0, ..pga::Plane::ZERO } ^ pga::Plane { e2: 1.0, ..pga::Plane::ZERO },
//!                pga::Line { e12: 1.0, ..pga::Line::ZERO });
//! }
//! ```
//!
//! - Attributes and doc comments on the module are kept on the emitted module, and so is its
//!   visibility. Attributes on a type go onto its struct (see [Attributes on types](#attributes-on-types)).
//! - The settings may come in any order, each at most once. `scalar`, `basis` and `types` are
//!   required; `metric`, `ops` and `features` are optional (all operations are emitted without
//!   `ops`, no feature without `features`).
//! - `scalar` is `f32` or `f64`.
//! - `basis` lists the basis vectors in bit order, each with its square: `1`, `-1` or `0`.
//! - `metric` declares any symmetric bilinear form instead: `metric[i][j]` = B(eᵢ, eⱼ), rational
//!   entries (`1`, `-1`, `1/2`, `-1/2`), and then `basis` lists names only. CGA on a null basis, whose
//!   rigid motors have PGA's coefficient count:
//!
//!   ```
//!   ga_macros::algebra! {
//!       pub mod cga {
//!           scalar = f64;
//!           basis = [e1, e2, e3, n0, ninf];
//!           metric = [[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1, 0, 0], [0, 0, 0, 0, -1], [0, 0, 0, -1, 0]];
//!           types { Motor = blades(scalar, e1_e2, e1_e3, e2_e3, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf); }
//!           // Every operation emitted for `Motor` must have a type for its result: the complements
//!           // and the polarity of a motor are not motors, so list the operations that are.
//!           ops = [geometric, reverse, transform];
//!       }
//!   }
//!
//!   // As many coefficients as PGA's `Motor = grades(0, 2, 4)`:
//!   # let pga = ga_codegen::Algebra::new(&ga_codegen::AlgebraDeclaration {
//!   #     scalar: ga_codegen::ScalarType::F64,
//!   #     basis: [("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]
//!   #         .map(|(name, square)| ga_codegen::BasisVectorDeclaration { name: name.into(), square })
//!   #         .to_vec(),
//!   #     metric: None,
//!   #     types: vec![ga_codegen::TypeDeclaration {
//!   #         name: "Motor".into(),
//!   #         layout: ga_codegen::Layout::Grades(vec![0, 2, 4]),
//!   #     }],
//!   #     operations: None,
//!   #     lowering: vec![],
//!   #     expressions: vec![],
//!   # })
//!   # .unwrap();
//!   assert_eq!(cga::Motor::BLADES.len(), pga.types[0].fields.len());
//!   // Translators 1 − ½ t ninf compose by adding their vectors t.
//!   let translator = |[x, y, z]: [f64; 3]| cga::Motor {
//!       scalar: 1.0, e1_ninf: -x / 2.0, e2_ninf: -y / 2.0, e3_ninf: -z / 2.0, ..cga::Motor::ZERO
//!   };
//!   assert_eq!(translator([1.0, 2.0, 3.0]) * translator([4.0, 5.0, 6.0]), translator([5.0, 7.0, 9.0]));
//!   ```
//!
//!   Without `ops`, this declaration is refused at `Motor` (as `tests/ui/no_result_type.rs` checks):
//!   "no declared type holds the result of `Motor.right_complement()`: it needs the blades [n0,
//!   e1_e2_n0, …]; declare a type with them (or `Multivector = all`), or list only the operations you
//!   need in `ops = [...]`, without `right_complement`".
//!
//!   Blades are outer products of basis vectors (`e1_ninf` = e1 ∧ ninf), so grades keep their
//!   meaning. The complements and the regressive product stay metric-free, relative to the basis
//!   pseudoscalar `I = e1 ∧ … ∧ en`; the polarity is `a I⁻¹` and uses the metric.
//! - A type is `grades(…)` (every blade of those grades, in canonical order), `blades(…)` (exactly
//!   those blades in that order; `scalar` is the grade-0 blade, and a permuted name such as `e31`
//!   stores −`e13`) or `all` (the full multivector, for small algebras only).
//! - `ops` takes the method names of [`ga_codegen::Operation`], e.g. `geometric`, `outer`,
//!   `left_contraction`, `reverse`, `transform`. Every operation is emitted for every type (pair), so
//!   some declared type must hold each result.
//! - `transform` is the sandwich `a x ~a` for unit versors (`a ~a = 1`), using that identity to do
//!   less work than `sandwich`, which holds for any `a`. Each emitted function's doc comment states its
//!   exact cost (`Cost: … multiplies, … adds.`), as [`ga_codegen::functions::cost`] counts it; for a
//!   PGA motor moving a point:
//!
//!   ```
//!   use ga_codegen::{functions, Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, Operation};
//!   use ga_codegen::{ScalarType, TypeDeclaration};
//!
//!   let pga = Algebra::new(&AlgebraDeclaration {
//!       scalar: ScalarType::F64,
//!       basis: [("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]
//!           .map(|(name, square)| BasisVectorDeclaration { name: name.into(), square })
//!           .to_vec(),
//!       metric: None,
//!       types: [("Motor", vec![0, 2, 4]), ("Point", vec![3])]
//!           .map(|(name, grades)| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) })
//!           .to_vec(),
//!       operations: None,
//!       lowering: vec![],
//!       expressions: vec![],
//!   })?;
//!   let multiplies = |operation| {
//!       functions::cost(&pga, operation, "Motor", Some("Point")).map(|cost| cost.unwrap().multiplies)
//!   };
//!   assert_eq!(multiplies(Operation::Transform)?, 21);
//!   assert_eq!(multiplies(Operation::Sandwich)?, 30);
//!   # Ok::<(), ga_codegen::Error>(())
//!   ```
//! - A product in `ops` may say how it is emitted: `sandwich(table)` or `geometric(unrolled)`. Unrolled
//!   code (one sum per output blade, shared subexpressions hoisted) is the default and the fastest; a
//!   product whose expansion has more than [`MAX_UNROLLED_TERMS`](ga_codegen::table::MAX_UNROLLED_TERMS)
//!   monomials or more than [`MAX_UNROLLED_LOCALS`](ga_codegen::table::MAX_UNROLLED_LOCALS) hoisted
//!   locals is emitted table-driven instead (a constant table of products and a loop, still a `const fn`;
//!   its doc comment says so), so that it builds in seconds: the sandwich of two full Cl(5,1)
//!   multivectors (68 608 monomials) is two tables of 4096 products.
//! - `features` takes `display`, `approx` and `mint` (see [Features](#features)).
//! - `fn name(parameters) -> Type = expression;` items, any number of them anywhere among the
//!   settings, declare formulas to fuse into one function each (see [Fused expressions](#fused-expressions)).
//!
//! ## Fused expressions
//!
//! A `fn` item names a formula over the declared types; the module receives one `pub const fn` that
//! computes the whole formula at once: the compiler expands it exactly into one polynomial per blade
//! of the result, in the parameters' coefficients, so that whatever cancels (the grade-0 and grade-4
//! parts of `m * l * ~m` for a motor and a line) costs nothing, and then shares the work common to the
//! result's blades. The function's doc comment quotes the formula and states its exact cost
//! (`Cost: … multiplies, … adds.`), to compare with the products it replaces.
//!
//! ```
//! ga_macros::algebra! {
//!     pub mod pga {
//!         scalar = f64;
//!         basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
//!         types {
//!             Motor = grades(0, 2, 4);
//!             Line = grades(2);
//!             Point = grades(3);
//!         }
//!         ops = [reverse, transform];  // the expressions need none of the operations emitted
//!         fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
//!         fn moved_point(m: Motor, p: Point) = m * p * ~m;  // returns the smallest type that fits: Point
//!         fn moved_twice(m: Motor, l: Line) -> Line = moved_line(m, moved_line(m, l));
//!         fn blend(a: Motor, b: Motor, t: f64) -> Motor = (1 - t) * a + t * b;
//!         fn parts(m: Motor, t: f64) -> Motor = 0.5 * m.grade_0() + t * m.grade_2() / 4 - m.outer(m).grade_4();
//!     }
//! }
//!
//! use pga::{Line, Motor, Point, Transform as _};
//!
//! // The translation by (10, 0, 0) moves the point (1, 2, 3) to (11, 2, 3); the functions are `const`.
//! const STEP: Motor = Motor { scalar: 1.0, e01: -5.0, ..Motor::ZERO };
//! const MOVED: Point = pga::moved_point(STEP, Point::from_array([-3.0, 2.0, -1.0, 1.0]));
//!
//! fn main() {
//!     assert_eq!(MOVED, Point::from_array([-3.0, 2.0, -11.0, 1.0]));
//!     let line = Line::from_array([1.0, 2.0, 3.0, 0.0, 1.0, 0.0]);
//!     assert_eq!(pga::moved_line(STEP, line), STEP.transform(line));
//!     let leap = Motor { scalar: 1.0, e01: -10.0, ..Motor::ZERO };
//!     assert_eq!(pga::moved_twice(STEP, line), pga::moved_line(leap, line));
//!     assert_eq!(pga::blend(Motor { scalar: 1.0, ..Motor::ZERO }, leap, 0.25), Motor { e01: -2.5, ..leap });
//!     // 2 + e01 + 4 e12 + 6 e0123, whose outer square is 2 · 2 · 6 e0123 (e01 ∧ e12 = 0).
//!     let motor = Motor { scalar: 2.0, e01: 1.0, e12: 4.0, e0123: 6.0, ..Motor::ZERO };
//!     let expected = Motor { scalar: 1.0, e01: 0.5, e12: 2.0, e0123: -24.0, ..Motor::ZERO };
//!     assert_eq!(pga::parts(motor, 2.0), expected);
//! }
//! ```
//!
//! - The expression is Rust syntax with Rust's precedence and left associativity, so it means what
//!   the same text means with the emitted operators, from the loosest: `|` (left contraction), `^`
//!   (outer), `&` (regressive), `+` and `-`, `*` (geometric) and `/`, then the prefix `-` and `~`
//!   (the reverse, which is not Rust: `~m` is `m.reverse()`), then method calls. Parentheses group.
//! - `/` divides only by a number literal (`x / 2.0`, the product with 1/2), since anything else
//!   would not be a polynomial; `&&`, `||`, `!`, `%`, comparisons and assignments are refused.
//! - Methods: `grade_k()` (the grade-k part), the unary operations by name (`reverse()`,
//!   `involute()`, `conjugate()`, `right_complement()`, `left_complement()`, `polarity()`,
//!   `norm_squared()`) and the products by name with one argument (`a.outer(b)`,
//!   `a.left_contraction(b)`, `a.right_contraction(b)`, `a.scalar_product(b)`, `a.hestenes_inner(b)`,
//!   `a.fat_dot(b)`, `a.commutator(b)`, `a.sandwich(b)`, …), all of them whether or not `ops` lists
//!   them. `inverse()` divides and `transform(x)` assumes a unit versor, so neither can be fused.
//! - Numbers are integer or decimal literals without a suffix (`2`, `0.5`, `1e-3`), taken exactly
//!   as rationals (0.5 is 1/2), so the compiler's cancellations stay exact; a literal that is not a
//!   rational with a 64-bit numerator and denominator is refused.
//! - Parameters have a declared type or the scalar type (`t: f64`, a scalar on the blade `1`). The
//!   result type after `->` is optional; without it, the function returns the smallest declared
//!   type that holds the result's blades (`-> f64` returns a bare scalar). With it, the result's
//!   blades must fit in it.
//! - An expression may call another (`moved_line(m, l)`), declared before or after it: the call is
//!   inlined and fused with the rest. Each argument must fit its parameter's type; calls must not
//!   recurse.
//! - `#[linear(l)]` before an expression linear in its parameter `l` (which enters every term exactly
//!   once, as the line in `m * l * ~m`) also emits it as a matrix: `moved_line_map(m)` (a `const fn`
//!   of the other parameters) builds a `MovedLineMap { matrix }` once, whose `apply(l)` then costs one
//!   multiply per entry that does not vanish identically — the batched form for one motor moving many
//!   lines (PGA: 26 multiplies to build the 6×6, 27 per line after).
//!
//! ```
//! ga_macros::algebra! {
//!     pub mod pga {
//!         scalar = f64;
//!         basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
//!         types { Motor = grades(0, 2, 4); Line = grades(2); }
//!         ops = [reverse];
//!         #[linear(l)]
//!         fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
//!     }
//! }
//! use pga::{Line, Motor};
//!
//! let motor = Motor { scalar: 0.6, e12: 0.8, e01: 0.3, ..Motor::ZERO };
//! let map: pga::MovedLineMap = pga::moved_line_map(motor);
//! for line in [Line { e12: 1.0, ..Line::ZERO }, Line { e01: 2.0, e23: -1.0, ..Line::ZERO }] {
//!     let (applied, fused) = (map.apply(line), pga::moved_line(motor, line));
//!     assert!(applied.to_array().iter().zip(fused.to_array()).all(|(a, b)| (a - b).abs() < 1e-12));
//! }
//! ```
//!
//! Mistakes are reported at their token: the unknown name in a body, the unknown parameter or
//! result type, the call with the wrong number of arguments, the method `inverse`, the result type
//! that does not hold the result, the operator `&&`.
//!
//! ## exp, log, sqrt and normalized
//!
//! An expression whose whole body is `exp(x)`, `log(x)`, `sqrt(x)` or `normalized(x)` of its one
//! parameter is emitted in closed form ([`ga_codegen::transcendental`] has the derivations): its
//! invariants (`⟨b²⟩₀`, `b ∧ b`, …) expanded exactly as above, then series near zero or the
//! trigonometric and hyperbolic functions (so these functions need `std` and are not `const`).
//! `exp` takes a bivector type, the others an even type; `log` and `sqrt` are for unit elements
//! (`m ~m = 1`, e.g. from `normalized`). They are generated for every algebra with n ≤ 5
//! (Euclidean, 2D and 3D PGA, STA, CGA on either basis, Cl(2,1), Cl(2,2), Cl(3,2)), where a
//! bivector splits into two commuting planes whose squares are real or, with two basis vectors of
//! each sign, a complex-conjugate pair. `sqrt` and `normalized` need `m ~m` to be a scalar plus a
//! 4-vector squaring to a scalar and commuting with `m` (not so for a general even element of
//! Cl(4,1)), and are refused otherwise. These functions cannot be part of a larger formula. `log` of an element with `⟨m ~m⟩₀ ≤ 0` (zero, NaN)
//! has no logarithm and returns NaN in every coefficient; NaN passes through the others.
//!
//! ```
//! ga_macros::algebra! {
//!     pub mod pga {
//!         scalar = f64;
//!         basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
//!         types { Motor = grades(0, 2, 4); Line = grades(2); }
//!         ops = [geometric, reverse];
//!         fn exp_line(b: Line) -> Motor = exp(b);
//!         fn log_motor(m: Motor) -> Line = log(m);
//!         fn sqrt_motor(m: Motor) -> Motor = sqrt(m);
//!     }
//! }
//! use pga::Line;
//!
//! // A quarter turn about the z axis through (1, 0, 0), and 2 along it: a screw motion.
//! let screw = Line { e12: -std::f64::consts::FRAC_PI_4, e01: 0.25 * std::f64::consts::PI, e03: -1.0, ..Line::ZERO };
//! let motor = pga::exp_line(screw);
//! let back = pga::log_motor(motor);
//! assert!(back.to_array().iter().zip(screw.to_array()).all(|(a, b)| (a - b).abs() < 1e-15));
//! let half = pga::sqrt_motor(motor);
//! assert!(((half * half).to_array().iter().zip(motor.to_array())).all(|(a, b)| (a - b).abs() < 1e-15));
//! ```
//!
//! ## Attributes on types
//!
//! Attributes on a type declaration go onto its struct: doc comments before the generated ones, any
//! other attribute after the struct's own `#[derive(Clone, Copy, Debug, PartialEq, Default)]` and
//! `#[repr(C)]`. So the types can derive the traits of other crates, with their helper attributes:
//!
//! ```
//! ga_macros::algebra! {
//!     pub mod vga {
//!         scalar = f32;
//!         basis = [e1 = 1, e2 = 1, e3 = 1];
//!         types {
//!             /// A direction, stored in GPU buffers and scene files.
//!             #[derive(serde::Serialize, serde::Deserialize, bytemuck::Pod, bytemuck::Zeroable)]
//!             #[serde(deny_unknown_fields)]
//!             Vector = grades(1);
//!             Rotor = grades(0, 2);
//!         }
//!         ops = [reverse, transform];
//!     }
//! }
//!
//! fn main() {
//!     # assert_eq!(ga_codegen::emit::DERIVED_TRAITS, ["Clone", "Copy", "Debug", "PartialEq", "Default"]);
//!     let v = vga::Vector { e1: 1.0, e2: 2.0, e3: 3.0 };
//!     assert_eq!(serde_json::to_string(&v).unwrap(), r#"{"e1":1.0,"e2":2.0,"e3":3.0}"#);
//!     assert_eq!(bytemuck::cast_slice::<vga::Vector, f32>(&[v, v]), [1.0, 2.0, 3.0, 1.0, 2.0, 3.0]);
//! }
//! ```
//!
//! (The same as a program: `cargo run -p ga-macros --example derives`.) Refused, at the offending
//! token:
//! - `#[cfg(…)]`: it would remove the struct but not the operations emitted for it with the other
//!   types. Put the `cfg` on the module.
//! - A derive of `Clone`, `Copy`, `Debug`, `PartialEq` or `Default`: already derived (also under a
//!   `core::`/`std::` path). `Eq`, `Ord` and `Hash` cannot be derived for floating-point fields.
//!   `PartialOrd` and the traits of other crates are fine.
//! - A `repr` other than `C` and `align(N)`: `packed` (the fields all have the scalar type, so there
//!   is no padding to remove; packing would only lower the alignment and make `&v.e1` an error),
//!   `transparent`, `Rust`, integer types. `#[repr(C)]` may be written (bytemuck's `Pod` wants to see
//!   it) and is merged with the struct's own; `#[repr(align(16))]` raises the alignment.
//! - Inside `#[cfg_attr(predicate, …)]`, the same rules apply to each attribute it adds.
//!
//! Any other attribute (lint levels, `must_use`, derive helpers such as `serde(…)`) is passed
//! through, for rustc and the derives to check.
//!
//! ## Features
//!
//! `features = [display, approx, mint]` adds impls of ecosystem traits to every declared type; the
//! rest of the module is the same with or without them. The emitted code names `::approx` and
//! `::mint`, so the crate that invokes the macro must depend on those crates (`approx` 0.5, `mint`
//! 0.5.8 or later).
//! - `display`: `core::fmt::Display`, the non-zero coefficients as a sum of blades in storage order,
//!   each followed by `*` and its field's name (none for `scalar`), signs folded into ` + ` / ` - `:
//!   `1.5 + 2*e12 - 0.5*e0123`. Zero coefficients are skipped; all zero prints `0`. A precision
//!   (`{:.3}`) applies to every coefficient. The `*` keeps `2*e12` from reading as 2·10¹².
//! - `approx`: `approx::AbsDiffEq`, `RelativeEq` and `UlpsEq`, true when every coefficient is within
//!   the tolerance of the other's (with the scalar's default tolerances).
//! - `mint`: `From` both ways and `mint::IntoMint`, for the types with an unambiguous mint type,
//!   decided by [`ga_codegen::features::mint_mapping`]: 2, 3 or 4 grade-1 blades of orthonormal basis
//!   vectors are a `mint::Vector2`/`3`/`4` (`x`, `y`, `z`, `w` in basis order), and the scalar with
//!   the three bivectors of three orthonormal basis vectors a, b, c is a `mint::Quaternion` with
//!   `s` = scalar, `v` = (−e_bc, e_ac, −e_ab), the signs that make a unit rotor's `transform` rotate
//!   like the quaternion's `q v q*`. Other types get no conversion; `mint` with no such type is an
//!   error.
//!
//! ```
//! ga_macros::algebra! {
//!     pub mod vga {
//!         scalar = f64;
//!         basis = [e1 = 1, e2 = 1, e3 = 1];
//!         types { Vector = grades(1); Rotor = blades(scalar, e12, e13, e23); }
//!         ops = [reverse, transform];
//!         features = [display, approx, mint];
//!     }
//! }
//!
//! use vga::Transform as _;
//!
//! fn main() {
//!     // A quarter turn about the z axis, from a quaternion.
//!     let half = std::f64::consts::FRAC_PI_4;
//!     let z = mint::Vector3 { x: 0.0, y: 0.0, z: half.sin() };
//!     let rotor = vga::Rotor::from(mint::Quaternion { v: z, s: half.cos() });
//!     assert_eq!(format!("{rotor:.4}"), "0.7071 - 0.7071*e12");
//!     let turned = rotor.transform(vga::Vector { e1: 1.0, e2: 0.0, e3: 0.0 });
//!     approx::assert_relative_eq!(turned, vga::Vector { e1: 0.0, e2: 1.0, e3: 0.0 }, epsilon = 1e-15);
//!     let turned: mint::Vector3<f64> = turned.into();
//!     assert!((turned.y - 1.0).abs() < 1e-15);
//! }
//! ```
//!
//! ## Limits
//!
//! So that every accepted declaration builds in reasonable time and memory:
//! - At most 32 basis vectors (blades are 32-bit masks), and `all` only up to 10 dimensions: its
//!   products have 4ⁿ terms.
//! - At most 1024 fields in any type (2¹⁰, the size of `all` in 10 dimensions), since a product of two
//!   types has up to fields² terms. The count is checked before any blade is listed, so `grades(16)`
//!   in 32 dimensions (601 080 390 fields) is refused at once.
//! - A declaration's functions together take at most 8 000 000 units of build work: a product emitted as a
//!   table costs one unit per entry (the full geometric product in 10 dimensions has 1 048 576), an unrolled
//!   one 32 per multiply, since it is optimised by the macro and checked by rustc term by term. At the limit a
//!   debug build takes about 45 s on a 2-core machine (the macro runs unoptimised there); beyond it the
//!   declaration is refused at the type whose function crossed it, naming the total. `all` in 10 dimensions
//!   with every operation (6.3 million) builds in 23 s; ten types of Cl(5,1) with every operation (10 million)
//!   are refused: declare the operations you use in `ops = [...]`.
//! - Expressions nest at most 128 levels: each pair of parentheses, prefix operator, call and each operation
//!   in a chain of `*`, `^`, `&`, `|` or method calls is a level, while a sum of n terms is only log₂ n
//!   (`a + a + … + a` with 100 000 terms is fine). The compiler walks the tree recursively, on rustc's stack.
//!
//! These figures are the compiler's:
//!
//! ```
//! use ga_codegen::algebra::{MAX_DIMENSION, MAX_FULL_MULTIVECTOR_DIMENSION, MAX_TYPE_FIELDS};
//! use ga_codegen::functions::{MAX_BUILD_WORK, UNROLLED_MULTIPLY_WORK};
//!
//! assert_eq!((MAX_BUILD_WORK, UNROLLED_MULTIPLY_WORK), (8_000_000, 32));
//! use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Error, Layout, ScalarType, TypeDeclaration};
//!
//! assert_eq!((MAX_DIMENSION, MAX_FULL_MULTIVECTOR_DIMENSION, MAX_TYPE_FIELDS), (32, 10, 1024));
//! assert_eq!(MAX_TYPE_FIELDS, 1 << MAX_FULL_MULTIVECTOR_DIMENSION);
//! let middle = AlgebraDeclaration {
//!     scalar: ScalarType::F64,
//!     basis: (0..32).map(|i| BasisVectorDeclaration { name: format!("v{i}"), square: 1 }).collect(),
//!     metric: None,
//!     types: vec![TypeDeclaration { name: "Middle".into(), layout: Layout::Grades(vec![16]) }],
//!     operations: None,
//!     lowering: vec![],
//!     expressions: vec![],
//! };
//! assert!(matches!(Algebra::new(&middle), Err(Error::TooManyFields { fields: 601_080_390, .. })));
//! ```
//!
//! ## Names
//!
//! Names are Rust identifiers, Unicode included (`basis = [α = 1, β = 1]`); raw identifiers and
//! keywords are refused. Type names must differ in snake case (they name the `const fn` products, as
//! in `geometric_motor`) and must not be a name the module defines or uses: the trait of an emitted
//! binary operation (`Geometric`, `Sandwich`, …), `From`, `core`, `str` or the scalar type. When blade
//! names join basis vector names with `_` (`n0_ninf`), basis vector names must not contain `_`, and no
//! blade may be named `scalar` or a keyword (as `f` + `o` + `r` would be).
//!
//! Mistakes are compile errors at the offending token (the square `2`, the blade `e05`, the unknown
//! setting, the metric entry `0.5` or the entry that breaks its symmetry, the refused attribute, the
//! operation whose result no type holds), all of them at once where they are independent.

#![deny(missing_docs)]

// The pipeline, each module referring only to those before it (`tests/integration/module_order.rs`,
// docs/architecture.md): parse the input → validate it against the compiler's rules → expand it into the
// module's items.
mod diagnostics;
mod parse;
mod validate;
mod expand;

use proc_macro::TokenStream;

/// Declares a geometric algebra module; see the [crate documentation](crate) for the syntax.
#[proc_macro]
pub fn algebra(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as parse::AlgebraInput);
    validate::validate(&input)
        .and_then(|validated| expand::expand(&input, &validated))
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
