//! `exp`, `log`, `sqrt` and `normalized`, generated in closed form: an expression whose whole body is one of
//! them applied to a parameter (`fn exp_line(b: Line) -> Motor = exp(b);`) is emitted as a function that combines
//! exact polynomial pieces of its argument (expanded and lowered as in [`crate::fuse`]) with a few scalar
//! functions (`sqrt`, `sin`, `cos`, …, so the emitted function needs `std`, and is not `const`).
//!
//! **The invariant decomposition** (Roelfs and De Keninck, "Graded symmetry groups: plane and simple", 2021)
//! writes a bivector of an algebra with n ≤ 5 as the sum of at most two commuting simple bivectors `B = B₁ + B₂`
//! with scalar squares `λᵢ = Bᵢ²`: `B² = λ₁ + λ₂ + W` with `W = B ∧ B = 2B₁B₂`, so λ₁ and λ₂ are the roots of
//! `λ² − ⟨B²⟩₀ λ + ¼W² = 0`, and `½W B = λ₁B₂ + λ₂B₁` (both checked on the exact expansion: W² a scalar, ½WB a
//! bivector). With `c(λ) = Σ λᵏ/(2k)!` (cos √−λ, cosh √λ) and `s(λ) = Σ λᵏ/(2k+1)!` (sin √−λ / √−λ, …) each
//! plane's exponential is `c(λᵢ) + s(λᵢ) Bᵢ`, and solving the two equations for B₁ and B₂ gives
//!
//! ```text
//! exp(B) = c₁c₂ + β B + s₁s₂ ½W + δ ½⟨W B⟩₂,
//! β = c₂ H[λ₁, λ₂] − λ₂ s₂ C[λ₁, λ₂],   δ = s₂ C[λ₁, λ₂] − c₂ S[λ₁, λ₂],
//! ```
//!
//! with `X[λ₁, λ₂] = (X(λ₁) − X(λ₂))/(λ₁ − λ₂)` the divided differences of c, s and `H(λ) = λ s(λ)`. They are
//! computed by series below |λ| = 0.1 (`Σ aₙ hₙ₋₁(λ₁, λ₂)`, the complete homogeneous polynomials), as differences
//! when the λ's are well apart, and for two close rotations `xᵢ = √−λᵢ` from their half sum u and half
//! difference v, which have no cancellation: `C[] = ½ sinc u sinc v`, `S[] = −(u cos u sinc v − sin u cos v) /
//! (2u(u² − v²))`, `H[] = (u cos u sinc v + sin u cos v)/(2u)`.
//!
//! **Two basis vectors of each sign** (Cl(2,2), Cl(3,2), Cl(2,3), also with a null vector). Two more cases occur
//! there, and only there (with at most one vector of one sign the λ's are real and at most one is positive), so
//! they are emitted only for such metrics ([`ClosedForm::indefinite`]):
//! - *Two close boosts*, `λᵢ = xᵢ² > 0`. With `shc x = sinh x / x` the same half-sum and half-difference forms
//!   hold with hyperbolic functions: `cosh x₁ − cosh x₂ = 2 sinh u sinh v` and `x₁² − x₂² = 4uv` give
//!   `C[] = ½ shc u shc v`; `u(sinh x₁ − sinh x₂) ∓ v(sinh x₁ + sinh x₂)` over `x₁x₂ · 4uv` give
//!   `S[] = (u cosh u shc v − sinh u cosh v)/(2u(u² − v²))` and `H[] = (u cosh u shc v + sinh u cosh v)/(2u)`.
//! - *A complex pair*, `λ₁ = a + ib`, `λ₂ = λ̄₁` (the discriminant `⟨B²⟩₀² − ⟨W²⟩₀` negative). c and s are real
//!   power series, so `c(λ₂) = c̄₁` and `s(λ₂) = s̄₁`: then `c₁c₂ = |c₁|²`, `s₁s₂ = |s₁|²`, and each divided
//!   difference is `X[λ₁, λ̄₁] = 2i Im X(λ₁) / 2i Im λ₁ = Im X(λ₁)/b`, real, and without cancellation since
//!   `Im X(λ₁)` is computed directly (`Im c(λ₁) = −sin x sinh y` for `x + iy = √−λ₁`, or by the series in
//!   complex arithmetic below |λ| = 0.1). In `β = c̄₁ H[] − conj(λ₁s₁) C[]` the imaginary part is
//!   `(−Im c₁ Im H₁ + Im H₁ Im c₁)/b = 0`, and likewise in δ, so `β = Re c₁ H[] − Re(λ₁s₁) C[]` and
//!   `δ = Re s₁ C[] − Re c₁ S[]`, with `H[] = Im(λ₁s₁)/b = a S[] + Re s₁`.
//!   For log the `w`'s are then a conjugate pair too; `λ₁ = y²` with `y = asinh √w₁` (since `s²λ = sinh²y`),
//!   evaluated as `ln(1 + u)`, `u = ζ + w₁/(1 + √(1 + w₁))`, `ζ = √w₁`, whose denominator has real part at least 1.
//!   The principal branches give `c₁ = √(1 + w₁)` with non-negative real part, so `⟨M⟩₀ = c₁c₂ = |c₁|²` must be
//!   positive: an element with a complex pair and `⟨M⟩₀ ≤ 0` has no logarithm (NaN).
//!
//! **One non-null plane** (W² = 0 identically: every algebra with n ≤ 3, 3D PGA's lines, CGA's rigid screws on
//! the null basis): then λ₂ = 0, `λ = ⟨B²⟩₀`, and with `d = (c − s)/λ` the formula is
//!
//! ```text
//! exp(B) = c + s B + s ½W + d ½⟨W B⟩₂.
//! ```
//!
//! **log** of a unit element turning in two planes. With `σ = ⟨⟨M⟩₂²⟩₀` and `q = ⟨⟨M⟩₄²⟩₀`, the planes'
//! `wᵢ = sᵢ²λᵢ` (−sin²θᵢ, sinh²xᵢ) are the roots of `w² − (σ − 2q) w + q` (from `cᵢ² − sᵢ²λᵢ = 1` and
//! `M ~M = 1`, without cancellation near M = 1). The plane with the larger cosine takes it from `√(1 + w)`, the
//! other is `⟨M⟩₀` divided by it, which gives θᵢ or xᵢ and so λᵢ. Then `⟨M⟩₂ = (β + (δ/γ)⟨M⟩₄) B` with β, γ = s₁s₂
//! and δ of exp, and `⟨M⟩₄²= q` a scalar, so `B = (β ⟨M⟩₂ − (δ/γ)⟨⟨M⟩₄⟨M⟩₂⟩₂)/(β² − (δ/γ)² q)`. These are
//! symmetric functions of the two planes, so the √ε error of each root where the planes' angles meet cancels.
//!
//! **log** of a unit element of the one-plane class. `⟨M⟩₀ = c`, `Bₘ = ⟨M⟩₂ = (s + d ½W) B`, `Q = ⟨M⟩₄ = s ½W`
//! and `⟨Bₘ²⟩₀ = s²λ` (W² = 0 and W commutes with B), which with `c² − s²λ = 1` gives λ: a rotation by
//! `θ = atan2(√(−s²λ), c)`, a boost by `x = asinh √(s²λ)`. Then `B = (s + (d/s) Q)⁻¹ Bₘ = Bₘ/s − (d/s³) ⟨Q Bₘ⟩₂`
//! (Q² = 0). `s` vanishes at θ = π (M = −1 on the plane), where log is not defined.
//!
//! **normalized.** `N = M ~M = n₀ + N₄` with `N₄² = ν` a scalar and N₄ commuting with M (both checked), and
//! `M N^(−1/2)` has `(M N^(−1/2)) ~(…) = 1`. For ν = 0, `N^(−1/2) = n₀^(−1/2) (1 − N₄/(2n₀))`; for ν > 0 through
//! `n₀ ± √ν`, `A = ½((n₀+r)^(−1/2) + (n₀−r)^(−1/2))`, `B = −1/(√(n₀²−r²)(√(n₀+r) + √(n₀−r)))`; for ν < 0 through the
//! complex `n₀ + i√−ν` (`N^(−1/2) = A + B N₄`).
//!
//! **sqrt** is `normalized(1 + M)`: with `R = exp(B/2)`, `1 + M = 1 + R² = R(~R + R) = 2R(r₀ + R₄)`, where
//! `r₀ + R₄` (R's scalar and 4-vector parts) commutes with R; normalising divides it out exactly (its principal
//! inverse square root), so `sqrt(M) = R` and `sqrt(M)² = M` wherever no plane turns by 2π.

