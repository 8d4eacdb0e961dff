//! Emission: Rust tokens for the declared types and every operation between them.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::algebra::Algebra;
use crate::error::Error;

/// Emits the items of the algebra's module.
pub fn emit(algebra: &Algebra) -> Result<TokenStream, Error> {
    let scalar = format_ident!("{}", algebra.scalar.name());
    let structs = algebra.types.iter().map(|ty| {
        let name = format_ident!("{}", ty.name);
        let fields = ty.fields.iter().map(|f| format_ident!("{}", f.name));
        quote! {
            #[derive(Clone, Copy, Debug, PartialEq, Default)]
            #[repr(C)]
            pub struct #name { #(pub #fields: #scalar,)* }
        }
    });
    Ok(quote! { #(#structs)* })
}
