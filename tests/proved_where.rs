//! `docs/guide/proved-where.md` carries, for every claim of the ledger, what
//! settles it: a Coq theorem for every N (`proofs/coq/claims.tsv`), the
//! symbolic prover for all real data at small N (`docs/prove-*.jsonl`), or
//! only the ledger's sampled checks. This test regenerates that table and
//! fails if the committed page is stale. To refresh it:
//! `STICKY_BLESS=1 cargo test --release --test proved_where`.

use std::path::Path;

use num_rational::BigRational;
use sticky::claims::coq::{coq_theorems, CoqKind, Statement};
use sticky::claims::ledger::Proofs;
use sticky::claims::macro_data::MASS_INTERPOLATED_MAX_N;
use sticky::claims::{registry, Kind};

const BEGIN: &str = "<!-- proved-where:begin -->\n";
const END: &str = "<!-- proved-where:end -->";

/// The Coq cell of one statement: theorems grouped by kind.
fn coq_cell(id: &str, statement: Statement) -> String {
    let rows: Vec<_> = coq_theorems(id)
        .iter()
        .filter(|t| t.statement == statement)
        .collect();
    let group = |kind: CoqKind, words: &str| {
        let names: Vec<String> = rows
            .iter()
            .filter(|t| t.kind == kind)
            .map(|t| format!("`{}`", t.qualified().trim_start_matches("Sticky.")))
            .collect();
        (!names.is_empty()).then(|| format!("{words} {}", names.join(", ")))
    };
    let parts: Vec<String> = [
        group(CoqKind::Proves, "**proved**:"),
        group(CoqKind::Part, "in part:"),
        group(CoqKind::Refutes, "**refuted**:"),
    ]
    .into_iter()
    .flatten()
    .collect();
    if parts.is_empty() {
        "—".to_string()
    } else {
        parts.join("; ")
    }
}

/// How the ledger samples a claim (the mass equation of ρ̃_N stops at
/// `MASS_INTERPOLATED_MAX_N`, for its cost).
fn sampled<S>(id: &str, kind: &Kind<S>) -> String {
    match kind {
        Kind::Case(_) => "random and shipped cases".into(),
        Kind::Scaling(_) if id == "prop:eulerian-formulation#mass-interpolated" => {
            format!("scaling, N = 4 … {MASS_INTERPOLATED_MAX_N}")
        }
        Kind::Scaling(_) => "scaling, N = 4 … 4096".into(),
        Kind::Formula(_) => "a fixed formula, checked once".into(),
        Kind::NotCheckable(_) => "not checkable".into(),
    }
}

fn table(proofs: &Proofs) -> String {
    let cell = |key: &str| proofs.get(key).map_or("—".to_string(), |p| p.cell.clone());
    let mut out = String::from(
        "| claim | statement | Coq, every N (over Q; R where the note says so) | `sticky prove`, all real data | sampled by the ledger |\n|---|---|---|---|---|\n",
    );
    for c in registry::<BigRational>() {
        out.push_str(&format!(
            "| `{}` | printed | {} | {} | {} |\n",
            c.id,
            coq_cell(c.id, Statement::Printed),
            cell(c.id),
            sampled(c.id, &c.kind)
        ));
        if let Some(corr) = &c.correction {
            out.push_str(&format!(
                "| `{}` | corrected | {} | {} | {} |\n",
                c.id,
                coq_cell(c.id, Statement::Corrected),
                cell(&format!("{} (corrected)", c.id)),
                sampled(c.id, &corr.check)
            ));
        }
    }
    out.push_str(&missing());
    out.push_str(&constants());
    out
}

/// The constants proved in Coq (`claims::proved::PROVED`): what the
/// scaling checkers compare every measurement with.
fn constants() -> String {
    let mut out = String::from(
        "\n### Constants proved in Coq, and the ledger's comparison\n\n\
         `M = max_i |u⁰_i|`, `S = x⁰_N − x⁰_0` with `x⁰_0 = x⁰_1 − 1/N − δ`, `δ = 1` (`df:x0`), \
         `T` the horizon, `‖·‖² = (1/N) Σ`. A claim fails when a measurement of its quantity \
         (any datum, any N = 4 … 4096) exceeds the constant; its tightness \
         `max measured / constant` is in its `CLAIMS.md` note and in `sticky claims --json` \
         (`proved.tightness`, per shipped scene and for the tightest random datum).\n\n\
         | claim | statement | Coq theorem | quantity | constant | compared by |\n|---|---|---|---|---|---|\n",
    );
    for p in sticky::claims::proved::PROVED {
        let statement = match p.statement {
            Statement::Printed => "printed",
            Statement::Corrected => "corrected",
        };
        let claim = registry::<BigRational>()
            .into_iter()
            .find(|c| c.id == p.claim)
            .expect("a proved constant names a claim");
        let kind = match p.statement {
            Statement::Printed => claim.kind,
            Statement::Corrected => claim.correction.expect("a corrected row").check,
        };
        let by = match (p.measure, kind) {
            (None, _) => "—",
            (Some(_), Kind::Case(_)) => "the ledger, on the scaling data once the cases hold",
            (Some(_), _) => "the scaling checker",
        };
        out.push_str(&format!(
            "| `{}` | {statement} | `{}` | {} | {} | {by} |\n",
            p.claim,
            p.theorem,
            p.quantity.replace('|', "\\|"),
            p.constant.replace('|', "\\|")
        ));
    }
    out
}

/// For every Coq row marked *part*: what it proves and what is missing, the
/// row's note in `proofs/coq/claims.tsv`.
fn missing() -> String {
    let mut out = String::from(
        "\n### What the Coq rows marked *in part* leave out\n\n\
         Each line is one row of `proofs/coq/claims.tsv`: the claim, the theorem, and its note \
         (what the theorem states and what it does not).\n\n",
    );
    for row in sticky::claims::coq::all()
        .iter()
        .filter(|t| t.kind == CoqKind::Part)
    {
        let statement = match row.statement {
            Statement::Printed => "printed",
            Statement::Corrected => "corrected",
        };
        out.push_str(&format!(
            "- `{}` ({statement}), `{}`: {}\n",
            row.claim,
            row.qualified().trim_start_matches("Sticky."),
            row.note
        ));
    }
    out
}

#[test]
fn proved_where_is_current() {
    let proofs = sticky::prove::record::ledger_proofs().expect("the committed proof record");
    let fresh = table(&proofs);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/proved-where.md");
    let page = std::fs::read_to_string(&path).unwrap_or_default();
    let (Some(a), Some(b)) = (page.find(BEGIN), page.find(END)) else {
        panic!("{} lacks the markers {BEGIN:?} … {END:?}", path.display());
    };
    let current = &page[a + BEGIN.len()..b];
    if current != fresh && std::env::var("STICKY_BLESS").is_ok_and(|v| v == "1") {
        let blessed = format!("{}{BEGIN}{fresh}{}", &page[..a], &page[b..]);
        std::fs::write(&path, blessed).expect("write proved-where.md");
        return;
    }
    assert!(
        current == fresh,
        "docs/guide/proved-where.md is stale: regenerate it with `STICKY_BLESS=1 cargo test --release --test proved_where`"
    );
}

#[test]
fn every_coq_row_reaches_the_table() {
    let proofs = sticky::prove::record::ledger_proofs().expect("the committed proof record");
    let t = table(&proofs);
    for row in sticky::claims::coq::all() {
        let name = row.qualified();
        assert!(
            t.contains(name.trim_start_matches("Sticky.")),
            "{name} missing from the table"
        );
    }
}
