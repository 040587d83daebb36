//! Column files read in segments: the rows of a CSV or NPY particle file
//! ([`crate::columns`]) cut into [`Segment`]s of whole rows, each read on
//! its own ([`ColumnFile::rows_of`], on any thread) and its rows handed
//! over one by one as [`Small`] pairs. A file can be read as many times as
//! a caller needs passes, so the streaming path keeps only what it
//! computes from the values, never the file or the values themselves; the
//! segments in memory at once hold at most [`CHUNK_BYTES`] together
//! ([`segment_bytes`]).

use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use crate::columns::{csv_header_small, f64_small, npy_layout_of, Small};

/// The bytes of the file in memory at once, over every thread: the read
/// buffers and what the segments being read give (at most 16 bytes per
/// row, a CSV row taking at least 4).
pub(crate) const CHUNK_BYTES: usize = 4 << 20;

/// The bytes of one segment, with `workers` threads reading: each of them
/// holds one segment being read and at most [`crate::parallel`]'s two
/// results ahead (16 bytes per row of at least 4 bytes): `16 · workers`
/// segments within [`CHUNK_BYTES`].
pub(crate) fn segment_bytes(workers: usize) -> usize {
    (CHUNK_BYTES / (16 * workers.max(1))).max(1 << 12) / 16 * 16
}

/// The bytes read at once when looking for the end of a line.
const LINE_PROBE: usize = 4096;

/// Longest `.npy` header read (NumPy writes less than a hundred bytes; a
/// longer one is left to the general path, which names what is wrong).
const MAX_NPY_HEADER: usize = 1 << 20;

/// How the values lie in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// CSV text: a header line, then one row per particle.
    Csv,
    /// `.npy` doubles from byte `offset` on: `n` rows `x, u` (C order), or
    /// all the positions then all the velocities (Fortran order).
    Npy {
        n: usize,
        fortran: bool,
        offset: u64,
    },
}

/// A stretch of whole rows of a column file, read apart from the others
/// ([`ColumnFile::segments`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Segment {
    /// CSV: the whole lines in bytes `start..end` (after the header).
    Lines { start: u64, end: u64 },
    /// NPY: the rows `first..end`.
    Rows { first: usize, end: usize },
}

/// A particle file of a known kind, its layout checked (the NPY header) but
/// its values not yet read.
#[derive(Debug, Clone)]
pub(crate) struct ColumnFile {
    path: PathBuf,
    len: u64,
    layout: Layout,
    /// The bytes of a segment ([`segment_bytes`]; smaller in the tests,
    /// to cut the file at many places).
    chunk: usize,
}

impl ColumnFile {
    /// The file at `path` when its extension is `csv` or `npy` and (NPY) its
    /// header is valid; `None` otherwise.
    pub(crate) fn open(path: &Path) -> Option<ColumnFile> {
        let len = std::fs::metadata(path).ok()?.len();
        let layout = match path.extension().and_then(|e| e.to_str()) {
            Some("csv") => Layout::Csv,
            Some("npy") => {
                let mut f = File::open(path).ok()?;
                let mut head = [0u8; 12];
                let got = f.read(&mut head).ok()?;
                let header_len = match head[..got] {
                    [_, _, _, _, _, _, 1, _, a, b, ..] => usize::from(u16::from_le_bytes([a, b])),
                    [_, _, _, _, _, _, 2 | 3, _, a, b, c, d] => {
                        u32::from_le_bytes([a, b, c, d]) as usize
                    }
                    _ => return None,
                };
                if header_len > MAX_NPY_HEADER {
                    return None;
                }
                let mut head = vec![0u8; 12 + header_len];
                f.seek(SeekFrom::Start(0)).ok()?;
                let got = read_full(&mut f, &mut head).ok()?;
                let (n, fortran, offset) = npy_layout_of(&head[..got], len).ok()?;
                Layout::Npy {
                    n,
                    fortran,
                    offset: offset as u64,
                }
            }
            _ => return None,
        };
        Some(ColumnFile {
            path: path.to_path_buf(),
            len,
            layout,
            chunk: segment_bytes(crate::parallel::workers()),
        })
    }

    /// The same file read `chunk` bytes at a time (a positive multiple of 16).
    #[cfg(test)]
    pub(crate) fn with_chunk(mut self, chunk: usize) -> ColumnFile {
        debug_assert!(chunk > 0 && chunk % 16 == 0);
        self.chunk = chunk;
        self
    }

    /// The file's length in bytes.
    pub(crate) fn len(&self) -> u64 {
        self.len
    }

    /// `true` when the header gives the number of rows (NPY).
    pub(crate) fn exact_count(&self) -> bool {
        matches!(self.layout, Layout::Npy { .. })
    }

    /// The number of rows, when the header gives it (NPY); an upper bound
    /// for a CSV file (a row takes at least 4 bytes: `a,b` and a newline).
    pub(crate) fn rows_at_most(&self) -> u64 {
        match self.layout {
            Layout::Npy { n, .. } => n as u64,
            Layout::Csv => self.len / 4,
        }
    }

