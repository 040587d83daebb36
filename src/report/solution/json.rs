//! The JSON side of the SOLUTION reader: a small exact JSON parser (a
//! number stays the text it is until read as the rational it denotes) and
//! the `sticky run --json` frame shape on top of it.

use num_rational::BigRational;
use num_traits::Signed;

use super::{cut, err, Frame, SolutionError};
use crate::rational::parse_exact;
use crate::scalar::Scalar;

#[derive(Debug, Clone)]
enum Json {
    Null,
    Bool,
    /// The number's text, validated against the JSON grammar.
    Number(String),
    /// `NaN`, `Infinity` or `-Infinity` (not JSON, but what some writers
    /// print): kept so that the message names the entry that holds it.
    NonFinite(&'static str),
    Str(String),
    Array(Vec<Value>),
    Object(Vec<(String, Value)>),
}

#[derive(Debug, Clone)]
struct Value {
    line: usize,
    v: Json,
}

struct Reader<'a> {
    s: &'a [u8],
    pos: usize,
    line: usize,
    depth: usize,
}

const MAX_DEPTH: usize = 64;

impl<'a> Reader<'a> {
    fn ws(&mut self) {
        while let Some(&c) = self.s.get(self.pos) {
            match c {
                b'\n' => self.line += 1,
                b' ' | b'\t' | b'\r' => {}
                _ => break,
            }
            self.pos += 1;
        }
    }

    fn peek(&self) -> Option<u8> {
        self.s.get(self.pos).copied()
    }

    fn expect(&mut self, c: u8) -> Result<(), SolutionError> {
        self.ws();
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            self.unexpected(&format!("'{}'", c as char))
        }
    }

    fn unexpected<T>(&self, wanted: &str) -> Result<T, SolutionError> {
        match self.peek() {
            None => err(
                self.line,
                format!("malformed JSON: end of input, expected {wanted}"),
            ),
            Some(_) => {
                let rest = String::from_utf8_lossy(&self.s[self.pos..]);
                let shown: String = rest.chars().take(12).collect();
                err(
                    self.line,
                    format!("malformed JSON at {shown:?}: expected {wanted}"),
                )
            }
        }
    }

    fn value(&mut self) -> Result<Value, SolutionError> {
        self.ws();
        let line = self.line;
        let Some(c) = self.peek() else {
            return self.unexpected("a value");
        };
        let v = match c {
            b'{' => {
                self.enter()?;
                self.pos += 1;
                let mut fields = Vec::new();
                self.ws();
                if self.peek() == Some(b'}') {
                    self.pos += 1;
                } else {
                    loop {
                        self.ws();
                        if self.peek() != Some(b'"') {
                            return self.unexpected("a key string");
                        }
                        let key = self.string()?;
                        self.expect(b':')?;
                        let val = self.value()?;
                        fields.push((key, val));
                        self.ws();
                        match self.peek() {
                            Some(b',') => self.pos += 1,
                            Some(b'}') => {
                                self.pos += 1;
                                break;
                            }
                            _ => return self.unexpected("',' or '}'"),
                        }
                    }
                }
                self.depth -= 1;
                Json::Object(fields)
            }
            b'[' => {
                self.enter()?;
                self.pos += 1;
                let mut items = Vec::new();
                self.ws();
                if self.peek() == Some(b']') {
                    self.pos += 1;
                } else {
                    loop {
                        items.push(self.value()?);
                        self.ws();
                        match self.peek() {
                            Some(b',') => self.pos += 1,
                            Some(b']') => {
                                self.pos += 1;
                                break;
                            }
                            _ => return self.unexpected("',' or ']'"),
                        }
                    }
                }
                self.depth -= 1;
                Json::Array(items)
            }
            b'"' => Json::Str(self.string()?),
            b'-' | b'0'..=b'9' | b'N' | b'I' => self.number()?,
            b't' => self.word("true", Json::Bool)?,
            b'f' => self.word("false", Json::Bool)?,
            b'n' => self.word("null", Json::Null)?,
            _ => return self.unexpected("a value"),
        };
        Ok(Value { line, v })
    }

    fn enter(&mut self) -> Result<(), SolutionError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return err(self.line, "malformed JSON: nested too deeply");
        }
        Ok(())
    }

    fn word(&mut self, w: &str, v: Json) -> Result<Json, SolutionError> {
        if self.s[self.pos..].starts_with(w.as_bytes()) {
            self.pos += w.len();
            Ok(v)
        } else {
            self.unexpected("a value")
        }
    }

    fn number(&mut self) -> Result<Json, SolutionError> {
        let rest = &self.s[self.pos..];
        for bad in ["NaN", "-NaN", "Infinity", "-Infinity"] {
            if rest.starts_with(bad.as_bytes()) {
                self.pos += bad.len();
                return Ok(Json::NonFinite(bad));
            }
        }
        let start = self.pos;
        let digits = |r: &mut Self| {
            let s = r.pos;
            while matches!(r.peek(), Some(b'0'..=b'9')) {
                r.pos += 1;
            }
            r.pos > s
        };
        if self.peek() == Some(b'-') {
            self.pos += 1;
        }
        let int_start = self.pos;
        if !digits(self) {
            return self.unexpected("a digit");
        }
        if self.s[int_start] == b'0' && self.pos - int_start > 1 {
            return err(self.line, "malformed JSON number: leading zero");
        }
        if self.peek() == Some(b'.') {
            self.pos += 1;
            if !digits(self) {
                return self.unexpected("a digit after '.'");
            }
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            self.pos += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.pos += 1;
            }
            if !digits(self) {
                return self.unexpected("an exponent");
            }
        }
        let text = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("");
        Ok(Json::Number(text.to_string()))
    }

    fn string(&mut self) -> Result<String, SolutionError> {
        // At the opening quote.
        self.pos += 1;
        let mut out = Vec::new();
        loop {
            let Some(c) = self.peek() else {
                return err(self.line, "malformed JSON: unterminated string");
            };
            self.pos += 1;
            match c {
                b'"' => break,
                b'\n' => return err(self.line, "malformed JSON: line break inside a string"),
                b'\\' => {
                    let Some(e) = self.peek() else {
                        return err(self.line, "malformed JSON: unterminated string");
                    };
                    self.pos += 1;
                    match e {
                        b'"' => out.push(b'"'),
                        b'\\' => out.push(b'\\'),
                        b'/' => out.push(b'/'),
                        b'b' | b'f' | b'n' | b'r' | b't' => out.push(b' '),
                        b'u' => {
                            let hex = self.s.get(self.pos..self.pos + 4).unwrap_or(b"");
                            let code = std::str::from_utf8(hex)
                                .ok()
                                .and_then(|h| u32::from_str_radix(h, 16).ok());
                            let Some(code) = code else {
                                return err(self.line, "malformed JSON: bad \\u escape");
                            };
                            self.pos += 4;
                            let ch = char::from_u32(code).unwrap_or('\u{fffd}');
                            let mut buf = [0u8; 4];
                            out.extend_from_slice(ch.encode_utf8(&mut buf).as_bytes());
                        }
                        _ => return err(self.line, "malformed JSON: bad escape in a string"),
                    }
                }
                _ => out.push(c),
            }
        }
        Ok(String::from_utf8_lossy(&out).into_owned())
    }
}

