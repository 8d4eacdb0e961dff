//! The module tree of a crate, read from its files: which modules exist, in the order the crate root declares
//! them, and what each module's top level defines and imports.

use std::fs;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// A module's path from the crate root: `[]` for the root, `["mechanism", "build"]` for `crate::mechanism::build`.
pub type ModulePath = Vec<String>;

/// `crate::a::b` for the path `[a, b]`, `crate` for the root.
pub fn display(path: &[String]) -> String {
    std::iter::once("crate")
        .chain(path.iter().map(String::as_str))
        .collect::<Vec<_>>()
        .join("::")
}

/// One `use` at a module's top level: the name it brings in and the path it comes from.
#[derive(Debug, Clone)]
pub struct Import {
    /// The name in the importing module (the `as` name where there is one).
    pub name: String,
    /// Where the path starts: the root for `crate::`, the module itself for `self::` and child names, its parent
    /// for `super::`, or `None` for another crate.
    pub base: Option<ModulePath>,
    /// The path's segments after its start.
    pub segments: Vec<String>,
}

/// One file module.
#[derive(Debug)]
pub struct Module {
    /// Its path from the crate root.
    pub path: ModulePath,
    /// Its file.
    pub file: PathBuf,
    /// Its token trees.
    pub tokens: Vec<TokenTree>,
    /// Its file modules, in the order it declares them.
    pub children: Vec<String>,
    /// The names its top level defines (functions, types, traits, constants, statics).
    pub defined: Vec<String>,
    /// Its top-level `use` items, expanded one name each.
    pub imports: Vec<Import>,
}

/// Every file module of the crate whose `src/lib.rs` is under `manifest_dir`, children before their parent and
/// siblings in the order their parent declares them (the root last): the pipeline order the crate root states.
pub fn read_crate(manifest_dir: &Path) -> Vec<Module> {
    let mut modules = Vec::new();
    read_module(Vec::new(), manifest_dir.join("src/lib.rs"), &mut modules);
    modules
}

fn read_module(path: ModulePath, file: PathBuf, modules: &mut Vec<Module>) {
    let source = fs::read_to_string(&file).unwrap_or_else(|error| panic!("{}: {error}", file.display()));
    let tokens: Vec<TokenTree> = TokenStream::from_str(&source)
        .unwrap_or_else(|error| panic!("{}: {error:?}", file.display()))
        .into_iter()
        .collect();
    let children = file_module_declarations(&tokens);
    // A child of `lib.rs` or `x/mod.rs` lives beside it; a child of `x.rs` lives in `x/`.
    let is_directory_owner = matches!(file.file_name().and_then(|n| n.to_str()), Some("lib.rs" | "mod.rs"));
    let directory = if is_directory_owner {
        file.parent().unwrap().to_path_buf()
    } else {
        file.with_extension("")
    };
    for child in &children {
        let flat = directory.join(format!("{child}.rs"));
        let nested = directory.join(child).join("mod.rs");
        let child_file = if flat.exists() { flat } else { nested };
        let mut child_path = path.clone();
        child_path.push(child.clone());
        read_module(child_path, child_file, modules);
    }
    let defined = defined_names(&tokens);
    let imports = top_level_imports(&tokens, &path, &children);
    modules.push(Module {
        path,
        file,
        tokens,
        children,
        defined,
        imports,
    });
}

/// The token trees of each top-level item, split at `;` and at item bodies, with the item's outer attributes.
pub fn items(tokens: &[TokenTree]) -> Vec<&[TokenTree]> {
    let mut items = Vec::new();
    let mut start = 0;
    for (index, tree) in tokens.iter().enumerate() {
        let ends_item = match tree {
            TokenTree::Punct(punct) => punct.as_char() == ';',
            // A brace group ends an item unless it is a `#[...]`'s bracket or an expression inside `= ...;`.
            TokenTree::Group(group) => {
                group.delimiter() == Delimiter::Brace && !ends_at_semicolon(&tokens[start..index])
            }
            _ => false,
        };
        if ends_item {
            items.push(&tokens[start..=index]);
            start = index + 1;
        }
    }
    items
}

/// `use a::{b, c};`, `const X: T = T { .. };`, `static` and `type`: a brace is inside the item, which ends at `;`.
fn ends_at_semicolon(head: &[TokenTree]) -> bool {
    const ITEM_KEYWORDS: &[&str] = &[
        "fn", "struct", "enum", "impl", "trait", "mod", "const", "static", "type", "use", "union", "extern",
    ];
    let words = words(head);
    let Some(at) = words.iter().position(|word| ITEM_KEYWORDS.contains(&word.as_str())) else {
        return false;
    };
    match words[at].as_str() {
        "const" => words.get(at + 1).is_none_or(|next| next != "fn" && next != "unsafe"),
        "static" | "type" | "use" => true,
        _ => false,
    }
}

/// Whether an item carries `#[cfg(test)]`: such items are the module's own tests, not part of its dependencies.
pub fn is_test_only(item: &[TokenTree]) -> bool {
    item.windows(2).any(|pair| match pair {
        [TokenTree::Punct(hash), TokenTree::Group(group)] if hash.as_char() == '#' => {
            let text = group.stream().to_string().replace(' ', "");
            text == "cfg(test)"
        }
        _ => false,
    })
}

