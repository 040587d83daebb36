//! Which engine answers: the caller's [`Engine`] (the cost model's choice
//! by default, or one forced by name), resolved by the cost model and the
//! work check into a [`Choice`], with its fallback when the work check
//! refuses the engine first chosen.

use std::fmt;
use std::str::FromStr;

use num_rational::BigRational;

use crate::error::Error;
use crate::fast::engine::{Blockwise, ExactEngine, Kernel, ENGINES};
use crate::initial::InitialData;
use crate::solver::cost::Cost;
use crate::solver::work::{check_work_for, WorkCap};

/// The name of [`Engine::Auto`] on the command line (`--engine auto`).
const AUTO: &str = "auto";

/// Which exact engine answers the one-shot states.
#[derive(Clone, Copy, Default)]
#[non_exhaustive]
pub enum Engine {
    /// The cheapest for the data by the cost model ([`Cost`]), with the
    /// fast paths (dyadic, streaming) first where the data allow and a
    /// fallback when the work check refuses the cost model's choice.
    #[default]
    Auto,
    /// This engine of [`ENGINES`], and nothing else (no fast path, no
    /// fallback): `sticky run --engine NAME`.
    Forced(&'static dyn ExactEngine),
}

impl fmt::Debug for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl PartialEq for Engine {
    fn eq(&self, other: &Engine) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Engine {}

impl Engine {
    /// The name the command line gives it (`auto`, or the engine's name).
    pub fn name(&self) -> &'static str {
        match self {
            Engine::Auto => AUTO,
            Engine::Forced(e) => e.name(),
        }
    }

    /// Every choice a caller can name, [`Engine::Auto`] first: the
    /// command line's `--engine` values and their help.
    pub fn choices() -> impl Iterator<Item = EngineChoice> {
        let auto = EngineChoice {
            name: AUTO,
            aliases: &[],
            summary: "the cheapest exact engine for the data",
        };
        std::iter::once(auto).chain(ENGINES.iter().map(|e| EngineChoice {
            name: e.name(),
            aliases: e.aliases(),
            summary: e.summary(),
        }))
    }
}

impl FromStr for Engine {
    type Err = Error;

    /// `auto`, or the name or an alias of an engine of [`ENGINES`].
    fn from_str(name: &str) -> Result<Engine, Error> {
        if name == AUTO {
            return Ok(Engine::Auto);
        }
        ENGINES
            .iter()
            .copied()
            .find(|e| e.name() == name || e.aliases().contains(&name))
            .map(Engine::Forced)
            .ok_or_else(|| Error::Unsupported {
                message: format!("unknown engine {name:?}"),
            })
    }
}

/// One value of `--engine`: its name, aliases and one-line help.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EngineChoice {
    /// The name.
    pub name: &'static str,
    /// Other names accepted for it.
    pub aliases: &'static [&'static str],
    /// One line: the algorithm and the numbers it runs on.
    pub summary: &'static str,
}

/// The cheapest exact engine for one-shot states by the cost model: the
/// integer kernel, which runs on the narrowest integer width the data allow
/// at each time (`i128`, 256-bit, `BigInt`), when the common denominator is
/// small enough; else the projection with one common denominator per block
/// ([`Blockwise`]).
pub fn cheapest(cost: &Cost) -> &'static dyn ExactEngine {
    if cost.common_is_cheaper() {
        &Kernel
    } else {
        &Blockwise
    }
}

/// Why the engine of a [`Choice`] answers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reason {
    /// The cost model chose it.
    CostModel,
    /// The caller named it.
    Named,
    /// The work check refused the cost model's choice (this engine's name)
    /// and this one passes it.
    Fallback(&'static str),
}

/// The engine that answers the one-shot states of some data, why, and what
/// its work check said.
#[derive(Clone)]
pub struct Choice {
    /// The engine.
    pub engine: &'static dyn ExactEngine,
    /// The cost model of the data.
    pub cost: Cost,
    /// Why this engine.
    pub reason: Reason,
    /// The work check's verdict on it: a refusal says why.
    pub work: Result<(), Error>,
}

impl Choice {
    /// Resolves `engine` on `data`: the named engine, or the cost model's
    /// choice — and when the work check refuses the latter, the blockwise
    /// projection on local denominators if its own check passes.
    pub fn resolve(data: &InitialData<BigRational>, engine: Engine, cap: WorkCap) -> Choice {
        let cost = Cost::of(data);
        let (chosen, reason) = match engine {
            Engine::Forced(e) => (e, Reason::Named),
            Engine::Auto => (cheapest(&cost), Reason::CostModel),
        };
        let work = check_work_for(data, chosen, cap, Some(&cost));
        if work.is_err() && reason == Reason::CostModel && chosen.name() != Blockwise.name() {
            let fallback = check_work_for(data, &Blockwise, cap, Some(&cost));
            if fallback.is_ok() {
                return Choice {
                    engine: &Blockwise,
                    cost,
                    reason: Reason::Fallback(chosen.name()),
                    work: fallback,
                };
            }
        }
        Choice {
            engine: chosen,
            cost,
            reason,
            work,
        }
    }

    /// What `sticky run --explain` prints: the engine, `N`, the common
    /// denominator, each candidate's estimate, and why.
    pub fn explain(&self) -> String {
        let how = match self.reason {
            Reason::CostModel => "chosen by the cost model".to_string(),
            Reason::Named => "named by --engine".to_string(),
            Reason::Fallback(first) => format!(
                "the cost model chose {first}, which the work check refuses: this one passes it"
            ),
        };
        format!("{} ({how})", self.cost.explain(self.engine))
    }
}