/// The exact value of a JSON number or number string (`what` names it in
/// messages).
fn number_of(v: &Value, what: &str) -> Result<BigRational, SolutionError> {
    match &v.v {
        Json::Str(s) => parse_exact(s).map_err(|e| SolutionError {
            line: v.line,
            message: format!("{what}: {:?} is not an exact number ({e})", cut(s)),
        }),
        Json::Number(text) => {
            // Rust's `parse::<f64>` rounds the decimal text to the nearest
            // double (ties to even), as a JSON reader on the solver's side
            // does; the double is then read as the exact binary rational it
            // is.
            let d: f64 = text.parse().map_err(|_| SolutionError {
                line: v.line,
                message: format!("{what}: {text} is not a number"),
            })?;
            d.to_big_rational().ok_or_else(|| SolutionError {
                line: v.line,
                message: format!("{what}: {text} is beyond the range of a double (infinite)"),
            })
        }
        Json::NonFinite(w) => err(
            v.line,
            format!("{what}: {w} is not a finite number (the solver diverged?)"),
        ),
        Json::Null => err(v.line, format!("{what}: null is not a number")),
        _ => err(v.line, format!("{what}: expected a number")),
    }
}

fn numbers_of(
    v: &Value,
    what: &str,
    expected: usize,
    n: usize,
) -> Result<Vec<BigRational>, SolutionError> {
    let Json::Array(items) = &v.v else {
        return err(v.line, format!("{what}: expected an array of numbers"));
    };
    if items.len() != expected {
        return err(
            v.line,
            format!(
                "{what}: {} values, the scene has N = {n} (needs {expected})",
                items.len()
            ),
        );
    }
    items
        .iter()
        .enumerate()
        .map(|(i, x)| number_of(x, &format!("{what}[{i}]")))
        .collect()
}

