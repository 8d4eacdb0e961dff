//! Declared expressions, fused: one `pub const fn` computing the whole formula, and for a formula linear in a
//! parameter the matrix type of that linear map, with its `apply` and the `const fn` building it.

use num_rational::Rational64;
use num_traits::Zero;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::emitter::{doc_lines, field_ident, Emitter};
use crate::blade::BladeMask;
use crate::expand::Variable;
use crate::expression::ExpressionDeclaration;
use crate::functions::{Finish, Output};
use crate::fuse::{Fused, LinearMap};
use crate::naming::{map_builder_name, map_type_name};
use crate::program::Program;

/// An expression function's documentation: the user's (if any), then the generated notes.
pub(super) fn expression_doc(declared: &ExpressionDeclaration, generated: &str) -> TokenStream {
    match &declared.doc {
        Some(user) => doc_lines(&format!("{user}\n\n{generated}")),
        None => doc_lines(generated),
    }
}

impl Emitter<'_> {
    /// How a fused expression's code reads its inputs: `m.e12`, or `t` for a scalar parameter.
    pub(super) fn parameter_fields<'f>(
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
    pub(super) fn fused_function(&self, declared: &ExpressionDeclaration, fused: &Fused) -> TokenStream {
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

    /// The matrix type of a linear map with its `apply`, and the `const fn` building it from the other
    /// parameters.
    pub(super) fn linear_map(&self, declared: &ExpressionDeclaration, map: &LinearMap) -> TokenStream {
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
}