/// The words of an item outside its attributes: `pub`, `mod`, `name`, …
fn words(item: &[TokenTree]) -> Vec<String> {
    let mut words = Vec::new();
    let mut skip_attribute = false;
    for tree in item {
        match tree {
            TokenTree::Punct(p) if p.as_char() == '#' => skip_attribute = true,
            TokenTree::Group(g) if skip_attribute && g.delimiter() == Delimiter::Bracket => skip_attribute = false,
            TokenTree::Ident(ident) => {
                skip_attribute = false;
                words.push(ident.to_string());
            }
            TokenTree::Group(_) => {
                skip_attribute = false;
                words.push(String::new());
            }
            TokenTree::Punct(_) | TokenTree::Literal(_) => skip_attribute = false,
        }
    }
    words
}

/// `mod name;` declarations (file modules), in order.
fn file_module_declarations(tokens: &[TokenTree]) -> Vec<String> {
    items(tokens)
        .into_iter()
        .filter(|item| matches!(item.last(), Some(TokenTree::Punct(p)) if p.as_char() == ';'))
        .filter_map(|item| {
            let words = words(item);
            let at = words.iter().position(|word| word == "mod")?;
            words.get(at + 1).cloned()
        })
        .collect()
}

fn defined_names(tokens: &[TokenTree]) -> Vec<String> {
    const KEYWORDS: &[&str] = &[
        "fn",
        "struct",
        "enum",
        "trait",
        "type",
        "const",
        "static",
        "union",
        "macro_rules",
    ];
    items(tokens)
        .into_iter()
        .filter_map(|item| {
            let words = words(item);
            let at = words.iter().position(|word| KEYWORDS.contains(&word.as_str()))?;
            words
                .get(at + 1)
                .filter(|name| !name.is_empty() && *name != "fn")
                .cloned()
        })
        .collect()
}

fn top_level_imports(tokens: &[TokenTree], module: &[String], children: &[String]) -> Vec<Import> {
    let mut imports = Vec::new();
    for item in items(tokens) {
        if is_test_only(item) {
            continue;
        }
        let Some(at) = item
            .iter()
            .position(|tree| matches!(tree, TokenTree::Ident(w) if w == "use"))
        else {
            continue;
        };
        let path: Vec<TokenTree> = item[at + 1..item.len() - 1].to_vec();
        let mut segments = Vec::new();
        expand_use_tree_into(&path, &mut segments, &mut |segments, name| {
            let (base, rest) = path_base(segments, module, children);
            imports.push(Import {
                name,
                base,
                segments: rest,
            });
        });
    }
    imports
}

/// Calls `found(path, name)` for each leaf of a use tree, `a::{b, c::d as e}`.
pub fn expand_use_tree_into(trees: &[TokenTree], prefix: &mut Vec<String>, found: &mut dyn FnMut(Vec<String>, String)) {
    let depth = prefix.len();
    let mut index = 0;
    while index < trees.len() {
        match &trees[index] {
            TokenTree::Ident(ident) => {
                let word = ident.to_string();
                let renamed = matches!(&trees.get(index + 1), Some(TokenTree::Ident(w)) if w == "as");
                if renamed {
                    let name = trees.get(index + 2).map(|tree| tree.to_string()).unwrap_or_default();
                    let mut path = prefix.clone();
                    path.push(word);
                    found(path, name);
                    index += 3;
                    continue;
                }
                prefix.push(word.clone());
                if !is_separator(&trees[index + 1..]) {
                    let name = if word == "self" {
                        prefix[prefix.len() - 2].clone()
                    } else {
                        word
                    };
                    let mut path = prefix.clone();
                    if path.last().is_some_and(|last| last == "self") {
                        path.pop();
                    }
                    found(path, name);
                }
            }
            TokenTree::Group(group) if group.delimiter() == Delimiter::Brace => {
                let inner: Vec<TokenTree> = group.stream().into_iter().collect();
                for part in inner.split(|tree| matches!(tree, TokenTree::Punct(p) if p.as_char() == ',')) {
                    let mut nested = prefix.clone();
                    expand_use_tree_into(part, &mut nested, found);
                }
            }
            TokenTree::Punct(p) if p.as_char() == ',' => prefix.truncate(depth),
            _ => {}
        }
        index += 1;
    }
}

/// Whether `trees` starts with `::`.
pub fn is_separator(trees: &[TokenTree]) -> bool {
    matches!(trees, [TokenTree::Punct(first), TokenTree::Punct(second), ..]
        if first.as_char() == ':' && second.as_char() == ':')
}

/// Where a path written in `module` starts and its segments after that start; `None` for another crate's path.
pub fn path_base(segments: Vec<String>, module: &[String], children: &[String]) -> (Option<ModulePath>, Vec<String>) {
    let mut base: ModulePath = module.to_vec();
    let mut rest = segments.as_slice();
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some("self") => rest = &rest[1..],
        Some("super") => {
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
        }
        Some(first) if children.iter().any(|child| child == first) => {}
        _ => return (None, segments),
    }
    (Some(base), rest.to_vec())
}

/// Every `.rs` file under `directory`, sorted.
pub fn source_files(directory: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let Ok(entries) = fs::read_dir(directory) else {
        return files;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(source_files(&path));
        } else if path.extension().is_some_and(|extension| extension == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}