use std::collections::BTreeMap;

use num_rational::Rational64;
use num_traits::One;

use crate::algebra::Algebra;
use crate::blade::{grade, BladeMask};
use crate::error::Error;
use crate::expression::ExpressionKind;
use crate::functions::Output;
use crate::fuse::{
    accumulate, blades_and_signs, lower_parameters, result_type, value_type, Expander, Fused, Polynomial, Symbolic,
};
use crate::operation::Operation;
use crate::product::Rules;
use crate::program::{sum_cost, Cost, Term};

// Public here too: this module generates them (they are defined with the syntax that names them).
pub use crate::expression::{called, Function};

/// A generated closed form: the polynomial pieces of its argument, lowered together.
#[derive(Clone, Debug)]
pub struct ClosedForm {
    /// Which function.
    pub function: Function,
    /// The parameter, the result type and the shared program (its locals; it has no outputs of its own).
    pub fused: Fused,
    /// Each piece by name, its non-zero blades and their sums over the program's values and inputs.
    pub pieces: BTreeMap<&'static str, Vec<(BladeMask, Vec<Term>)>>,
    /// Whether the metric has two basis vectors of each sign, so that two planes' squares can be a complex pair
    /// or two boosts (only then are those cases emitted).
    pub indefinite: bool,
}

