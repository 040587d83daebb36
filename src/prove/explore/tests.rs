//! The explorer's tests: the query ladder on a logged query, the union
//! of outcomes, the implied decisions.

use super::*;
use crate::progress::Silent;
use crate::prove::poly::Var;

/// A term of the SMT-LIB text the prover writes ([`Poly::smt`]).
fn parse_term(tokens: &[&str], at: &mut usize, names: &[String]) -> Poly {
    let tok = tokens[*at];
    *at += 1;
    if tok != "(" {
        if let Some(v) = names.iter().position(|n| n == tok) {
            return Poly::var(Var::try_from(v).unwrap());
        }
        let int = tok.strip_suffix(".0").unwrap();
        return Poly::constant(BigRational::from_integer(int.parse().unwrap()));
    }
    let op = tokens[*at];
    *at += 1;
    let mut args = Vec::new();
    while tokens[*at] != ")" {
        args.push(parse_term(tokens, at, names));
    }
    *at += 1;
    let q = |p: &Poly| p.as_constant().unwrap();
    match (op, args.as_slice()) {
        ("-", [a]) => a.neg(),
        ("/", [a, b]) => Poly::constant(q(a) / q(b)),
        ("*", _) => args.iter().fold(
            Poly::constant(BigRational::from_integer(1.into())),
            |m, a| m.mul(a),
        ),
        ("+", _) => args.iter().fold(Poly::zero(), |m, a| m.add(a)),
        _ => panic!("unexpected term ({op} …)"),
    }
}

/// A sign condition `(rel p 0.0)` or `(not (= p 0.0))`.
fn parse_atom(tokens: &[&str], at: &mut usize, names: &[String]) -> (Poly, Rel) {
    assert_eq!(tokens[*at], "(");
    let op = tokens[*at + 1];
    *at += 2;
    let (poly, rel) = if op == "not" {
        let (p, rel) = parse_atom(tokens, at, names);
        assert_eq!(rel, Rel::Eq);
        (p, Rel::Ne)
    } else {
        let rel = match op {
            "<" => Rel::Lt,
            "<=" => Rel::Le,
            "=" => Rel::Eq,
            ">" => Rel::Gt,
            ">=" => Rel::Ge,
            _ => panic!("unexpected relation {op}"),
        };
        let p = parse_term(tokens, at, names);
        assert!(parse_term(tokens, at, names).is_zero());
        (p, rel)
    };
    assert_eq!(tokens[*at], ")");
    *at += 1;
    (poly, rel)
}

/// The assertions of a transcript as hypotheses (`or` of atoms as
/// [`Hypothesis::Any`]), with the variable names declared.
fn parse_assertions(text: &str) -> (Vec<String>, Vec<Hypothesis>) {
    let mut names = Vec::new();
    let mut out = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with(';')) {
        let spaced = line.replace('(', " ( ").replace(')', " ) ");
        let tokens: Vec<&str> = spaced.split_whitespace().collect();
        match tokens.get(1) {
            Some(&"declare-const") => names.push(tokens[2].to_string()),
            Some(&"assert") if tokens[3] == "or" => {
                let mut at = 4;
                let mut atoms = Vec::new();
                while tokens[at] != ")" {
                    atoms.push(parse_atom(&tokens, &mut at, &names));
                }
                out.push(Hypothesis::Any(atoms));
            }
            Some(&"assert") => {
                let (p, rel) = parse_atom(&tokens, &mut 2, &names);
                out.push(Hypothesis::Sign(p, rel));
            }
            _ => {}
        }
    }
    (names, out)
}

