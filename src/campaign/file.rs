//! A shard's file: JSON lines. The first line is the [`Header`] (which
//! campaign, its setup, which shard, how many units in all); each further
//! line is one unit's result, `{"unit": u, "result": …}`. [`merge`] reads
//! every shard's file of one campaign and returns the results in unit
//! order, refusing missing or duplicated shards, missing units, and files
//! of different campaigns or setups.

use std::collections::BTreeMap;
use std::fmt;
use std::io::{self, Write};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::Shard;

/// The first line of a shard's file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The campaign: `claims` or `prove`.
    pub campaign: String,
    /// Everything the results depend on (budget, limits, the solver's
    /// version, the scene): equal in every shard of one campaign.
    pub setup: Value,
    /// Which shard wrote the file.
    pub shard: Shard,
    /// The number of units of the whole campaign.
    pub units: usize,
}

/// One unit's line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitLine<R> {
    /// The unit's index in the campaign.
    pub unit: usize,
    /// Its result.
    pub result: R,
}

/// A shard's results: its lines, and the number of units of the whole
/// campaign (for the header).
#[derive(Debug, Clone, PartialEq)]
pub struct ShardLines<R> {
    /// Units of the whole campaign.
    pub units: usize,
    /// This shard's units, in order.
    pub lines: Vec<UnitLine<R>>,
}

/// Why shards' files do not merge.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum MergeError {
    /// No file given.
    NoFiles,
    /// A line is not the JSON expected there.
    Parse {
        /// The file's name.
        file: String,
        /// The line, from 1.
        line: usize,
        /// serde_json's message.
        message: String,
    },
    /// A file of another campaign, or the same campaign with another setup
    /// (budget, limits, solver, scene) or another shard count.
    Mixed {
        /// The file that differs from the first one.
        file: String,
        /// What differs.
        what: String,
    },
    /// Shards of the campaign that no file holds.
    MissingShards {
        /// Their indices, with the count: `1/4, 3/4`.
        shards: Vec<Shard>,
    },
    /// Two files of one shard.
    DuplicateShard {
        /// The shard.
        shard: Shard,
        /// The two files.
        files: [String; 2],
    },
    /// A unit of the shard missing from its file (a job stopped early).
    MissingUnits {
        /// The file.
        file: String,
        /// The first units missing.
        units: Vec<usize>,
    },
    /// A unit that is not the shard's, or given twice.
    StrayUnit {
        /// The file.
        file: String,
        /// The unit.
        unit: usize,
    },
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MergeError::NoFiles => write!(f, "no shard file given"),
            MergeError::Parse {
                file,
                line,
                message,
            } => write!(f, "{file}:{line}: not a shard's line: {message}"),
            MergeError::Mixed { file, what } => write!(
                f,
                "{file} is not a shard of the same campaign as the first file: {what}"
            ),
            MergeError::MissingShards { shards } => {
                let list: Vec<String> = shards.iter().map(Shard::to_string).collect();
                write!(
                    f,
                    "missing shard{}: {}",
                    plural(shards.len()),
                    list.join(", ")
                )
            }
            MergeError::DuplicateShard { shard, files } => write!(
                f,
                "shard {shard} given twice: {} and {}",
                files[0], files[1]
            ),
            MergeError::MissingUnits { file, units } => {
                let list: Vec<String> = units.iter().map(usize::to_string).collect();
                write!(
                    f,
                    "{file}: unit{} {} of the shard missing (did the job stop early?)",
                    plural(units.len()),
                    list.join(", ")
                )
            }
            MergeError::StrayUnit { file, unit } => write!(
                f,
                "{file}: unit {unit} is not this shard's or is given twice"
            ),
        }
    }
}

impl std::error::Error for MergeError {}

fn plural(k: usize) -> &'static str {
    if k == 1 {
        ""
    } else {
        "s"
    }
}

/// Writes a shard's file: the header, then one line per unit.
pub fn write<R: Serialize>(
    out: &mut impl Write,
    header: &Header,
    results: &[UnitLine<R>],
) -> io::Result<()> {
    debug_assert!(results.iter().all(|r| header.shard.owns(r.unit)));
    serde_json::to_writer(&mut *out, header)?;
    out.write_all(b"\n")?;
    for r in results {
        serde_json::to_writer(&mut *out, r)?;
        out.write_all(b"\n")?;
    }
    Ok(())
}

/// The header of a shard's file (its first line).
pub fn header(file: &str, text: &str) -> Result<Header, MergeError> {
    let line = text.lines().next().unwrap_or("");
    serde_json::from_str(line).map_err(|e| MergeError::Parse {
        file: file.to_string(),
        line: 1,
        message: e.to_string(),
    })
}

/// The merged campaign: its header's setup and every unit's result in
/// unit order.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged<R> {
    /// The campaign's name.
    pub campaign: String,
    /// Its setup.
    pub setup: Value,
    /// `results[u]` is unit `u`'s.
    pub results: Vec<R>,
}

