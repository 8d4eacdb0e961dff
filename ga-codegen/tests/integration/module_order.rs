//! The modules of ga-codegen read one way, in pipeline order: each refers only to modules before it (in a `use`
//! or a path `crate::module::item` in code), so that every stage can be read knowing only the stages before it.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// Every module of `src`, in pipeline order; `lib`, the crate root, comes last.
const ORDER: &[&str] = &[
    // The declaration: blade masks, operations, the syntax tree of declared expressions, the declaration, its errors.
    "blade",
    "operation",
    "expression",
    "declaration",
    "error",
    // The validated algebra model: the metric, the names of emitted items, the algebra.
    "metric",
    "naming",
    "algebra",
    // Product rules per blade pair, and the evaluator applying them to dense multivectors.
    "product",
    "evaluator",
    // Symbolic expansion of a product and its lowering to straight-line code or tables, one function each.
    "expand",
    "program",
    "table",
    "functions",
    // Declared expressions expanded as a whole: fused into one function, or in closed form.
    "fuse",
    "transcendental",
    // Emission: the opt-in trait impls, the Rust tokens, and the crate root's entry points.
    "features",
    "emit",
    "lib",
];

fn sources() -> Vec<(String, PathBuf)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files: Vec<(String, PathBuf)> = fs::read_dir(&src)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|extension| extension == "rs"))
        .map(|path| (path.file_stem().unwrap().to_str().unwrap().to_string(), path))
        .collect();
    files.sort();
    files
}

fn tokens(path: &Path) -> Vec<TokenTree> {
    let source = fs::read_to_string(path).unwrap();
    TokenStream::from_str(&source).unwrap().into_iter().collect()
}

fn ident(tree: Option<&TokenTree>) -> Option<String> {
    match tree {
        Some(TokenTree::Ident(ident)) => Some(ident.to_string()),
        _ => None,
    }
}

fn is_path_separator(trees: &[TokenTree]) -> bool {
    matches!(trees, [TokenTree::Punct(first), TokenTree::Punct(second), ..]
        if first.as_char() == ':' && second.as_char() == ':')
}

/// The first segment after each `crate::` in `trees`, at any depth: `module` in `crate::module::item`, and each
/// path's first segment in `crate::{a::X, b}`. Comments are not tokens, and doc comments are string literals, so
/// intra-doc links are not counted: a link may point forward, to where a reader goes next.
fn crate_references(trees: &[TokenTree], found: &mut Vec<String>) {
    for (index, tree) in trees.iter().enumerate() {
        if let TokenTree::Group(group) = tree {
            crate_references(&group.stream().into_iter().collect::<Vec<_>>(), found);
        }
        if !matches!(tree, TokenTree::Ident(word) if word == "crate") || !is_path_separator(&trees[index + 1..]) {
            continue;
        }
        match trees.get(index + 3) {
            Some(TokenTree::Group(group)) if group.delimiter() == Delimiter::Brace => {
                let inner: Vec<TokenTree> = group.stream().into_iter().collect();
                let items = inner.split(|tree| matches!(tree, TokenTree::Punct(p) if p.as_char() == ','));
                found.extend(items.filter_map(|item| ident(item.first())));
            }
            next => found.extend(ident(next)),
        }
    }
}

/// What `lib.rs` re-exports at the root, by name: the module it comes from, or `None` for another crate's item.
fn root_re_exports(modules: &[String]) -> BTreeMap<String, Option<String>> {
    let lib = tokens(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs"));
    let mut re_exports = BTreeMap::new();
    let statements = lib.split(|tree| matches!(tree, TokenTree::Punct(p) if p.as_char() == ';'));
    for statement in statements {
        let Some(start) = statement
            .iter()
            .position(|tree| matches!(tree, TokenTree::Ident(word) if word == "use"))
        else {
            continue;
        };
        let path = &statement[start + 1..];
        let source = ident(path.first()).filter(|name| modules.contains(name));
        let names: Vec<String> = match path.last() {
            Some(TokenTree::Group(group)) => {
                let inner: Vec<TokenTree> = group.stream().into_iter().collect();
                let items = inner.split(|tree| matches!(tree, TokenTree::Punct(p) if p.as_char() == ','));
                items.filter_map(|item| ident(item.last())).collect()
            }
            last => ident(last).into_iter().collect(),
        };
        re_exports.extend(names.into_iter().map(|name| (name, source.clone())));
    }
    re_exports
}

fn position(module: &str) -> usize {
    ORDER
        .iter()
        .position(|&m| m == module)
        .unwrap_or_else(|| panic!("`{module}` is not in ORDER"))
}

#[test]
fn the_order_lists_every_module_once() {
    let mut listed: Vec<&str> = ORDER.to_vec();
    listed.sort();
    listed.dedup();
    assert_eq!(listed.len(), ORDER.len(), "a module is listed twice in ORDER");
    let files: Vec<String> = sources().into_iter().map(|(module, _)| module).collect();
    assert_eq!(listed, files, "ORDER and the files of src/ differ");
}

#[test]
fn modules_refer_only_to_earlier_modules() {
    let sources = sources();
    let modules: Vec<String> = sources.iter().map(|(module, _)| module.clone()).collect();
    let re_exports = root_re_exports(&modules);
    let mut violations = Vec::new();
    for (module, path) in &sources {
        let mut found = Vec::new();
        crate_references(&tokens(path), &mut found);
        for name in found {
            // A root path names a module (`crate::fuse`), an item the root re-exports (`crate::Algebra`, of
            // `algebra`; `crate::Rational64`, of another crate) or one the root defines (`crate::generate`).
            let target = match re_exports.get(&name) {
                None if modules.contains(&name) => name.clone(),
                Some(Some(source)) => source.clone(),
                Some(None) => continue,
                None => "lib".to_string(),
            };
            if position(&target) > position(module) {
                violations.push(format!("{module} refers to crate::{name} (in {target})"));
            }
        }
    }
    violations.sort();
    violations.dedup();
    assert!(
        violations.is_empty(),
        "modules referring to later modules in the pipeline order:\n{}",
        violations.join("\n")
    );
}
