//! `CLAIMS.md` is the ledger computed by `sticky claims --markdown` with the
//! default budget: this test recomputes it and fails if the committed file
//! is stale (every status is computed, never typed in). To refresh it:
//! `STICKY_BLESS=1 cargo test --release --test claims_ledger -- --ignored`.

use std::path::Path;

use sticky::claims::ledger::{self, Budget, Status};

#[test]
#[ignore = "campaign: the whole ledger (every checker, every case), ~3 min; CI runs it (cargo test --release -- --ignored)"]
fn claims_md_is_current() {
    let budget = Budget::default();
    let entries = ledger::run(budget, &sticky::progress::Silent);
    let proofs = sticky::prove::record::ledger_proofs().expect("the committed proof record");
    let md = ledger::markdown(&entries, budget, &proofs);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("CLAIMS.md");
    if std::env::var("STICKY_BLESS").is_ok_and(|v| v == "1") {
        std::fs::write(&path, &md).expect("write CLAIMS.md");
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == md,
        "CLAIMS.md is stale: regenerate it with `STICKY_BLESS=1 cargo test --release --test claims_ledger -- --ignored` (or `sticky claims --markdown > CLAIMS.md`)"
    );
    // The guide page of the ledger carries the summary between markers.
    let readme_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/claims.md");
    let readme = std::fs::read_to_string(&readme_path).unwrap_or_default();
    let (begin, end) = (
        "<!-- ledger-summary:begin -->\n",
        "<!-- ledger-summary:end -->",
    );
    let summary = ledger::summary(&entries);
    if std::env::var("STICKY_BLESS").is_ok_and(|v| v == "1") {
        if let (Some(a), Some(b)) = (readme.find(begin), readme.find(end)) {
            let fresh = format!("{}{begin}{summary}{}", &readme[..a], &readme[b..]);
            std::fs::write(&readme_path, fresh).expect("write docs/guide/claims.md");
        }
    }
    let readme = std::fs::read_to_string(&readme_path).unwrap_or_default();
    assert!(
        readme.contains(&format!("{begin}{summary}{end}")),
        "docs/guide/claims.md's ledger summary is stale: regenerate with `STICKY_BLESS=1 cargo test --release --test claims_ledger -- --ignored`"
    );
    // Every correction holds: a claim found false is reported, and what we
    // state instead is itself checked.
    for e in &entries {
        if let Some((_, o, _)) = &e.correction {
            assert_eq!(
                o.status,
                Status::Holds,
                "{}: the corrected statement fails: {:?}",
                e.id,
                o.witness
            );
        }
        if e.correction.is_none() {
            assert!(
                e.outcome.status != Status::Counterexample,
                "{}: a claim without a correction has a counterexample: {:?}",
                e.id,
                e.outcome.witness
            );
        }
    }
}
