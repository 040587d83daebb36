//! `I/N`: the share of a campaign's units that one job runs.

use std::fmt;
use std::str::FromStr;

/// Shard `index` of `count`: it runs the units `u` with
/// `u mod count = index`. Round robin rather than contiguous ranges, since
/// neighbouring units tend to cost alike (the same claim at the next case,
/// the next N), so every shard gets a like share of cheap and dear ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct Shard {
    /// `I`, from 0.
    pub index: usize,
    /// `N`, at least 1.
    pub count: usize,
}

/// Why a text is not a shard `I/N`.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShardError {
    /// Not two integers around one `/`.
    Syntax {
        /// The text given.
        text: String,
    },
    /// `N = 0`: no shard at all.
    NoShards,
    /// `I ≥ N` (shards count from 0).
    OutOfRange {
        /// `I`.
        index: usize,
        /// `N`.
        count: usize,
    },
}

impl fmt::Display for ShardError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShardError::Syntax { text } => write!(
                f,
                "shard {text:?} is not I/N (two integers, for example 0/4)"
            ),
            ShardError::NoShards => write!(f, "shard count 0: N must be at least 1"),
            ShardError::OutOfRange { index, count } => write!(
                f,
                "shard {index}/{count}: shards count from 0, so I must be below N (0/{count} … {}/{count})",
                count - 1
            ),
        }
    }
}

impl std::error::Error for ShardError {}

impl Shard {
    /// The whole campaign: shard `0/1`.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Shard `index/count`, checked.
    pub fn new(index: usize, count: usize) -> Result<Shard, ShardError> {
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if index >= count {
            return Err(ShardError::OutOfRange { index, count });
        }
        Ok(Shard { index, count })
    }

    /// Whether unit `unit` is this shard's.
    pub fn owns(self, unit: usize) -> bool {
        debug_assert!(self.index < self.count);
        unit % self.count == self.index
    }

    /// This shard's units among `0 … units − 1`, in order.
    pub fn units(self, units: usize) -> Vec<usize> {
        (0..units).filter(|&u| self.owns(u)).collect()
    }
}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Shard, ShardError> {
        let syntax = || ShardError::Syntax {
            text: text.to_string(),
        };
        let (i, n) = text.trim().split_once('/').ok_or_else(syntax)?;
        let number = |s: &str| -> Result<usize, ShardError> {
            if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
                return Err(syntax());
            }
            s.parse().map_err(|_| syntax())
        };
        Shard::new(number(i)?, number(n)?)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_refuses() {
        assert_eq!("3/4".parse(), Ok(Shard { index: 3, count: 4 }));
        assert_eq!("0/1".parse(), Ok(Shard::WHOLE));
        assert_eq!(
            "4/4".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 4, count: 4 })
        );
        assert_eq!("0/0".parse::<Shard>(), Err(ShardError::NoShards));
        for bad in ["", "3", "a/4", "-1/4", "1/+4", "1/4/5", "/4", "1/"] {
            assert!(
                matches!(bad.parse::<Shard>(), Err(ShardError::Syntax { .. })),
                "{bad}"
            );
        }
        let message = "4/4".parse::<Shard>().unwrap_err().to_string();
        assert!(message.contains("below N"), "{message}");
    }

    #[test]
    fn shards_partition_the_units() {
        for count in 1..7 {
            let mut seen = vec![0; 23];
            for index in 0..count {
                for u in (Shard { index, count }).units(23) {
                    seen[u] += 1;
                }
            }
            assert!(seen.iter().all(|&k| k == 1), "{count}: {seen:?}");
        }
    }
}
