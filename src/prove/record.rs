//! The committed proof record: what `sticky prove --json` printed on the
//! development machine (`docs/prove-n1-3.jsonl`, `docs/prove-n4.jsonl`),
//! summarised per claim for the ledger's column "proved for all real data,
//! N ≤ n" (issue 11, item 5). `tests/prove.rs` re-runs the prover at
//! N ≤ 3 and checks that every status recorded here is the one it gets, so
//! the record cannot drift from the code.

use std::collections::BTreeMap;

use serde::Deserialize;

use super::Status;

/// The record files, embedded (N = 1 … 3 for every claim; N = 4 for the
/// main section-2 claims, several attempts with growing time limits).
pub const COMMITTED: [(&str, &str); 2] = [
    (
        "docs/prove-n1-3.jsonl",
        include_str!("../../docs/prove-n1-3.jsonl"),
    ),
    (
        "docs/prove-n4.jsonl",
        include_str!("../../docs/prove-n4.jsonl"),
    ),
];

/// One line of a record: a claim at one N (the fields of a
/// [`ProofRecord`](super::json::ProofRecord) the ledger reads; the others
/// are ignored).
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
pub struct Line {
    /// The claim id as `sticky prove` prints it (` (corrected)` suffix for
    /// a correction).
    pub id: String,
    /// N.
    pub n: usize,
    /// The status.
    pub status: Status,
    /// The hypotheses, in words.
    pub hypotheses: String,
}

/// Parses one line of `sticky prove --json`.
pub fn parse_line(line: &str) -> Result<Line, String> {
    serde_json::from_str(line)
        .map_err(|e| format!("not a `sticky prove --json` line ({e}): {line}"))
}

/// Every line of the committed record, in file order.
pub fn committed() -> Result<Vec<Line>, String> {
    let mut out = Vec::new();
    for (file, text) in COMMITTED {
        for (k, line) in text.lines().enumerate() {
            if !line.trim().is_empty() {
                out.push(parse_line(line).map_err(|e| format!("{file}:{}: {e}", k + 1))?);
            }
        }
    }
    Ok(out)
}

/// What the record says of one claim.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Summary {
    /// The least N recorded: the statement's least N (2 where the paper
    /// says `N > 1`; nothing is recorded below it).
    pub from: usize,
    /// The largest n such that the claim is proved at every N = `from` …
    /// n (`from − 1` when not proved at `from`).
    pub proved_up_to: usize,
    /// The smallest N at which it is refuted.
    pub refuted_at: Option<usize>,
    /// The smallest N above `proved_up_to` attempted without a verdict.
    pub unknown_at: Option<usize>,
    /// The hypotheses of the proof at `proved_up_to`.
    pub hypotheses: Option<String>,
}

impl Summary {
    /// One cell of the ledger: `N ≤ 3`, `N ≤ 3 (N = 4: unknown)`,
    /// `refuted at N = 2`.
    pub fn cell(&self) -> String {
        if let Some(n) = self.refuted_at {
            return format!("refuted at N = {n}");
        }
        let mut s = if self.proved_up_to < self.from {
            "not proved".to_string()
        } else {
            format!("N ≤ {}", self.proved_up_to)
        };
        if let Some(n) = self.unknown_at {
            s.push_str(&format!(" (N = {n}: unknown)"));
        }
        s
    }
}

