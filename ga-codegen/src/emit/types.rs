//! The declared types: per type a `#[repr(C)]` struct with its constructors, its arithmetic with scalars, and the
//! `From` conversions into the types that hold all its blades.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::emitter::{field_ident, Emitter};
use crate::algebra::SparseType;

/// The traits every emitted struct derives (it is also `#[repr(C)]`).
pub const DERIVED_TRAITS: [&str; 5] = ["Clone", "Copy", "Debug", "PartialEq", "Default"];

impl Emitter<'_> {
    pub(super) fn type_definition(&self, ty: &SparseType) -> TokenStream {
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

    pub(super) fn scalar_arithmetic(&self, ty: &SparseType) -> TokenStream {
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
    pub(super) fn conversion(&self, from: &SparseType, to: &SparseType) -> TokenStream {
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
}
