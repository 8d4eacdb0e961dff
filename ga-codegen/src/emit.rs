//! Emission: Rust tokens for the declared types and every operation between them.
//!
//! Per declared type: a `#[repr(C)]` struct with one pub field per blade, constructors and unary
//! methods (`const fn`). Binary operations are traits (`Geometric<Rhs>`, `Outer<Rhs>`, …) implemented
//! for every type pair, with `core::ops` sugar (`*` geometric, `^` outer, `&` regressive, `|` left
//! contraction); each is also an inherent `const fn` named after the operation and the right-hand
//! type (`a.geometric_motor(b)`), so products can be evaluated in constants and const assertions.
//! The code uses only `core`, and each function's doc comment states its exact cost.

use num_rational::Rational64;
use num_traits::{One, Signed, ToPrimitive, Zero};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote, ToTokens};

use crate::algebra::{Algebra, SparseType};
use crate::blade::BladeMask;
use crate::declaration::ScalarType;
use crate::error::{collect, Error};
use crate::expand::{Operand, Variable};
use crate::expression::ExpressionDeclaration;
use crate::functions::{self, Code, Finish, Function, Output};
use crate::fuse::{self, Fused, LinearMap};
use crate::naming::{const_method_name, map_builder_name, map_type_name, trait_name};
use crate::operation::Operation;
use crate::product::reverse_sign;
use crate::program::{Definition, Program, Term, Value};
use crate::table::{EncodedStage, Source, Table};
use crate::transcendental::{self, ClosedForm, Function as Closed};

/// The traits every emitted struct derives (it is also `#[repr(C)]`).
pub const DERIVED_TRAITS: [&str; 5] = ["Clone", "Copy", "Debug", "PartialEq", "Default"];

/// Emits the items of the algebra's module, refusing a declaration whose functions take more than
/// [`functions::MAX_BUILD_WORK`] to build.
pub fn emit(algebra: &Algebra) -> Result<TokenStream, Error> {
    emit_within(algebra, functions::MAX_BUILD_WORK)
}

