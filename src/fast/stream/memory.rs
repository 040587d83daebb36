//! The memory a run on the streaming path needs, said before it reads the
//! data: from the particle count (the NPY header) or a bound on it (a CSV
//! file's size), and the limit it is held to.
//!
//! The path keeps two `i64` columns (16 bytes per particle), the segments
//! of the file being read on every core (`CHUNK_BYTES` together) and the
//! PAVA stack: one
//! run (`ΣY`, `ΣU`, size) per block, at most one per particle, touched only as blocks
//! form, twice (the halves' stacks, then the joined blocks). The projection charges the stack its worst case, so a file whose
//! projection passes the limit cannot exhaust the memory on this path.

use std::fmt;

use crate::fast::kernel::Run;

/// Bytes per particle of the two `i64` columns.
pub const COLUMN_BYTES: u64 = 16;

/// Bytes per PAVA block: one `Run` on `i128` sums in the stack of the half
/// of the entries that formed it ([`crate::fast::kernel`], both cores) and
/// one in the joined vector the state is read from.
pub const BLOCK_BYTES: u64 = 2 * std::mem::size_of::<Run<i128>>() as u64;

/// The environment variable that sets the limit, in MiB.
pub const LIMIT_VAR: &str = "STICKY_MAX_MEMORY";

/// The limit when the machine's memory cannot be read: 4 GiB.
const FALLBACK_LIMIT: u64 = 4 << 30;

/// The projected peak memory of a run on the streaming path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// The particle count, or (CSV) a bound on it.
    pub particles: u64,
    /// `true` when `particles` is the exact count (NPY header).
    pub exact_count: bool,
    /// The column file's size in bytes.
    pub file_bytes: u64,
    /// The `i64` columns.
    pub columns: u64,
    /// The read buffer.
    pub buffer: u64,
    /// The PAVA stack when every particle is its own block.
    pub stack_at_most: u64,
}

impl Footprint {
    /// The projection for `particles` particles read from a file of
    /// `file_bytes` bytes.
    pub fn new(particles: u64, exact_count: bool, file_bytes: u64) -> Footprint {
        Footprint {
            particles,
            exact_count,
            file_bytes,
            columns: particles.saturating_mul(COLUMN_BYTES),
            buffer: super::read::CHUNK_BYTES as u64,
            stack_at_most: particles.saturating_mul(BLOCK_BYTES),
        }
    }

    /// The peak: columns, buffer and the stack at its largest.
    pub fn peak(&self) -> u64 {
        self.columns
            .saturating_add(self.buffer)
            .saturating_add(self.stack_at_most)
    }
}

impl fmt::Display for Footprint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let count = if self.exact_count {
            format!("N = {}", self.particles)
        } else {
            format!("N ≤ {} (from the CSV size)", self.particles)
        };
        write!(
            f,
            "at most {} ({count}, file {}): i64 columns {} ({COLUMN_BYTES} B/particle), \
             read buffer {}, PAVA stack ≤ {} ({BLOCK_BYTES} B/block, one block per particle at worst)",
            mib(self.peak()),
            mib(self.file_bytes),
            mib(self.columns),
            mib(self.buffer),
            mib(self.stack_at_most),
        )
    }
}

/// `b` bytes in MiB, one decimal.
pub fn mib(b: u64) -> String {
    format!("{:.1} MiB", b as f64 / f64::from(1 << 20))
}

/// The limit a streaming run is held to, in bytes: `STICKY_MAX_MEMORY`
/// (MiB) when set, else three quarters of the machine's memory
/// (`MemTotal` of `/proc/meminfo`), else 4 GiB.
pub fn limit() -> u64 {
    if let Some(mib) = std::env::var(LIMIT_VAR)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
    {
        return mib.saturating_mul(1 << 20);
    }
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| mem_total(&text))
        .map_or(FALLBACK_LIMIT, |total| total / 4 * 3)
}

/// `MemTotal` of a `/proc/meminfo` text, in bytes.
fn mem_total(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib = line.split_whitespace().nth(1)?.parse::<u64>().ok()?;
    kib.checked_mul(1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_total_reads_the_line() {
        let text = "MemFree:  10 kB\nMemTotal:       24576000 kB\n";
        assert_eq!(mem_total(text), Some(24_576_000 * 1024));
        assert_eq!(mem_total("MemFree: 1 kB\n"), None);
    }

    #[test]
    fn the_peak_adds_columns_buffer_and_worst_stack() {
        let f = Footprint::new(100_000_000, true, 1_600_000_128);
        assert_eq!(f.columns, 1_600_000_000);
        assert_eq!(f.stack_at_most, 100_000_000 * BLOCK_BYTES);
        assert_eq!(
            f.peak(),
            1_600_000_000 + (4 << 20) + 100_000_000 * BLOCK_BYTES
        );
    }
}
