//! The rule that makes a crate read one way: each module refers only to modules before it in the order the crate
//! root declares them, children before their parent (a parent module re-exports what its children define, and its
//! children never reach back into it). No import circle can then form.

use std::collections::HashMap;
use std::path::Path;

use crate::references::{references, Reference};
use crate::tree::{self, display, Module, ModulePath};

/// The crate's modules in pipeline order, `crate::…` paths.
pub fn module_order(manifest_dir: &Path) -> Vec<String> {
    tree::read_crate(manifest_dir)
        .iter()
        .map(|module| display(&module.path))
        .collect()
}

/// Every reference from a module to a module after it in the order, one line each, and every `.rs` file under
/// `src/` that is no module.
pub fn order_violations(manifest_dir: &Path) -> Vec<String> {
    let modules = tree::read_crate(manifest_dir);
    let position: HashMap<&ModulePath, usize> = modules
        .iter()
        .enumerate()
        .map(|(index, module)| (&module.path, index))
        .collect();
    let by_path: HashMap<&ModulePath, &Module> = modules.iter().map(|module| (&module.path, module)).collect();
    let mut violations = Vec::new();
    for module in &modules {
        for reference in references(module) {
            let target = resolve(&by_path, &reference, 0);
            if target != module.path && position[&target] > position[&module.path] {
                violations.push(format!(
                    "{} ({}) refers to {} (defined in {}, which comes after it)",
                    display(&module.path),
                    module.file.strip_prefix(manifest_dir).unwrap_or(&module.file).display(),
                    written(&reference),
                    display(&target),
                ));
            }
        }
    }
    let files: Vec<&Path> = modules.iter().map(|module| module.file.as_path()).collect();
    for file in tree::source_files(&manifest_dir.join("src")) {
        if !files.contains(&file.as_path()) {
            let name = file.strip_prefix(manifest_dir).unwrap_or(&file).display().to_string();
            violations.push(format!("{name} is no module of the crate"));
        }
    }
    violations.sort();
    violations.dedup();
    violations
}

fn written(reference: &Reference) -> String {
    let mut path = display(&reference.base);
    for segment in &reference.segments {
        path.push_str("::");
        path.push_str(segment);
    }
    path
}

/// The module that defines what `reference` names: the deepest module its segments walk through, and from there
/// through `use` items to where the item is defined.
fn resolve(modules: &HashMap<&ModulePath, &Module>, reference: &Reference, depth: usize) -> ModulePath {
    let mut current: ModulePath = reference.base.clone();
    // An inline module (`mod tests { … }`) is part of its file's module.
    while !modules.contains_key(&current) {
        current.pop();
    }
    for segment in &reference.segments {
        let module = modules[&current];
        if module.children.contains(segment) {
            current.push(segment.clone());
            continue;
        }
        if module.defined.contains(segment) || depth > 16 {
            return current;
        }
        return match module.imports.iter().find(|import| &import.name == segment) {
            Some(tree::Import {
                base: Some(base),
                segments,
                ..
            }) => {
                let onward = Reference {
                    base: base.clone(),
                    segments: segments.clone(),
                };
                resolve(modules, &onward, depth + 1)
            }
            _ => current,
        };
    }
    current
}
