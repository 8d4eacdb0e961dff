//! The closed forms of [`crate::transcendental`] (`exp`, `log`, `sqrt`, `normalized`) as functions: the pieces'
//! polynomials as locals, then the scalar functions of the invariants and the result blade by blade.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

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
        let local = |name: &str| format_ident!("{prefix}_{name}");
        let piece_ident = |piece: &str, blade: BladeMask| local(&format!("{piece}_{}", self.algebra.blade_name(blade)));
        let mut pieces: Vec<TokenStream> = Vec::new();
        for (piece, blades) in &form.pieces {
            for (blade, terms) in blades {
                let ident = piece_ident(piece, *blade);
                let value = self.sum(&input, &fused.program, terms, false);
                pieces.push(quote! { let #ident = #value; });
            }
        }
        // Typed, so that a combination with no terms (a metric whose invariants vanish identically, such as
        // Cl(1,0,1)'s or an all-null one's) still takes `.abs()` and `.sqrt()`.
        let zero = {
            let scalar = &self.scalar;
            quote! { (0.0 as #scalar) }
        };
        // The canonical coefficient of `blade` in a piece, as tokens (zero where the piece has no such blade).
        let coefficient = |piece: &str, blade: BladeMask| {
            form.blades(piece).contains(&blade).then(|| {
                let ident = piece_ident(piece, blade);
                quote! { #ident }
            })
        };
        // `a₁ x₁ + a₂ x₂ + …` over the terms whose x is not identically zero (`0` if none is); a term without x is
        // its factor alone.
        let combination = |terms: Vec<(TokenStream, Option<Option<TokenStream>>)>| -> TokenStream {
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
                quote! { #zero }
            } else {
                quote! { #(#present)+* }
            }
        };
        let parameter_kind = fused.parameters[0];
        let canonical_input = |blade: BladeMask| match parameter_kind {
            Output::Type(ty) => {
                let ty = &self.algebra.types[ty];
                match ty.fields.iter().position(|f| f.blade == blade) {
                    Some(index) => {
                        let field = field_ident(ty, index);
                        Some(match ty.fields[index].sign {
                            1 => quote! { #parameter_ident.#field },
                            _ => quote! { (-#parameter_ident.#field) },
                        })
                    }
                    None => None,
                }
            }
            Output::Scalar if blade == 0 => Some(quote! { #parameter_ident }),
            Output::Scalar => None,
        };
        let [c, s, d, lambda, t, r, inverse, k] = ["c", "s", "d", "lambda", "t", "r", "inverse", "k"].map(local);
        // c(λ), s(λ) and d(λ) = (c − s)/λ by their Taylor series for |λ| < 0.1 (terms to λ⁷: truncation below
        // 1e-20), otherwise from the trigonometric or hyperbolic functions (cancellation in d at most 1e-15).
        let series = quote! {{
            let #c = 1.0 + #lambda * (1.0 / 2.0 + #lambda * (1.0 / 24.0 + #lambda * (1.0 / 720.0 + #lambda * (1.0 / 40320.0
                + #lambda * (1.0 / 3628800.0 + #lambda * (1.0 / 479001600.0 + #lambda * (1.0 / 87178291200.0)))))));
            let #s = 1.0 + #lambda * (1.0 / 6.0 + #lambda * (1.0 / 120.0 + #lambda * (1.0 / 5040.0 + #lambda * (1.0 / 362880.0
                + #lambda * (1.0 / 39916800.0 + #lambda * (1.0 / 6227020800.0 + #lambda * (1.0 / 1307674368000.0)))))));
            let #d = (1.0 / 2.0 - 1.0 / 6.0) + #lambda * ((1.0 / 24.0 - 1.0 / 120.0) + #lambda * ((1.0 / 720.0 - 1.0 / 5040.0)
                + #lambda * ((1.0 / 40320.0 - 1.0 / 362880.0) + #lambda * ((1.0 / 3628800.0 - 1.0 / 39916800.0)
                + #lambda * ((1.0 / 479001600.0 - 1.0 / 6227020800.0) + #lambda * (1.0 / 87178291200.0 - 1.0 / 1307674368000.0))))));
            (#c, #s, #d)
        }};
        let output_blades: Vec<(proc_macro2::Ident, BladeMask, i64)> = match fused.output {
            Output::Type(ty) => {
                let ty = &self.algebra.types[ty];
                ty.fields
                    .iter()
                    .enumerate()
                    .map(|(i, f)| (field_ident(ty, i), f.blade, f.sign))
                    .collect()
            }
            Output::Scalar => vec![],
        };
        let result = |value: &dyn Fn(BladeMask) -> TokenStream| -> TokenStream {
            match fused.output {
                Output::Type(_) => {
                    let fields = output_blades.iter().map(|(field, blade, sign)| {
                        let value = value(*blade);
                        match sign {
                            1 => quote! { #field: #value },
                            _ => quote! { #field: -(#value) },
                        }
                    });
                    quote! { #output { #(#fields),* } }
                }
                Output::Scalar => value(0),
            }
        };
        // Two planes (exp and log): each plane's c(λ) and s(λ), and the divided differences over the two squares.
        let scalar = &self.scalar;
        let [l1, l2, c1, s1, c2, s2, dc, ds, dh, alpha, beta, gamma, delta, plane, divided] = [
            "l1", "l2", "c1", "s1", "c2", "s2", "dc", "ds", "dh", "alpha", "beta", "gamma", "delta", "plane", "divided",
        ]
        .map(local);
        // Two close boosts (λᵢ = xᵢ² > 0) exist only with two basis vectors of each sign: the half-sum and
        // half-difference forms with hyperbolic functions (derivation in ga_codegen::transcendental).
        let (two_boosts_apart, close_boosts) = if form.indefinite {
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
        };
        let closures = quote! {
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
        };
        // A complex pair λ₁ = re + i·im, λ₂ = λ̄₁ (two basis vectors of each sign): c(λ₂) = c̄₁ and s(λ₂) = s̄₁, so
        // exp's c₁c₂ and s₁s₂ are |c₁|² and |s₁|², the divided differences X[λ₁, λ₁̄] = Im X(λ₁)/Im λ₁ (no
        // cancellation: Im X(λ₁) is computed directly), and β and δ the real parts of their formulas (the
        // imaginary parts cancel). The value is (α, β, γ, δ).
        let complex_coefficients = quote! {
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
        };
        // exp's result `f₀ + f₁ b + f₂ ½(b∧b) + f₃ ½⟨(b∧b) b⟩₂` for the factors of either form.
        let exp_result = |[scalar_factor, b_factor, w_factor, v_factor]: [&proc_macro2::Ident; 4]| {
            result(&|blade: BladeMask| {
                combination(vec![
                    (quote! { #scalar_factor }, (blade == 0).then_some(None)),
                    (quote! { #b_factor }, canonical_input(blade).map(Some)),
                    (quote! { #w_factor }, coefficient("half_wedge", blade).map(Some)),
                    (quote! { #v_factor }, coefficient("v", blade).map(Some)),
                ])
            })
        };
        // log's result `inverse ⟨m⟩₂ + k ⟨⟨m⟩₄⟨m⟩₂⟩₂`, and its guard: an element with `⟨m ~m⟩₀ ≤ 0` (zero, or not
        // finite) has no logarithm, and every coefficient of the result is NaN rather than a quiet zero.
        let log_result = result(&|blade: BladeMask| {
            combination(vec![
                (quote! { #inverse }, coefficient("bivector", blade).map(Some)),
                (quote! { #k }, coefficient("q_b", blade).map(Some)),
            ])
        });
        let not_a_number = result(&|_| quote! { #scalar::NAN });
        let (body, what) = match form.function {
            Closed::Exp if !form.blades("product").is_empty() => {
                let square = coefficient("square", 0).unwrap_or_else(|| quote! { #zero });
                let product = coefficient("product", 0).unwrap_or_else(|| quote! { #zero });
                let result = exp_result([&alpha, &beta, &gamma, &delta]);
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
                let coefficients = if form.indefinite {
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
            Closed::Exp => {
                let square = coefficient("square", 0).unwrap_or_else(|| quote! { #zero });
                let result = exp_result([&c, &s, &s, &d]);
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
            Closed::Log if form.pieces.contains_key("q_square") => {
                let a = coefficient("scalar", 0).unwrap_or_else(|| quote! { #zero });
                let real = quote! {
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
                };
                let log_coefficients = if form.indefinite {
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
                } else {
                    real
                };
                let square = coefficient("square", 0).unwrap_or_else(|| quote! { #zero });
                let q_square = coefficient("q_square", 0).unwrap_or_else(|| quote! { #zero });
                let result = &log_result;
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
            Closed::Log => {
                let a = coefficient("scalar", 0).unwrap_or_else(|| quote! { #zero });
                let square = coefficient("square", 0).unwrap_or_else(|| quote! { #zero });
                let result = &log_result;
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
            Closed::Sqrt | Closed::Normalized => {
                let n0 = coefficient("n0", 0).unwrap_or_else(|| quote! { #zero });
                let value = |blade: BladeMask| {
                    combination(vec![
                        (quote! { #inverse }, coefficient("value", blade).map(Some)),
                        (quote! { #k }, coefficient("y_n4", blade).map(Some)),
                    ])
                };
                let result = result(&value);
                let what = match form.function {
                    Closed::Sqrt => "the square root of a unit element: `normalized(1 + m)`, exact where `⟨m⟩₀ > −1`",
                    _ => "`m (m ~m)^(−1/2)`, with `m ~m = n₀ + N₄` and N₄² a scalar",
                };
                let body = match coefficient("n4_square", 0) {
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
