//! The closed forms of [`crate::transcendental`] (`exp`, `log`, `sqrt`, `normalized`) as functions: the pieces'
//! polynomials as locals, then the scalar functions of the invariants and the result blade by blade.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::code::Inputs;
use super::emitter::{field_ident, Emitter};
use super::fused::expression_doc;
use crate::blade::BladeMask;
use crate::expression::ExpressionDeclaration;
use crate::functions::Output;
use crate::transcendental::{ClosedForm, Function as Closed};

impl Emitter<'_> {
    /// A closed form of [`crate::transcendental`]: the pieces' polynomials as locals, then the scalar functions
    /// of the invariants and the result blade by blade (derivations in that module).
    pub(super) fn closed_form_function(&self, declared: &ExpressionDeclaration, form: &ClosedForm) -> TokenStream {
        let fused = &form.fused;
        let name = format_ident!("{}", declared.name);
        let parameter = &declared.parameters[0];
        let parameter_ident = format_ident!("{}", parameter.name);
        let parameter_type = self.output_type(fused.parameters[0]);
        let output = self.output_type(fused.output);
        let input = self.parameter_fields(declared, fused);
        let locals = self.locals(&input, &fused.program);
        // The function's own names start with a prefix that neither the parameter nor a shared local starts with.
        let mut prefix = String::from("form");
        let taken = |prefix: &str| {
            let start = format!("{prefix}_");
            parameter.name.starts_with(&start) || fused.program.locals.iter().any(|l| l.name.starts_with(&start))
        };
        while taken(&prefix) {
            prefix.push('_');
        }
        let form_body = FormBody {
            emitter: self,
            form,
            parameter: parameter_ident.clone(),
            output: output.clone(),
            prefix,
        };
        let pieces = form_body.pieces(&input);
        let (body, what) = match form.function {
            Closed::Exp if !form.blades("product").is_empty() => form_body.exp_two_planes(),
            Closed::Exp => form_body.exp_one_plane(),
            Closed::Log if form.pieces.contains_key("q_square") => form_body.log_two_planes(),
            Closed::Log => form_body.log_one_plane(),
            Closed::Sqrt | Closed::Normalized => form_body.normalized(),
        };
        let doc = expression_doc(
            declared,
            &format!(
                "`{}`, in closed form ([`ga_codegen::transcendental`]): {what}.\n\nCost of the polynomial part: {}.",
                declared.body, fused.cost
            ),
        );
        quote! {
            #doc
            #[inline]
            pub fn #name(#parameter_ident: #parameter_type) -> #output {
                #locals
                #(#pieces)*
                #body
            }
        }
    }
}

/// What the parts of a closed form's body share: the emitter, the form, the parameter and result type, and the
/// prefix of the function's own names.
struct FormBody<'e> {
    emitter: &'e Emitter<'e>,
    form: &'e ClosedForm,
    parameter: Ident,
    output: TokenStream,
    prefix: String,
}

