//! A `[particles]` scene with its columns inline (`positions = […]`,
//! `velocities = […]`), read straight into machine words for the streaming
//! path ([`crate::fast::stream`], issue 13 part 2): no `toml::Value` and no
//! `BigRational` per number.
//!
//! The reader takes a strict subset of TOML, the shape `sticky generate`
//! writes and people type: ASCII text; comments; bare keys; basic strings
//! without escapes (`"1/3"`); the top-level keys `name`, `description`,
//! `t_end` (strings) before one `[particles]` header with `radius`
//! (a string), `positions` and `velocities` (arrays of strings and plain
//! decimal integers such as `-3`, over any number of lines, a trailing
//! comma allowed). Every number is read by
//! [`parse_small`] after the white space [`crate::rational::parse_exact`]
//! trims.
//!
//! **Same results.** Whatever it accepts is a valid TOML document that
//! [`super::parse`] reads to the same keys and values; anything else (an
//! escape, a literal or multi-line string, an integer with `_` or a
//! `0x`-style prefix, a float, a dotted or
//! quoted key, another table, a repeated key, a `data` file, a number off
//! words or malformed) gives `None`, and the general path reads the file
//! (with the error of record when there is one).

use num_rational::BigRational;
use num_traits::Signed;

use crate::columns::{parse_small, Small};
use crate::rational::parse_exact;

/// An inline `[particles]` scene on machine words.
#[derive(Debug, Clone, PartialEq)]
pub struct InlineScene {
    /// The `radius` field, if given (else `1/(2N)`, as for [`super::parse`]).
    pub radius: Option<BigRational>,
    /// The bits [`super::MAX_NUMBER_BITS`] is charged for besides the columns
    /// (`t_end` and `radius`).
    pub charged_bits: u64,
    /// `particles.positions`.
    pub positions: Vec<Small>,
    /// `particles.velocities`.
    pub velocities: Vec<Small>,
}

/// A cursor over the bytes of the document.
struct Cursor<'a> {
    b: &'a [u8],
    i: usize,
}

impl<'a> Cursor<'a> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    /// Spaces and tabs.
    fn blanks(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t')) {
            self.i += 1;
        }
    }

    /// A comment to the end of the line (not the newline), if one starts
    /// here; `None` on a byte TOML refuses in a comment.
    fn comment(&mut self) -> Option<()> {
        if self.peek() == Some(b'#') {
            self.i += 1;
            while let Some(c) = self.peek() {
                match c {
                    b'\n' | b'\r' => break,
                    b'\t' | 0x20..=0x7e => self.i += 1,
                    _ => return None,
                }
            }
        }
        Some(())
    }

    /// A newline (`\n` or `\r\n`); `Some(false)` at the end of the text,
    /// `None` on anything else.
    fn newline(&mut self) -> Option<bool> {
        match self.peek() {
            None => Some(false),
            Some(b'\n') => {
                self.i += 1;
                Some(true)
            }
            Some(b'\r') if self.b.get(self.i + 1) == Some(&b'\n') => {
                self.i += 2;
                Some(true)
            }
            _ => None,
        }
    }

    /// The rest of a line after a value or header: blanks, a comment, the
    /// newline or the end.
    fn end_of_line(&mut self) -> Option<()> {
        self.blanks();
        self.comment()?;
        self.newline().map(|_| ())
    }

    /// Blanks, comments and newlines (inside an array).
    fn space(&mut self) -> Option<()> {
        loop {
            self.blanks();
            self.comment()?;
            if !matches!(self.peek(), Some(b'\n' | b'\r')) {
                return Some(());
            }
            self.newline()?;
        }
    }

    /// A bare key.
    fn key(&mut self) -> Option<&'a [u8]> {
        let start = self.i;
        while matches!(
            self.peek(),
            Some(b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'_' | b'-')
        ) {
            self.i += 1;
        }
        (self.i > start).then(|| &self.b[start..self.i])
    }

    /// A basic string without escapes; its content.
    fn string(&mut self) -> Option<&'a [u8]> {
        if self.peek() != Some(b'"') {
            return None;
        }
        self.i += 1;
        let start = self.i;
        loop {
            match self.peek()? {
                b'"' => break,
                b'\t' | 0x20 | 0x21 | 0x23..=0x5b | 0x5d..=0x7e => self.i += 1,
                _ => return None,
            }
        }
        let s = &self.b[start..self.i];
        self.i += 1;
        Some(s)
    }

    /// A TOML decimal integer in its plainest form, `[+-]?` then digits
    /// without a leading zero (`0`, `-0`, `+0` allowed); its text without
    /// the `+`. An underscore, a `0x`/`0o`/`0b` prefix, a float or anything
    /// else that is not plain gives `None`.
    fn integer(&mut self) -> Option<&'a [u8]> {
        let start = self.i;
        let sign = matches!(self.peek(), Some(b'+' | b'-'));
        if sign {
            self.i += 1;
        }
        let digits = self.i;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.i += 1;
        }
        let body = &self.b[digits..self.i];
        let ends = matches!(
            self.peek(),
            None | Some(b' ' | b'\t' | b',' | b']' | b'#' | b'\n' | b'\r')
        );
        if body.is_empty() || !ends || (body.len() > 1 && body[0] == b'0') {
            return None;
        }
        Some(if self.b[start] == b'+' {
            body
        } else {
            &self.b[start..self.i]
        })
    }

    /// An array of strings and plain integers, each read by `f`.
    fn array(&mut self, mut f: impl FnMut(&'a [u8]) -> Option<()>) -> Option<()> {
        if self.peek() != Some(b'[') {
            return None;
        }
        self.i += 1;
        loop {
            self.space()?;
            if self.peek() == Some(b']') {
                break;
            }
            let item = if self.peek() == Some(b'"') {
                self.string()?
            } else {
                self.integer()?
            };
            f(item)?;
            self.space()?;
            match self.peek()? {
                b',' => self.i += 1,
                b']' => break,
                _ => return None,
            }
        }
        self.i += 1;
        Some(())
    }
}

