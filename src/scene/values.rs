//! The TOML readers shared by the tables: error messages, key checks, and
//! exact numbers under the per-scene number budget.

use num_bigint::BigInt;
use num_rational::BigRational;
use toml::{Table, Value};

use super::{MAX_NUMBER_BITS, MAX_QUOTED_CHARS};
use crate::error::Error;
use crate::rational::parse_exact;

/// A one-line TOML syntax error: "line L, column C: message".
pub(super) fn toml_error(text: &str, e: &toml::de::Error) -> Error {
    let message = e
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let message = match e.span() {
        Some(span) => {
            let start = span.start.min(text.len());
            let before = text.get(..start).unwrap_or("");
            let line = before.matches('\n').count() + 1;
            let column = before
                .rsplit('\n')
                .next()
                .map(|l| l.chars().count())
                .unwrap_or(0)
                + 1;
            format!("line {line}, column {column}: {message}")
        }
        None => message,
    };
    Error::Toml { message }
}

/// `prefix.key`, or `key` at top level.
pub(super) fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// Refuses any key of `table` not in `allowed` (the first in TOML order).
pub(super) fn check_keys(table: &Table, prefix: &str, allowed: &[&str]) -> Result<(), Error> {
    match table.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(Error::UnknownField {
            field: join(prefix, k),
        }),
        None => Ok(()),
    }
}

pub(super) fn optional_string(table: &Table, key: &str) -> Result<Option<String>, Error> {
    match table.get(key) {
        None => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(_) => Err(Error::WrongType {
            field: key.to_string(),
            expected: "a string",
        }),
    }
}

pub(super) fn required<'a>(table: &'a Table, prefix: &str, key: &str) -> Result<&'a Value, Error> {
    table.get(key).ok_or_else(|| Error::MissingField {
        field: join(prefix, key),
    })
}

pub(super) fn as_table<'a>(value: &'a Value, field: &str) -> Result<&'a Table, Error> {
    match value {
        Value::Table(t) => Ok(t),
        _ => Err(Error::WrongType {
            field: field.to_string(),
            expected: "a table",
        }),
    }
}

/// What [`exact`] expects, for [`Error::WrongType`].
pub(super) const EXACT_NUMBER: &str =
    "an exact number: a TOML integer, or a quoted integer, fraction, decimal or scientific number such as \"-7/4\" or \"1.5e-3\"";

/// Cuts `text` to [`MAX_QUOTED_CHARS`] characters.
pub(super) fn quoted(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTED_CHARS) {
        Some((cut, _)) => format!("{}…", text.get(..cut).unwrap_or("")),
        None => text.to_string(),
    }
}

/// The running total of number sizes of one scene, against
/// [`MAX_NUMBER_BITS`].
pub(super) struct Budget {
    left: std::cell::Cell<u64>,
}

impl Budget {
    pub(super) fn new() -> Self {
        Budget {
            left: std::cell::Cell::new(MAX_NUMBER_BITS),
        }
    }

    /// Charges the bits of `q` (plus a fixed 64 for its header).
    pub(super) fn charge(&self, q: &BigRational, field: &str) -> Result<(), Error> {
        let cost = bits(q).saturating_add(64);
        match self.left.get().checked_sub(cost) {
            Some(left) => {
                self.left.set(left);
                Ok(())
            }
            None => Err(Error::Unsupported {
                message: format!(
                    "field `{field}`: the exact numbers of this scene exceed {} MiB in total",
                    MAX_NUMBER_BITS / (8 * 1024 * 1024)
                ),
            }),
        }
    }
}

/// An exact number: a TOML integer or a string read by [`parse_exact`].
pub(super) fn exact(value: &Value, field: &str, budget: &Budget) -> Result<BigRational, Error> {
    match value {
        Value::Integer(i) => Ok(BigRational::from_integer(BigInt::from(*i))),
        Value::String(s) => {
            let q = parse_exact(s).map_err(|reason| Error::Number {
                field: field.to_string(),
                text: quoted(s),
                reason,
            })?;
            budget.charge(&q, field)?;
            Ok(q)
        }
        Value::Float(f) if f.is_finite() => Err(Error::Float {
            field: field.to_string(),
            // Shortest round-trip form ("0.5", "1e-7"): quoting it gives the
            // decimal the author most likely meant.
            value: format!("{f:?}"),
        }),
        Value::Float(_) => Err(Error::WrongType {
            field: field.to_string(),
            expected: "a finite exact number (inf and nan are not numbers here)",
        }),
        _ => Err(Error::WrongType {
            field: field.to_string(),
            expected: EXACT_NUMBER,
        }),
    }
}

/// An array of exact numbers.
pub(super) fn exact_array(
    value: &Value,
    field: &str,
    budget: &Budget,
) -> Result<Vec<BigRational>, Error> {
    let Value::Array(items) = value else {
        return Err(Error::WrongType {
            field: field.to_string(),
            expected: "an array of exact numbers",
        });
    };
    items
        .iter()
        .enumerate()
        .map(|(i, v)| exact(v, &format!("{field}[{i}]"), budget))
        .collect()
}

/// Bits of a rational's numerator and denominator.
pub(super) fn bits(q: &BigRational) -> u64 {
    q.numer().bits() + q.denom().bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_budget_is_enforced() {
        let budget = Budget {
            left: std::cell::Cell::new(14_000),
        };
        let big = Value::String("1e4096".into());
        assert!(exact(&big, "x", &budget).is_ok());
        let e = exact(&big, "particles.positions[1]", &budget).unwrap_err();
        assert!(matches!(e, Error::Unsupported { .. }), "{e:?}");
        assert!(e.to_string().contains("particles.positions[1]"), "{e}");
        // TOML integers are small and not charged.
        assert!(exact(&Value::Integer(7), "y", &budget).is_ok());
    }
}
