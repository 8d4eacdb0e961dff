//! The output: the items `ga_codegen::generate` emits, wrapped in the user's module, with the doc
//! comments of each type declaration moved onto its struct.

use ga_codegen::AlgebraDeclaration;
use proc_macro2::TokenStream;
use quote::quote;
use syn::{Attribute, Item};

use crate::diagnostics::collect;
use crate::parse::{AlgebraInput, TypeEntry};
use crate::validate::locate;

/// `#[attrs] vis mod name { generated items }`.
pub fn expand(input: &AlgebraInput, declaration: &AlgebraDeclaration) -> syn::Result<TokenStream> {
    let items = ga_codegen::generate(declaration).map_err(|error| locate(input, &error))?;
    let items = document_types(input, items)?;
    let AlgebraInput {
        attrs,
        vis,
        mod_token,
        name,
        ..
    } = input;
    Ok(quote! {
        #(#attrs)*
        #vis #mod_token #name {
            #items
        }
    })
}

/// Prepends each type declaration's doc comments to the struct emitted for it. `ga_codegen` knows
/// nothing of documentation, so its output is re-parsed to find the structs.
fn document_types(input: &AlgebraInput, items: TokenStream) -> syn::Result<TokenStream> {
    let documented: Vec<&TypeEntry> = input.types.iter().filter(|entry| !entry.attrs.is_empty()).collect();
    // Big algebras emit a lot of code: re-parse it only when there is documentation to place.
    if documented.is_empty() {
        return Ok(items);
    }
    let mut file: syn::File = syn::parse2(items).map_err(|error| {
        syn::Error::new(
            input.name.span(),
            format!("internal error: ga-codegen emitted code that does not parse: {error}"),
        )
    })?;
    collect(documented.into_iter().map(|entry| {
        let docs: &[Attribute] = &entry.attrs;
        let structure = file.items.iter_mut().find_map(|item| match item {
            Item::Struct(structure) if structure.ident == entry.name => Some(structure),
            _ => None,
        });
        match structure {
            Some(structure) => {
                structure.attrs.splice(0..0, docs.iter().cloned());
                Ok(())
            }
            None => Err(syn::Error::new(
                entry.name.span(),
                format!(
                    "internal error: ga-codegen emitted no struct `{}` to carry its documentation",
                    entry.name
                ),
            )),
        }
    }))?;
    Ok(quote!(#file))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input() -> AlgebraInput {
        syn::parse_str(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = 1];
                types {
                    /// A direction.
                    Vector = grades(1);
                    Rotor = grades(0, 2);
                }
            }",
        )
        .unwrap()
    }

    #[test]
    fn type_docs_go_before_the_emitted_attributes_of_their_struct() {
        let emitted = quote! {
            #[derive(Clone)]
            pub struct Vector { pub e1: f64, pub e2: f64 }
            pub struct Rotor { pub scalar: f64, pub e12: f64 }
        };
        let documented: syn::File = syn::parse2(document_types(&input(), emitted).unwrap()).unwrap();
        let expected: syn::File = syn::parse_quote! {
            #[doc = " A direction."]
            #[derive(Clone)]
            pub struct Vector { pub e1: f64, pub e2: f64 }
            pub struct Rotor { pub scalar: f64, pub e12: f64 }
        };
        assert_eq!(documented, expected);
    }

    #[test]
    fn a_documented_type_without_a_struct_is_reported() {
        let emitted = quote! { pub struct Rotor { pub scalar: f64, pub e12: f64 } };
        let error = document_types(&input(), emitted).unwrap_err();
        assert_eq!(
            error.to_string(),
            "internal error: ga-codegen emitted no struct `Vector` to carry its documentation"
        );
    }
}