/// A query `nlsat` does not answer within its 20 s limit (a cell step
/// of `lem:density` at N = 3, from a transcript) is settled by its
/// linear part after the short first try, well within a 10 s budget;
/// asked only as one long query first, it would spend the whole budget
/// on it and end `unknown`.
#[test]
fn a_query_nlsat_cannot_answer_is_refuted_after_the_first_try() {
    if super::super::smt::available().is_none() {
        eprintln!("z3 not installed: skipped");
        return;
    }
    let text = include_str!("../fixtures/cell_step_n3.smt2");
    let (names, mut hyps) = parse_assertions(text);
    let Some(Hypothesis::Sign(question, Rel::Gt)) = hyps.pop() else {
        panic!("the fixture ends with its question `p > 0`");
    };
    let program = || match decide(&question, &[Rel::Gt, Rel::Le]) {
        0 => PathEnd::Violated("the cell step fails".into()),
        _ => PathEnd::Holds,
    };
    let limits = Limits {
        time: Duration::from_secs(10),
        ..Limits::default()
    };
    assert_eq!(limits.query_ms, 20_000);
    let e = explore(&names, &hyps, limits, &program, &Silent).unwrap();
    assert!(matches!(e.verdict, Verdict::Proved), "{:?}", e.verdict);
    assert_eq!(e.paths, 1);
}

/// The union of outcomes asked in one query allows exactly their signs
/// (a wrong union, e.g. `Lt ∪ Eq` as `Lt`, would drop feasible paths).
#[test]
fn union_of_outcomes_is_exact() {
    assert_eq!(union_rel([Rel::Lt, Rel::Eq].into_iter()), Some(Rel::Le));
    assert_eq!(union_rel([Rel::Eq, Rel::Gt].into_iter()), Some(Rel::Ge));
    assert_eq!(union_rel([Rel::Lt, Rel::Gt].into_iter()), Some(Rel::Ne));
    assert_eq!(union_rel([Rel::Gt].into_iter()), Some(Rel::Gt));
    assert_eq!(union_rel([Rel::Lt, Rel::Eq, Rel::Gt].into_iter()), None);
    for a in [Rel::Lt, Rel::Le, Rel::Eq, Rel::Ne, Rel::Gt, Rel::Ge] {
        for b in [Rel::Lt, Rel::Le, Rel::Eq, Rel::Ne, Rel::Gt, Rel::Ge] {
            if let Some(u) = union_rel([a, b].into_iter()) {
                assert_eq!(u.mask(), a.mask() | b.mask());
            }
        }
    }
}

/// The variable names are cleared on every exit of [`explore`]: here the
/// early return on unsatisfiable hypotheses, which left them installed
/// (for the next exploration on the thread to print stale names) before
/// they were held by a guard.
#[test]
fn names_are_cleared_when_the_hypotheses_are_unsatisfiable() {
    if super::super::smt::available().is_none() {
        eprintln!("z3 not installed: skipped");
        return;
    }
    let names = vec!["x".to_string()];
    let x = Poly::var(0);
    let hyps = [
        Hypothesis::Sign(x.clone(), Rel::Gt),
        Hypothesis::Sign(x, Rel::Lt),
    ];
    let program = || PathEnd::Holds;
    let e = explore(&names, &hyps, Limits::default(), &program, &Silent).unwrap();
    assert!(matches!(e.verdict, Verdict::Unknown(_)), "{:?}", e.verdict);
    assert!(
        super::names().is_empty(),
        "stale names: {:?}",
        super::names()
    );
}

/// Two outcomes feasible: the first is taken and the other queued, so the
/// program runs on both paths, and the decision replayed on the second is
/// the alternative (a replay that took the recorded outcome again, or
/// dropped the branch, would see one sign only).
#[test]
fn both_feasible_outcomes_are_explored() {
    if super::super::smt::available().is_none() {
        eprintln!("z3 not installed: skipped");
        return;
    }
    let names = vec!["x".to_string()];
    let x = Poly::var(0);
    let seen = std::cell::RefCell::new(Vec::new());
    let program = || {
        let k = decide(&x, &[Rel::Gt, Rel::Le]);
        seen.borrow_mut().push(k);
        PathEnd::Holds
    };
    let e = explore(&names, &[], Limits::default(), &program, &Silent).unwrap();
    assert!(matches!(e.verdict, Verdict::Proved), "{:?}", e.verdict);
    assert_eq!(e.paths, 2);
    let mut seen = seen.into_inner();
    seen.sort_unstable();
    assert_eq!(seen, vec![0, 1]);
}