/// [`emit`] with a limit of `max_build_work` ([`Function::build_work`] summed over the functions), checked as the
/// functions are made, so a refusal comes before the rest is built.
pub fn emit_within(algebra: &Algebra, max_build_work: usize) -> Result<TokenStream, Error> {
    let emitter = Emitter {
        algebra,
        scalar: format_ident!("{}", algebra.scalar.name()),
    };
    let mut work = 0usize;
    let mut within = |function: &Function| {
        work = work.saturating_add(function.build_work());
        if work <= max_build_work {
            return Ok(());
        }
        Err(Error::TooMuchCode {
            ty_index: function.lhs,
            ty: algebra.types[function.lhs].name.clone(),
            work,
            limit: max_build_work,
            unrolled_multiply: functions::UNROLLED_MULTIPLY_WORK,
        })
    };
    let mut items = Vec::new();
    let binary: Vec<Operation> = algebra.operations.iter().copied().filter(|op| op.is_binary()).collect();
    items.extend(binary.iter().map(|&op| binary_trait(op)));
    for (index, ty) in algebra.types.iter().enumerate() {
        items.push(emitter.type_definition(ty));
        let mut methods = Vec::new();
        for &op in algebra.operations.iter().filter(|op| !op.is_binary()) {
            for function in functions::unary(algebra, op, index)? {
                within(&function)?;
                methods.push(emitter.unary_method(&function));
            }
        }
        let name = format_ident!("{}", ty.name);
        items.push(quote! { impl #name { #(#methods)* } });
        items.push(emitter.scalar_arithmetic(ty));
    }
    for lhs in 0..algebra.types.len() {
        for rhs in 0..algebra.types.len() {
            for subtract in [false, true] {
                if let Some(function) = functions::sum(algebra, lhs, rhs, subtract) {
                    within(&function)?;
                    items.push(emitter.sum_impl(&function));
                }
            }
            if lhs != rhs && algebra.types[rhs].holds(&blades(&algebra.types[lhs])) {
                items.push(emitter.conversion(&algebra.types[lhs], &algebra.types[rhs]));
            }
            for &op in &binary {
                let function = functions::binary(algebra, op, lhs, rhs)?;
                within(&function)?;
                items.push(binary_function(algebra, &function));
            }
        }
    }
    items.extend(collect(
        (0..algebra.expressions.len()).map(|index| fused_function(algebra, index)),
    )?);
    Ok(quote! { #(#items)* })
}

/// The function of `algebra.expressions[index]`, fused (see [`crate::fuse`]), and its linear map if it asks
/// for one, e.g. to inspect or snapshot them.
///
/// # Errors
/// Those of [`fuse::fuse`].
pub fn fused_function(algebra: &Algebra, index: usize) -> Result<TokenStream, Error> {
    let emitter = Emitter {
        algebra,
        scalar: format_ident!("{}", algebra.scalar.name()),
    };
    let declared = &algebra.expressions[index];
    if transcendental::called(declared).is_some() {
        return Ok(emitter.closed_form_function(declared, &transcendental::closed_form(algebra, index)?));
    }
    let linear = declared.linear.as_ref().map(|linear| {
        let parameter = declared.parameters.iter().position(|p| p.name == *linear);
        parameter.expect("`Algebra::new` checks the linear parameter")
    });
    // A linear map carries the fused function it was expanded with: one expansion for both.
    Ok(match linear {
        Some(parameter) => {
            let map = fuse::linear_map(algebra, index, parameter)?;
            let mut items = emitter.fused_function(declared, &map.fused);
            items.extend(emitter.linear_map(declared, &map));
            items
        }
        None => emitter.fused_function(declared, &fuse::fuse(algebra, index)?),
    })
}

/// The trait impl (and operator sugar) of one binary function, e.g. to inspect or snapshot it.
pub fn binary_function(algebra: &Algebra, function: &Function) -> TokenStream {
    Emitter {
        algebra,
        scalar: format_ident!("{}", algebra.scalar.name()),
    }
    .binary_impl(function)
}

fn blades(ty: &SparseType) -> Vec<u32> {
    ty.fields.iter().map(|f| f.blade).collect()
}

fn field_ident(ty: &SparseType, index: usize) -> Ident {
    format_ident!("{}", ty.fields[index].name)
}

/// The trait of a binary operation.
fn trait_ident(operation: Operation) -> Ident {
    format_ident!("{}", trait_name(operation))
}

fn operation_doc(operation: Operation) -> &'static str {
    match operation {
        Operation::Geometric => "The geometric product `a b` (operator `*`).",
        Operation::Outer => "The outer (wedge) product `a ∧ b` (operator `^`).",
        Operation::LeftContraction => "The left contraction `a ⌋ b`: ⟨a_r b_s⟩_{s−r}, zero if s < r (operator `|`).",
        Operation::RightContraction => "The right contraction `a ⌊ b`: ⟨a_r b_s⟩_{r−s}, zero if r < s.",
        Operation::ScalarProduct => "The scalar product ⟨a b⟩₀.",
        Operation::HestenesInner => "The Hestenes inner product ⟨a_r b_s⟩_{|r−s|}, zero if r = 0 or s = 0.",
        Operation::FatDot => "The \"fat dot\" inner product ⟨a_r b_s⟩_{|r−s|}, scalars included.",
        Operation::Regressive => "The regressive product (join in PGA): LC(RC(a) ∧ RC(b)), metric-free (operator `&`).",
        Operation::Commutator => "The commutator product (a b − b a)/2.",
        Operation::Sandwich => {
            "The sandwich `a x ~a`, as the cheaper of one fused polynomial and the commutator form\n\
             `(a ~a) x + a (x ~a − ~a x)`."
        }
        Operation::Transform => {
            "The sandwich `a x ~a` for a unit versor `a` (`a ~a = 1`: a normalised motor, rotor or\n\
             reflection), computed with fewer operations by using that identity. Only the grades of `x`\n\
             are kept (a versor preserves grades). For `a ~a ≠ 1` it is not the sandwich."
        }
        Operation::Reverse => "The reverse: grade k times (−1)^{k(k−1)/2}.",
        Operation::Involute => "The grade involution: grade k times (−1)^k.",
        Operation::Conjugate => "The Clifford conjugate: grade k times (−1)^{k(k+1)/2}.",
        Operation::RightComplement => "The right complement: RC(e_m) ∧ … chosen so that e_m ∧ RC(e_m) = I.",
        Operation::LeftComplement => "The left complement, chosen so that LC(e_m) ∧ e_m = I.",
        Operation::Polarity => "The polarity (dual) a I⁻¹.",
        Operation::Grade => "The grade projection.",
        Operation::NormSquared => "The squared norm ⟨a ~a⟩₀.",
        Operation::Inverse => {
            "The inverse ~a / (a ~a), defined because a ~a is a scalar for this type. \
             Not finite where a ~a = 0."
        }
    }
}

/// One `#[doc]` attribute per line, so that formatted code shows `///` lines.
fn doc_lines(text: &str) -> TokenStream {
    let lines = text.lines().map(|line| {
        if line.is_empty() {
            String::new()
        } else {
            format!(" {line}")
        }
    });
    quote! { #(#[doc = #lines])* }
}

/// An expression function's documentation: the user's (if any), then the generated notes.
fn expression_doc(declared: &ExpressionDeclaration, generated: &str) -> TokenStream {
    match &declared.doc {
        Some(user) => doc_lines(&format!("{user}\n\n{generated}")),
        None => doc_lines(generated),
    }
}

fn binary_trait(operation: Operation) -> TokenStream {
    let name = trait_ident(operation);
    let method = format_ident!("{}", operation.name());
    let doc = doc_lines(operation_doc(operation));
    quote! {
        #doc
        pub trait #name<Rhs> {
            type Output;
            #doc
            fn #method(self, rhs: Rhs) -> Self::Output;
        }
    }
}

/// How emitted code reads an input variable (an operand's field).
type Inputs<'a> = &'a dyn Fn(Variable) -> TokenStream;

/// How a tabled function's doc reads its tables.
const TABLE_LAYOUT: &str = "A table holds one entry `i, j, k, n` per product, each a little-endian `u16` (`u32` where \
     an index needs it): `stage[k] += coefficients[n] · left[i] · right[j]`.";

struct Emitter<'a> {
    algebra: &'a Algebra,
    scalar: Ident,
}

impl Emitter<'_> {
    fn literal(&self, value: Rational64) -> Literal {
        let value = value.to_f64().unwrap_or(f64::NAN);
        match self.algebra.scalar {
            ScalarType::F32 => Literal::f32_unsuffixed(value as f32),
            ScalarType::F64 => Literal::f64_unsuffixed(value),
        }
    }

    fn output_type(&self, output: Output) -> TokenStream {
        match output {
            Output::Type(index) => {
                let name = format_ident!("{}", self.algebra.types[index].name);
                quote! { #name }
            }
            Output::Scalar => {
                let scalar = &self.scalar;
                quote! { #scalar }
            }
        }
    }

    fn type_definition(&self, ty: &SparseType) -> TokenStream {
        let scalar = &self.scalar;
        let name = format_ident!("{}", ty.name);
        let fields: Vec<Ident> = (0..ty.fields.len()).map(|i| field_ident(ty, i)).collect();
        let field_docs = ty.fields.iter().map(|f| {
            let canonical = self.algebra.blade_name(f.blade);
            if f.sign < 0 {
                format!("Coefficient of `{}` (= −`{canonical}`).", f.name)
            } else {
                format!("Coefficient of `{canonical}`.")
            }
        });
        let names = ty.fields.iter().map(|f| f.name.as_str());
        let count = ty.fields.len();
        let doc = format!(
            "A `{}` multivector with blades [{}].",
            ty.name,
            ty.fields.iter().map(|f| f.name.as_str()).collect::<Vec<_>>().join(", ")
        );
        let zeros = fields.iter().map(|f| quote! { #f: 0.0 });
        let indices = 0..count;
        let derived = DERIVED_TRAITS.map(|name| format_ident!("{name}"));
        quote! {
            #[doc = #doc]
            #[derive(#(#derived),*)]
            #[repr(C)]
            pub struct #name {
                #( #[doc = #field_docs] pub #fields: #scalar, )*
            }

            impl #name {
                /// The blade of each field, in storage order.
                pub const BLADES: &'static [&'static str] = &[#(#names),*];
                /// All coefficients zero.
                pub const ZERO: Self = Self { #(#zeros),* };

                /// All coefficients zero.
                #[inline]
                pub const fn zero() -> Self {
                    Self::ZERO
                }

                /// Builds from coefficients in [`Self::BLADES`] order.
                #[inline]
                pub const fn from_array(values: [#scalar; #count]) -> Self {
                    Self { #( #fields: values[#indices], )* }
                }

                /// The coefficients in [`Self::BLADES`] order.
                #[inline]
                pub const fn to_array(self) -> [#scalar; #count] {
                    [#(self.#fields),*]
                }
            }
        }
    }

    fn scalar_arithmetic(&self, ty: &SparseType) -> TokenStream {
        let scalar = &self.scalar;
        let name = format_ident!("{}", ty.name);
        let fields: Vec<Ident> = (0..ty.fields.len()).map(|i| field_ident(ty, i)).collect();
        quote! {
            impl core::ops::Neg for #name {
                type Output = #name;
                #[inline]
                fn neg(self) -> #name {
                    #name { #( #fields: -self.#fields, )* }
                }
            }
            impl core::ops::Mul<#scalar> for #name {
                type Output = #name;
                /// Scales every coefficient.
                #[inline]
                fn mul(self, factor: #scalar) -> #name {
                    #name { #( #fields: self.#fields * factor, )* }
                }
            }
            impl core::ops::Mul<#name> for #scalar {
                type Output = #name;
                /// Scales every coefficient.
                #[inline]
                fn mul(self, value: #name) -> #name {
                    value * self
                }
            }
            impl core::ops::Div<#scalar> for #name {
                type Output = #name;
                /// Divides every coefficient.
                #[inline]
                fn div(self, divisor: #scalar) -> #name {
                    #name { #( #fields: self.#fields / divisor, )* }
                }
            }
            impl core::ops::MulAssign<#scalar> for #name {
                #[inline]
                fn mul_assign(&mut self, factor: #scalar) {
                    #( self.#fields *= factor; )*
                }
            }
            impl core::ops::AddAssign for #name {
                #[inline]
                fn add_assign(&mut self, other: #name) {
                    #( self.#fields += other.#fields; )*
                }
            }
            impl core::ops::SubAssign for #name {
                #[inline]
                fn sub_assign(&mut self, other: #name) {
                    #( self.#fields -= other.#fields; )*
                }
            }
        }
    }

    /// `From<A> for B` where B holds every blade of A.
    fn conversion(&self, from: &SparseType, to: &SparseType) -> TokenStream {
        let (source, target) = (format_ident!("{}", from.name), format_ident!("{}", to.name));
        let assignments = to.fields.iter().map(|field| {
            let name = format_ident!("{}", field.name);
            match from.field_of(field.blade) {
                Some(source_field) => {
                    let source_name = format_ident!("{}", source_field.name);
                    if source_field.sign == field.sign {
                        quote! { #name: value.#source_name }
                    } else {
                        quote! { #name: -value.#source_name }
                    }
                }
                None => quote! { #name: 0.0 },
            }
        });
        let doc = format!(
            "Embeds a `{}` in a `{}` (the other coefficients are zero).",
            from.name, to.name
        );
        quote! {
            impl From<#source> for #target {
                #[doc = #doc]
                #[inline]
                fn from(value: #source) -> #target {
                    #target { #(#assignments),* }
                }
            }
        }
    }

    fn value(&self, input: Inputs, program: &Program, value: Value) -> TokenStream {
        match value {
            Value::Input(variable) => input(variable),
            Value::Local(index) => {
                let name = format_ident!("{}", program.locals[index].name);
                quote! { #name }
            }
        }
    }

    /// How a product's function reads its operands' fields: `self.e12`, `rhs.e0`.
    fn operand_fields(&self, function: &Function) -> impl Fn(Variable) -> TokenStream + '_ {
        let (lhs, rhs) = (function.lhs, function.rhs);
        move |variable: Variable| match variable.operand {
            Operand::Lhs => {
                let name = field_ident(&self.algebra.types[lhs], variable.field);
                quote! { self.#name }
            }
            Operand::Rhs => {
                let rhs = rhs.expect("a right-hand variable implies a binary function");
                let name = field_ident(&self.algebra.types[rhs], variable.field);
                quote! { rhs.#name }
            }
        }
    }

    /// `c · x · y`, without the sign (the sum places it).
    fn magnitude(&self, input: Inputs, program: &Program, term: &Term) -> TokenStream {
        let mut factors = term.factors.iter().map(|&v| self.value(input, program, v));
        let coefficient = term.coefficient.abs();
        let mut tokens = if coefficient.is_one() {
            factors
                .next()
                .unwrap_or_else(|| self.literal(coefficient).into_token_stream())
        } else {
            self.literal(coefficient).into_token_stream()
        };
        for factor in factors {
            tokens.extend(quote! { * #factor });
        }
        tokens
    }

    /// A signed sum of terms, positive terms first so that no leading negation is needed.
    fn sum(&self, input: Inputs, program: &Program, terms: &[Term], negate: bool) -> TokenStream {
        if terms.is_empty() {
            let zero = self.literal(Rational64::zero());
            return quote! { #zero };
        }
        let mut ordered: Vec<(bool, TokenStream)> = terms
            .iter()
            .map(|t| (t.coefficient.is_negative() != negate, self.magnitude(input, program, t)))
            .collect();
        ordered.sort_by_key(|(negative, _)| *negative);
        let mut tokens = TokenStream::new();
        for (position, (negative, magnitude)) in ordered.into_iter().enumerate() {
            tokens.extend(match (position, negative) {
                (0, false) => magnitude,
                (0, true) => quote! { -#magnitude },
                (_, false) => quote! { + #magnitude },
                (_, true) => quote! { - #magnitude },
            });
        }
        tokens
    }

    /// The statements computing the outputs, and the result expression.
    fn body(&self, function: &Function) -> TokenStream {
        match &function.code {
            Code::Unrolled(program) => self.unrolled_body(
                &self.operand_fields(function),
                program,
                function.output,
                function.finish,
            ),
            Code::Table(table) => self.table_body(function, table),
        }
    }

    /// A program's hoisted locals, as `let` statements.
    fn locals(&self, input: Inputs, program: &Program) -> TokenStream {
        let locals = program.locals.iter().map(|local| {
            let name = format_ident!("{}", local.name);
            let expression = match &local.definition {
                Definition::Sum(terms) => self.sum(input, program, terms, false),
                Definition::Double(value) => {
                    let value = self.value(input, program, *value);
                    quote! { #value + #value }
                }
            };
            quote! { let #name = #expression; }
        });
        quote! { #(#locals)* }
    }

    /// The locals, then the result built from the output sums.
    fn unrolled_body(&self, input: Inputs, program: &Program, output: Output, finish: Finish) -> TokenStream {
        let locals = self.locals(input, program);
        let output_terms = |blade: BladeMask| program.outputs.get(&blade).map(Vec::as_slice).unwrap_or(&[]);
        let result = match (output, finish) {
            (Output::Scalar, _) => self.sum(input, program, output_terms(0), false),
            (Output::Type(index), Finish::Coefficients) => {
                let ty = &self.algebra.types[index];
                let name = format_ident!("{}", ty.name);
                let fields = ty.fields.iter().map(|field| {
                    let ident = format_ident!("{}", field.name);
                    let value = self.sum(input, program, output_terms(field.blade), field.sign < 0);
                    quote! { #ident: #value }
                });
                quote! { #name { #(#fields),* } }
            }
            (Output::Type(index), Finish::DivideReverseByNorm) => {
                let ty = &self.algebra.types[index];
                let name = format_ident!("{}", ty.name);
                let norm = self.sum(input, program, output_terms(0), false);
                let one = self.literal(Rational64::one());
                let fields = ty.fields.iter().map(|field| {
                    let ident = format_ident!("{}", field.name);
                    if reverse_sign(field.blade).is_negative() {
                        quote! { #ident: -self.#ident * scale }
                    } else {
                        quote! { #ident: self.#ident * scale }
                    }
                });
                quote! {{
                    let scale = #one / (#norm);
                    #name { #(#fields),* }
                }}
            }
        };
        quote! { #locals #result }
    }

    /// Per stage a constant table and a loop `stage[k] += c · left[i] · right[j]` (a `while` loop: the function
    /// stays `const`), then the result read from the last stage.
    ///
    /// A table is one byte-string literal of entries `i, j, k, n`, each a little-endian `u16` (or `u32` where an
    /// index needs it), `n` indexing the stage's distinct coefficients: one token however many entries, where an
    /// array of tuples is ten per entry, which rustc and the macro's token bridge handle entry by entry (a
    /// million-entry product took minutes to build).
    fn table_body(&self, function: &Function, table: &Table) -> TokenStream {
        let scalar = &self.scalar;
        let zero = self.literal(Rational64::zero());
        let array = |source: Source| match source {
            Source::Lhs => format_ident!("lhs"),
            Source::Rhs => format_ident!("rhs"),
            Source::Stage(s) => format_ident!("stage_{s}"),
        };
        let reads_rhs = table
            .stages
            .iter()
            .any(|s| s.left == Source::Rhs || s.right == Source::Rhs);
        let rhs = reads_rhs.then(|| quote! { let rhs = rhs.to_array(); });
        let stages = table.stages.iter().enumerate().map(|(s, stage)| {
            let (entries_name, coefficients_name) = (format_ident!("STAGE_{s}"), format_ident!("COEFFICIENTS_{s}"));
            let output = array(Source::Stage(s));
            let (left, right) = (array(stage.left), array(stage.right));
            let encoded = EncodedStage::new(stage);
            let index = Literal::usize_unsuffixed;
            let (bytes, size) = (index(encoded.bytes.len()), index(stage.blades.len()));
            let coefficients = encoded.coefficients.iter().map(|&c| {
                let literal = self.literal(c.abs());
                if c.is_negative() {
                    quote! { -#literal }
                } else {
                    quote! { #literal }
                }
            });
            let coefficient_count = index(encoded.coefficients.len());
            let literal = Literal::byte_string(&encoded.bytes);
            let width = encoded.width;
            // Shifts and ors rather than `u16::from_le_bytes`, a call per index in an unoptimised build.
            let read = |position: usize| {
                let bytes = (0..width).map(|b| {
                    let byte = match position * width + b {
                        0 => quote! { table[at] as usize },
                        offset => {
                            let offset = index(offset);
                            quote! { table[at + #offset] as usize }
                        }
                    };
                    match 8 * b {
                        0 => byte,
                        shift => {
                            let shift = index(shift);
                            quote! { (#byte) << #shift }
                        }
                    }
                });
                quote! { #(#bytes)|* }
            };
            let (i, j, k, n) = (read(0), read(1), read(2), read(3));
            let stride = index(4 * width);
            // Read through references: `&CONST` is promoted to a static, where indexing the constant itself would
            // build it on the stack at every iteration in an unoptimised build.
            quote! {
                const #entries_name: &[u8; #bytes] = #literal;
                const #coefficients_name: [#scalar; #coefficient_count] = [#(#coefficients),*];
                let (table, coefficients) = (#entries_name, &#coefficients_name);
                let mut #output = [#zero; #size];
                let mut at = 0;
                while at < #bytes {
                    let (i, j, k, n) = (#i, #j, #k, #n);
                    #output[k] += coefficients[n] * #left[i] * #right[j];
                    at += #stride;
                }
            }
        });
        let last = table.stages.last().expect("a table has a stage");
        let result_array = array(Source::Stage(table.stages.len() - 1));
        let read = |blade: BladeMask, negate: bool| match last
            .blades
            .iter()
            .position(|&b| b == blade)
            .map(Literal::usize_unsuffixed)
        {
            Some(k) if negate => quote! { -#result_array[#k] },
            Some(k) => quote! { #result_array[#k] },
            None => quote! { #zero },
        };
        let result = match function.output {
            Output::Scalar => read(0, false),
            Output::Type(index) => {
                let ty = &self.algebra.types[index];
                let name = format_ident!("{}", ty.name);
                let fields = ty.fields.iter().map(|field| {
                    let ident = format_ident!("{}", field.name);
                    let value = read(field.blade, field.sign < 0);
                    quote! { #ident: #value }
                });
                quote! { #name { #(#fields),* } }
            }
        };
        quote! {
            let lhs = self.to_array();
            #rhs
            #(#stages)*
            #result
        }
    }

    /// One `#[doc]` per line (so formatted code shows `///` lines): what it computes, then its cost.
    fn doc(&self, function: &Function) -> TokenStream {
        let what = match (function.operation, &function.code) {
            (Some(Operation::Grade), _) => {
                format!("The grade-{} part.", function.method.trim_start_matches("grade_"))
            }
            (Some(Operation::Sandwich), Code::Table(_)) => "The sandwich `a x ~a`.".to_string(),
            (Some(Operation::Transform), Code::Table(_)) => "The sandwich `a x ~a` for a unit versor `a` \
                 (`a ~a = 1`), keeping only the grades of `x` (a versor preserves grades)."
                .to_string(),
            (Some(operation), _) => operation_doc(operation).to_string(),
            (None, _) => String::new(),
        };
        let lowering = match &function.code {
            Code::Unrolled(_) => String::new(),
            Code::Table(table) if table.stages.len() == 2 => format!(
                "\n\nTable-driven: {} products in two stages, `m = a x` then `m ~a`, each a constant table and a loop. \
                 {TABLE_LAYOUT}",
                table.entries()
            ),
            Code::Table(table) => {
                format!(
                    "\n\nTable-driven: {} products in a constant table and a loop. {TABLE_LAYOUT}",
                    table.entries()
                )
            }
        };
        doc_lines(&format!("{what}\n\nCost: {}.{lowering}", function.cost))
    }

    fn unary_method(&self, function: &Function) -> TokenStream {
        let method = format_ident!("{}", function.method);
        let output = self.output_type(function.output);
        let body = self.body(function);
        let doc = self.doc(function);
        quote! {
            #doc
            #[inline]
            pub const fn #method(self) -> #output {
                #body
            }
        }
    }

    /// How a fused expression's code reads its inputs: `m.e12`, or `t` for a scalar parameter.
    fn parameter_fields<'f>(
        &'f self,
        declared: &'f ExpressionDeclaration,
        fused: &'f Fused,
    ) -> impl Fn(Variable) -> TokenStream + 'f {
        move |variable: Variable| {
            let index = fused.parameter_of(variable.field);
            let parameter = format_ident!("{}", declared.parameters[index].name);
            match fused.parameters[index] {
                Output::Type(ty) => {
                    let field = field_ident(&self.algebra.types[ty], variable.field - fused.offsets[index]);
                    quote! { #parameter.#field }
                }
                Output::Scalar => quote! { #parameter },
            }
        }
    }

    /// `name: Type` for the parameters of a fused expression (all, or all but one) that `program` reads;
    /// one it does not read (every term of it cancelled) is named `_name`, which draws no warning.
    fn parameter_list(
        &self,
        declared: &ExpressionDeclaration,
        fused: &Fused,
        program: &Program,
        skip: Option<usize>,
    ) -> Vec<TokenStream> {
        (0..declared.parameters.len())
            .filter(|&index| Some(index) != skip)
            .map(|index| {
                let ty = self.output_type(fused.parameters[index]);
                let name = &declared.parameters[index].name;
                let ident = match program.reads(|v| fused.parameter_of(v.field) == index) {
                    true => format_ident!("{name}"),
                    false => format_ident!("_{name}"),
                };
                quote! { #ident: #ty }
            })
            .collect()
    }

    /// `pub const fn name(parameters) -> Result`, computing a fused expression.
    fn fused_function(&self, declared: &ExpressionDeclaration, fused: &Fused) -> TokenStream {
        let name = format_ident!("{}", declared.name);
        let parameters = self.parameter_list(declared, fused, &fused.program, None);
        let input = self.parameter_fields(declared, fused);
        let body = self.unrolled_body(&input, &fused.program, fused.output, Finish::Coefficients);
        let output = self.output_type(fused.output);
        let doc = expression_doc(
            declared,
            &format!(
                "`{}`, fused: expanded exactly as one polynomial per output blade, common subexpressions \
                 shared.\n\nCost: {}.",
                declared.body, fused.cost
            ),
        );
        // A formula of many operands (a second derivative takes eight) is declared so by the user; the generated
        // signature mirrors it.
        let many = (parameters.len() > 7).then(|| quote! { #[allow(clippy::too_many_arguments)] });
        quote! {
            #doc
            #[inline]
            #many
            pub const fn #name(#(#parameters),*) -> #output {
                #body
            }
        }
    }

    /// A closed form of [`crate::transcendental`]: the pieces' polynomials as locals, then the scalar functions
    /// of the invariants and the result blade by blade (derivations in that module).
    fn closed_form_function(&self, declared: &ExpressionDeclaration, form: &ClosedForm) -> TokenStream {
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

    /// The matrix type of a linear map with its `apply`, and the `const fn` building it from the other
    /// parameters.
    fn linear_map(&self, declared: &ExpressionDeclaration, map: &LinearMap) -> TokenStream {
        let fused = &map.fused;
        let scalar = &self.scalar;
        let (rows, columns) = map.shape;
        let map_type = format_ident!("{}", map_type_name(&declared.name));
        let builder = format_ident!("{}", map_builder_name(&declared.name));
        let linear = &declared.parameters[map.linear];
        let linear_ident = format_ident!("{}", linear.name);
        let linear_type = self.output_type(fused.parameters[map.linear]);
        let output = self.output_type(fused.output);
        let column_value = |column: usize| match fused.parameters[map.linear] {
            Output::Type(ty) => {
                let field = field_ident(&self.algebra.types[ty], column);
                quote! { #linear_ident.#field }
            }
            Output::Scalar => quote! { #linear_ident },
        };
        let zero = self.literal(Rational64::zero());
        // Apply: per result field, the products with the entries that do not vanish identically.
        let row_sum = |row: usize| {
            let products: Vec<TokenStream> = (0..columns)
                .filter(|column| {
                    map.entries
                        .outputs
                        .contains_key(&((row * columns + column) as BladeMask))
                })
                .map(|column| {
                    let (r, c) = (Literal::usize_unsuffixed(row), Literal::usize_unsuffixed(column));
                    let x = column_value(column);
                    quote! { self.matrix[#r][#c] * #x }
                })
                .collect();
            match products.is_empty() {
                true => quote! { #zero },
                false => quote! { #(#products)+* },
            }
        };
        let result = match fused.output {
            Output::Scalar => row_sum(0),
            Output::Type(ty) => {
                let ty = &self.algebra.types[ty];
                let name = format_ident!("{}", ty.name);
                let fields = ty.fields.iter().enumerate().map(|(row, field)| {
                    let ident = format_ident!("{}", field.name);
                    let value = row_sum(row);
                    quote! { #ident: #value }
                });
                quote! { #name { #(#fields),* } }
            }
        };
        let (non_zero, apply_cost) = (map.entries.outputs.len(), map.apply_cost());
        let input = self.parameter_fields(declared, fused);
        let locals = self.locals(&input, &map.entries);
        // Each entry is bound to a local first: an array element that is a sum or a product would trip clippy's
        // `possible_missing_comma` in the user's crate (every emitted token spans the whole macro invocation).
        // Named apart from the parameters and the shared locals (`entry_0_1`, or `entry__0_1` if a parameter or local
        // already starts with `entry_`, and so on).
        let mut prefix = String::from("entry");
        let taken = |prefix: &str| {
            let start = format!("{prefix}_");
            declared.parameters.iter().any(|p| p.name.starts_with(&start))
                || map.entries.locals.iter().any(|local| local.name.starts_with(&start))
        };
        while taken(&prefix) {
            prefix.push('_');
        }
        let entry = |row: usize, column: usize| format_ident!("{prefix}_{row}_{column}");
        let entry_values = (0..rows)
            .flat_map(|row| (0..columns).map(move |column| (row, column)))
            .map(|(row, column)| {
                let terms = map.entries.outputs.get(&((row * columns + column) as BladeMask));
                let value = self.sum(&input, &map.entries, terms.map(Vec::as_slice).unwrap_or(&[]), false);
                let name = entry(row, column);
                quote! { let #name = #value; }
            });
        let matrix_rows = (0..rows).map(|row| {
            let entries = (0..columns).map(|column| entry(row, column));
            quote! { [#(#entries),*] }
        });
        let parameters = self.parameter_list(declared, fused, &map.entries, Some(map.linear));
        let (rows_literal, columns_literal) = (Literal::usize_unsuffixed(rows), Literal::usize_unsuffixed(columns));
        let type_doc = doc_lines(&format!(
            "`{}` as a matrix in `{}`: `{}_map(…)` builds it once from the other parameters, `apply` maps \
             each `{}` (a {rows}×{columns} matrix; {non_zero} entries do not vanish identically).",
            declared.body, linear.name, declared.name, linear.type_name
        ));
        let apply_doc = doc_lines(&format!(
            "`{}` for the parameters the map was built from.\n\nCost: {apply_cost}.",
            declared.name
        ));
        let builder_doc = doc_lines(&format!(
            "The matrix of `{}` in `{}` (see [`{map_type}`]).\n\nCost: {}.",
            declared.body, linear.name, map.cost
        ));
        quote! {
            #type_doc
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct #map_type {
                /// Row `i`, column `j`: the coefficient of the argument's field `j` in the result's field `i`.
                pub matrix: [[#scalar; #columns_literal]; #rows_literal],
            }

            impl #map_type {
                #apply_doc
                #[inline]
                pub const fn apply(&self, #linear_ident: #linear_type) -> #output {
                    #result
                }
            }

            #builder_doc
            #[inline]
            pub const fn #builder(#(#parameters),*) -> #map_type {
                #locals
                #(#entry_values)*
                #map_type { matrix: [#(#matrix_rows),*] }
            }
        }
    }

    fn uses_rhs(function: &Function) -> bool {
        match &function.code {
            Code::Unrolled(program) => program.reads(|variable| variable.operand == Operand::Rhs),
            Code::Table(table) => table
                .stages
                .iter()
                .any(|s| s.left == Source::Rhs || s.right == Source::Rhs),
        }
    }

    fn binary_impl(&self, function: &Function) -> TokenStream {
        let operation = function.operation.expect("binary functions have an operation");
        let lhs = format_ident!("{}", self.algebra.types[function.lhs].name);
        let rhs_type = format_ident!("{}", self.algebra.types[function.rhs.expect("binary")].name);
        let trait_name = trait_ident(operation);
        let method = format_ident!("{}", operation.name());
        let output = self.output_type(function.output);
        let body = self.body(function);
        let doc = self.doc(function);
        let parameter = if Self::uses_rhs(function) {
            format_ident!("rhs")
        } else {
            format_ident!("_rhs")
        };
        let sugar = match operation {
            Operation::Geometric => Some((quote! { Mul }, quote! { mul })),
            Operation::Outer => Some((quote! { BitXor }, quote! { bitxor })),
            Operation::Regressive => Some((quote! { BitAnd }, quote! { bitand })),
            Operation::LeftContraction => Some((quote! { BitOr }, quote! { bitor })),
            _ => None,
        };
        let operator = sugar.map(|(op_trait, op_method)| {
            let doc = format!("Sugar for [`{trait_name}::{method}`].");
            quote! {
                impl core::ops::#op_trait<#rhs_type> for #lhs {
                    type Output = #output;
                    #[doc = #doc]
                    #[inline]
                    fn #op_method(self, rhs: #rhs_type) -> #output {
                        #trait_name::#method(self, rhs)
                    }
                }
            }
        });
        let const_method = format_ident!(
            "{}",
            const_method_name(operation, &self.algebra.types[function.rhs.expect("binary")].name)
        );
        let forward_doc = format!("Forwards to the `const fn` [`{lhs}::{const_method}`].");
        quote! {
            impl #lhs {
                #doc
                #[inline]
                pub const fn #const_method(self, #parameter: #rhs_type) -> #output {
                    #body
                }
            }
            impl #trait_name<#rhs_type> for #lhs {
                type Output = #output;
                #[doc = #forward_doc]
                #[inline]
                fn #method(self, rhs: #rhs_type) -> #output {
                    self.#const_method(rhs)
                }
            }
            #operator
        }
    }

    fn sum_impl(&self, function: &Function) -> TokenStream {
        let lhs = format_ident!("{}", self.algebra.types[function.lhs].name);
        let rhs_type = format_ident!("{}", self.algebra.types[function.rhs.expect("binary")].name);
        let (op_trait, method) = if function.method == "sub" {
            (quote! { Sub }, quote! { sub })
        } else {
            (quote! { Add }, quote! { add })
        };
        let output = self.output_type(function.output);
        let body = self.body(function);
        // A sum can hold only subtractions (a field stored sign-flipped, like `e31`), which clippy's
        // `suspicious_arithmetic_impl` mistakes for a wrong operator.
        quote! {
            #[allow(clippy::suspicious_arithmetic_impl)]
            impl core::ops::#op_trait<#rhs_type> for #lhs {
                type Output = #output;
                #[inline]
                fn #method(self, rhs: #rhs_type) -> #output {
                    #body
                }
            }
        }
    }
}
