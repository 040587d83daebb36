//! Which Coq theorem proves (or disproves) each ledger claim for every N.
//!
//! The mapping lives in one table, `proofs/coq/claims.tsv`, compiled into the
//! crate with `include_str!`; the Coq development itself is `proofs/coq/`
//! (issue 26). The tests below tie every row to the ledger's registry, to a
//! declaration in `proofs/coq/theories/FILE` and to
//! `proofs/coq/main-theorems.txt` (whose theorems `make -C proofs/coq check`
//! runs `Print Assumptions` on).

use std::sync::OnceLock;

/// The table, one row per (claim, theorem); `#` lines are comments.
const TABLE: &str = include_str!("../../proofs/coq/claims.tsv");

/// Which statement of a claim a theorem is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize),
    serde(rename_all = "lowercase")
)]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub enum Statement {
    /// The statement as printed in the paper.
    Printed,
    /// The ledger's corrected statement (claims found false as printed).
    Corrected,
}

/// What a theorem does for the statement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize),
    serde(rename_all = "lowercase")
)]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub enum CoqKind {
    /// With the claim's other `Proves` rows, it is the statement, for every N,
    /// over Q (over R where the note says so).
    Proves,
    /// It proves part of the statement (the note says which part).
    Part,
    /// It is `~ (forall …)` of the statement: a machine-checked refutation
    /// with the witness named in the note.
    Refutes,
}

impl CoqKind {
    /// The word used in the table and in the JSON output.
    pub fn label(self) -> &'static str {
        match self {
            CoqKind::Proves => "proves",
            CoqKind::Part => "part",
            CoqKind::Refutes => "refutes",
        }
    }
}

/// One row of `proofs/coq/claims.tsv`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CoqTheorem {
    /// The ledger claim id.
    pub claim: &'static str,
    /// The printed or the corrected statement of that claim.
    pub statement: Statement,
    /// The `.v` file in `proofs/coq/theories/`.
    pub file: &'static str,
    /// The theorem's name inside that file (module = file stem).
    pub name: &'static str,
    /// Proves, proves part, or refutes.
    pub kind: CoqKind,
    /// Hypotheses and scope, in words.
    pub note: &'static str,
}

impl CoqTheorem {
    /// The fully qualified name, as in `main-theorems.txt`
    /// (`Sticky.Module.name`).
    pub fn qualified(&self) -> String {
        format!(
            "Sticky.{}.{}",
            self.file.strip_suffix(".v").unwrap_or(self.file),
            self.name
        )
    }
}

/// A malformed row of the table.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableError {
    /// 1-based line in `claims.tsv`.
    pub line: usize,
    /// What is wrong.
    pub reason: &'static str,
}

/// Parses the table; rows of one claim must be consecutive.
fn parse(text: &'static str) -> Result<Vec<CoqTheorem>, TableError> {
    let mut rows: Vec<CoqTheorem> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let err = |reason| TableError {
            line: i + 1,
            reason,
        };
        let cols: Vec<&'static str> = line.split('\t').collect();
        let [claim, statement, file, name, kind, note] = cols[..] else {
            return Err(err("expected 6 tab-separated columns"));
        };
        let statement = match statement {
            "printed" => Statement::Printed,
            "corrected" => Statement::Corrected,
            _ => return Err(err("statement must be printed or corrected")),
        };
        let kind = match kind {
            "proves" => CoqKind::Proves,
            "part" => CoqKind::Part,
            "refutes" => CoqKind::Refutes,
            _ => return Err(err("kind must be proves, part or refutes")),
        };
        if !file.ends_with(".v") || name.is_empty() || claim.is_empty() {
            return Err(err("empty claim or theorem, or file not *.v"));
        }
        let seen_before = rows.iter().any(|r| r.claim == claim);
        let last = rows.last().map(|r| r.claim);
        if seen_before && last != Some(claim) {
            return Err(err("the rows of one claim must be consecutive"));
        }
        rows.push(CoqTheorem {
            claim,
            statement,
            file,
            name,
            kind,
            note,
        });
    }
    Ok(rows)
}

