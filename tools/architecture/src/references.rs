//! The modules a module refers to: every path in its code that starts at the crate root (`crate::`), at a module
//! around it (`self::`, `super::`) or at one of its child modules, resolved through `use` re-exports to the module
//! that defines the item. Doc comments are string literals, so intra-doc links are not counted: a link may point
//! forward, to where a reader goes next. Items under `#[cfg(test)]` are the module's tests, not its dependencies.

use proc_macro2::{Delimiter, TokenTree};

use crate::tree::{self, Module, ModulePath};

/// One path in a module's code.
#[derive(Debug, Clone)]
pub struct Reference {
    /// The module the path starts at.
    pub base: ModulePath,
    /// Its segments after that start.
    pub segments: Vec<String>,
}

/// Every path in `module`'s code outside its tests.
pub fn references(module: &Module) -> Vec<Reference> {
    let mut found = Vec::new();
    for item in tree::items(&module.tokens) {
        if !tree::is_test_only(item) {
            collect(item, &module.path, &module.children, &mut found);
        }
    }
    found
}

fn collect(trees: &[TokenTree], scope: &[String], children: &[String], found: &mut Vec<Reference>) {
    for (index, tree) in trees.iter().enumerate() {
        if let TokenTree::Group(group) = tree {
            let inner: Vec<TokenTree> = group.stream().into_iter().collect();
            // `mod name { … }`: paths inside start from the inline module.
            let inline = inline_module_name(&trees[..index]).filter(|_| group.delimiter() == Delimiter::Brace);
            match inline {
                Some(name) => {
                    let mut nested = scope.to_vec();
                    nested.push(name);
                    collect(&inner, &nested, &[], found);
                }
                None => collect(&inner, scope, children, found),
            }
            continue;
        }
        let TokenTree::Ident(first) = tree else { continue };
        let first = first.to_string();
        let starts_path = matches!(first.as_str(), "crate" | "self" | "super") || children.contains(&first);
        let continues_path = index >= 2 && tree::is_separator(&trees[index - 2..]);
        if !starts_path || continues_path || !tree::is_separator(&trees[index + 1..]) {
            continue;
        }
        let mut segments = vec![first];
        let mut at = index + 3;
        let mut use_tree = None;
        loop {
            match trees.get(at) {
                Some(TokenTree::Ident(segment)) => segments.push(segment.to_string()),
                Some(TokenTree::Group(group)) if group.delimiter() == Delimiter::Brace => {
                    use_tree = Some(group.stream().into_iter().collect::<Vec<_>>());
                    break;
                }
                _ => break,
            }
            if !tree::is_separator(&trees[at + 1..]) {
                break;
            }
            at += 3;
        }
        let mut push = |segments: Vec<String>| {
            if let (Some(base), rest) = tree::path_base(segments, scope, children) {
                found.push(Reference { base, segments: rest });
            }
        };
        match use_tree {
            Some(inner) => {
                let mut prefix = segments;
                let mut leaves = Vec::new();
                let braced = [TokenTree::Group(proc_macro2::Group::new(
                    Delimiter::Brace,
                    inner.into_iter().collect(),
                ))];
                tree::expand_use_tree_into(&braced, &mut prefix, &mut |path, _| leaves.push(path));
                leaves.into_iter().for_each(&mut push);
            }
            None => push(segments),
        }
    }
}

/// `name` when `head` ends with `mod name`.
fn inline_module_name(head: &[TokenTree]) -> Option<String> {
    match head {
        [.., TokenTree::Ident(keyword), TokenTree::Ident(name)] if keyword == "mod" => Some(name.to_string()),
        _ => None,
    }
}
