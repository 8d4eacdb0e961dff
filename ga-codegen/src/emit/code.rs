//! A function's body: a straight-line program as `let` statements and signed sums, or constant tables and `while`
//! loops for a product too big to unroll.

use num_rational::Rational64;
use num_traits::{One, Signed, Zero};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote, ToTokens};

use super::emitter::{field_ident, Emitter};
use crate::blade::BladeMask;
use crate::expand::{Operand, Variable};
use crate::functions::{Code, Finish, Function, Output};
use crate::product::reverse_sign;
use crate::program::{Definition, Program, Term, Value};
use crate::table::{EncodedStage, Source, Table};

/// How emitted code reads an input variable (an operand's field).
pub(super) type Inputs<'a> = &'a dyn Fn(Variable) -> TokenStream;

impl Emitter<'_> {
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
    pub(super) fn sum(&self, input: Inputs, program: &Program, terms: &[Term], negate: bool) -> TokenStream {
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
    pub(super) fn body(&self, function: &Function) -> TokenStream {
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
    pub(super) fn locals(&self, input: Inputs, program: &Program) -> TokenStream {
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
    pub(super) fn unrolled_body(
        &self,
        input: Inputs,
        program: &Program,
        output: Output,
        finish: Finish,
    ) -> TokenStream {
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
}