impl FormBody<'_> {
    /// The function's own names, each `{prefix}_{name}`.
    fn names<const N: usize>(&self, names: [&str; N]) -> [Ident; N] {
        names.map(|name| format_ident!("{}_{name}", self.prefix))
    }

    /// The local holding a piece's coefficient of `blade`.
    fn piece_ident(&self, piece: &str, blade: BladeMask) -> Ident {
        format_ident!("{}_{piece}_{}", self.prefix, self.emitter.algebra.blade_name(blade))
    }

    /// The pieces' polynomials as locals, one per blade.
    fn pieces(&self, input: Inputs) -> Vec<TokenStream> {
        let mut pieces: Vec<TokenStream> = Vec::new();
        for (piece, blades) in &self.form.pieces {
            for (blade, terms) in blades {
                let ident = self.piece_ident(piece, *blade);
                let value = self.emitter.sum(input, &self.form.fused.program, terms, false);
                pieces.push(quote! { let #ident = #value; });
            }
        }
        pieces
    }

    /// Zero, typed, so that a combination with no terms (a metric whose invariants vanish identically, such as
    /// Cl(1,0,1)'s or an all-null one's) still takes `.abs()` and `.sqrt()`.
    fn zero(&self) -> TokenStream {
        let scalar = &self.emitter.scalar;
        quote! { (0.0 as #scalar) }
    }

    /// The canonical coefficient of `blade` in a piece, as tokens (`None` where the piece has no such blade).
    fn coefficient(&self, piece: &str, blade: BladeMask) -> Option<TokenStream> {
        self.form.blades(piece).contains(&blade).then(|| {
            let ident = self.piece_ident(piece, blade);
            quote! { #ident }
        })
    }

    /// A scalar piece, zero where it vanishes identically.
    fn scalar_piece(&self, piece: &str) -> TokenStream {
        let zero = self.zero();
        self.coefficient(piece, 0).unwrap_or_else(|| quote! { #zero })
    }

    /// `a₁ x₁ + a₂ x₂ + …` over the terms whose x is not identically zero (`0` if none is); a term without x is
    /// its factor alone.
    fn combination(&self, terms: Vec<(TokenStream, Option<Option<TokenStream>>)>) -> TokenStream {
        let present: Vec<TokenStream> = terms
            .into_iter()
            .filter_map(|(factor, x)| {
                x.map(|x| match x {
                    Some(x) => quote! { #factor * #x },
                    None => factor,
                })
            })
            .collect();
        if present.is_empty() {
            let zero = self.zero();
            quote! { #zero }
        } else {
            quote! { #(#present)+* }
        }
    }

    /// The parameter's canonical coefficient of `blade`, as tokens (`None` where it has no such blade).
    fn canonical_input(&self, blade: BladeMask) -> Option<TokenStream> {
        let parameter = &self.parameter;
        match self.form.fused.parameters[0] {
            Output::Type(ty) => {
                let ty = &self.emitter.algebra.types[ty];
                match ty.fields.iter().position(|f| f.blade == blade) {
                    Some(index) => {
                        let field = field_ident(ty, index);
                        Some(match ty.fields[index].sign {
                            1 => quote! { #parameter.#field },
                            _ => quote! { (-#parameter.#field) },
                        })
                    }
                    None => None,
                }
            }
            Output::Scalar if blade == 0 => Some(quote! { #parameter }),
            Output::Scalar => None,
        }
    }

    /// c(λ), s(λ) and d(λ) = (c − s)/λ by their Taylor series for |λ| < 0.1 (terms to λ⁷: truncation below
    /// 1e-20), otherwise from the trigonometric or hyperbolic functions (cancellation in d at most 1e-15).
    fn series(&self) -> TokenStream {
        let [c, s, d, lambda] = self.names(["c", "s", "d", "lambda"]);
        quote! {{
            let #c = 1.0 + #lambda * (1.0 / 2.0 + #lambda * (1.0 / 24.0 + #lambda * (1.0 / 720.0 + #lambda * (1.0 / 40320.0
                + #lambda * (1.0 / 3628800.0 + #lambda * (1.0 / 479001600.0 + #lambda * (1.0 / 87178291200.0)))))));
            let #s = 1.0 + #lambda * (1.0 / 6.0 + #lambda * (1.0 / 120.0 + #lambda * (1.0 / 5040.0 + #lambda * (1.0 / 362880.0
                + #lambda * (1.0 / 39916800.0 + #lambda * (1.0 / 6227020800.0 + #lambda * (1.0 / 1307674368000.0)))))));
            let #d = (1.0 / 2.0 - 1.0 / 6.0) + #lambda * ((1.0 / 24.0 - 1.0 / 120.0) + #lambda * ((1.0 / 720.0 - 1.0 / 5040.0)
                + #lambda * ((1.0 / 40320.0 - 1.0 / 362880.0) + #lambda * ((1.0 / 3628800.0 - 1.0 / 39916800.0)
                + #lambda * ((1.0 / 479001600.0 - 1.0 / 6227020800.0) + #lambda * (1.0 / 87178291200.0 - 1.0 / 1307674368000.0))))));
            (#c, #s, #d)
        }}
    }

    /// The result, its value of each blade given by `value`.
    fn result(&self, value: &dyn Fn(BladeMask) -> TokenStream) -> TokenStream {
        let output = &self.output;
        match self.form.fused.output {
            Output::Type(ty) => {
                let ty = &self.emitter.algebra.types[ty];
                let fields = ty.fields.iter().enumerate().map(|(i, f)| {
                    let field = field_ident(ty, i);
                    let value = value(f.blade);
                    match f.sign {
                        1 => quote! { #field: #value },
                        _ => quote! { #field: -(#value) },
                    }
                });
                quote! { #output { #(#fields),* } }
            }
            Output::Scalar => value(0),
        }
    }

    /// Two planes (exp and log): each plane's c(λ) and s(λ), and the divided differences over the two squares.
    fn two_planes(&self) -> TokenStream {
        let scalar = &self.emitter.scalar;
        let [c, s, lambda, t, r, l1, l2, c1, s1, c2, s2, plane, divided] = self.names([
            "c", "s", "lambda", "t", "r", "l1", "l2", "c1", "s1", "c2", "s2", "plane", "divided",
        ]);
        let series = self.series();
        let (two_boosts_apart, close_boosts) = self.close_boosts();
        quote! {
            // c(λ) and s(λ) of one plane: the series below |λ| = 0.1, else cos/sin or cosh/sinh.
            let #plane = |#lambda: #scalar| -> (#scalar, #scalar) {
                if #lambda.abs() < 0.1 {
                    let (#c, #s, _) = #series;
                    (#c, #s)
                } else if #lambda < 0.0 {
                    let #t = (-#lambda).sqrt();
                    (#t.cos(), #t.sin() / #t)
                } else {
                    let #t = #lambda.sqrt();
                    (#t.cosh(), #t.sinh() / #t)
                }
            };
            let (#c1, #s1) = #plane(#l1);
            let (#c2, #s2) = #plane(#l2);
            // The divided differences C[λ₁, λ₂], S[λ₁, λ₂] and H[λ₁, λ₂] of c, s and H(λ) = λ s(λ).
            let #divided = || -> (#scalar, #scalar, #scalar) {
                let (#t, #r) = (#l1.abs().sqrt(), #l2.abs().sqrt());
                let (u, v) = (0.5 * (#t + #r), 0.5 * (#t - #r));
                let largest = #l1.abs().max(#l2.abs());
                if largest < 0.1 {
                    // Σ aₙ (λ₁ⁿ − λ₂ⁿ)/(λ₁ − λ₂) = Σ aₙ hₙ₋₁(λ₁, λ₂), the complete homogeneous polynomials.
                    let (mut h, mut power2, mut factorial) = (1.0, 1.0, 1.0);
                    let (mut dc, mut ds, mut dh) = (0.0, 0.0, 0.0);
                    for n in 1..12 {
                        let k = (2 * n) as #scalar;
                        // factorial is (2n − 2)! here.
                        dh += h / (factorial * (k - 1.0));
                        factorial *= (k - 1.0) * k;
                        dc += h / factorial;
                        ds += h / (factorial * (k + 1.0));
                        power2 *= #l2;
                        h = #l1 * h + power2;
                    }
                    (dc, ds, dh)
                } else if (#l1 - #l2).abs() >= 0.5 * largest #two_boosts_apart {
                    // Well apart: differences.
                    let (h1, h2) = (#l1 * #s1, #l2 * #s2);
                    let gap = #l1 - #l2;
                    ((#c1 - #c2) / gap, (#s1 - #s2) / gap, (h1 - h2) / gap)
                } #close_boosts else {
                    // Two rotations by x₁ = √−λ₁ and x₂ = √−λ₂ close to each other: u and v are their
                    // half sum and half difference (derivations in ga_codegen::transcendental).
                    let sinc = |x: #scalar| if x.abs() < 1e-4 { 1.0 - x * x / 6.0 } else { x.sin() / x };
                    let (sin, cos) = u.sin_cos();
                    let (sv, cv) = (sinc(v), v.cos());
                    (
                        0.5 * sinc(u) * sv,
                        -(u * cos * sv - sin * cv) / (2.0 * u * (u * u - v * v)),
                        (u * cos * sv + sin * cv) / (2.0 * u),
                    )
                }
            };
        }
    }

    /// Two close boosts (λᵢ = xᵢ² > 0) exist only with two basis vectors of each sign: the half-sum and
    /// half-difference forms with hyperbolic functions (derivation in ga_codegen::transcendental). Returns what the
    /// divided differences add for them: a condition to the test for λ's well apart, and a branch for close ones.
    fn close_boosts(&self) -> (TokenStream, TokenStream) {
        let scalar = &self.emitter.scalar;
        let [l1] = self.names(["l1"]);
        if self.form.indefinite {
            let close = quote! {
                else if #l1 > 0.0 {
                    let shc = |x: #scalar| if x.abs() < 1e-4 { 1.0 + x * x / 6.0 } else { x.sinh() / x };
                    let (sinh, cosh) = (u.sinh(), u.cosh());
                    let (sv, cv) = (shc(v), v.cosh());
                    (
                        0.5 * shc(u) * sv,
                        (u * cosh * sv - sinh * cv) / (2.0 * u * (u * u - v * v)),
                        (u * cosh * sv + sinh * cv) / (2.0 * u),
                    )
                }
            };
            (quote! {}, close)
        } else {
            // Two boosts cannot occur; were they to, differences are still right.
            (quote! { || #l1 > 0.0 }, quote! {})
        }
    }

    /// A complex pair λ₁ = re + i·im, λ₂ = λ̄₁ (two basis vectors of each sign): c(λ₂) = c̄₁ and s(λ₂) = s̄₁, so
    /// exp's c₁c₂ and s₁s₂ are |c₁|² and |s₁|², the divided differences X[λ₁, λ₁̄] = Im X(λ₁)/Im λ₁ (no
    /// cancellation: Im X(λ₁) is computed directly), and β and δ the real parts of their formulas (the
    /// imaginary parts cancel). The value is (α, β, γ, δ).
    fn complex_coefficients(&self) -> TokenStream {
        let scalar = &self.emitter.scalar;
        let [c, s, t, dc, ds, dh] = self.names(["c", "s", "t", "dc", "ds", "dh"]);
        quote! {
            let (#c, #s) = if re.hypot(im) < 0.1 {
                // The series to λ⁷ by Horner's rule in complex arithmetic.
                let horner = |coefficients: [#scalar; 8]| {
                    coefficients.iter().fold((0.0, 0.0), |(x, y): (#scalar, #scalar), a| {
                        (x * re - y * im + a, x * im + y * re)
                    })
                };
                (
                    horner([1.0 / 87178291200.0, 1.0 / 479001600.0, 1.0 / 3628800.0, 1.0 / 40320.0, 1.0 / 720.0,
                        1.0 / 24.0, 1.0 / 2.0, 1.0]),
                    horner([1.0 / 1307674368000.0, 1.0 / 6227020800.0, 1.0 / 39916800.0, 1.0 / 362880.0,
                        1.0 / 5040.0, 1.0 / 120.0, 1.0 / 6.0, 1.0]),
                )
            } else {
                // z = x + iy = √(−λ₁) (either root: c and s are even in z), c = cos z, s = sin z / z.
                let (p, q) = (-re, -im);
                let #t = (0.5 * (p.hypot(q) + p.abs())).sqrt();
                let (x, y) = if p >= 0.0 { (#t, 0.5 * q / #t) } else { (0.5 * q.abs() / #t, q.signum() * #t) };
                let (sin, cos) = x.sin_cos();
                let (sinh, cosh) = (y.sinh(), y.cosh());
                let (n_re, n_im) = (sin * cosh, cos * sinh);
                let modulus = x * x + y * y;
                ((cos * cosh, -sin * sinh), ((n_re * x + n_im * y) / modulus, (n_im * x - n_re * y) / modulus))
            };
            let (#dc, #ds) = (#c.1 / im, #s.1 / im);
            // H = λ s: Im(λ₁ s₁)/Im λ₁ = re S[] + Re s₁.
            let #dh = re * #ds + #s.0;
            (
                #c.0 * #c.0 + #c.1 * #c.1,
                #c.0 * #dh - (re * #s.0 - im * #s.1) * #dc,
                #s.0 * #s.0 + #s.1 * #s.1,
                #s.0 * #dc - #c.0 * #ds,
            )
        }
    }

    /// exp's result `f₀ + f₁ b + f₂ ½(b∧b) + f₃ ½⟨(b∧b) b⟩₂` for the factors of either form.
    fn exp_result(&self, [scalar_factor, b_factor, w_factor, v_factor]: [&Ident; 4]) -> TokenStream {
        self.result(&|blade: BladeMask| {
            self.combination(vec![
                (quote! { #scalar_factor }, (blade == 0).then_some(None)),
                (quote! { #b_factor }, self.canonical_input(blade).map(Some)),
                (quote! { #w_factor }, self.coefficient("half_wedge", blade).map(Some)),
                (quote! { #v_factor }, self.coefficient("v", blade).map(Some)),
            ])
        })
    }

    /// log's result `inverse ⟨m⟩₂ + k ⟨⟨m⟩₄⟨m⟩₂⟩₂`.
    fn log_result(&self) -> TokenStream {
        let [inverse, k] = self.names(["inverse", "k"]);
        self.result(&|blade: BladeMask| {
            self.combination(vec![
                (quote! { #inverse }, self.coefficient("bivector", blade).map(Some)),
                (quote! { #k }, self.coefficient("q_b", blade).map(Some)),
            ])
        })
    }

    /// log's guard: an element with `⟨m ~m⟩₀ ≤ 0` (zero, or not finite) has no logarithm, and every coefficient
    /// of the result is NaN rather than a quiet zero.
    fn not_a_number(&self) -> TokenStream {
        let scalar = &self.emitter.scalar;
        self.result(&|_| quote! { #scalar::NAN })
    }

    /// exp of a bivector with two commuting planes, and what it computes.
    fn exp_two_planes(&self) -> (TokenStream, &'static str) {
        let [lambda, r, l1, l2, c1, s1, c2, s2, dc, ds, dh, alpha, beta, gamma, delta, divided] = self.names([
            "lambda", "r", "l1", "l2", "c1", "s1", "c2", "s2", "dc", "ds", "dh", "alpha", "beta", "gamma", "delta",
            "divided",
        ]);
        let (closures, complex_coefficients) = (self.two_planes(), self.complex_coefficients());
        let square = self.scalar_piece("square");
        let product = self.scalar_piece("product");
        let result = self.exp_result([&alpha, &beta, &gamma, &delta]);
        let real = quote! {
            let #r = (#lambda * #lambda - 4.0 * #product).max(0.0).sqrt();
            let #l1 = if #lambda >= 0.0 { 0.5 * (#lambda + #r) } else { 0.5 * (#lambda - #r) };
            let #l2 = if #l1 == 0.0 { 0.0 } else { #product / #l1 };
            #closures
            let (#dc, #ds, #dh) = #divided();
            let #alpha = #c1 * #c2;
            let #beta = #c2 * #dh - #l2 * #s2 * #dc;
            let #gamma = #s1 * #s2;
            let #delta = #s2 * #dc - #c2 * #ds;
        };
        let coefficients = if self.form.indefinite {
            quote! {
                let discriminant = #lambda * #lambda - 4.0 * #product;
                let (#alpha, #beta, #gamma, #delta) = if discriminant < 0.0 {
                    let (re, im) = (0.5 * #lambda, 0.5 * (-discriminant).sqrt());
                    #complex_coefficients
                } else {
                    #real
                    (#alpha, #beta, #gamma, #delta)
                };
            }
        } else {
            real
        };
        (
            quote! {
                // λ₁ and λ₂, the squares of the two commuting planes: the roots of λ² − ⟨b²⟩₀ λ + ¼⟨(b∧b)²⟩₀.
                let #lambda = #square;
                #coefficients
                #result
            },
            "the exponential of a bivector with two commuting planes of squares λ₁ and λ₂: \
             `c₁c₂ + β b + s₁s₂ ½(b∧b) + δ ½⟨(b∧b) b⟩₂` with β and δ from the divided differences of \
             c(λ), s(λ) and λ s(λ) (series, differences, or half-sum and half-difference forms where λ₁ ≈ λ₂)",
        )
    }

    /// exp of a bivector of one non-null plane, and what it computes.
    fn exp_one_plane(&self) -> (TokenStream, &'static str) {
        let [c, s, d, lambda, t] = self.names(["c", "s", "d", "lambda", "t"]);
        let series = self.series();
        let square = self.scalar_piece("square");
        let result = self.exp_result([&c, &s, &s, &d]);
        (
            quote! {
                let #lambda = #square;
                let (#c, #s, #d) = if #lambda.abs() < 0.1 #series else if #lambda < 0.0 {
                    let #t = (-#lambda).sqrt();
                    let (sin, cos) = #t.sin_cos();
                    (cos, sin / #t, (cos - sin / #t) / #lambda)
                } else {
                    let #t = #lambda.sqrt();
                    let (cosh, sinh) = (#t.cosh(), #t.sinh());
                    (cosh, sinh / #t, (cosh - sinh / #t) / #lambda)
                };
                #result
            },
            "the exponential: with λ = ⟨b²⟩₀, `c + s b + s ½(b∧b) + d ½⟨(b∧b) b⟩₂`, c = cos √−λ or cosh √λ, \
             s = sin √−λ / √−λ or sinh √λ / √λ, d = (c − s)/λ (series near λ = 0)",
        )
    }

    /// log of a unit element turning in two planes: the planes' squares, then β, γ and δ as for exp (the real
    /// case), and what it computes.
    fn log_two_planes(&self) -> (TokenStream, &'static str) {
        let [inverse, k, beta, gamma, delta] = self.names(["inverse", "k", "beta", "gamma", "delta"]);
        let a = self.scalar_piece("scalar");
        let real = self.log_two_plane_squares(&a);
        let log_coefficients = if self.form.indefinite {
            self.log_complex_pair(&a, real)
        } else {
            real
        };
        let not_a_number = self.not_a_number();
        let square = self.scalar_piece("square");
        let q_square = self.scalar_piece("q_square");
        let result = self.log_result();
        (
            quote! {
                // wᵢ = sᵢ²λᵢ (−sin²θᵢ for a rotation, sinh²xᵢ for a boost) are the roots of
                // w² − (σ − 2q) w + q, σ = ⟨⟨m⟩₂²⟩₀ and q = ⟨⟨m⟩₄²⟩₀ (for m ~m = 1; no cancellation near m = 1).
                let (sigma, q) = (#square, #q_square);
                if !(#a * #a - sigma + q > 0.0) {
                    return #not_a_number;
                }
                let sum = sigma - 2.0 * q;
                #log_coefficients
                // ⟨m⟩₂ = (β + (δ/γ)⟨m⟩₄) b, and ⟨m⟩₄² = q is a scalar.
                let ratio = #delta / #gamma;
                let denominator = #beta * #beta - ratio * ratio * q;
                let #inverse = #beta / denominator;
                let #k = -ratio / denominator;
                #result
            },
            "the logarithm of a unit element turning in two planes: their squares λ₁, λ₂ from the invariants of \
             `⟨m⟩₂` and `⟨m⟩₄`, then `b = (β + (δ/γ)⟨m⟩₄)⁻¹ ⟨m⟩₂` with the coefficients of `exp`",
        )
    }

    /// The two planes' squares λ₁, λ₂ of a unit element with real `w`s (its scalar part `a`), then β, γ and δ.
    fn log_two_plane_squares(&self, a: &TokenStream) -> TokenStream {
        let scalar = &self.emitter.scalar;
        let [r, t, l1, l2, s1, c2, s2, dc, ds, dh, beta, gamma, delta, divided] = self.names([
            "r", "t", "l1", "l2", "s1", "c2", "s2", "dc", "ds", "dh", "beta", "gamma", "delta", "divided",
        ]);
        let closures = self.two_planes();
        quote! {
            let #r = (sum * sum - 4.0 * q).max(0.0).sqrt();
            let w1 = if sum <= 0.0 { 0.5 * (sum - #r) } else { 0.5 * (sum + #r) };
            let w2 = if w1 == 0.0 { 0.0 } else { q / w1 };
            // The plane with the larger cosine takes it from 1 + w; the other cosine is ⟨m⟩₀ divided by it.
            let (wide, narrow) = if w1 >= w2 { (w1, w2) } else { (w2, w1) };
            let wide_cos = (1.0 + wide).max(0.0).sqrt();
            let narrow_cos = if wide_cos > 0.0 { #a / wide_cos } else { 0.0 };
            let square_of = |w: #scalar, cos: #scalar| -> #scalar {
                if w < 0.0 {
                    let #t = (-w).sqrt().atan2(cos);
                    -#t * #t
                } else {
                    let #t = w.sqrt().asinh();
                    #t * #t
                }
            };
            let (#l1, #l2) = (square_of(wide, wide_cos), square_of(narrow, narrow_cos));
            #closures
            let (#dc, #ds, #dh) = #divided();
            let #beta = #c2 * #dh - #l2 * #s2 * #dc;
            let #gamma = #s1 * #s2;
            let #delta = #s2 * #dc - #c2 * #ds;
        }
    }

    /// β, γ and δ of a unit element whose `w`s are a complex pair (scalar part `a`), or of `real` ones.
    fn log_complex_pair(&self, a: &TokenStream, real: TokenStream) -> TokenStream {
        let scalar = &self.emitter.scalar;
        let [t, beta, gamma, delta] = self.names(["t", "beta", "gamma", "delta"]);
        let (complex_coefficients, not_a_number) = (self.complex_coefficients(), self.not_a_number());
        quote! {
            let discriminant = sum * sum - 4.0 * q;
            let (#beta, #gamma, #delta) = if discriminant < 0.0 {
                // w₁ = w_re + i w_im and its conjugate: c₁c₂ = |c₁|² = ⟨m⟩₀ must be positive.
                if !(#a > 0.0) {
                    return #not_a_number;
                }
                let (w_re, w_im) = (0.5 * sum, 0.5 * (-discriminant).sqrt());
                // The principal square root of a complex number, without cancellation.
                let root = |p: #scalar, q: #scalar| -> (#scalar, #scalar) {
                    let #t = (0.5 * (p.hypot(q) + p.abs())).sqrt();
                    if #t == 0.0 {
                        (0.0, 0.0)
                    } else if p >= 0.0 {
                        (#t, 0.5 * q / #t)
                    } else {
                        (0.5 * q.abs() / #t, q.signum() * #t)
                    }
                };
                // λ₁ = y², y = asinh ζ with ζ = √w₁ (s²λ = sinh²y = w): y = ln(1 + u) with
                // u = ζ + w₁/(1 + √(1 + w₁)), whose denominator has real part at least 1.
                let (z_re, z_im) = root(w_re, w_im);
                let (d_re, d_im) = root(1.0 + w_re, w_im);
                let (d_re, modulus) = (1.0 + d_re, (1.0 + d_re) * (1.0 + d_re) + d_im * d_im);
                let u_re = z_re + (w_re * d_re + w_im * d_im) / modulus;
                let u_im = z_im + (w_im * d_re - w_re * d_im) / modulus;
                let y_re = 0.5 * (u_re * (2.0 + u_re) + u_im * u_im).ln_1p();
                let y_im = u_im.atan2(1.0 + u_re);
                let (re, im) = ((y_re - y_im) * (y_re + y_im), 2.0 * y_re * y_im);
                let (_, #beta, #gamma, #delta) = { #complex_coefficients };
                (#beta, #gamma, #delta)
            } else {
                #real
                (#beta, #gamma, #delta)
            };
        }
    }

    /// log of a unit element of the one-plane class, and what it computes.
    fn log_one_plane(&self) -> (TokenStream, &'static str) {
        let [s, d, lambda, t, r, inverse, k] = self.names(["s", "d", "lambda", "t", "r", "inverse", "k"]);
        let series = self.series();
        let not_a_number = self.not_a_number();
        let a = self.scalar_piece("scalar");
        let square = self.scalar_piece("square");
        let result = self.log_result();
        (
            quote! {
                if !(#a * #a - #square > 0.0) {
                    return #not_a_number;
                }
                let #r = #square.abs().sqrt();
                // The plane's angle (rotation) or rapidity (boost), λ = ∓t², then s(λ) and d(λ).
                let (#t, #lambda) = if #square < 0.0 {
                    let #t = #r.atan2(#a);
                    (#t, -#t * #t)
                } else {
                    let #t = #r.asinh();
                    (#t, #t * #t)
                };
                // c is ⟨m⟩₀ itself for a unit element; only s and d enter B.
                let (_, #s, #d) = if #lambda.abs() < 0.1 #series else if #lambda < 0.0 {
                    let #s = #t.sin() / #t;
                    (#t.cos(), #s, (#t.cos() - #s) / #lambda)
                } else {
                    let #s = #t.sinh() / #t;
                    (#t.cosh(), #s, (#t.cosh() - #s) / #lambda)
                };
                let #inverse = 1.0 / #s;
                let #k = -#d * #inverse * #inverse * #inverse;
                #result
            },
            "the logarithm of a unit element (`m ~m = 1`): with `b = ⟨m⟩₂`, `q = ⟨m⟩₄` and the plane's angle \
             from `⟨m⟩₀` and `⟨b²⟩₀`, `b/s − (d/s³)⟨q b⟩₂`; not defined where s = 0 (a turn by 2π)",
        )
    }

    /// `sqrt` or `normalized`, and what it computes.
    fn normalized(&self) -> (TokenStream, &'static str) {
        let [r, inverse, k] = self.names(["r", "inverse", "k"]);
        let n0 = self.scalar_piece("n0");
        let value = |blade: BladeMask| {
            self.combination(vec![
                (quote! { #inverse }, self.coefficient("value", blade).map(Some)),
                (quote! { #k }, self.coefficient("y_n4", blade).map(Some)),
            ])
        };
        let result = self.result(&value);
        let what = match self.form.function {
            Closed::Sqrt => "the square root of a unit element: `normalized(1 + m)`, exact where `⟨m⟩₀ > −1`",
            _ => "`m (m ~m)^(−1/2)`, with `m ~m = n₀ + N₄` and N₄² a scalar",
        };
        let body = match self.coefficient("n4_square", 0) {
            None => quote! {
                let #inverse = 1.0 / #n0.sqrt();
                let #k = -0.5 * #inverse / #n0;
                #result
            },
            // (n₀ + N₄)^(−1/2) = A + B N₄ with ν = N₄² a scalar: through n₀ ± √ν for ν > 0, through the
            // complex n₀ + i√−ν for ν < 0 (both without cancellation as ν → 0).
            Some(nu) => quote! {
                let nu = #nu;
                let #r = nu.abs().sqrt();
                let (#inverse, #k) = if #r == 0.0 {
                    let #inverse = 1.0 / #n0.sqrt();
                    (#inverse, -0.5 * #inverse / #n0)
                } else if nu > 0.0 {
                    let (plus, minus) = ((#n0 + #r).sqrt(), (#n0 - #r).sqrt());
                    (0.5 * (1.0 / plus + 1.0 / minus), -1.0 / (plus * minus * (plus + minus)))
                } else {
                    let modulus = (#n0 * #n0 + nu.abs()).sqrt().sqrt();
                    let half = 0.5 * #r.atan2(#n0);
                    (half.cos() / modulus, -half.sin() / (modulus * #r))
                };
                #result
            },
        };
        (body, what)
    }
}