/// Every row of the table (empty if the compiled-in table were malformed,
/// which the unit tests rule out).
pub fn all() -> &'static [CoqTheorem] {
    static ROWS: OnceLock<Vec<CoqTheorem>> = OnceLock::new();
    ROWS.get_or_init(|| parse(TABLE).unwrap_or_default())
}

/// The Coq theorems about `claim_id` (printed and corrected statements),
/// in table order; empty when no theorem is about it.
pub fn coq_theorems(claim_id: &str) -> &'static [CoqTheorem] {
    let rows = all();
    match rows.iter().position(|r| r.claim == claim_id) {
        None => &[],
        Some(start) => {
            let len = rows[start..]
                .iter()
                .take_while(|r| r.claim == claim_id)
                .count();
            &rows[start..start + len]
        }
    }
}

/// One Coq theorem about a claim, as `sticky claims --json` lists it in
/// the claim's `"coq"` array.
#[cfg(feature = "json")]
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub struct CoqRow {
    /// The `.v` file, from the repository's root.
    pub file: String,
    /// The theorem's fully qualified name (`Sticky.Module.name`).
    pub theorem: String,
    /// `proves` (with the claim's other `proves` rows, the statement for
    /// every N, over Q or, where the note says so, over R), `part` (part of
    /// it, the note says which) or
    /// `refutes` (the negation of the statement, machine-checked).
    pub kind: CoqKind,
    /// Whether it is about the `printed` statement or the ledger's
    /// `corrected` one.
    pub statement: Statement,
    /// Hypotheses and scope, in words.
    pub note: String,
}

/// The Coq rows of `claim_id`, in table order.
#[cfg(feature = "json")]
pub fn rows(claim_id: &str) -> Vec<CoqRow> {
    coq_theorems(claim_id)
        .iter()
        .map(|t| CoqRow {
            file: format!("proofs/coq/theories/{}", t.file),
            theorem: t.qualified(),
            kind: t.kind,
            statement: t.statement,
            note: t.note.to_string(),
        })
        .collect()
}