/// Summarises the lines per claim id. Several attempts at one (id, N) keep
/// the decisive one (a later attempt with more time may prove what an
/// earlier one left unknown); a claim both proved and refuted at one N is
/// an error (it would mean the prover is unsound).
pub fn summarise(lines: &[Line]) -> Result<BTreeMap<String, Summary>, String> {
    let mut best: BTreeMap<(String, usize), &Line> = BTreeMap::new();
    for l in lines {
        let key = (l.id.clone(), l.n);
        match best.get(&key) {
            Some(prev) if prev.status != Status::Unknown && l.status != Status::Unknown => {
                if prev.status != l.status {
                    return Err(format!(
                        "{} at N = {}: recorded both {} and {}",
                        l.id,
                        l.n,
                        prev.status.as_str(),
                        l.status.as_str()
                    ));
                }
            }
            Some(prev) if prev.status != Status::Unknown => {}
            _ => {
                best.insert(key, l);
            }
        }
    }
    let mut out: BTreeMap<String, Summary> = BTreeMap::new();
    for ((id, n), l) in &best {
        // The lines come in increasing N: the first one of an id is its least N.
        let s = out.entry(id.clone()).or_insert(Summary {
            from: *n,
            proved_up_to: n - 1,
            refuted_at: None,
            unknown_at: None,
            hypotheses: None,
        });
        match l.status {
            Status::Proved if *n == s.proved_up_to + 1 && s.unknown_at.is_none() => {
                s.proved_up_to = *n;
                s.hypotheses = Some(l.hypotheses.clone());
            }
            // Proved beyond a gap: not part of the contiguous range.
            Status::Proved => {}
            Status::Refuted => {
                s.refuted_at.get_or_insert(*n);
            }
            Status::Unknown => {
                s.unknown_at.get_or_insert(*n);
            }
        }
    }
    Ok(out)
}

/// The committed record as the ledger's column (claim id → cell and
/// hypotheses).
pub fn ledger_proofs() -> Result<crate::claims::ledger::Proofs, String> {
    Ok(summarise(&committed()?)?
        .into_iter()
        .map(|(id, s)| {
            let proof = crate::claims::ledger::Proof {
                cell: s.cell(),
                // A refuted claim's line names no hypotheses: the witness is
                // one datum.
                hypotheses: s.hypotheses.clone().filter(|_| s.refuted_at.is_none()),
            };
            (id, proof)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(id: &str, n: usize, status: &str) -> String {
        format!(
            "{{\"id\": \"{id}\", \"n\": {n}, \"status\": \"{status}\", \"paths\": 2, \"queries\": 2, \"seconds\": 0.031, \"hypotheses\": \"N = {n}, \\\"all\\\" real\", \"witness\": null, \"erratum\": false, \"note\": null}}"
        )
    }

    fn summary(lines: &[String]) -> Result<BTreeMap<String, Summary>, String> {
        let parsed: Vec<Line> = lines.iter().map(|l| parse_line(l).unwrap()).collect();
        summarise(&parsed)
    }

    #[test]
    fn a_line_parses_back() {
        let l = parse_line(&line("df:KN", 12, "unknown")).unwrap();
        assert_eq!(
            (l.id.as_str(), l.n, l.status),
            ("df:KN", 12, Status::Unknown)
        );
        assert_eq!(l.hypotheses, "N = 12, \"all\" real");
        assert!(parse_line("{\"id\": \"a\", \"n\": 1}").is_err());
        assert!(parse_line(&line("a", 1, "maybe")).is_err());
    }

    #[test]
    fn the_proved_range_is_contiguous_and_later_attempts_decide() {
        let s = summary(&[
            line("a", 1, "proved"),
            line("a", 2, "proved"),
            line("a", 3, "unknown"),
            line("a", 4, "proved"),
            line("b", 1, "proved"),
            line("b", 2, "unknown"),
            line("b", 2, "proved"),
            line("c", 1, "proved"),
            line("c", 2, "refuted"),
        ])
        .unwrap();
        assert_eq!(s["a"].cell(), "N ≤ 2 (N = 3: unknown)");
        assert_eq!(s["b"].cell(), "N ≤ 2");
        assert_eq!(s["b"].hypotheses.as_deref(), Some("N = 2, \"all\" real"));
        assert_eq!(s["c"].cell(), "refuted at N = 2");
    }

    #[test]
    fn proved_and_refuted_at_one_n_is_an_error() {
        assert!(summary(&[line("a", 2, "proved"), line("a", 2, "refuted")]).is_err());
    }

    #[test]
    fn the_committed_record_parses() {
        let s = summarise(&committed().unwrap()).unwrap();
        assert!(s["df:KN"].proved_up_to >= 3, "{:?}", s["df:KN"]);
    }
}
