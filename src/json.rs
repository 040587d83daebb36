//! The spelling every JSON output of the crate shares (feature `json`):
//! one line, `", "` between items and `": "` after a key (the interop
//! contract of docs/guide/json.md), doubles in Rust's shortest round-trip
//! exponent form (`1e-1`, `3.333333333333333e-1`), and strings escaped so
//! that a literal is also a TOML basic string ([`crate::text::string`]'s
//! escapes). The contracts themselves are serde types next to the data they
//! describe; [`to_string`] and [`to_writer`] print any of them.
//!
//! ```
//! use serde::Serialize;
//!
//! #[derive(Serialize)]
//! struct Point {
//!     t: &'static str,
//!     parts: Vec<u32>,
//!     x: f64,
//! }
//! let p = Point { t: "1/2", parts: vec![1, 2], x: 0.1 };
//! assert_eq!(sticky::json::to_string(&p), r#"{"t": "1/2", "parts": [1, 2], "x": 1e-1}"#);
//! ```

use std::io::{self, Write};

use serde::Serialize;
use serde_json::ser::{CharEscape, Formatter, Serializer};

/// The contract's [`Formatter`]: serde_json's compact output with a space
/// after each separator, doubles as `{:e}`, DEL and the controls without a
/// short JSON escape written `\u00XX`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Contract;

impl Formatter for Contract {
    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if first {
            Ok(())
        } else {
            w.write_all(b", ")
        }
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if first {
            Ok(())
        } else {
            w.write_all(b", ")
        }
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn write_f64<W: ?Sized + Write>(&mut self, w: &mut W, value: f64) -> io::Result<()> {
        // Only finite doubles reach here (serde_json writes `null` for the
        // others); `{:e}` is their shortest decimal that reads back as them.
        write!(w, "{value:e}")
    }

    fn write_char_escape<W: ?Sized + Write>(&mut self, w: &mut W, e: CharEscape) -> io::Result<()> {
        let short: &[u8] = match e {
            CharEscape::Quote => b"\\\"",
            CharEscape::ReverseSolidus => b"\\\\",
            CharEscape::Solidus => b"\\/",
            CharEscape::LineFeed => b"\\n",
            CharEscape::CarriageReturn => b"\\r",
            CharEscape::Tab => b"\\t",
            CharEscape::Backspace => return control(w, 0x08),
            CharEscape::FormFeed => return control(w, 0x0c),
            CharEscape::AsciiControl(b) => return control(w, b),
        };
        w.write_all(short)
    }

    fn write_string_fragment<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        text: &str,
    ) -> io::Result<()> {
        // serde_json leaves DEL as it is; a TOML basic string may not hold it.
        if !text.as_bytes().contains(&0x7f) {
            return w.write_all(text.as_bytes());
        }
        let mut pieces = text.split('\u{7f}');
        if let Some(first) = pieces.next() {
            w.write_all(first.as_bytes())?;
        }
        for piece in pieces {
            control(w, 0x7f)?;
            w.write_all(piece.as_bytes())?;
        }
        Ok(())
    }
}

/// `\u00XX`, lower-case hex.
fn control<W: ?Sized + Write>(w: &mut W, byte: u8) -> io::Result<()> {
    write!(w, "\\u{:04x}", byte)
}

/// Writes `value` in the contract's spelling (no final newline).
pub fn to_writer<W: Write, T: Serialize + ?Sized>(out: W, value: &T) -> io::Result<()> {
    let mut ser = Serializer::with_formatter(out, Contract);
    value.serialize(&mut ser).map_err(io::Error::from)
}

/// `value` in the contract's spelling, one line.
pub fn to_string<T: Serialize + ?Sized>(value: &T) -> String {
    let mut out = Vec::new();
    // Writing into a Vec fails only if `value`'s own Serialize does, which
    // the contract types never do (no map with non-string keys).
    let written = to_writer(&mut out, value);
    debug_assert!(written.is_ok(), "a contract type failed to serialize");
    // serde_json writes UTF-8 only.
    String::from_utf8(out).unwrap_or_default()
}

/// An exact rational as the contract writes it: a string in lowest terms,
/// `"p/q"` or `"p"` ([`crate::rational::render_exact`]).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct Rational(pub String);

impl Rational {
    /// The rendering of any scalar of the crate.
    pub fn of<S: crate::scalar::Scalar>(v: &S) -> Rational {
        Rational(v.render())
    }
}

/// A value written through its `Display` as a JSON string, with no string
/// allocated on the way (serde's `collect_str`): the streaming writers'
/// exact values.
#[derive(Debug, Clone, Copy)]
pub struct Displayed<'a, T: std::fmt::Display>(pub &'a T);

impl<T: std::fmt::Display> Serialize for Displayed<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self.0)
    }
}

