//! The operations: a trait per binary operation, and per function of the catalogue its code with a doc comment
//! stating what it computes and its cost: unary methods, binary trait impls (each forwarding to an inherent
//! `const fn`, with operator sugar) and `Add`/`Sub` impls.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::emitter::{doc_lines, Emitter};
use crate::algebra::Algebra;
use crate::expand::Operand;
use crate::functions::{Code, Function};
use crate::naming::{const_method_name, trait_name};
use crate::operation::Operation;
use crate::table::Source;

/// The trait impl (and operator sugar) of one binary function, e.g. to inspect or snapshot it.
pub fn binary_function(algebra: &Algebra, function: &Function) -> TokenStream {
    Emitter::new(algebra).binary_impl(function)
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

pub(super) fn binary_trait(operation: Operation) -> TokenStream {
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

/// How a tabled function's doc reads its tables.
const TABLE_LAYOUT: &str = "A table holds one entry `i, j, k, n` per product, each a little-endian `u16` (`u32` where \
     an index needs it): `stage[k] += coefficients[n] · left[i] · right[j]`.";

impl Emitter<'_> {
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

    pub(super) fn unary_method(&self, function: &Function) -> TokenStream {
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

    pub(super) fn sum_impl(&self, function: &Function) -> TokenStream {
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
