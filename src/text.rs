//! Quoting text for the JSON and TOML this crate writes (one escaper for
//! both: a JSON string literal is also a valid TOML basic string).

use std::fmt::Write as _;

/// A JSON string literal. Control characters and DEL are written as
/// `\uXXXX`, so the literal is also a valid TOML basic string.
pub fn string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 || c == '\u{7f}' => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
