//! Sizes a reader can hold: a source file of at most `MAX_FILE_LINES` lines, a function of at most
//! `MAX_FUNCTION_LINES` (from `fn` to its closing brace).

use std::fs;
use std::path::Path;
use std::str::FromStr;

use proc_macro2::{Delimiter, TokenStream, TokenTree};

use crate::tree;

/// The longest hand-written source file, in lines.
pub const MAX_FILE_LINES: usize = 1200;
/// The longest function, in lines.
pub const MAX_FUNCTION_LINES: usize = 200;

/// Every `.rs` file under `directories` (relative to `root`) longer than `MAX_FILE_LINES`, and every function in
/// them longer than `MAX_FUNCTION_LINES`, one line each.
pub fn size_violations(root: &Path, directories: &[&str]) -> Vec<String> {
    let mut violations = Vec::new();
    for directory in directories {
        for file in tree::source_files(&root.join(directory)) {
            let source = fs::read_to_string(&file).unwrap();
            let name = file.strip_prefix(root).unwrap_or(&file).display().to_string();
            let lines = source.lines().count();
            if lines > MAX_FILE_LINES {
                violations.push(format!("{name}: {lines} lines (at most {MAX_FILE_LINES})"));
            }
            let tokens: Vec<TokenTree> = TokenStream::from_str(&source)
                .unwrap_or_else(|error| panic!("{name}: {error:?}"))
                .into_iter()
                .collect();
            long_functions(&tokens, &mut |function, lines| {
                violations.push(format!(
                    "{name}: fn {function} has {lines} lines (at most {MAX_FUNCTION_LINES})"
                ));
            });
        }
    }
    violations
}

fn long_functions(trees: &[TokenTree], found: &mut dyn FnMut(String, usize)) {
    for (index, tree) in trees.iter().enumerate() {
        match tree {
            TokenTree::Group(group) => {
                long_functions(&group.stream().into_iter().collect::<Vec<_>>(), found);
            }
            TokenTree::Ident(keyword) if keyword == "fn" => {
                let Some(TokenTree::Ident(name)) = trees.get(index + 1) else {
                    continue;
                };
                let body = trees[index + 2..].iter().find_map(|tree| match tree {
                    TokenTree::Group(group) if group.delimiter() == Delimiter::Brace => Some(Some(group)),
                    TokenTree::Punct(punct) if punct.as_char() == ';' => Some(None),
                    _ => None,
                });
                if let Some(Some(body)) = body {
                    let lines = body.span().end().line - keyword.span().start().line + 1;
                    if lines > MAX_FUNCTION_LINES {
                        found(name.to_string(), lines);
                    }
                }
            }
            _ => {}
        }
    }
}
