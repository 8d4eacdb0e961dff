//! The emitter: the algebra it emits for and its scalar type, and the small pieces every emitted item is made of
//! (literals, identifiers, output types, doc lines).

use num_rational::Rational64;
use num_traits::ToPrimitive;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::algebra::{Algebra, SparseType};
use crate::declaration::ScalarType;
use crate::functions::Output;

pub(super) struct Emitter<'a> {
    pub(super) algebra: &'a Algebra,
    pub(super) scalar: Ident,
}

impl<'a> Emitter<'a> {
    /// An emitter for `algebra`, its scalar type named as in emitted code (`f64`).
    pub(super) fn new(algebra: &'a Algebra) -> Emitter<'a> {
        Emitter {
            algebra,
            scalar: format_ident!("{}", algebra.scalar.name()),
        }
    }

    pub(super) fn literal(&self, value: Rational64) -> Literal {
        let value = value.to_f64().unwrap_or(f64::NAN);
        match self.algebra.scalar {
            ScalarType::F32 => Literal::f32_unsuffixed(value as f32),
            ScalarType::F64 => Literal::f64_unsuffixed(value),
        }
    }

    pub(super) fn output_type(&self, output: Output) -> TokenStream {
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
}

pub(super) fn field_ident(ty: &SparseType, index: usize) -> Ident {
    format_ident!("{}", ty.fields[index].name)
}

/// One `#[doc]` attribute per line, so that formatted code shows `///` lines.
pub(super) fn doc_lines(text: &str) -> TokenStream {
    let lines = text.lines().map(|line| {
        if line.is_empty() {
            String::new()
        } else {
            format!(" {line}")
        }
    });
    quote! { #(#[doc = #lines])* }
}