/// The name under which serde_json's serializer writes a struct's one
/// field verbatim, with no escape scan: what its own `RawValue` serializes
/// as (feature `raw_value`). The tests check that [`Elements`] written
/// through it give serde's own bytes.
const VERBATIM: &str = "$serde_json::private::RawValue";

/// A run of array elements already in the contract's spelling, written as
/// they are: JSON strings of ASCII digits, `-` and `/` only (which need no
/// escape), `", "` between two of them. The streaming writers format their
/// exact values so on worker threads; serde_json then copies the run without
/// its per-byte escape scan. Written as one element of a sequence, it gives
/// the bytes of its strings written one by one (the separator before it is
/// the sequence's own); it must not be empty.
#[derive(Debug, Clone, Copy)]
pub struct Elements<'a>(&'a str);

impl<'a> Elements<'a> {
    /// The run `text` (its form checked in debug builds: the callers build
    /// it so).
    pub fn new(text: &'a str) -> Elements<'a> {
        debug_assert!(
            is_digit_strings(text),
            "not a run of digit strings: {text:?}"
        );
        Elements(text)
    }
}

/// Is `text` one or more `"…"` of digits, `-` and `/`, joined by `", "`?
fn is_digit_strings(text: &str) -> bool {
    !text.is_empty()
        && text.split(", ").all(|e| {
            e.len() >= 2
                && e.starts_with('"')
                && e.ends_with('"')
                && e[1..e.len() - 1]
                    .bytes()
                    .all(|b| b.is_ascii_digit() || b == b'-' || b == b'/')
        })
}

impl Serialize for Elements<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct(VERBATIM, 1)?;
        st.serialize_field(VERBATIM, self.0)?;
        st.end()
    }
}

/// A JSON number with exactly `DIGITS` decimals (`0.031`): a measured time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fixed<const DIGITS: usize>(pub f64);

impl<const DIGITS: usize> Serialize for Fixed<DIGITS> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::Error;
        if !self.0.is_finite() {
            return s.serialize_none();
        }
        let text = format!("{:.*}", DIGITS, self.0);
        serde_json::value::RawValue::from_string(text)
            .map_err(S::Error::custom)?
            .serialize(s)
    }
}

#[cfg(test)]
pub(crate) mod schema {
    //! The JSON Schema of the number types above (the derived contract
    //! types use these).

    use std::borrow::Cow;

    use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};

    impl JsonSchema for super::Rational {
        fn schema_name() -> Cow<'static, str> {
            "Rational".into()
        }

        fn json_schema(_: &mut SchemaGenerator) -> Schema {
            json_schema!({
                "description": "An exact rational in lowest terms, \"p/q\" or \"p\".",
                "type": "string",
                "pattern": "^-?(0|[1-9][0-9]*)(/[1-9][0-9]*)?$"
            })
        }
    }

    impl<const DIGITS: usize> JsonSchema for super::Fixed<DIGITS> {
        fn schema_name() -> Cow<'static, str> {
            "Seconds".into()
        }

        fn json_schema(_: &mut SchemaGenerator) -> Schema {
            json_schema!({
                "description": "A measured duration in seconds (a JSON number).",
                "type": "number",
                "minimum": 0
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_escape_as_text_string_does() {
        let s = "a\"b\\c\n\r\t\u{1}\u{8}\u{c}\u{7f}é/";
        assert_eq!(to_string(s), crate::text::string(s));
    }

    #[test]
    fn separators_doubles_and_fixed() {
        let v = serde_json::json!({"a": [1, 2], "b": {"c": null}});
        assert_eq!(to_string(&v), r#"{"a": [1, 2], "b": {"c": null}}"#);
        assert_eq!(
            to_string(&[0.0, 0.1, -1.0, 1.0 / 3.0]),
            "[0e0, 1e-1, -1e0, 3.333333333333333e-1]"
        );
        assert_eq!(
            to_string(&(Fixed::<3>(0.5), Fixed::<3>(f64::NAN))),
            "[0.500, null]"
        );
    }

    /// Runs of elements written verbatim give the bytes of their strings
    /// serialised one by one, whatever the cut into runs.
    #[test]
    fn elements_are_the_strings_bytes() {
        let values = ["-4367/1000", "0", "811/1375", "12", "-1/3"];
        let want = to_string(&values);
        for cut in 1..values.len() {
            let runs: Vec<String> = [&values[..cut], &values[cut..]]
                .iter()
                .map(|run| {
                    let quoted: Vec<String> =
                        run.iter().map(|v| ["\"", v, "\""].concat()).collect();
                    quoted.join(", ")
                })
                .collect();
            let elements: Vec<Elements<'_>> = runs.iter().map(|r| Elements::new(r)).collect();
            assert_eq!(to_string(&elements), want, "cut at {cut}");
        }
        assert!(!is_digit_strings(""));
        assert!(!is_digit_strings("\"1\\\""));
        assert!(!is_digit_strings("\"1\",\"2\""));
        assert!(is_digit_strings("\"-1/2\", \"3\""));
    }
}
