//! No JSON is written by hand in `src/`: every output is a serde type
//! printed by `src/json.rs`. This reads every library and command source
//! file and fails on a formatting macro (`format!`, `write!`, `writeln!`,
//! `print!`, `println!`, `push_str`, `write_all`) whose text holds a JSON
//! key (`\"key\": `) or opens an object (`{{\"`). Test modules
//! (`#[cfg(test)]` to the end of a file) and comments are skipped.

mod common;

/// Files allowed to, and why (a pending writer goes when its output is
/// typed); none today: the readers too parse with serde.
const PENDING: &[(&str, &str)] = &[];

const WRITERS: [&str; 7] = [
    "format!(",
    "write!(",
    "writeln!(",
    "print!(",
    "println!(",
    "push_str(",
    "write_all(",
];

/// The first string literal of `code` (raw text, escapes kept).
fn first_literal(code: &str) -> Option<&str> {
    let start = code.find('"')? + 1;
    let mut escaped = false;
    for (i, c) in code[start..].char_indices() {
        match c {
            '\\' if !escaped => escaped = true,
            '"' if !escaped => return Some(&code[start..start + i]),
            _ => escaped = false,
        }
    }
    None
}

/// Whether a literal writes JSON structure.
fn writes_json(literal: &str) -> bool {
    let key = literal.match_indices("\\\": ").any(|(i, _)| {
        literal[..i].rsplit("\\\"").next().is_some_and(|k| {
            k.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '{' || c == '}')
        })
    });
    key || literal.contains("{{\\\"")
}

/// The hand-written JSON writers in `code`: (line, literal).
fn hand_json(code: &str) -> Vec<(usize, String)> {
    let code = common::without_tests(code);
    let mut out = Vec::new();
    for writer in WRITERS {
        for (at, _) in code.match_indices(writer) {
            let line_start = code[..at].rfind('\n').map_or(0, |i| i + 1);
            if code[line_start..at].trim_start().starts_with("//") {
                continue;
            }
            let rest = &code[at + writer.len()..];
            let end = (0..=rest.len().min(400))
                .rev()
                .find(|&i| rest.is_char_boundary(i))
                .unwrap_or(0);
            let window = &rest[..end];
            if let Some(lit) = first_literal(window) {
                if writes_json(lit) {
                    let line = code[..at].lines().count() + 1;
                    out.push((line, lit.to_string()));
                }
            }
        }
    }
    out
}

#[test]
fn no_json_is_written_by_hand() {
    let mut found = Vec::new();
    let mut checked = 0;
    for file in common::rust_files(&common::root().join("src")) {
        let rel = &file.rel;
        if PENDING.iter().any(|(f, _)| f == rel) {
            continue;
        }
        checked += 1;
        for (line, lit) in hand_json(&file.text()) {
            found.push(format!("src/{rel}:{line}: {lit}"));
        }
    }
    assert!(checked > 100, "{checked} files");
    common::assert_none("JSON written by hand", &found);
}

#[test]
fn the_check_sees_a_hand_written_object() {
    let mutant = "fn f(x: u8) -> String {\n    format!(\n        \"{{\\\"n\\\": {}}}\",\n        x\n    )\n}\n";
    assert_eq!(hand_json(mutant).len(), 1);
    let key_only = "fn f() { out.write_all(b\"], \\\"velocities\\\": [\")?; }";
    assert_eq!(hand_json(key_only).len(), 1);
    let prose = "fn f() { format!(\"a {} b\", 1); }";
    assert!(hand_json(prose).is_empty());
    assert!(hand_json("#[cfg(test)]\nfn t() { format!(\"{{\\\"n\\\": 1}}\"); }").is_empty());
}
