//! Helpers shared by the tests that read the repository's own files for a
//! source rule (`tests/layers.rs`, `tests/json_by_serde.rs`,
//! `tests/source_rules.rs`): one walker, one idea of "a source file".

#![allow(dead_code)] // each test uses its own subset

use std::fs;
use std::path::{Path, PathBuf};

/// The repository's root (the crate's manifest directory).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A folder the walk never enters: hidden ones, build outputs, caches.
fn skipped(name: &str) -> bool {
    name.starts_with('.')
        || matches!(name, "target" | "build" | "dist" | "_build" | "__pycache__")
        || name.ends_with(".egg-info")
}

/// A file read by a source rule: its path from the walked folder, with `/`
/// separators (`fast/stream/mod.rs`), and its full path.
pub struct SourceFile {
    pub rel: String,
    pub path: PathBuf,
}

impl SourceFile {
    /// The file's text; a source rule cannot run without it.
    pub fn text(&self) -> String {
        fs::read_to_string(&self.path).unwrap_or_else(|e| panic!("{}: {e}", self.path.display()))
    }
}

/// Every file under `dir` whose name ends with one of `extensions` (no
/// dot), in path order.
pub fn files_under(dir: &Path, extensions: &[&str]) -> Vec<SourceFile> {
    let mut out = Vec::new();
    for path in walk(dir, false) {
        if path
            .extension()
            .is_some_and(|e| extensions.iter().any(|x| e == *x))
        {
            out.push(SourceFile {
                rel: relative(dir, &path),
                path,
            });
        }
    }
    out
}

/// The `.rs` files under `dir`, in path order.
pub fn rust_files(dir: &Path) -> Vec<SourceFile> {
    files_under(dir, &["rs"])
}

/// Every folder under `dir` (not `dir` itself), as paths from `dir`
/// (`fast/merge/split`), in path order.
pub fn folders_under(dir: &Path) -> Vec<String> {
    walk(dir, true).iter().map(|p| relative(dir, p)).collect()
}

fn relative(dir: &Path, path: &Path) -> String {
    path.strip_prefix(dir)
        .expect("walked under dir")
        .to_string_lossy()
        .replace('\\', "/")
}

/// The files (or, with `folders`, the folders) below `dir`, sorted.
fn walk(dir: &Path, folders: bool) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        let entries = fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display()));
        for entry in entries {
            let path = entry.expect("directory entry").path();
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            if path.is_dir() {
                if !name.as_deref().is_some_and(skipped) {
                    if folders {
                        out.push(path.clone());
                    }
                    todo.push(path);
                }
            } else if !folders {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// `code` without its test modules: from the first `#[cfg(test)]` to the
/// end of the file (the project's layout puts them last).
pub fn without_tests(code: &str) -> &str {
    code.split("#[cfg(test)]").next().unwrap_or(code)
}

/// Fails, listing every breach of a rule one per line, unless there is none.
pub fn assert_none<S: AsRef<str>>(rule: &str, breaches: &[S]) {
    let list: Vec<&str> = breaches.iter().map(AsRef::as_ref).collect();
    assert!(list.is_empty(), "{rule}:\n{}", list.join("\n"));
}
