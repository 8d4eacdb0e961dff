//! The items of an algebra's module, in order: the operation traits, then per type its struct, methods and
//! arithmetic, then per pair of types their sums, conversion and binary operations, then the declared expressions.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::emitter::Emitter;
use super::operations::{binary_function, binary_trait};
use crate::algebra::{Algebra, SparseType};
use crate::error::{collect, Error};
use crate::functions::{self, Function};
use crate::fuse;
use crate::operation::Operation;
use crate::transcendental;

/// Emits the items of the algebra's module, refusing a declaration whose functions take more than
/// [`functions::MAX_BUILD_WORK`] to build.
pub fn emit(algebra: &Algebra) -> Result<TokenStream, Error> {
    emit_within(algebra, functions::MAX_BUILD_WORK)
}

/// [`emit`] with a limit of `max_build_work` ([`Function::build_work`] summed over the functions), checked as the
/// functions are made, so a refusal comes before the rest is built.
pub fn emit_within(algebra: &Algebra, max_build_work: usize) -> Result<TokenStream, Error> {
    let emitter = Emitter::new(algebra);
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
    let emitter = Emitter::new(algebra);
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

fn blades(ty: &SparseType) -> Vec<u32> {
    ty.fields.iter().map(|f| f.blade).collect()
}
