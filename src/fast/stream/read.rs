//! Column files read in chunks: the rows of a CSV or NPY particle file
//! ([`crate::columns`]) handed over one by one as [`Small`] pairs, with at
//! most [`CHUNK_BYTES`] of the file in memory at a time. A file can be read
//! as many times as a caller needs passes ([`ColumnFile::rows`]), so the
//! streaming path keeps only what it computes from the values, never the
//! file or the values themselves.

use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use crate::columns::{csv_header_small, csv_line_small, f64_small, npy_layout_of, CsvLine, Small};

/// The bytes of the file read at once (the reader's buffer).
pub(crate) const CHUNK_BYTES: usize = 4 << 20;

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

/// A particle file of a known kind, its layout checked (the NPY header) but
/// its values not yet read.
#[derive(Debug, Clone)]
pub(crate) struct ColumnFile {
    path: PathBuf,
    len: u64,
    layout: Layout,
    /// The bytes read at once ([`CHUNK_BYTES`]; smaller in the tests, to
    /// cross chunk boundaries).
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
            chunk: CHUNK_BYTES,
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

    /// Calls `f(x, u)` on every row in order, reading the file once in
    /// chunks; the number of rows, or `None` when the file cannot be read,
    /// a value is not [`Small`], the CSV text is not a valid particle file,
    /// or `f` answers `None`.
    pub(crate) fn rows(&self, mut f: impl FnMut(Small, Small) -> Option<()>) -> Option<usize> {
        match self.layout {
            Layout::Csv => self.csv_rows(&mut f),
            Layout::Npy { n, fortran, offset } => {
                self.npy_rows(n, fortran, offset, &mut f)?;
                Some(n)
            }
        }
    }

    fn csv_rows(&self, f: &mut dyn FnMut(Small, Small) -> Option<()>) -> Option<usize> {
        let mut reader = BufReader::with_capacity(self.chunk, File::open(&self.path).ok()?);
        let mut line = Vec::new();
        let mut header = false;
        let mut count = 0usize;
        loop {
            line.clear();
            if reader.read_until(b'\n', &mut line).ok()? == 0 {
                break;
            }
            // `str::lines`: drop the '\n' and one '\r' before it.
            let mut text = line.strip_suffix(b"\n").unwrap_or(&line);
            text = text.strip_suffix(b"\r").unwrap_or(text);
            if !header {
                if !text.is_ascii() {
                    return None;
                }
                if crate::columns::trim_ascii(text).is_empty() {
                    continue;
                }
                if !csv_header_small(text) {
                    return None;
                }
                header = true;
                continue;
            }
            if let CsvLine::Row(x, u) = csv_line_small(text)? {
                f(x, u)?;
                count += 1;
            }
        }
        header.then_some(count)
    }

    fn npy_rows(
        &self,
        n: usize,
        fortran: bool,
        offset: u64,
        f: &mut dyn FnMut(Small, Small) -> Option<()>,
    ) -> Option<()> {
        let value = |b: &[u8]| f64_small(f64::from_le_bytes(b.try_into().ok()?));
        if !fortran {
            let mut doubles = Doubles::at(&self.path, offset, 2 * n, self.chunk)?;
            while let Some(chunk) = doubles.next_chunk()? {
                for row in chunk.chunks_exact(16) {
                    f(value(&row[..8])?, value(&row[8..])?)?;
                }
            }
            return Some(());
        }
        // All the positions, then all the velocities: two cursors in step.
        let mut xs = Doubles::at(&self.path, offset, n, self.chunk)?;
        let mut us = Doubles::at(&self.path, offset + 8 * n as u64, n, self.chunk)?;
        let (mut xc, mut uc) = (Vec::new(), Vec::new());
        let (mut xi, mut ui) = (0usize, 0usize);
        for _ in 0..n {
            if xi == xc.len() {
                xc = xs.next_chunk()?.map(<[u8]>::to_vec)?;
                xi = 0;
            }
            if ui == uc.len() {
                uc = us.next_chunk()?.map(<[u8]>::to_vec)?;
                ui = 0;
            }
            f(value(&xc[xi..xi + 8])?, value(&uc[ui..ui + 8])?)?;
            xi += 8;
            ui += 8;
        }
        Some(())
    }
}

/// `count` doubles from byte `offset` of a file, in chunks of whole doubles.
struct Doubles {
    file: File,
    left: usize,
    buf: Vec<u8>,
}

impl Doubles {
    fn at(path: &Path, offset: u64, count: usize, chunk: usize) -> Option<Doubles> {
        let mut file = File::open(path).ok()?;
        file.seek(SeekFrom::Start(offset)).ok()?;
        Some(Doubles {
            file,
            left: count.checked_mul(8)?,
            buf: vec![0u8; chunk.min(count.saturating_mul(8))],
        })
    }

    /// The next chunk (`Some(None)` at the end; `None` on a read error or a
    /// file shorter than its header said).
    fn next_chunk(&mut self) -> Option<Option<&[u8]>> {
        if self.left == 0 {
            return Some(None);
        }
        let want = self.left.min(self.buf.len());
        let got = read_full(&mut self.file, &mut self.buf[..want]).ok()?;
        if got != want {
            return None;
        }
        self.left -= want;
        Some(Some(&self.buf[..want]))
    }
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