    /// The file cut into segments of about `chunk` bytes, in order:
    /// together they hold every row once. `None` when the file cannot be
    /// read or (CSV) has no valid header line.
    pub(crate) fn segments(&self) -> Option<Vec<Segment>> {
        match self.layout {
            Layout::Csv => self.csv_segments(),
            Layout::Npy { n, .. } => {
                let rows = (self.chunk / 16).max(1);
                let cut = |first| Segment::Rows {
                    first,
                    end: (first + rows).min(n),
                };
                Some((0..n).step_by(rows).map(cut).collect())
            }
        }
    }

    /// The CSV body after its header line, cut after a `'\n'` every
    /// `chunk` bytes or so.
    fn csv_segments(&self) -> Option<Vec<Segment>> {
        let mut file = File::open(&self.path).ok()?;
        let mut at = self.csv_body(&mut file)?;
        let mut segments = Vec::new();
        while at < self.len {
            let nominal = at.saturating_add(self.chunk as u64);
            let end = if nominal >= self.len {
                self.len
            } else {
                // After the first '\n' at `nominal - 1` or later.
                line_end(&mut file, nominal - 1, self.len)?
            };
            debug_assert!(end > at);
            segments.push(Segment::Lines { start: at, end });
            at = end;
        }
        Some(segments)
    }

    /// Where the rows of a CSV file start: after its header line (blank
    /// lines before it allowed); `None` when there is none or the text
    /// before it is not ASCII.
    fn csv_body(&self, file: &mut File) -> Option<u64> {
        let mut reader = BufReader::with_capacity(LINE_PROBE, file);
        let mut line = Vec::new();
        let mut at = 0u64;
        loop {
            line.clear();
            let got = reader.read_until(b'\n', &mut line).ok()?;
            if got == 0 {
                return None;
            }
            at += got as u64;
            // `str::lines`: drop the '\n' and one '\r' before it.
            let mut text = line.strip_suffix(b"\n").unwrap_or(&line);
            text = text.strip_suffix(b"\r").unwrap_or(text);
            if !text.is_ascii() {
                return None;
            }
            if crate::columns::trim_ascii(text).is_empty() {
                continue;
            }
            return csv_header_small(text).then_some(at);
        }
    }

    /// Calls `f(x, u)` on every row of `segment` in order; the number of
    /// rows, or `None` when the file cannot be read, a value is not
    /// [`Small`], the CSV text is not a valid particle file, or `f`
    /// answers `None`.
    pub(crate) fn rows_of(
        &self,
        segment: &Segment,
        mut f: impl FnMut(Small, Small) -> Option<()>,
    ) -> Option<usize> {
        match (*segment, self.layout) {
            (Segment::Lines { start, end }, Layout::Csv) => {
                let mut file = File::open(&self.path).ok()?;
                let text = read_at(&mut file, start, usize::try_from(end - start).ok()?)?;
                super::csv::rows(&text, &mut f)
            }
            (Segment::Rows { first, end }, Layout::Npy { fortran, offset, n }) => {
                let value = |b: &[u8]| f64_small(f64::from_le_bytes(b.try_into().ok()?));
                let mut file = File::open(&self.path).ok()?;
                let rows = end.checked_sub(first)?;
                if !fortran {
                    let at = offset + 16 * first as u64;
                    let bytes = read_at(&mut file, at, rows.checked_mul(16)?)?;
                    for row in bytes.chunks_exact(16) {
                        f(value(&row[..8])?, value(&row[8..])?)?;
                    }
                } else {
                    // All the positions, then all the velocities.
                    let xs = read_at(&mut file, offset + 8 * first as u64, rows * 8)?;
                    let at = offset + 8 * (n + first) as u64;
                    let us = read_at(&mut file, at, rows * 8)?;
                    for (x, u) in xs.chunks_exact(8).zip(us.chunks_exact(8)) {
                        f(value(x)?, value(u)?)?;
                    }
                }
                Some(rows)
            }
            _ => None,
        }
    }
}

/// The `len` bytes of `file` from byte `at`; `None` on a read error or a
/// file shorter than that.
fn read_at(file: &mut File, at: u64, len: usize) -> Option<Vec<u8>> {
    file.seek(SeekFrom::Start(at)).ok()?;
    let mut buf = vec![0u8; len];
    (read_full(file, &mut buf).ok()? == len).then_some(buf)
}

/// The position just after the first `'\n'` of `file` at `from` or later
/// (`len`, the file's length, when there is none).
fn line_end(file: &mut File, from: u64, len: u64) -> Option<u64> {
    let mut at = from;
    let mut buf = vec![0u8; LINE_PROBE];
    file.seek(SeekFrom::Start(at)).ok()?;
    while at < len {
        let got = read_full(file, &mut buf).ok()?;
        if got == 0 {
            return None;
        }
        if let Some(k) = buf[..got].iter().position(|&b| b == b'\n') {
            return Some(at + k as u64 + 1);
        }
        at += got as u64;
    }
    Some(len)
}

/// Reads until `buf` is full or the file ends; the bytes read.
fn read_full(file: &mut File, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match file.read(&mut buf[got..])? {
            0 => break,
            k => got += k,
        }
    }
    Ok(got)
}
