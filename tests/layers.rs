//! The folders under `src/` are layers (see the crate documentation): a
//! layer may import the layers below it, never one above it, and two modules
//! of the same rank outside the core do not exist. This test reads every
//! library source file and fails on an import of a higher layer — the
//! check behind "no import cycle between top-level modules".
//!
//! Test modules (`#[cfg(test)]` to the end of a file) and comments are
//! not imports and are skipped.

mod common;

/// Rank of a top-level module: the model core is 0, then the layers.
fn rank(module: &str) -> Option<usize> {
    const LAYERS: [&str; 7] = [
        "fast",
        "solver",
        "reference",
        "limit",
        "claims",
        "prove",
        "report",
    ];
    match LAYERS.iter().position(|l| *l == module) {
        Some(i) => Some(i + 1),
        None if module.chars().all(|c| c.is_ascii_lowercase() || c == '_') => Some(0),
        None => None,
    }
}

/// The top-level modules a piece of source code names through `crate::`.
fn imports(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in code.lines() {
        let line = line.trim_start();
        if line.starts_with("//") {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_lowercase() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.push(name);
            }
        }
        // `use crate::{a, b::c}` lists several modules at once.
        if let Some(i) = line.find("crate::{") {
            let list = &line[i + "crate::{".len()..];
            for item in list.split(',') {
                let name: String = item
                    .trim()
                    .chars()
                    .take_while(|c| c.is_ascii_lowercase() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    out.push(name);
                }
            }
        }
    }
    out
}

#[test]
fn no_layer_imports_a_layer_above_it() {
    let mut violations = Vec::new();
    let mut checked = 0;
    for file in common::rust_files(&common::root().join("src")) {
        let rel = &file.rel;
        let first = rel.split('/').next().expect("non-empty path");
        if first == "bin" || first == "lib.rs" {
            continue; // the binary sits above every layer; lib.rs declares them
        }
        let module = first.trim_end_matches(".rs").to_string();
        let own = rank(&module).expect("a known module name");
        let text = file.text();
        let code = common::without_tests(&text);
        for name in imports(code) {
            let Some(r) = rank(&name) else { continue };
            if name != module && r > own {
                violations.push(format!(
                    "{rel} (layer {own}) imports crate::{name} (layer {r})"
                ));
            }
            if name != module && r == own && own > 0 {
                violations.push(format!("{rel} imports crate::{name} of the same layer"));
            }
        }
        checked += 1;
    }
    assert!(checked > 20, "only {checked} files read: is src/ there?");
    common::assert_none("upward or same-layer imports", &violations);
}

#[test]
fn the_check_sees_an_upward_import() {
    // The check above must be able to fail: a core file naming the claims
    // layer, and a braced import of the report layer, are both seen.
    let found = imports("use crate::claims::Violation;\nuse crate::{report, scalar::Scalar};");
    assert_eq!(found, ["claims", "report", "scalar"]);
    assert!(rank("claims") > rank("projection"));
    assert!(imports("// see crate::report").is_empty());
}
