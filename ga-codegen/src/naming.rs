//! The names of emitted items that derive from declared names: the trait and the `const fn` form of each binary
//! operation, and the type and builder of an expression's linear map. Validation ([`crate::algebra`]) refuses
//! declarations whose derived names would collide, emission ([`crate::emit`]) spells them: both by these rules.

use crate::operation::Operation;

/// `PlaneSet` → `plane_set` (`Ω` → `ω`): the suffix of the `const fn` form of a binary operation.
pub(crate) fn snake_case(name: &str) -> String {
    let mut out = String::with_capacity(name.len() + 4);
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.extend(c.to_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// `moved_line` → `MovedLine`.
fn upper_camel_case(name: &str) -> String {
    name.split('_')
        .filter(|part| !part.is_empty())
        .map(|part| {
            let mut chars = part.chars();
            chars
                .next()
                .map(|c| c.to_uppercase().chain(chars).collect::<String>())
                .unwrap_or_default()
        })
        .collect()
}

/// The name of a binary operation's trait (`left_contraction` → `LeftContraction`).
pub(crate) fn trait_name(operation: Operation) -> String {
    upper_camel_case(operation.name())
}

/// The `const fn` form of a binary operation on a right-hand type: `geometric` on `PlaneSet` → `geometric_plane_set`.
pub(crate) fn const_method_name(operation: Operation, rhs_type: &str) -> String {
    format!("{}_{}", operation.name(), snake_case(rhs_type))
}

/// The name of the type of an expression's linear map: `moved_line` → `MovedLineMap`.
pub(crate) fn map_type_name(expression: &str) -> String {
    upper_camel_case(expression) + "Map"
}

/// The name of the function building an expression's linear map: `moved_line` → `moved_line_map`.
pub(crate) fn map_builder_name(expression: &str) -> String {
    format!("{expression}_map")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_names_follow_rust_conventions() {
        assert_eq!(trait_name(Operation::LeftContraction), "LeftContraction");
        assert_eq!(
            const_method_name(Operation::Geometric, "PlaneSet"),
            "geometric_plane_set"
        );
        assert_eq!(snake_case("Ω"), "ω");
        assert_eq!(map_type_name("moved_line"), "MovedLineMap");
        assert_eq!(map_builder_name("moved_line"), "moved_line_map");
    }
}