impl ClosedForm {
    /// The blades of a piece (empty if it vanishes identically).
    pub fn blades(&self, piece: &str) -> Vec<BladeMask> {
        self.pieces
            .get(piece)
            .map(|p| p.iter().map(|(b, _)| *b).collect())
            .unwrap_or_default()
    }
}

/// Expands `algebra.expressions[index]`, whose body calls a [`Function`], into its closed form's pieces.
///
/// ```
/// use ga_codegen::expression::{Expression, ExpressionKind, Parameter};
/// use ga_codegen::transcendental::{closed_form, Function};
/// use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, ExpressionDeclaration, Layout};
/// use ga_codegen::{ScalarType, TypeDeclaration};
///
/// // 3D PGA's lines: exp(b) needs ⟨b²⟩₀, ½ b∧b and ½⟨(b∧b) b⟩₂.
/// let basis = [("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]
///     .map(|(name, square)| BasisVectorDeclaration { name: name.into(), square });
/// let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// let b = Expression::new(ExpressionKind::Parameter("b".into()));
/// let exp_line = ExpressionDeclaration {
///     name: "exp_line".into(),
///     parameters: vec![Parameter { name: "b".into(), type_name: "Line".into() }],
///     result: Some("Motor".into()),
///     body: Expression::new(ExpressionKind::Call("exp".into(), vec![b])),
///     linear: None,
///     doc: None,
/// };
/// let algebra = Algebra::new(&AlgebraDeclaration {
///     scalar: ScalarType::F64,
///     basis: basis.to_vec(),
///     metric: None,
///     types: vec![ty("Line", vec![2]), ty("Motor", vec![0, 2, 4]), ty("Odd", vec![1, 3])],
///     operations: None,
///     lowering: vec![],
///     expressions: vec![exp_line],
/// })?;
/// let form = closed_form(&algebra, 0)?;
/// assert_eq!(form.function, Function::Exp);
/// assert_eq!(form.blades("square"), [0]); // ⟨b²⟩₀
/// assert_eq!(form.blades("half_wedge").len(), 1); // e0123
/// assert_eq!(form.blades("v").len(), 3); // e01, e02, e03
/// # Ok::<(), ga_codegen::Error>(())
/// ```
///
/// # Errors
/// [`Error::TranscendentalUse`] if the call's argument is not a parameter, [`Error::NoClosedForm`] if the
/// parameter's type is not of the generated class, [`Error::ResultDoesNotFit`] or
/// [`Error::NoExpressionResultType`] if no (declared) type holds the result.
pub fn closed_form(algebra: &Algebra, index: usize) -> Result<ClosedForm, Error> {
    let declared = &algebra.expressions[index];
    let (function, parameter) = called_parameter(algebra, index)?;
    let kind = value_type(algebra, &declared.parameters[parameter].type_name);
    let no_closed_form = |reason: String| Error::NoClosedForm {
        index,
        function: function.name(),
        type_name: declared.parameters[parameter].type_name.clone(),
        reason,
    };

    // The parameter as a multivector of its fields (program inputs 0..k).
    let fields = blades_and_signs(algebra, kind);
    let mut x = Symbolic::new();
    for (offset, (blade, sign)) in fields.iter().enumerate() {
        let input = Polynomial([(vec![offset as u32], Rational64::from(*sign))].into());
        accumulate(&mut x, *blade, &input, Rational64::one());
    }
    let expander = Expander {
        algebra,
        rules: Rules::new(&algebra.metric),
        top: index,
    };
    let grades: Vec<u32> = fields.iter().map(|(blade, _)| grade(*blade)).collect();
    let (pieces, result) = match function {
        Function::Exp => exp_pieces(&expander, &x, &grades, &no_closed_form)?,
        Function::Log => log_pieces(&expander, &x, &grades, &no_closed_form)?,
        Function::Sqrt | Function::Normalized => normalized_pieces(&expander, function, x, &grades, &no_closed_form)?,
    };

    // The result type: declared, or the smallest declared type holding the blades.
    let mut blades = result;
    blades.sort_unstable();
    blades.dedup();
    let output = result_type(algebra, index, &blades)?;
    let (fused, pieces) = lower_pieces(algebra, index, (kind, fields.len()), output, &pieces);
    Ok(ClosedForm {
        function,
        fused,
        pieces,
        indefinite: {
            let (positive, negative, _) = algebra.metric.signature();
            positive.min(negative) >= 2
        },
    })
}