/// Merges the files `(name, text)` of every shard of one campaign.
pub fn merge<R: DeserializeOwned>(files: &[(String, String)]) -> Result<Merged<R>, MergeError> {
    let Some((first_name, first_text)) = files.first() else {
        return Err(MergeError::NoFiles);
    };
    let first = header(first_name, first_text)?;
    let count = first.shard.count;
    let mut by_shard: BTreeMap<usize, &str> = BTreeMap::new();
    let mut results: Vec<Option<R>> = (0..first.units).map(|_| None).collect();
    for (name, text) in files {
        let h = header(name, text)?;
        let mixed = |what: String| MergeError::Mixed {
            file: name.clone(),
            what,
        };
        if h.campaign != first.campaign {
            return Err(mixed(format!(
                "campaign `{}`, not `{}`",
                h.campaign, first.campaign
            )));
        }
        if h.setup != first.setup {
            return Err(mixed(format!("setup {}, not {}", h.setup, first.setup)));
        }
        if h.shard.count != count || h.units != first.units {
            return Err(mixed(format!(
                "shard {} of {} units, not of {count} shards and {} units",
                h.shard, h.units, first.units
            )));
        }
        if let Some(other) = by_shard.insert(h.shard.index, name) {
            return Err(MergeError::DuplicateShard {
                shard: h.shard,
                files: [other.to_string(), name.clone()],
            });
        }
        for (k, line) in text.lines().enumerate().skip(1) {
            if line.trim().is_empty() {
                continue;
            }
            let u: UnitLine<R> = serde_json::from_str(line).map_err(|e| MergeError::Parse {
                file: name.clone(),
                line: k + 1,
                message: e.to_string(),
            })?;
            let stray = MergeError::StrayUnit {
                file: name.clone(),
                unit: u.unit,
            };
            if !h.shard.owns(u.unit) {
                return Err(stray);
            }
            match results.get_mut(u.unit) {
                Some(slot @ None) => *slot = Some(u.result),
                _ => return Err(stray),
            }
        }
        let missing: Vec<usize> = h
            .shard
            .units(first.units)
            .into_iter()
            .filter(|&u| results[u].is_none())
            .take(8)
            .collect();
        if !missing.is_empty() {
            return Err(MergeError::MissingUnits {
                file: name.clone(),
                units: missing,
            });
        }
    }
    let absent: Vec<Shard> = (0..count)
        .filter(|i| !by_shard.contains_key(i))
        .map(|index| Shard { index, count })
        .collect();
    if !absent.is_empty() {
        return Err(MergeError::MissingShards { shards: absent });
    }
    debug_assert!(results.iter().all(Option::is_some));
    Ok(Merged {
        campaign: first.campaign,
        setup: first.setup,
        results: results.into_iter().flatten().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shard_file(shard: Shard, setup: &str, units: usize, skip: Option<usize>) -> String {
        let header = Header {
            campaign: "test".into(),
            setup: Value::String(setup.into()),
            shard,
            units,
        };
        let lines: Vec<UnitLine<usize>> = shard
            .units(units)
            .into_iter()
            .filter(|&u| Some(u) != skip)
            .map(|u| UnitLine {
                unit: u,
                result: 10 * u,
            })
            .collect();
        let mut out = Vec::new();
        write(&mut out, &header, &lines).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn files(count: usize, setup: &str) -> Vec<(String, String)> {
        (0..count)
            .map(|index| {
                let s = Shard { index, count };
                (format!("s{index}"), shard_file(s, setup, 11, None))
            })
            .collect()
    }

    #[test]
    fn merges_in_unit_order_and_refuses_bad_sets() {
        let mut fs = files(3, "a");
        fs.reverse();
        let m: Merged<usize> = merge(&fs).unwrap();
        assert_eq!(m.results, (0..11).map(|u| 10 * u).collect::<Vec<_>>());
        // A missing shard.
        let err = merge::<usize>(&fs[..2]).unwrap_err();
        assert!(matches!(err, MergeError::MissingShards { .. }), "{err}");
        assert!(err.to_string().contains("missing shard: 0/3"), "{err}");
        // A duplicated one.
        let mut dup = fs.clone();
        dup.push(fs[0].clone());
        let err = merge::<usize>(&dup).unwrap_err();
        assert!(matches!(err, MergeError::DuplicateShard { .. }), "{err}");
        // Another setup (a budget).
        let mut mixed = fs.clone();
        mixed[1] = files(3, "b").swap_remove(1);
        let err = merge::<usize>(&mixed).unwrap_err();
        assert!(matches!(err, MergeError::Mixed { .. }), "{err}");
        // Shards of another count.
        let mut counts = fs.clone();
        counts[0] = files(4, "a").swap_remove(0);
        let err = merge::<usize>(&counts).unwrap_err();
        assert!(matches!(err, MergeError::Mixed { .. }), "{err}");
        // A unit missing from its shard's file.
        let mut short = fs.clone();
        short[0].1 = shard_file(Shard { index: 2, count: 3 }, "a", 11, Some(5));
        let err = merge::<usize>(&short).unwrap_err();
        assert_eq!(
            err,
            MergeError::MissingUnits {
                file: "s2".into(),
                units: vec![5]
            }
        );
        assert!(matches!(merge::<usize>(&[]), Err(MergeError::NoFiles)));
    }
}