fn index_of(v: &Value, what: &str) -> Result<usize, SolutionError> {
    if let Json::Number(text) = &v.v {
        if let Ok(k) = text.parse::<usize>() {
            return Ok(k);
        }
    }
    err(v.line, format!("{what}: expected a non-negative integer"))
}

fn clusters_of(v: &Value, n: usize) -> Result<Vec<bool>, SolutionError> {
    let Json::Array(items) = &v.v else {
        return err(v.line, "clusters: expected [[first, size], …]");
    };
    let mut contacts = vec![false; n.saturating_sub(1)];
    let mut next = 0usize;
    for (k, item) in items.iter().enumerate() {
        let Json::Array(pair) = &item.v else {
            return err(item.line, format!("clusters[{k}]: expected [first, size]"));
        };
        if pair.len() != 2 {
            return err(item.line, format!("clusters[{k}]: expected [first, size]"));
        }
        let first = index_of(&pair[0], &format!("clusters[{k}][0]"))?;
        let size = index_of(&pair[1], &format!("clusters[{k}][1]"))?;
        if first != next || size == 0 || first.checked_add(size).is_none_or(|e| e > n) {
            return err(
                item.line,
                format!(
                    "clusters[{k}] = [{first}, {size}]: clusters must partition particles 0..{n} left to right (next first index {next})"
                ),
            );
        }
        for flag in &mut contacts[first..first + size - 1] {
            *flag = true;
        }
        next = first + size;
    }
    if next != n {
        return err(
            v.line,
            format!("clusters cover particles 0..{next}, the scene has N = {n}"),
        );
    }
    Ok(contacts)
}

fn frame_of(v: &Value, n: usize) -> Result<Frame, SolutionError> {
    let Json::Object(fields) = &v.v else {
        return err(v.line, "expected an object {\"t\": …, \"positions\": […]}");
    };
    let get = |k: &str| fields.iter().find(|(key, _)| key == k).map(|(_, v)| v);
    if let Some((k, _)) = fields
        .iter()
        .enumerate()
        .find(|(i, (k, _))| fields[..*i].iter().any(|(j, _)| j == k))
        .map(|(_, f)| f)
    {
        return err(v.line, format!("key {k:?} given twice"));
    }
    let Some(tv) = get("t") else {
        return err(v.line, "missing \"t\": every object needs its time");
    };
    let t = number_of(tv, "t")?;
    if t.is_negative() {
        return err(tv.line, format!("t = {} is negative", t.render()));
    }
    if let Some(nv) = get("n") {
        let m = index_of(nv, "n")?;
        if m != n {
            return err(nv.line, format!("n = {m}, the scene has N = {n}"));
        }
    }
    let Some(pv) = get("positions") else {
        return err(v.line, "missing \"positions\"");
    };
    let positions = numbers_of(pv, "positions", n, n)?;
    let velocities = match get("velocities") {
        None => None,
        Some(Value { v: Json::Null, .. }) => None,
        Some(uv) => Some(numbers_of(uv, "velocities", n, n)?),
    };
    let multipliers = match get("multipliers") {
        None => None,
        Some(Value { v: Json::Null, .. }) => None,
        Some(lv) => Some(numbers_of(lv, "multipliers", n.saturating_sub(1), n)?),
    };
    let contacts = match get("clusters") {
        None => None,
        Some(Value { v: Json::Null, .. }) => None,
        Some(cv) => Some(clusters_of(cv, n)?),
    };
    Ok(Frame {
        line: v.line,
        t,
        positions,
        velocities,
        multipliers,
        contacts,
    })
}

pub(super) fn parse_json(text: &str, n: usize) -> Result<Vec<Frame>, SolutionError> {
    let mut r = Reader {
        s: text.as_bytes(),
        pos: 0,
        line: 1,
        depth: 0,
    };
    let mut values = Vec::new();
    loop {
        r.ws();
        if r.peek().is_none() {
            break;
        }
        let start = r.line;
        match r.value() {
            Ok(v) => values.push(v),
            // An object left open: name the line where it starts.
            Err(e) if r.peek().is_none() && e.line != start => {
                return err(
                    start,
                    format!(
                        "malformed JSON: the value starting here is not closed ({})",
                        e.message
                    ),
                )
            }
            Err(e) => return Err(e),
        }
    }
    let objects: Vec<Value> = match values.as_slice() {
        [Value {
            v: Json::Array(items),
            ..
        }] => items.clone(),
        _ => {
            if let Some(a) = values.iter().find(|v| matches!(v.v, Json::Array(_))) {
                return err(
                    a.line,
                    "a JSON array must be the whole solution (or give one object per line)",
                );
            }
            values
        }
    };
    objects.iter().map(|o| frame_of(o, n)).collect()
}
