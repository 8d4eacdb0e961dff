//! Docs that run: every library crate denies missing docs, and every public constructor shows a
//! runnable example. `cargo test --doc` runs the examples; this test makes sure a new constructor cannot
//! arrive without one.
//!
//! A constructor here is a `pub fn` without a `self` receiver whose return type names `Self` or the type of
//! the enclosing `impl` (so `-> Result<Self, E>` and `-> Option<Body>` count). The scan is textual: it reads
//! the signature up to its body and the `///` lines above it.

use std::fs;
use std::path::{Path, PathBuf};

const LIBRARY_CRATES: [&str; 6] = [
    "dynamics",
    "ga-codegen",
    "ga-macros",
    "reference",
    "scenarios",
    "report",
];

fn rust_files(dir: &Path, files: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("source directory is readable") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
}

/// The type an `impl` line implements for: `impl<A: Algebra> Pin<A>` and `impl Path<X> for Fixed<X>` give
/// `Pin` and `Fixed`.
fn implemented_type(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix("impl")?;
    if !(rest.starts_with(' ') || rest.starts_with('<')) {
        return None;
    }
    let rest = skip_generics(rest.trim_start());
    let rest = rest.rsplit_once(" for ").map_or(rest, |(_, target)| target);
    let name: &str = rest
        .trim_start()
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .next()?;
    name.starts_with(|c: char| c.is_ascii_uppercase()).then_some(name)
}

/// `text` after a leading `<…>` (nested angle brackets counted).
fn skip_generics(text: &str) -> &str {
    if !text.starts_with('<') {
        return text;
    }
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        match c {
            '<' => depth += 1,
            '>' => {
                depth -= 1;
                if depth == 0 {
                    return &text[i + 1..];
                }
            }
            _ => {}
        }
    }
    ""
}

/// Whether `text` contains `word` as a whole identifier.
fn names(text: &str, word: &str) -> bool {
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + word.len()..].chars().next();
        let is_ident = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        !is_ident(before) && !is_ident(after)
    })
}

/// `file:line Type::name` of every public constructor in `source` whose doc comment has no code block.
fn constructors_without_example(file: &Path, source: &str) -> Vec<String> {
    let lines: Vec<&str> = source.lines().collect();
    let mut implemented = None;
    let mut missing = Vec::new();
    // Code inside `quote! { … }` is emitted code, not this crate's API: skipped, by brace depth.
    let (mut depth, mut quoted_from) = (0usize, None);
    for (index, line) in lines.iter().enumerate() {
        let depth_before = depth;
        depth = (depth + line.matches('{').count()).saturating_sub(line.matches('}').count());
        match quoted_from {
            Some(start) if depth <= start => quoted_from = None,
            None if line.contains("quote! {") && depth > depth_before => quoted_from = Some(depth_before),
            _ => {}
        }
        if quoted_from.is_some() {
            continue;
        }
        if let Some(name) = implemented_type(line) {
            implemented = Some(name);
        }
        // The end of a top-level item: later free functions belong to no type.
        if *line == "}" {
            implemented = None;
        }
        let trimmed = line.trim_start();
        let Some(after_fn) = trimmed
            .strip_prefix("pub fn ")
            .or_else(|| trimmed.strip_prefix("pub const fn "))
        else {
            continue;
        };
        let name: String = after_fn
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let mut signature = String::new();
        for line in &lines[index..] {
            signature.push_str(line);
            signature.push(' ');
            if line.contains('{') || line.trim_end().ends_with(';') {
                break;
            }
        }
        let signature = signature.split('{').next().unwrap_or_default();
        let Some((arguments, returned)) = signature.split_once('(').and_then(|(_, rest)| rest.rsplit_once("->")) else {
            continue;
        };
        let first_argument = arguments
            .trim_start()
            .trim_start_matches(['&', ' '])
            .trim_start_matches('\'');
        let receiver = ["self", "mut self"].iter().any(|r| first_argument.starts_with(r))
            || first_argument
                .split_whitespace()
                .nth(1)
                .is_some_and(|w| w.starts_with("self") || w == "mut");
        let returns_own_type = names(returned, "Self") || implemented.is_some_and(|t| names(returned, t));
        if receiver || !returns_own_type {
            continue;
        }
        let documented_example = lines[..index]
            .iter()
            .rev()
            .map(|l| l.trim_start())
            .take_while(|l| l.starts_with("///") || l.starts_with("#["))
            .any(|l| l.starts_with("/// ```"));
        if !documented_example {
            missing.push(format!(
                "{}:{} {}::{name}",
                file.display(),
                index + 1,
                implemented.unwrap_or("?")
            ));
        }
    }
    missing
}

#[test]
fn every_library_crate_denies_missing_docs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for krate in LIBRARY_CRATES {
        let lib = fs::read_to_string(root.join(krate).join("src/lib.rs")).expect("lib.rs is readable");
        assert!(
            lib.contains("#![deny(missing_docs)]"),
            "{krate}/src/lib.rs lacks #![deny(missing_docs)]"
        );
    }
}

#[test]
fn every_public_constructor_has_an_example() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut missing = Vec::new();
    let mut constructors_seen = 0;
    for krate in LIBRARY_CRATES {
        let mut files = Vec::new();
        rust_files(&root.join(krate).join("src"), &mut files);
        files.sort();
        for file in files {
            let source = fs::read_to_string(&file).expect("source is readable");
            constructors_seen += source.matches("-> Self").count();
            let relative = file.strip_prefix(root).unwrap_or(&file);
            missing.extend(constructors_without_example(relative, &source));
        }
    }
    assert!(
        constructors_seen > 50,
        "the scan found almost no constructors: is it reading the sources?"
    );
    assert!(
        missing.is_empty(),
        "public constructors without an example:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_scan_recognises_constructors_and_receivers() {
    let source = "impl<A: Algebra> Pin<A> {\n    /// Makes one.\n    pub fn new(x: f64) -> Result<Self, E> {\n    }\n    \
                  pub fn value(&self) -> Self {\n    }\n    /// ```\n    /// let p = Pin::at(1.0);\n    /// ```\n    \
                  pub const fn at(x: f64) -> Pin<A> {\n    }\n    pub fn with(mut self, y: f64) -> Self {\n    }\n}\n\
                  pub fn free(x: f64) -> Pin<A> {\n}\n\
                  fn emit() -> TokenStream {\n    quote! {\n        pub const fn zero() -> Self {\n        }\n    }\n}\n\
                  impl Pin<B> {\n    pub fn one() -> Self {\n    }\n}\n";
    let missing = constructors_without_example(Path::new("x.rs"), source);
    assert_eq!(
        missing,
        vec!["x.rs:3 Pin::new".to_string(), "x.rs:24 Pin::one".to_string()]
    );
}
