//! Citations that a machine checks (issue 29, item 7), in the way s2n-quic
//! checks its RFC quotes:
//!
//! * every `\label` cited in the code (`src/`, `tests/`, `proofs/`),
//!   `CLAIMS.md` and the ledger's claim ids exists in the paper's source;
//! * every statement the ledger quotes — the text between double quotes in a
//!   claim's statement — is the paper's text, once both are reduced to a
//!   skeleton: the paper's comments and `\label`, `\ref`, `\eqref`,
//!   `\cite`, `\begin`, `\end` with their argument removed, its own macros
//!   (`\newcommand`) expanded, operator names (`\sup`, `\max`, …) kept as
//!   words, every other macro name dropped; the quote's label citations
//!   (`eq:Lagr-1`) removed; then, on both sides, superscript and subscript
//!   digits read as digits, a letter with a precomposed tilde (`Ũ`) read
//!   as the letter, and everything but ASCII letters and digits dropped,
//!   lower case. A quote may leave text out with `…` (each piece must then
//!   appear, in order) and insert words of its own in `[…]` when they cite a
//!   label (`[cond:Linfty]`: ignored; other brackets are the paper's).
//!
//! The paper stays outside the repository: the test reads `$STICKY_PAPER`, or
//! `../shared/paper/` relative to the repository root (where CI has it), and
//! says it skipped when there is no `.tex` there — except under `CI=true`,
//! where a missing paper fails.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use num_rational::BigRational;

/// Results of the paper that carry no `\label`, cited by a project id: the
/// id and the title of the environment (`\begin{prop}[title]`), which must
/// be in the paper.
const UNLABELLED: &[(&str, &str)] = &[("prop:eulerian-formulation", "Eulerian formulation")];

/// Macros printed as a word, kept in the skeleton (`\sup_i` is `sup_i`).
const OPERATORS: &[&str] = &[
    "sup", "inf", "max", "min", "lim", "log", "exp", "sin", "cos", "det", "ker",
];

/// The prefixes of the paper's labels (`prop:`, `eq:`, …), as cited.
const PREFIXES: &[&str] = &[
    "prop", "eq", "df", "def", "lem", "thm", "app", "cond", "hyp", "sec", "ssec", "rmk", "cor",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The paper's LaTeX source (every `.tex` of the directory), or `None` when
/// it is absent (and not under CI).
fn paper() -> Option<String> {
    let dir = std::env::var_os("STICKY_PAPER")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("../shared/paper"));
    let mut text = String::new();
    if let Ok(entries) = std::fs::read_dir(&dir) {
        let mut files: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "tex"))
            .collect();
        files.sort();
        for f in files {
            text.push_str(&std::fs::read_to_string(&f).expect("read the paper"));
            text.push('\n');
        }
    }
    if text.is_empty() {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true");
        assert!(
            !ci,
            "CI=true but the paper is not in {} (set STICKY_PAPER)",
            dir.display()
        );
        eprintln!(
            "citations: skipped, no paper in {} (set STICKY_PAPER to its directory)",
            dir.display()
        );
        return None;
    }
    Some(text)
}

/// The arguments of every `\name{…}` in `text` (no nested braces).
fn arguments<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let open = format!("\\{name}{{");
    text.match_indices(&open)
        .filter_map(|(i, _)| {
            let rest = &text[i + open.len()..];
            rest.find('}').map(|j| &rest[..j])
        })
        .collect()
}

fn labels(paper: &str) -> BTreeSet<String> {
    arguments(paper, "label")
        .into_iter()
        .map(str::to_string)
        .collect()
}

/// Every label-like citation `prefix:name` in `text` (a prefix of
/// [`PREFIXES`] after a character that is not part of a word, the name
/// up to the first character other than a letter, digit, `-` or `_`).
fn citations(text: &str) -> Vec<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    for p in PREFIXES {
        let pat = format!("{p}:");
        for (i, _) in text.match_indices(&pat) {
            let before_ok = i == 0 || {
                let c = bytes[i - 1];
                !(c.is_ascii_alphanumeric() || c == b'_' || c == b'-' || c == b':')
            };
            if !before_ok {
                continue;
            }
            let rest = &text[i + pat.len()..];
            let len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '_'))
                .unwrap_or(rest.len());
            let name = rest[..len].trim_end_matches(['-', '_']);
            if name.is_empty() || !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
                continue;
            }
            out.push(format!("{p}:{name}"));
        }
    }
    out
}

fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, ext, out);
        } else if p.extension().is_some_and(|x| x == ext) {
            out.push(p);
        }
    }
}