/// The called function of `algebra.expressions[index]`, and the index of the parameter it is applied to: the
/// whole body is one call of one argument, the expression's only parameter, and the expression is not linear.
fn called_parameter(algebra: &Algebra, index: usize) -> Result<(Function, usize), Error> {
    let declared = &algebra.expressions[index];
    let ExpressionKind::Call(name, arguments) = &declared.body.kind else {
        unreachable!("`closed_form` is called on calls of a function only")
    };
    let function = Function::named(name).expect("a call of a generated function");
    let use_error = |reason: String| Error::TranscendentalUse {
        index,
        node: declared.body.id,
        function: function.name(),
        reason,
    };
    let [argument] = arguments.as_slice() else {
        return Err(use_error(format!("it has {} arguments", arguments.len())));
    };
    let ExpressionKind::Parameter(parameter_name) = &argument.kind else {
        return Err(use_error(format!("its argument `{argument}` is not a parameter")));
    };
    let Some(parameter) = declared.parameters.iter().position(|p| p.name == *parameter_name) else {
        return Err(use_error(format!(
            "`{parameter_name}` is not a parameter of `{}`",
            declared.name
        )));
    };
    if declared.parameters.len() != 1 {
        return Err(use_error(format!(
            "`{}` has {} parameters",
            declared.name,
            declared.parameters.len()
        )));
    }
    if declared.linear.is_some() {
        return Err(use_error("it is not linear, so it has no `#[linear]` map".to_string()));
    }
    Ok((function, parameter))
}

