//! The output: the items `ga_codegen` emits (with the opt-in features), wrapped in the user's
//! module, with the attributes of each type declaration moved onto its struct.

use proc_macro2::TokenStream;
use quote::{quote, ToTokens};
use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{Attribute, Item, Meta, MetaList, Token};

use crate::diagnostics::collect;
use crate::parse::{AlgebraInput, TypeEntry};
use crate::validate::{locate, Validated};

/// `#[attrs] vis mod name { generated items }`.
pub fn expand(input: &AlgebraInput, validated: &Validated) -> syn::Result<TokenStream> {
    let items = ga_codegen::generate_with_features(&validated.declaration, &validated.features)
        .map_err(|error| locate(input, &error))?;
    let items = attach_attributes(input, items)?;
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

/// Puts each type declaration's attributes on the struct emitted for it: doc comments before the
/// emitted ones (the declaration's documentation comes first), every other attribute (checked by
/// [`crate::validate`]) after the emitted `#[derive(…)]` and `#[repr(C)]`, less any `C` hint of its
/// own (see [`without_repr_c`]). `ga_codegen` knows nothing of attributes, so its output is re-parsed
/// to find the structs.
fn attach_attributes(input: &AlgebraInput, items: TokenStream) -> syn::Result<TokenStream> {
    let attributed: Vec<&TypeEntry> = input.types.iter().filter(|entry| !entry.attrs.is_empty()).collect();
    // Big algebras emit a lot of code: re-parse it only when there are attributes to place.
    if attributed.is_empty() {
        return Ok(items);
    }
    let mut file: syn::File = syn::parse2(items).map_err(|error| {
        syn::Error::new(
            input.name.span(),
            format!("internal error: ga-codegen emitted code that does not parse: {error}"),
        )
    })?;
    collect(attributed.into_iter().map(|entry| {
        let (docs, others): (Vec<&Attribute>, Vec<&Attribute>) = entry
            .attrs
            .iter()
            .partition(|attribute| attribute.path().is_ident("doc"));
        let others = collect(others.into_iter().map(|attribute| {
            Ok(without_repr_c(&attribute.meta)?.map(|meta| Attribute {
                meta,
                ..attribute.clone()
            }))
        }))?;
        let structure = file.items.iter_mut().find_map(|item| match item {
            Item::Struct(structure) if structure.ident == entry.name => Some(structure),
            _ => None,
        });
        match structure {
            Some(structure) => {
                structure.attrs.splice(0..0, docs.into_iter().cloned());
                structure.attrs.extend(others.into_iter().flatten());
                Ok(())
            }
            None => Err(syn::Error::new(
                entry.name.span(),
                format!(
                    "internal error: ga-codegen emitted no struct `{}` to carry its attributes",
                    entry.name
                ),
            )),
        }
    }))?;
    Ok(quote!(#file))
}

/// `meta` without the `C` hints of its `repr`s (also inside `cfg_attr`), or `None` if nothing is
/// left. The struct is always `repr(C)`; rustc accepts a second `C` hint, but derives that read the
/// representation, such as bytemuck's `Pod`, refuse it as a conflict.
fn without_repr_c(meta: &Meta) -> syn::Result<Option<Meta>> {
    let rebuilt = |list: &MetaList, tokens: TokenStream| Meta::List(MetaList { tokens, ..list.clone() });
    let path = meta.path();
    if path.is_ident("repr") {
        let list = meta.require_list()?;
        let hints = list.parse_args_with(Punctuated::<Meta, Token![,]>::parse_terminated)?;
        let kept: Punctuated<Meta, Token![,]> = hints
            .into_iter()
            .filter(|hint| !(hint.path().is_ident("C") && matches!(hint, Meta::Path(_))))
            .collect();
        Ok((!kept.is_empty()).then(|| rebuilt(list, kept.into_token_stream())))
    } else if path.is_ident("cfg_attr") {
        let list = meta.require_list()?;
        let (predicate, added) = list.parse_args_with(|input: ParseStream| {
            let predicate: Meta = input.parse()?;
            input.parse::<Token![,]>()?;
            Ok((predicate, Punctuated::<Meta, Token![,]>::parse_terminated(input)?))
        })?;
        let mut kept = Punctuated::<Meta, Token![,]>::new();
        for meta in &added {
            kept.extend(without_repr_c(meta)?);
        }
        Ok((!kept.is_empty()).then(|| rebuilt(list, quote!(#predicate, #kept))))
    } else {
        Ok(Some(meta.clone()))
    }
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
                    #[derive(serde::Serialize)]
                    #[repr(C)]
                    #[repr(C, align(16))]
                    #[cfg_attr(feature = \"gpu\", repr(C), derive(bytemuck::Pod))]
                    #[cfg_attr(feature = \"gpu\", repr(C))]
                    Vector = grades(1);
                    Rotor = grades(0, 2);
                }
            }",
        )
        .unwrap()
    }

    #[test]
    fn type_docs_go_before_the_emitted_attributes_of_their_struct_and_the_others_after() {
        let emitted = quote! {
            #[derive(Clone)]
            pub struct Vector { pub e1: f64, pub e2: f64 }
            pub struct Rotor { pub scalar: f64, pub e12: f64 }
        };
        let documented: syn::File = syn::parse2(attach_attributes(&input(), emitted).unwrap()).unwrap();
        let expected: syn::File = syn::parse_quote! {
            #[doc = " A direction."]
            #[derive(Clone)]
            #[derive(serde::Serialize)]
            #[repr(align(16))]
            #[cfg_attr(feature = "gpu", derive(bytemuck::Pod))]
            pub struct Vector { pub e1: f64, pub e2: f64 }
            pub struct Rotor { pub scalar: f64, pub e12: f64 }
        };
        assert_eq!(documented, expected);
    }

    #[test]
    fn a_documented_type_without_a_struct_is_reported() {
        let emitted = quote! { pub struct Rotor { pub scalar: f64, pub e12: f64 } };
        let error = attach_attributes(&input(), emitted).unwrap_err();
        assert_eq!(
            error.to_string(),
            "internal error: ga-codegen emitted no struct `Vector` to carry its attributes"
        );
    }

    /// The whole macro (parse, validate, expand) on the longest and deepest expressions it accepts, on a
    /// thread with rustc's stack (8 MiB), where a proc macro runs.
    #[test]
    fn the_longest_and_deepest_accepted_expressions_expand_on_rustcs_stack() {
        let sum = vec!["a"; 5000].join(" + ");
        let deep = format!(
            "{}a{}",
            "-".repeat(crate::parse::MAX_NESTING / 2),
            ".reverse()".repeat(crate::parse::MAX_NESTING / 2 - 1)
        );
        let source = format!(
            "mod pga {{
                scalar = f64;
                basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
                ops = [reverse];
                types {{ Line = grades(2); }}
                fn long(a: Line) -> Line = {sum};
                fn deep(a: Line) -> Line = {deep};
            }}"
        );
        let expanded = std::thread::Builder::new()
            .stack_size(8 << 20)
            .spawn(move || {
                let input: AlgebraInput = syn::parse_str(&source)?;
                let validated = crate::validate::validate(&input)?;
                expand(&input, &validated).map(|tokens| tokens.to_string())
            })
            .unwrap()
            .join()
            .expect("no overflow")
            .unwrap();
        assert!(expanded.contains("fn long"), "{expanded}");
        assert!(expanded.contains("5000"), "the sum is 5000 a: {expanded}");
    }
}