/// The sources that cite the paper: `src/`, `tests/`, `proofs/` (`.rs`) and
/// `CLAIMS.md`.
fn citing_files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for d in ["src", "tests", "proofs"] {
        files(&root().join(d), "rs", &mut out);
    }
    out.push(root().join("CLAIMS.md"));
    out.sort();
    out
}

/// The citations of `text` that are neither a label of the paper nor an
/// unlabelled result of [`UNLABELLED`].
fn unknown(text: &str, labels: &BTreeSet<String>) -> Vec<String> {
    citations(text)
        .into_iter()
        .filter(|c| !labels.contains(c) && !UNLABELLED.iter().any(|(id, _)| id == c))
        .collect()
}

/// A digit for a superscript or subscript digit (`⁰`, `₁`, …).
fn small_digit(c: char) -> Option<char> {
    let sup = "⁰¹²³⁴⁵⁶⁷⁸⁹";
    let sub = "₀₁₂₃₄₅₆₇₈₉";
    sup.chars()
        .position(|d| d == c)
        .or_else(|| sub.chars().position(|d| d == c))
        .and_then(|k| char::from_digit(k as u32, 10))
}

/// The letter under a precomposed tilde (`Ũ` → `U`).
fn untilde(c: char) -> char {
    let tilde = "ÃãẼẽĨĩÑñÕõŨũỸỹ";
    let plain = "AaEeIiNnOoUuYy";
    tilde
        .chars()
        .position(|t| t == c)
        .and_then(|k| plain.chars().nth(k))
        .unwrap_or(c)
}

/// ASCII letters and digits, lower case (small digits read as digits, a
/// tilde dropped from its letter).
fn letters(text: &str) -> String {
    text.chars()
        .map(untilde)
        .filter_map(|c| small_digit(c).or(Some(c)))
        .filter(char::is_ascii_alphanumeric)
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

/// The paper reduced to its skeleton: comments and `\label{…}` removed, the
/// paper's `\newcommand`s replaced by their skeleton, every other macro name
/// dropped, then [`letters`].
fn paper_skeleton(paper: &str) -> String {
    let mut text: String = paper
        .lines()
        .map(|l| {
            let mut cut = l.len();
            let b = l.as_bytes();
            for (i, &c) in b.iter().enumerate() {
                if c == b'%' && (i == 0 || b[i - 1] != b'\\') {
                    cut = i;
                    break;
                }
            }
            &l[..cut]
        })
        .collect::<Vec<_>>()
        .join("\n");
    for name in ["label", "ref", "eqref", "cite", "begin", "end"] {
        let args: BTreeSet<String> = arguments(&text, name)
            .into_iter()
            .map(str::to_string)
            .collect();
        for a in args {
            text = text.replace(&format!("\\{name}{{{a}}}"), " ");
        }
    }
    // \newcommand{\name}{body}: the name, and the body's letters outside
    // macro names.
    let mut defs: Vec<(String, String)> = Vec::new();
    for kw in ["\\newcommand{", "\\renewcommand{"] {
        for (i, _) in paper.match_indices(kw) {
            let rest = &paper[i + kw.len()..];
            let Some(j) = rest.find('}') else { continue };
            let name = rest[..j].to_string();
            let body_start = &rest[j + 1..];
            let Some(body) = body_start.strip_prefix('{') else {
                continue;
            };
            // The body up to its matching brace.
            let mut depth = 1;
            let mut end = body.len();
            for (k, c) in body.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            end = k;
                            break;
                        }
                    }
                    _ => {}
                }
            }
            defs.push((name, strip_macros(&body[..end])));
        }
    }
    // Longest names first, so that \tLambda is not read as \tL + ambda.
    defs.sort_by_key(|(n, _)| std::cmp::Reverse(n.len()));
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(i) = rest.find('\\') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let len = after
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(after.len());
        let name = format!("\\{}", &after[..len]);
        if let Some((_, body)) = defs.iter().find(|(n, _)| *n == name) {
            out.push(' ');
            out.push_str(body);
            out.push(' ');
        } else if OPERATORS.contains(&&after[..len]) {
            out.push(' ');
            out.push_str(&after[..len]);
            out.push(' ');
        }
        // Any other macro name is dropped; `\{`, `\,` and the like too.
        rest = &after[macro_end(after, len)..];
    }
    out.push_str(rest);
    letters(&out)
}

/// Where a macro name of `len` letters ends in `after` (the text after its
/// backslash): a one-character macro (`\,`, `\{`) when there are no letters.
fn macro_end(after: &str, len: usize) -> usize {
    if len > 0 {
        return len;
    }
    after.chars().next().map_or(0, char::len_utf8)
}

/// `text` without its macro names (`\name`), keeping the rest.
fn strip_macros(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find('\\') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let len = after
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(after.len());
        rest = &after[macro_end(after, len)..];
    }
    out.push_str(rest);
    out
}