/// `s` without the leading and trailing spaces and tabs (the only white
/// space a string here can hold; what `parse_exact` trims).
fn trim(mut s: &[u8]) -> &[u8] {
    while let [b' ' | b'\t', rest @ ..] = s {
        s = rest;
    }
    while let [rest @ .., b' ' | b'\t'] = s {
        s = rest;
    }
    s
}

/// A number given as a string (`t_end`, `radius`): the exact value, when
/// it is one.
fn exact(s: &[u8]) -> Option<BigRational> {
    parse_exact(std::str::from_utf8(s).ok()?).ok()
}

/// The scene in `text` as an [`InlineScene`], when it has the shape of the
/// module documentation and every position and velocity is [`Small`];
/// `None` otherwise.
pub fn inline_scene(text: &[u8]) -> Option<InlineScene> {
    if !text.is_ascii() {
        return None;
    }
    let mut c = Cursor { b: text, i: 0 };
    let mut seen: Vec<&[u8]> = Vec::new();
    let mut in_particles = false;
    let mut scene = InlineScene {
        radius: None,
        charged_bits: 0,
        positions: Vec::new(),
        velocities: Vec::new(),
    };
    let (mut has_x, mut has_u) = (false, false);
    loop {
        c.blanks();
        match c.peek() {
            None => break,
            Some(b'#' | b'\n' | b'\r') => {
                c.end_of_line()?;
                continue;
            }
            Some(b'[') => {
                if in_particles {
                    return None; // a second table
                }
                c.i += 1;
                c.blanks();
                if c.key()? != b"particles" {
                    return None;
                }
                c.blanks();
                if c.peek() != Some(b']') {
                    return None;
                }
                c.i += 1;
                c.end_of_line()?;
                in_particles = true;
                continue;
            }
            Some(_) => {}
        }
        let key = c.key()?;
        let full: &[u8] = match (in_particles, key) {
            (false, b"name" | b"description" | b"t_end") => key,
            (true, b"radius") => b"particles.radius",
            (true, b"positions") => b"particles.positions",
            (true, b"velocities") => b"particles.velocities",
            _ => return None,
        };
        if seen.contains(&full) {
            return None;
        }
        seen.push(full);
        c.blanks();
        if c.peek() != Some(b'=') {
            return None;
        }
        c.i += 1;
        c.blanks();
        match full {
            b"name" | b"description" => {
                c.string()?;
            }
            b"t_end" => {
                let t = exact(c.string()?)?;
                if t.is_negative() {
                    return None;
                }
                scene.charged_bits += t.numer().bits() + t.denom().bits() + 64;
            }
            b"particles.radius" => {
                let r = exact(c.string()?)?;
                scene.charged_bits += r.numer().bits() + r.denom().bits() + 64;
                scene.radius = Some(r);
            }
            b"particles.positions" => {
                has_x = true;
                let v = &mut scene.positions;
                v.reserve(text.len() / 16);
                c.array(|s| {
                    v.push(parse_small(trim(s))?);
                    Some(())
                })?;
            }
            _ => {
                has_u = true;
                let v = &mut scene.velocities;
                v.reserve(scene.positions.len());
                c.array(|s| {
                    v.push(parse_small(trim(s))?);
                    Some(())
                })?;
            }
        }
        c.end_of_line()?;
    }
    scene.positions.shrink_to_fit();
    scene.velocities.shrink_to_fit();
    (has_x && has_u).then_some(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_generated_shape() {
        let text = b"name = \"g\"\n# c\n\n[particles]\nradius = \"1/64\"\npositions = [\"0\", \" 1/32 \",\n  \"1.5e-1\", # three\n]\nvelocities = [\"1\", \"-1\", \"0.25\"]\n";
        let s = inline_scene(text).unwrap();
        assert_eq!(s.positions, vec![(0, 1), (1, 32), (3, 20)]);
        assert_eq!(s.velocities, vec![(1, 1), (-1, 1), (1, 4)]);
        assert_eq!(s.radius, Some(BigRational::new(1.into(), 64.into())));
        // Plain TOML integers, mixed with strings as TOML 1.0 allows.
        let text = b"[particles]\npositions = [0, +2, \"7/2\", 5 ,9]\nvelocities = [-0, -1,\n\"1/3\", 12, -7 # last\n]\n";
        let s = inline_scene(text).unwrap();
        assert_eq!(s.positions, vec![(0, 1), (2, 1), (7, 2), (5, 1), (9, 1)]);
        assert_eq!(
            s.velocities,
            vec![(0, 1), (-1, 1), (1, 3), (12, 1), (-7, 1)]
        );
    }

    #[test]
    fn declines_what_it_does_not_hold() {
        let ok = "[particles]\npositions = [\"0\", \"1\"]\nvelocities = [\"0\", \"0\"]\n";
        assert!(inline_scene(ok.as_bytes()).is_some());
        for bad in [
            ok.replace("\"1\"]", "1_0]"),                    // TOML integer with _
            ok.replace("\"1\"]", "0x1]"),                    // hex integer
            ok.replace("\"1\"]", "01]"),                     // leading zero
            ok.replace("\"1\"]", "1.5]"),                    // TOML float
            ok.replace("\"1\"]", "1e3]"),                    // TOML float
            ok.replace("\"1\"]", "inf]"),                    // TOML float
            ok.replace("\"1\"]", "-]"),                      // no digits
            ok.replace("\"1\"]", "99999999999999999999]"),   // off i64
            ok.replace("\"1\"", "\"\\u0031\""),              // an escape
            ok.replace("\"1\"", "'1'"),                      // literal string
            ok.replace("\"1\"", "\"99999999999999999999\""), // off words
            ok.replace("\"1\"", "\"1/0\""),                  // malformed
            ok.replace("[particles]", "[macro]"),            // another table
            ok.replace("[particles]", "[particles]\nradius = \"1\"\nradius = \"1\""), // repeated key
            ok.replace("positions", "data = \"a.csv\"\npositions"),                   // a data file
            ok.replace("positions =", "particles.positions ="),                       // dotted key
            ok.replace("\n", "\r"),                                                   // lone CR
            ok.replace("velocities = [\"0\", \"0\"]\n", ""), // missing column
            format!("{ok}[particles]\n"),                    // second table
            format!("{ok}x = \"1\"\n"),                      // unknown key
            ok.replace("[\"0\", \"1\"]", "[\"0\", \"1\"] \"2\""), // junk after a value
            format!("name = \"é\"\n{ok}"),                   // not ASCII
        ] {
            assert!(inline_scene(bad.as_bytes()).is_none(), "{bad:?}");
        }
    }
}
