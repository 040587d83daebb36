//! How much work the ledger does: random cases per claim, their sizes, the
//! sizes of the checks across N, and the seed.

/// How much work the ledger does.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// Random cases per claim.
    pub cases: usize,
    /// Largest N of a random case.
    pub max_n: usize,
    /// Largest N of the scaling checks.
    pub scaling_max_n: usize,
    /// Seed of the random cases.
    pub seed: u64,
}

impl Budget {
    /// The budget a caller asks for (the command line's flags, Python's
    /// arguments): each field its [default](Budget::default) when not
    /// given, the sizes clamped to what the checks need (a random case
    /// has at least 1 particle, the checks across N go up to at least 8).
    pub fn asked(
        cases: Option<usize>,
        max_n: Option<usize>,
        scaling_max_n: Option<usize>,
        seed: Option<u64>,
    ) -> Budget {
        let d = Budget::default();
        Budget {
            cases: cases.unwrap_or(d.cases),
            max_n: max_n.unwrap_or(d.max_n).max(1),
            scaling_max_n: scaling_max_n.unwrap_or(d.scaling_max_n).max(8),
            seed: seed.unwrap_or(d.seed),
        }
    }
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            cases: 200,
            max_n: 24,
            scaling_max_n: 4096,
            seed: 0x5EED,
        }
    }
}
