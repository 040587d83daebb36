//! A counterexample as the ledger reports it: the violation's text, the
//! witness scene (shrunk random data, a shipped scene, a formula) and the
//! same in machine-readable form.

use num_rational::BigRational;

use super::found::Found;
use super::shrink::shrink;
use super::{Outcome, Status};
use crate::claims::domain::Domain;
use crate::claims::witness::{self, Failure, WitnessData, WitnessScene};
use crate::claims::{CaseCheck, Violation};
use crate::generate::{initial_data, Limits};
use crate::scalar::Scalar;
use crate::scene::{self, particles_toml};

/// The counterexample outcome of `cases` cases whose failure `found` lies
/// on `scene`: its witness text (`tail` last) and data.
fn outcome(
    cases: usize,
    found: &Found,
    scene: WitnessScene,
    domain: &Domain,
    tail: String,
) -> Outcome {
    let mut text = found.violations[0].witness.clone();
    if let (Some(iv), [_, b]) = (&found.interval, found.violations.as_slice()) {
        text.push_str(&format!(
            "\nfor a.e. t: it fails at t = {} and at t = {}, both in the open interval ({}, {}) between collision instants; the second: {}",
            found.times[0].render(),
            found.times[1].render(),
            iv.lo.render(),
            iv.hi.as_ref().map_or("∞".to_string(), |h| h.render()),
            b.witness.lines().next().unwrap_or("")
        ));
    }
    text.push_str(&tail);
    let data = WitnessData {
        scene,
        domain: witness::DomainData::of(domain),
        times: found
            .times
            .iter()
            .map(crate::rational::render_exact)
            .collect(),
        interval: found.interval.as_ref().map(witness::interval),
        failures: found.violations.iter().map(Failure::of).collect(),
    };
    Outcome {
        status: Status::Counterexample,
        cases,
        witness: Some(text),
        note: None,
        witness_data: Some(data),
        tightness: Vec::new(),
    }
}

/// The outcome of a random case that fails `check` inside `domain`: shrunk
/// to a small witness scene; `cases` counts the cases run, this one included.
pub(super) fn random_counterexample(
    cases: usize,
    bytes: Vec<u8>,
    limits: Limits,
    check: CaseCheck<BigRational>,
    domain: &Domain,
) -> Outcome {
    let (b, l, found) = shrink(bytes, limits, check, domain);
    let data = initial_data(&b, l);
    outcome(
        cases,
        &found,
        witness::particles(&data),
        domain,
        format!(
            "\nwitness scene (N = {}):\n{}",
            data.n(),
            particles_toml(&data, Some("witness"))
        ),
    )
}

/// The outcome of a shipped scene that fails inside `domain`: the
/// violation and the file.
pub(super) fn shipped_counterexample(
    cases: usize,
    name: &str,
    found: &Found,
    domain: &Domain,
) -> Outcome {
    outcome(
        cases,
        found,
        WitnessScene::Shipped {
            name: name.to_string(),
        },
        domain,
        format!("\nwitness: scenes/{name}.toml"),
    )
}

/// The witness data of a claim checked without a particle datum (a
/// formula, or a scaling check on a shipped scene named first in the
/// witness text).
pub(crate) fn timeless(v: &Violation, domain: &Domain) -> WitnessData {
    let name = v.witness.split(':').next().unwrap_or("");
    let scene = if scene::shipped(name).is_some() {
        WitnessScene::Shipped {
            name: name.to_string(),
        }
    } else if let Some((blocks, _)) = v
        .witness
        .strip_prefix("blocks = ")
        .and_then(|rest| rest.split_once(", N = "))
    {
        WitnessScene::Macro {
            blocks: blocks.to_string(),
        }
    } else {
        WitnessScene::Formula
    };
    WitnessData {
        scene,
        domain: witness::DomainData::of(domain),
        times: Vec::new(),
        interval: None,
        failures: vec![Failure::of(v)],
    }
}
