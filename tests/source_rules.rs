//! Rules of the code's shape that a reader checks by hand and this test
//! checks by machine:
//!
//! * no function over 100 lines under `src/prove/` (signature to closing
//!   brace, comments included);
//! * `docs/guide/architecture.md` names every folder of `src/`, `python/`
//!   and `proofs/` by its path from the repository root (`src/fast/dyadic`);
//! * a file that a code comment cites by a path (`src/fast/engine.rs`,
//!   `docs/journal.md`) exists in the repository.

mod common;

use std::path::Path;

/// The longest function allowed under `src/prove/`, in lines.
const MAX_FUNCTION_LINES: usize = 100;

/// `code` with every comment, string and character literal blanked (spaces;
/// newlines kept), so that braces counted are the code's own.
fn code_only(code: &str) -> String {
    let b = code.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let blank = |out: &mut Vec<u8>, s: &[u8]| {
        out.extend(s.iter().map(|&c| if c == b'\n' { b'\n' } else { b' ' }));
    };
    let mut i = 0;
    while i < b.len() {
        let rest = &b[i..];
        let end = if rest.starts_with(b"//") {
            rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len())
        } else if rest.starts_with(b"/*") {
            rest.windows(2)
                .position(|w| w == b"*/")
                .map_or(rest.len(), |k| k + 2)
        } else if rest.starts_with(b"r#\"") || rest.starts_with(b"r\"") {
            let hashes = rest[1..].iter().take_while(|&&c| c == b'#').count();
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            let open = 2 + hashes;
            rest[open..]
                .windows(close.len())
                .position(|w| w == close.as_slice())
                .map_or(rest.len(), |k| open + k + close.len())
        } else if rest[0] == b'"' {
            let mut k = 1;
            while k < rest.len() && rest[k] != b'"' {
                k += if rest[k] == b'\\' { 2 } else { 1 };
            }
            (k + 1).min(rest.len())
        } else if rest[0] == b'\'' {
            // A character literal ('{', '\''); a lifetime ('a) stays.
            if rest.get(1) == Some(&b'\\') {
                rest[2..]
                    .iter()
                    .position(|&c| c == b'\'')
                    .map_or(1, |k| k + 3)
            } else {
                let ch = std::str::from_utf8(&rest[1..])
                    .ok()
                    .or_else(|| std::str::from_utf8(&rest[1..rest.len().min(5)]).ok())
                    .and_then(|s| s.chars().next())
                    .map_or(1, char::len_utf8);
                if rest.get(1 + ch) == Some(&b'\'') {
                    ch + 2
                } else {
                    1
                }
            }
        } else {
            out.push(rest[0]);
            i += 1;
            continue;
        };
        blank(&mut out, &rest[..end]);
        i += end;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The functions of `code` with a body: (name, first line, line count).
fn function_lengths(code: &str) -> Vec<(String, usize, usize)> {
    let code = code_only(code);
    let lines: Vec<&str> = code.lines().collect();
    let starts: Vec<usize> = std::iter::once(0)
        .chain(code.match_indices('\n').map(|(i, _)| i + 1))
        .collect();
    let mut out = Vec::new();
    for (at, _) in code.match_indices("fn ") {
        if at > 0 && code.as_bytes()[at - 1].is_ascii_alphanumeric() {
            continue;
        }
        let name: String = code[at + 3..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() {
            continue; // `fn(` types
        }
        // The body opens at the first `{` after the signature, unless a
        // `;` ends a declaration first (a trait method without a body).
        let rest = &code[at..];
        let Some(open) = rest.find(['{', ';']) else {
            continue;
        };
        if rest.as_bytes()[open] == b';' {
            continue;
        }
        let mut depth = 0usize;
        let mut close = None;
        for (k, c) in rest[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        close = Some(at + open + k);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(close) = close else { continue };
        let line_of = |i: usize| starts.partition_point(|&s| s <= i);
        let (first, last) = (line_of(at), line_of(close));
        debug_assert!(last <= lines.len());
        out.push((name, first, last - first + 1));
    }
    out
}

#[test]
fn no_function_under_prove_is_over_100_lines() {
    let prove = common::root().join("src/prove");
    let mut long = Vec::new();
    let mut functions = 0;
    for file in common::rust_files(&prove) {
        for (name, line, count) in function_lengths(&file.text()) {
            functions += 1;
            if count > MAX_FUNCTION_LINES {
                long.push(format!(
                    "src/prove/{}:{line}: {name} is {count} lines",
                    file.rel
                ));
            }
        }
    }
    assert!(functions > 200, "only {functions} functions read");
    common::assert_none(
        &format!("over {MAX_FUNCTION_LINES} lines (split them)"),
        &long,
    );
}

#[test]
fn the_length_check_sees_a_long_function() {
    let body = "    let x = '{';\n".repeat(101);
    let long = format!("/// }}\nfn long() {{\n{body}}}\nfn short() -> &'static str {{ \"}}\" }}\n");
    let found = function_lengths(&long);
    assert_eq!(
        found,
        [("long".to_string(), 2, 103), ("short".to_string(), 105, 1)]
    );
    assert!(function_lengths("trait T { fn f(&self); }\nfn g() {}").len() == 1);
}

/// The folders the architecture page must name, from the repository root.
fn folders() -> Vec<String> {
    let root = common::root();
    let mut out = Vec::new();
    for top in ["src", "python", "proofs"] {
        out.push(top.to_string());
        for f in common::folders_under(&root.join(top)) {
            out.push(format!("{top}/{f}"));
        }
    }
    out
}

/// The folders of `folders` that `page` does not name: a path word of the
/// page (`src/fast/`, `` `src/fast` ``) names one folder, not its parents.
fn unnamed<'a>(page: &str, folders: &'a [String]) -> Vec<&'a str> {
    let named: std::collections::BTreeSet<&str> = page
        .split(|c: char| !(c.is_alphanumeric() || "_-./".contains(c)))
        .map(|w| w.trim_end_matches(['/', '.']))
        .collect();
    folders
        .iter()
        .filter(|f| !named.contains(f.as_str()))
        .map(String::as_str)
        .collect()
}

#[test]
fn the_architecture_page_names_every_folder() {
    let page = std::fs::read_to_string(common::root().join("docs/guide/architecture.md"))
        .expect("docs/guide/architecture.md");
    let folders = folders();
    assert!(folders.len() > 30, "{folders:?}");
    let missing = unnamed(&page, &folders);
    common::assert_none("docs/guide/architecture.md does not name", &missing);
}

#[test]
fn the_folder_check_sees_a_missing_folder() {
    let folders = ["src/fast".to_string(), "src/fast/merge".to_string()];
    assert!(unnamed("`src/fast/merge/` and `src/fast/`", &folders).is_empty());
    assert_eq!(unnamed("`src/fast/merge/`", &folders), ["src/fast"]);
    assert_eq!(
        unnamed("`src/fast/merger`", &folders),
        ["src/fast", "src/fast/merge"]
    );
}

/// The extensions of a file a comment may cite.
const CITED: [&str; 12] = [
    "rs", "md", "toml", "py", "pyi", "v", "json", "jsonl", "sh", "yml", "txt", "tex",
];

/// The paths `comment` cites: words with a `/` ending in a cited extension
/// (globs and `{a,b}` alternatives are not paths).
fn cited_paths(comment: &str) -> Vec<&str> {
    comment
        .split(|c: char| !(c.is_alphanumeric() || "_-./".contains(c)))
        .map(|w| w.trim_end_matches('.'))
        .filter(|w| w.contains('/') && !w.starts_with('/') && !w.contains("..."))
        .filter(|w| {
            w.rsplit_once('.')
                .is_some_and(|(_, ext)| CITED.contains(&ext))
        })
        .collect()
}

/// File names that stand for any file of a folder in a pattern.
const PLACEHOLDERS: [&str; 3] = ["NAME", "ID", "N"];

/// Where a cited path may be read from: the repository root, the crate's
/// `src/`, the citing file's folder, or the repository a tool's output
/// names as it goes (`out/`, `target/`: never files of the repository).
fn exists(root: &Path, citing: &Path, cited: &str) -> bool {
    if cited.starts_with("out/") || cited.starts_with("target/") {
        return true;
    }
    // A pattern (`docs/guide/schema/NAME.json`): its folder must exist.
    if let Some((folder, file)) = cited.rsplit_once('/') {
        if PLACEHOLDERS
            .iter()
            .any(|p| file.starts_with(&format!("{p}.")))
        {
            return root.join(folder).is_dir();
        }
    }
    let dir = citing.parent().unwrap_or(root);
    [root.to_path_buf(), root.join("src"), dir.to_path_buf()]
        .iter()
        .any(|base| base.join(cited).exists())
}

#[test]
fn comments_cite_files_that_exist() {
    let root = common::root();
    let mut missing = Vec::new();
    let mut cited = 0;
    for top in [
        "src",
        "tests",
        "benches",
        "examples",
        "python/src",
        "proofs",
    ] {
        for file in common::rust_files(&root.join(top)) {
            for (k, line) in file.text().lines().enumerate() {
                let Some(at) = line.find("//") else { continue };
                for path in cited_paths(&line[at..]) {
                    cited += 1;
                    if !exists(&root, &file.path, path) {
                        missing.push(format!("{top}/{}:{}: {path}", file.rel, k + 1));
                    }
                }
            }
        }
    }
    assert!(cited > 50, "only {cited} citations read");
    common::assert_none("comments cite files that do not exist", &missing);
}

#[test]
fn the_citation_check_sees_a_missing_file() {
    let root = common::root();
    let here = root.join("tests/source_rules.rs");
    assert_eq!(
        cited_paths("see `src/fast/engine.rs` and docs/guide/gone.md."),
        ["src/fast/engine.rs", "docs/guide/gone.md"]
    );
    assert!(exists(&root, &here, "src/fast/engine.rs"));
    assert!(exists(&root, &here, "fast/engine.rs"));
    assert!(!exists(&root, &here, "docs/guide/gone.md"));
    assert!(cited_paths("in DESIGN.md, src/*.rs, a/{b,c}.rs").is_empty());
    assert!(exists(&root, &here, "docs/guide/schema/NAME.json"));
}