/// The quotes of a statement: the texts between pairs of `"`.
fn quotes(statement: &str) -> Vec<&str> {
    statement.split('"').skip(1).step_by(2).collect()
}

/// The pieces of a quote that must appear in the paper, in order: the
/// quote cut at `…` (or `...`), without its inserted `[…]` that cite a label
/// and without its label citations, as skeletons (empty pieces dropped).
fn pieces(quote: &str) -> Vec<String> {
    let mut plain = String::new();
    let mut rest = quote;
    while let Some(i) = rest.find('[') {
        plain.push_str(&rest[..i]);
        match rest[i..].find(']') {
            Some(j) if !citations(&rest[i..i + j]).is_empty() => rest = &rest[i + j + 1..],
            _ => {
                plain.push('[');
                rest = &rest[i + 1..];
            }
        }
    }
    plain.push_str(rest);
    for c in citations(&plain) {
        plain = plain.replace(&c, " ");
    }
    plain
        .replace("...", "…")
        .split('…')
        .map(letters)
        .filter(|p| !p.is_empty())
        .collect()
}

/// Where `quote` fails to be the paper's text: the first piece not found
/// after the previous one, or `None` when it matches.
fn mismatch(quote: &str, skeleton: &str) -> Option<String> {
    let mut from = 0;
    for p in pieces(quote) {
        match skeleton[from..].find(&p) {
            Some(i) => from += i + p.len(),
            None => return Some(p),
        }
    }
    None
}

/// Every claim statement of the ledger (the quotes live there).
fn statements() -> Vec<(&'static str, &'static str)> {
    sticky::claims::registry::<BigRational>()
        .into_iter()
        .map(|c| (c.id, c.statement))
        .collect()
}

#[test]
fn every_cited_label_is_in_the_paper() {
    let Some(paper) = paper() else { return };
    let labels = labels(&paper);
    assert!(labels.len() > 50, "the paper's labels were not read");
    for (id, title) in UNLABELLED {
        assert!(
            !labels.contains(*id),
            "{id} is a label of the paper now: drop it from UNLABELLED"
        );
        assert!(
            paper.contains(&format!("[{title}]")),
            "{id}: no environment titled [{title}] in the paper"
        );
    }
    let mut bad = Vec::new();
    let mut cited = 0usize;
    for f in citing_files() {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        cited += citations(&text).len();
        for c in unknown(&text, &labels) {
            bad.push(format!(
                "{}: {c}",
                f.strip_prefix(root()).unwrap_or(&f).display()
            ));
        }
    }
    // The ledger's ids name a label before `#` (some carry no prefix, such
    // as pwUN-L1, and are not found by the scan above).
    for (id, _) in statements() {
        let label = id.split('#').next().unwrap_or(id);
        if !labels.contains(label) && !UNLABELLED.iter().any(|(u, _)| *u == label) {
            bad.push(format!("claim id {id}"));
        }
    }
    bad.sort();
    bad.dedup();
    assert!(
        cited > 500,
        "only {cited} citations found: the scan is broken"
    );
    assert!(
        bad.is_empty(),
        "{} citation(s) of labels the paper does not have:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

#[test]
fn every_quote_is_the_papers_text() {
    let Some(paper) = paper() else { return };
    let skeleton = paper_skeleton(&paper);
    let mut bad = Vec::new();
    let mut checked = 0usize;
    for (id, statement) in statements() {
        for q in quotes(statement) {
            checked += 1;
            if let Some(p) = mismatch(q, &skeleton) {
                bad.push(format!("{id}: \"{q}\"\n    piece not in the paper: {p}"));
            }
        }
    }
    assert!(
        checked > 30,
        "only {checked} quotes found: the scan is broken"
    );
    assert!(
        bad.is_empty(),
        "{} of {checked} quotes differ from the paper:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// The checks can fail: a made-up label, and a real quote with one word
/// changed.
#[test]
fn a_made_up_label_and_a_changed_quote_are_caught() {
    let Some(paper) = paper() else { return };
    let labels = labels(&paper);
    assert!(unknown("see prop:L2-micro and eq:Lagr-1.", &labels).is_empty());
    // Spelled at run time, so that the scan of this file does not see it.
    let made_up = format!("prop:{}", "L2-micro-bis");
    assert_eq!(
        unknown(&format!("see {made_up}, as in eq:Lagr-1"), &labels),
        vec![made_up]
    );
    let skeleton = paper_skeleton(&paper);
    let real = "the set of active constraints is non-decreasing in time";
    assert_eq!(mismatch(real, &skeleton), None, "a real quote");
    let changed = "the set of active constraints is non-increasing in time";
    assert!(mismatch(changed, &skeleton).is_some(), "a changed quote");
}