/// The line under a claim in `sticky claims --markdown` (empty when no Coq
/// theorem is about it).
pub fn markdown_line(claim_id: &str) -> String {
    let rows = coq_theorems(claim_id);
    if rows.is_empty() {
        return String::new();
    }
    let items: Vec<String> = rows
        .iter()
        .map(|t| {
            let which = match t.statement {
                Statement::Printed => "",
                Statement::Corrected => "corrected statement, ",
            };
            format!("{} `{}` ({which}{})", t.kind.label(), t.qualified(), t.note)
        })
        .collect();
    format!(
        "Coq (every N; over Q, or over R where the note says so): {}.\n\n",
        items.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;
    use std::path::PathBuf;

    fn coq_dir() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("proofs/coq")
    }

    /// Problems of one row: a claim the ledger does not have, a corrected
    /// statement for a claim without correction, a theorem not declared in
    /// its file, a theorem not in `main-theorems.txt`.
    fn row_problems(t: &CoqTheorem) -> Vec<String> {
        let claims = crate::claims::registry::<BigRational>();
        let mut out = Vec::new();
        match claims.iter().find(|c| c.id == t.claim) {
            None => out.push(format!("{}: not a ledger claim id", t.claim)),
            Some(c) if t.statement == Statement::Corrected && c.correction.is_none() => out.push(
                format!("{}: the ledger has no corrected statement", t.claim),
            ),
            Some(_) => {}
        }
        let path = coq_dir().join("theories").join(t.file);
        match std::fs::read_to_string(&path) {
            Err(e) => out.push(format!("{}: {e}", path.display())),
            Ok(src) => {
                let declared = src.lines().any(|l| {
                    ["Theorem", "Lemma", "Corollary", "Proposition"]
                        .iter()
                        .any(|kw| {
                            l.strip_prefix(kw)
                                .and_then(|rest| rest.strip_prefix(' '))
                                .and_then(|rest| rest.strip_prefix(t.name))
                                .is_some_and(|rest| {
                                    rest.starts_with([' ', ':', '(']) || rest.is_empty()
                                })
                        })
                });
                if !declared {
                    out.push(format!("{} is not declared in {}", t.name, t.file));
                }
            }
        }
        let main = std::fs::read_to_string(coq_dir().join("main-theorems.txt")).unwrap_or_default();
        if !main.lines().any(|l| l.trim() == t.qualified()) {
            out.push(format!("{} is not in main-theorems.txt", t.qualified()));
        }
        out
    }

    #[test]
    fn table_parses() {
        let rows = parse(TABLE).expect("claims.tsv parses");
        assert!(!rows.is_empty());
        assert_eq!(all().len(), rows.len());
    }

    #[test]
    fn every_row_names_a_claim_and_a_checked_theorem() {
        let problems: Vec<String> = all().iter().flat_map(row_problems).collect();
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }

    #[test]
    fn a_wrong_row_is_caught() {
        let good = &coq_theorems("prop:Oleinik")[0];
        let wrong_name = CoqTheorem {
            name: "oleinik_strict",
            ..good.clone()
        };
        assert!(row_problems(&wrong_name)
            .iter()
            .any(|p| p.contains("not declared")));
        // Declared but not a main theorem (Print Assumptions does not cover it).
        let helper = CoqTheorem {
            name: "oleinik_pair",
            ..good.clone()
        };
        assert_eq!(
            row_problems(&helper),
            vec!["Sticky.Oleinik.oleinik_pair is not in main-theorems.txt".to_string()]
        );
        let wrong_claim = CoqTheorem {
            claim: "prop:Oleinik#nope",
            ..good.clone()
        };
        assert!(!row_problems(&wrong_claim).is_empty());
        let no_correction = CoqTheorem {
            statement: Statement::Corrected,
            ..good.clone()
        };
        assert!(!row_problems(&no_correction).is_empty());
    }

    #[test]
    fn malformed_tables_are_rejected() {
        assert!(parse("a\tprinted\tX.v\tt\tproves\n").is_err());
        assert!(parse("a\tprinted\tX.v\tt\tmaybe\tn\n").is_err());
        assert!(parse("a\tp\tX.v\tt\tproves\tn\n").is_err());
        assert!(parse("a\tprinted\tX\tt\tproves\tn\n").is_err());
        let split = "a\tprinted\tX.v\tt\tproves\tn\nb\tprinted\tX.v\tt\tproves\tn\na\tprinted\tX.v\tu\tproves\tn\n";
        assert_eq!(parse(split).map_err(|e| e.line), Err(3));
    }

    #[test]
    fn lookup_returns_the_rows_of_one_claim() {
        let rows = coq_theorems("eq:dyn-micro");
        assert_eq!(rows.len(), 4);
        assert!(rows.iter().all(|r| r.claim == "eq:dyn-micro"));
        assert!(coq_theorems("no-such-claim").is_empty());
        let oleinik = coq_theorems("prop:Oleinik");
        assert_eq!(oleinik[0].qualified(), "Sticky.Oleinik.oleinik");
        assert_eq!(oleinik[0].kind.label(), "proves");
        assert_eq!(oleinik[0].file, "Oleinik.v");
        assert!(markdown_line("no-such-claim").is_empty());
        assert!(markdown_line("prop:Oleinik")
            .starts_with(
                "Coq (every N; over Q, or over R where the note says so): proves `Sticky.Oleinik.oleinik` (t > 0"
            ));
        assert!(markdown_line("eq:w-Hs-perp")
            .contains("proves `Sticky.InclHSN.incl_HSN` (corrected statement, "));
    }
}