/// A closed form's pieces by name, before lowering.
type Pieces = Vec<(&'static str, Symbolic)>;

/// Each piece by name, its non-zero blades and their sums ([`ClosedForm::pieces`]).
type LoweredPieces = BTreeMap<&'static str, Vec<(BladeMask, Vec<Term>)>>;

/// The geometric product.
fn geometric(expander: &Expander, a: &Symbolic, b: &Symbolic) -> Result<Symbolic, Error> {
    expander.product(Operation::Geometric, a, b)
}

/// The grade-`k` part.
fn part(x: &Symbolic, k: u32) -> Symbolic {
    x.iter()
        .filter(|(b, _)| grade(**b) == k)
        .map(|(b, p)| (*b, p.clone()))
        .collect()
}

/// `x` times `factor`.
fn scaled(x: &Symbolic, factor: Rational64) -> Symbolic {
    let mut out = Symbolic::new();
    for (blade, polynomial) in x {
        accumulate(&mut out, *blade, polynomial, factor);
    }
    out
}

/// exp's pieces of a bivector `x` (its blades of `grades`), and the blades of the result.
fn exp_pieces(
    expander: &Expander,
    x: &Symbolic,
    grades: &[u32],
    no_closed_form: &dyn Fn(String) -> Error,
) -> Result<(Pieces, Vec<BladeMask>), Error> {
    if grades.iter().any(|&g| g != 2) {
        return Err(no_closed_form(
            "exp is generated for bivector types (every blade of grade 2)".into(),
        ));
    }
    let square = part(&geometric(expander, x, x)?, 0);
    let wedge = expander.product(Operation::Outer, x, x)?;
    let half_wedge = scaled(&wedge, Rational64::new(1, 2));
    // Two planes of non-zero square: λ₁λ₂ = ¼⟨W²⟩₀, which must be all of W² (n ≤ 5), and ½W B must be
    // the bivector λ₁B₂ + λ₂B₁.
    let wedge_square = geometric(expander, &wedge, &wedge)?;
    let half_wedge_b = geometric(expander, &half_wedge, x)?;
    let off_grade = |value: &Symbolic, k: u32| value.keys().any(|&blade| grade(blade) != k);
    if off_grade(&wedge_square, 0) || off_grade(&half_wedge_b, 2) {
        return Err(no_closed_form(
            "`(b ∧ b)²` is not a scalar or `(b ∧ b) b` not a bivector: it has more than two planes".into(),
        ));
    }
    let product = scaled(&wedge_square, Rational64::new(1, 4));
    let v = part(&half_wedge_b, 2);
    let mut blades: Vec<BladeMask> = vec![0];
    blades.extend(x.keys().chain(half_wedge.keys()).chain(v.keys()));
    let mut pieces = vec![("square", square), ("half_wedge", half_wedge), ("v", v)];
    if !product.is_empty() {
        pieces.push(("product", product));
    }
    Ok((pieces, blades))
}

/// log's pieces of an even element `x` (its blades of `grades`), and the blades of the result.
fn log_pieces(
    expander: &Expander,
    x: &Symbolic,
    grades: &[u32],
    no_closed_form: &dyn Fn(String) -> Error,
) -> Result<(Pieces, Vec<BladeMask>), Error> {
    if grades.iter().any(|g| ![0, 2, 4].contains(g)) || !grades.contains(&0) {
        return Err(no_closed_form(
            "log is generated for even types of grades 0, 2 and 4 with a scalar".into(),
        ));
    }
    let (scalar, bivector, quadvector) = (part(x, 0), part(x, 2), part(x, 4));
    let wedge = expander.product(Operation::Outer, &bivector, &bivector)?;
    let (wedge_square, q_square) = (
        geometric(expander, &wedge, &wedge)?,
        geometric(expander, &quadvector, &quadvector)?,
    );
    let q_bivector = geometric(expander, &quadvector, &bivector)?;
    // Two planes: for a unit element M = exp(B) (n ≤ 5) ⟨M⟩₄² is a scalar and ⟨M⟩₄⟨M⟩₂ a bivector; in n = 5
    // a general even element's are not, so their grade-0 and grade-2 parts are taken, exact on the elements
    // log is defined for.
    let two_planes_of_it = !wedge_square.is_empty() || !q_square.is_empty();
    let square = part(&geometric(expander, &bivector, &bivector)?, 0);
    let q_b = part(&q_bivector, 2);
    let blades: Vec<BladeMask> = bivector.keys().chain(q_b.keys()).copied().collect();
    let mut pieces = vec![
        ("scalar", scalar),
        ("bivector", bivector),
        ("square", square),
        ("q_b", q_b),
    ];
    if two_planes_of_it {
        pieces.push(("q_square", part(&q_square, 0)));
    }
    Ok((pieces, blades))
}

/// sqrt's or normalized's pieces of an even element `x` (its blades of `grades`), and the blades of the result.
fn normalized_pieces(
    expander: &Expander,
    function: Function,
    x: Symbolic,
    grades: &[u32],
    no_closed_form: &dyn Fn(String) -> Error,
) -> Result<(Pieces, Vec<BladeMask>), Error> {
    if grades.iter().any(|g| g % 2 == 1) {
        return Err(no_closed_form(format!(
            "{} is generated for even types",
            function.name()
        )));
    }
    let mut y = x;
    if function == Function::Sqrt {
        // 1 + M.
        accumulate(
            &mut y,
            0,
            &Polynomial([(vec![], Rational64::one())].into()),
            Rational64::one(),
        );
    }
    let norm = geometric(expander, &y, &expander.reverse(&y))?;
    let (n0, n4) = (part(&norm, 0), part(&norm, 4));
    let rest: Vec<String> = norm
        .keys()
        .filter(|&&b| grade(b) != 0 && grade(b) != 4)
        .map(|&b| expander.algebra.blade_name(b))
        .collect();
    let n4_square = geometric(expander, &n4, &n4)?;
    let off_scalar = n4_square.keys().any(|&blade| blade != 0);
    if !rest.is_empty() || off_scalar {
        return Err(no_closed_form(format!(
            "its `m ~m` must be a scalar plus a 4-vector whose square is a scalar (it has {})",
            if rest.is_empty() {
                "a 4-vector whose square is not a scalar".to_string()
            } else {
                format!("the blades {}", rest.join(", "))
            }
        )));
    }
    let y_n4 = geometric(expander, &y, &n4)?;
    let n4_y = geometric(expander, &n4, &y)?;
    if y_n4 != n4_y {
        return Err(no_closed_form(
            "the 4-vector part of its `m ~m` does not commute with it".into(),
        ));
    }
    let blades: Vec<BladeMask> = y.keys().chain(y_n4.keys()).copied().collect();
    let mut pieces = vec![("value", y), ("n0", n0), ("y_n4", y_n4)];
    if !n4_square.is_empty() {
        pieces.push(("n4_square", n4_square));
    }
    Ok((pieces, blades))
}

/// Lowers every piece's polynomials together, sharing products; one group of inputs, the `field_count` fields of
/// the parameter of type `kind`. Returns the shared program with its cost, and each piece's sums by blade.
fn lower_pieces(
    algebra: &Algebra,
    index: usize,
    (kind, field_count): (Output, usize),
    output: Output,
    pieces: &[(&'static str, Symbolic)],
) -> (Fused, LoweredPieces) {
    let declared = &algebra.expressions[index];
    let offsets = vec![0];
    let inputs = 0..field_count as u32;
    let keys: Vec<(&'static str, BladeMask)> = pieces
        .iter()
        .flat_map(|(name, value)| value.keys().map(move |&b| (*name, b)))
        .collect();
    let polynomials: Vec<&Polynomial> = pieces.iter().flat_map(|(_, value)| value.values()).collect();
    let (program, sums) = lower_parameters(
        algebra,
        declared,
        (&[kind], &offsets),
        &polynomials,
        std::slice::from_ref(&inputs),
    );
    let mut lowered: LoweredPieces = pieces.iter().map(|(name, _)| (*name, Vec::new())).collect();
    for ((name, blade), sum) in keys.into_iter().zip(sums) {
        lowered.entry(name).or_default().push((blade, sum));
    }
    // The polynomial part's cost: the shared locals and each piece's sums.
    let pieces_cost = lowered
        .values()
        .flatten()
        .fold(Cost::default(), |total, (_, terms)| total + sum_cost(terms));
    let fused = Fused {
        parameters: vec![kind],
        offsets,
        output,
        cost: program.cost() + pieces_cost,
        program,
    };
    (fused, lowered)
}
