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

/// Reads the JSON string literal at the start of `s` (the inverse of
/// [`string`]); returns its value and the rest of `s`, or `None` when `s`
/// does not start with a well-formed literal.
pub fn unstring(s: &str) -> Option<(String, &str)> {
    let body = s.strip_prefix('"')?;
    let mut out = String::new();
    let mut chars = body.char_indices();
    while let Some((i, ch)) = chars.next() {
        match ch {
            '"' => return Some((out, &body[i + 1..])),
            '\\' => {
                let (_, e) = chars.next()?;
                match e {
                    '"' | '\\' | '/' => out.push(e),
                    'n' => out.push('\n'),
                    'r' => out.push('\r'),
                    't' => out.push('\t'),
                    'u' => {
                        let hex: String =
                            (0..4).filter_map(|_| chars.next().map(|c| c.1)).collect();
                        let code = u32::from_str_radix(&hex, 16).ok()?;
                        out.push(char::from_u32(code)?);
                    }
                    _ => return None,
                }
            }
            c => out.push(c),
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unstring_inverts_string() {
        for s in [
            "",
            "plain",
            "q\"uo\\te",
            "line\nbreak\ttab\r",
            "\u{1}\u{7f}",
            "x⁰ ∈ K^N",
        ] {
            let lit = string(s);
            let rest = format!("{lit}, \"next\"");
            assert_eq!(unstring(&rest), Some((s.to_string(), ", \"next\"")));
        }
        for bad in ["", "x", "\"open", "\"bad \\q escape\"", "\"\\u12\""] {
            assert_eq!(unstring(bad), None, "{bad:?}");
        }
    }
}
