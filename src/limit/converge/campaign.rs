//! `sticky converge` as a campaign (issue 38, item 3): one unit per N (and
//! one for the engine check), each unit's [`super::UnitResult`] written by its
//! shard, and the single run's report built from them by the merge
//! ([`ConvergeSetup::study`], then [`Study::report`]).

use serde::{Deserialize, Serialize};

use super::{ConvergeOptions, Study};
use crate::error::Error;
use crate::scene;

/// Everything the study depends on: equal in every shard of one campaign.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ConvergeSetup {
    /// The `[macro]` scene's TOML text (the merge sets the study up from it).
    pub scene: String,
    /// Largest N.
    pub n_max: usize,
    /// Largest N computed exactly.
    pub exact_max: usize,
}

impl ConvergeSetup {
    /// The options of the study (those of `sticky converge`).
    pub fn options(&self) -> ConvergeOptions {
        ConvergeOptions {
            n_max: self.n_max.max(8),
            exact_max: self.exact_max,
            ..ConvergeOptions::default()
        }
    }

    /// The study set up from the scene's text.
    pub fn study(&self) -> Result<Study, Error> {
        Study::new(&scene::parse(&self.scene)?, &self.options())
    }
}
