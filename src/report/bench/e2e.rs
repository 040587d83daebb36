//! `sticky bench --e2e`: what a user pays from file to answer to file
//! (issue 13, part 5). Each pipeline is a whole child process, timed from
//! spawn to exit, on one set of N particles written three ways:
//!
//! * **CSV**: `position,velocity` as 3-decimal strings (`x/1000`, radius
//!   `0.001`) behind a `[particles] data = "dec.csv"` scene, so that
//!   `numpy.loadtxt` reads the very file `sticky` reads;
//! * **NPY**: the same integers over 1024 (`x/1024`, radius `1/1024`), an
//!   `(N, 2)` `<f8` file every value of which is exactly a double, behind
//!   `data = "dyadic.npy"`;
//! * **TOML**: the CSV's strings inline (`positions = […]`,
//!   `velocities = […]`), the form of a hand-written scene.
//!
//! The pipelines: `sticky run SCENE --at 1 --json > FILE`,
//! `sticky run SCENE --at 1 --format npy --lossy > FILE` (CSV and NPY
//! input: the doubles scipy's NPY pipeline writes) and
//! `sticky events SCENE --json > FILE` on each input, and scipy's own
//! (`scripts/peers/e2e_scipy.py`): `numpy.loadtxt` → `isotonic_regression`
//! → `numpy.savetxt` on the CSV, `numpy.load` → … → `numpy.save` on the
//! NPY. A `sticky` row's ratio is to scipy's pipeline on the same input
//! (the TOML rows: to scipy's CSV pipeline, the same numbers in a text
//! file). The repetitions are interleaved (every pipeline once, then
//! again) and the median is reported.
//!
//! **Peak memory** is each child's own high-water mark of resident memory
//! (`VmHWM` of `/proc/self/status`, what `getrusage` calls `ru_maxrss`),
//! which the child writes at exit into the file named by [`PEAK_RSS_VAR`]:
//! the `sticky` binary does so when the variable is set
//! ([`write_peak_rss`]), and so does the Python helper. No polling, no
//! platform call: where `/proc` is missing the column stays empty.
//!
//! **The I/O floor** of a row is what the same bytes cost without any
//! work on them, measured in the same run right after each repetition of
//! the row, page cache warm: reading the row's input files whole
//! (the scene and its column file) and writing as many bytes as its answer
//! file holds into a fresh file at the same place ([`io_floor`]). A row's
//! `× floor` is its wall time over that floor (medians of each).
//!
//! When Python, numpy or scipy is missing, the scipy rows say why and the
//! `sticky` rows still run.

use crate::json::Fixed;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

use crate::columns::write_npy;
use crate::generate::SplitMix64;

/// The environment variable naming the file into which a child process
/// of the end-to-end bench writes its peak resident memory (kB) at exit.
pub const PEAK_RSS_VAR: &str = "STICKY_PEAK_RSS_FILE";

/// Writes this process's peak resident memory (`VmHWM`, kB) into `path`;
/// the `sticky` binary calls it at exit when [`PEAK_RSS_VAR`] is set.
pub fn write_peak_rss(path: &Path) -> std::io::Result<()> {
    let text = std::fs::read_to_string("/proc/self/status")?;
    let kib = text
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.split_whitespace().next())
        .ok_or_else(|| std::io::Error::other("no VmHWM in /proc/self/status"))?;
    std::fs::write(path, format!("{kib}\n"))
}

/// The input format of a pipeline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Input {
    /// A scene with the columns inline.
    Toml,
    /// A scene naming a CSV column file (the file scipy reads).
    Csv,
    /// A scene naming an NPY column file (the file scipy reads).
    Npy,
}

impl Input {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Input::Toml => "toml",
            Input::Csv => "csv",
            Input::Npy => "npy",
        }
    }
}

/// Who runs a pipeline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tool {
    /// `sticky run SCENE --at 1 --json`.
    Run,
    /// `sticky run SCENE --at 1 --format npy --lossy`: the state as an
    /// `(1, N, 3)` `<f8` array.
    RunNpy,
    /// `sticky events SCENE --json`.
    Events,
    /// `scripts/peers/e2e_scipy.py` (CSV or NPY only).
    Scipy,
}

impl Tool {
    /// The row's name.
    pub fn name(self) -> &'static str {
        match self {
            Tool::Run => "sticky run --at 1 --json",
            Tool::RunNpy => "sticky run --format npy",
            Tool::Events => "sticky events --json",
            Tool::Scipy => "scipy pipeline",
        }
    }
}

/// The pipelines, in the order of the table.
pub const PIPELINES: [(Tool, Input); 10] = [
    (Tool::Scipy, Input::Csv),
    (Tool::Run, Input::Csv),
    (Tool::RunNpy, Input::Csv),
    (Tool::Events, Input::Csv),
    (Tool::Scipy, Input::Npy),
    (Tool::Run, Input::Npy),
    (Tool::RunNpy, Input::Npy),
    (Tool::Events, Input::Npy),
    (Tool::Run, Input::Toml),
    (Tool::Events, Input::Toml),
];

/// What `sticky bench --e2e` measures.
#[derive(Debug, Clone)]
pub struct E2eOptions {
    /// Number of particles.
    pub n: usize,
    /// Repetitions (interleaved; the median is reported).
    pub reps: usize,
    /// Run scipy's pipelines or not.
    pub peers: super::Peers,
    /// The `sticky` binary.
    pub sticky: PathBuf,
    /// The folder holding the peers' drivers (the repository's `scripts/`,
    /// with `scripts/peers/e2e_scipy.py`).
    pub scripts: PathBuf,
}

/// One measured pipeline.
#[derive(Debug, Clone)]
pub struct E2eRow {
    /// Who ran it.
    pub tool: Tool,
    /// On which input.
    pub input: Input,
    /// Median wall time of the whole process, seconds (`None`: not run or
    /// failed, see the note).
    pub wall_s: Option<f64>,
    /// Median peak resident memory of the process, kB (`None`: not
    /// reported).
    pub peak_kib: Option<f64>,
    /// Size of the answer file of the last run, bytes.
    pub out_bytes: Option<u64>,
    /// Median I/O floor for the same bytes, seconds ([`io_floor`]; `None`:
    /// the row was not measured).
    pub floor_s: Option<f64>,
    /// Input and output sizes, or why the row is empty.
    pub note: String,
}

/// The end-to-end report.
#[derive(Debug, Clone)]
pub struct E2eReport {
    /// N.
    pub n: usize,
    /// The rows, in [`PIPELINES`] order.
    pub rows: Vec<E2eRow>,
}

impl E2eReport {
    /// The row of `tool` on `input`.
    pub fn row(&self, tool: Tool, input: Input) -> Option<&E2eRow> {
        self.rows
            .iter()
            .find(|r| r.tool == tool && r.input == input)
    }

    /// The wall time of `row` over scipy's on the same input (the TOML
    /// rows: over scipy's CSV pipeline, the same numbers).
    pub fn vs_scipy(&self, row: &E2eRow) -> Option<f64> {
        if row.tool == Tool::Scipy {
            return None;
        }
        let base = match row.input {
            Input::Npy => Input::Npy,
            Input::Csv | Input::Toml => Input::Csv,
        };
        let b = self.row(Tool::Scipy, base)?.wall_s?;
        let w = row.wall_s?;
        (b > 0.0).then(|| w / b)
    }

    /// The wall time of `row` over its I/O floor ([`io_floor`]).
    pub fn vs_floor(&self, row: &E2eRow) -> Option<f64> {
        let (w, f) = (row.wall_s?, row.floor_s?);
        (f > 0.0).then(|| w / f)
    }

    /// Peak memory per particle, bytes.
    pub fn bytes_per_particle(&self, row: &E2eRow) -> Option<f64> {
        row.peak_kib.map(|k| k * 1024.0 / self.n.max(1) as f64)
    }
}

/// The inputs, written into `dir`: the scenes (`dec.toml`, `dyadic.toml`,
/// `inline.toml`) and the column files scipy reads (`dec.csv`,
/// `dyadic.npy`). Integer data from `seed`: gaps `2 + g` with `g` in
/// `{0, 0, 0, 1, 2, 5, 10, 40}` (a contact when `g = 0`), velocities in
/// `{−5000, …, 5000}`, raised across a contact to stay in the velocity cone
/// (`def:velcone`); positions over 1000 (CSV, TOML) or 1024 (NPY), `2r` two
/// units.
pub fn write_inputs(dir: &Path, n: usize, seed: u64) -> std::io::Result<()> {
    let mut rng = SplitMix64::new(seed);
    let mut xs = Vec::with_capacity(n);
    let mut us = Vec::with_capacity(n);
    let (mut x, mut prev, mut contact) = (0i64, 0i64, false);
    for _ in 0..n {
        let r = rng.next_u64();
        let mut u = (r % 10_001) as i64 - 5000;
        if contact {
            u = u.max(prev);
        }
        xs.push(x);
        us.push(u);
        let g = [0, 0, 0, 1, 2, 5, 10, 40][((r >> 32) % 8) as usize];
        contact = g == 0;
        x += 2 + g;
        prev = u;
    }
    let milli = |v: i64| {
        let sign = if v < 0 { "-" } else { "" };
        format!("{sign}{}.{:03}", v.abs() / 1000, v.abs() % 1000)
    };
    let mut csv = String::with_capacity(20 * n + 20);
    csv.push_str("position,velocity\n");
    for (x, u) in xs.iter().zip(&us) {
        csv.push_str(&milli(*x));
        csv.push(',');
        csv.push_str(&milli(*u));
        csv.push('\n');
    }
    std::fs::write(dir.join("dec.csv"), csv)?;
    std::fs::write(
        dir.join("dec.toml"),
        "[particles]\nradius = \"0.001\"\ndata = \"dec.csv\"\n",
    )?;
    let quoted = |v: &[i64]| {
        v.iter()
            .map(|&a| format!("\"{}\"", milli(a)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    std::fs::write(
        dir.join("inline.toml"),
        format!(
            "[particles]\nradius = \"0.001\"\npositions = [{}]\nvelocities = [{}]\n",
            quoted(&xs),
            quoted(&us)
        ),
    )?;
    let rows: Vec<(f64, f64)> = xs
        .iter()
        .zip(&us)
        .map(|(&x, &u)| (x as f64 / 1024.0, u as f64 / 1024.0))
        .collect();
    std::fs::write(dir.join("dyadic.npy"), write_npy(&rows))?;
    std::fs::write(
        dir.join("dyadic.toml"),
        "[particles]\nradius = \"1/1024\"\ndata = \"dyadic.npy\"\n",
    )
}

/// The I/O floor of a pipeline, in seconds: reading every file of
/// `inputs` whole, then writing `out_bytes` bytes into a new file `out`
/// (created or truncated, as the child's answer file is), the buffer to
/// write filled before the clock starts. The file is left in place (the
/// caller removes it), `out_bytes` long.
pub fn io_floor(inputs: &[PathBuf], out: &Path, out_bytes: u64) -> Result<f64, String> {
    let len = usize::try_from(out_bytes).map_err(|e| format!("{out_bytes} bytes: {e}"))?;
    let answer = vec![b'0'; len];
    let t0 = Instant::now();
    let mut read = 0usize;
    for path in inputs {
        read += std::fs::read(path)
            .map_err(|e| format!("{}: {e}", path.display()))?
            .len();
    }
    let mut file = File::create(out).map_err(|e| format!("{}: {e}", out.display()))?;
    file.write_all(&answer)
        .map_err(|e| format!("{}: {e}", out.display()))?;
    drop(file);
    let wall = t0.elapsed().as_secs_f64();
    debug_assert!(read > 0 || inputs.is_empty());
    Ok(wall)
}

/// One run of a child: wall seconds and peak kB, or why it failed.
fn run_child(mut cmd: Command, dir: &Path, out: &Path) -> Result<(f64, Option<f64>), String> {
    let peak = dir.join("peak");
    let err = dir.join("stderr");
    let _ = std::fs::remove_file(&peak);
    let stderr = File::create(&err).map_err(|e| e.to_string())?;
    let stdout = File::create(out).map_err(|e| e.to_string())?;
    cmd.env(PEAK_RSS_VAR, &peak)
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr);
    let t0 = Instant::now();
    let status = cmd.status().map_err(|e| format!("cannot start: {e}"))?;
    let wall = t0.elapsed().as_secs_f64();
    if !status.success() {
        let text = std::fs::read_to_string(&err).unwrap_or_default();
        let last = text.lines().rev().find(|l| !l.trim().is_empty());
        return Err(format!("failed ({status}): {}", last.unwrap_or("")));
    }
    let kib = std::fs::read_to_string(&peak)
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok());
    Ok((wall, kib))
}

/// The median (the mean of the two middle values for an even count).
fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    match v.len() {
        0 => None,
        k if k % 2 == 0 => Some((v[m - 1] + v[m]) / 2.0),
        _ => Some(v[m]),
    }
}

fn mib(bytes: u64) -> String {
    if bytes < 1 << 20 {
        format!("{:.1} KiB", bytes as f64 / 1024.0)
    } else {
        format!("{:.1} MiB", bytes as f64 / (1024.0 * 1024.0))
    }
}

/// Runs every pipeline of [`PIPELINES`] `reps` times, interleaved, in a
/// fresh temporary folder (removed at the end); `progress` is told each
/// pipeline as it starts.
pub fn run(opts: &E2eOptions, mut progress: impl FnMut(&str)) -> Result<E2eReport, String> {
    let n = opts.n.max(1);
    let dir = std::env::temp_dir().join(format!("sticky-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let result = measure(opts, n, &dir, &mut progress);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn measure(
    opts: &E2eOptions,
    n: usize,
    dir: &Path,
    progress: &mut impl FnMut(&str),
) -> Result<E2eReport, String> {
    progress(&format!("writing the inputs (N = {n})"));
    write_inputs(dir, n, 7).map_err(|e| format!("{}: {e}", dir.display()))?;
    let size = |name: &str| std::fs::metadata(dir.join(name)).map_or(0, |m| m.len());
    let input_note = |input: Input| match input {
        Input::Csv => format!("dec.csv {}", mib(size("dec.csv"))),
        Input::Npy => format!("dyadic.npy {}", mib(size("dyadic.npy"))),
        Input::Toml => format!("inline.toml {}", mib(size("inline.toml"))),
    };
    let script = opts.scripts.join("peers").join("e2e_scipy.py");
    let mut walls: Vec<Vec<f64>> = vec![Vec::new(); PIPELINES.len()];
    let mut peaks: Vec<Vec<f64>> = vec![Vec::new(); PIPELINES.len()];
    let mut notes: Vec<Option<String>> = vec![None; PIPELINES.len()];
    let mut out_bytes: Vec<Option<u64>> = vec![None; PIPELINES.len()];
    let mut floors: Vec<Vec<f64>> = vec![Vec::new(); PIPELINES.len()];
    // Skipped, or failed once: not run again.
    let mut stopped = [false; PIPELINES.len()];
    for rep in 0..opts.reps.max(1) {
        for (k, &(tool, input)) in PIPELINES.iter().enumerate() {
            if stopped[k] {
                continue;
            }
            let (scene, columns) = match input {
                Input::Csv => ("dec.toml", "dec.csv"),
                Input::Npy => ("dyadic.toml", "dyadic.npy"),
                Input::Toml => ("inline.toml", "dec.csv"),
            };
            let out = dir.join(format!("out.{}", input.name()));
            let inputs: Vec<PathBuf> = match input {
                Input::Toml => vec![dir.join(scene)],
                Input::Csv | Input::Npy => vec![dir.join(scene), dir.join(columns)],
            };
            let cmd = match tool {
                Tool::Scipy if opts.peers == super::Peers::Skip => {
                    notes[k] = Some("skipped (--no-peers)".into());
                    stopped[k] = true;
                    continue;
                }
                Tool::Scipy => {
                    let mut c = Command::new("python3");
                    let two_r = if input == Input::Npy {
                        "1/512"
                    } else {
                        "0.002"
                    };
                    c.arg(&script)
                        .args([input.name()])
                        .arg(dir.join(columns))
                        .arg(&out)
                        .args(["--t", "1", "--two-r", two_r]);
                    c
                }
                Tool::Run | Tool::RunNpy | Tool::Events => {
                    let mut c = Command::new(&opts.sticky);
                    match tool {
                        Tool::Events => c.arg("events").arg(dir.join(scene)).arg("--json"),
                        Tool::RunNpy => c
                            .arg("run")
                            .arg(dir.join(scene))
                            .args(["--at", "1", "--format", "npy", "--lossy"]),
                        _ => c
                            .arg("run")
                            .arg(dir.join(scene))
                            .args(["--at", "1", "--json"]),
                    };
                    c
                }
            };
            progress(&format!(
                "{} on {} ({}/{})",
                tool.name(),
                input.name(),
                rep + 1,
                opts.reps.max(1)
            ));
            match run_child(cmd, dir, &out) {
                Ok((wall, kib)) => {
                    walls[k].push(wall);
                    peaks[k].extend(kib);
                    let bytes = std::fs::metadata(&out).map_or(0, |m| m.len());
                    out_bytes[k] = Some(bytes);
                    notes[k] = Some(format!("in {}, out {}", input_note(input), mib(bytes)));
                    // The same bytes, no work, right after (page cache warm).
                    match io_floor(&inputs, &out, bytes) {
                        Ok(f) => floors[k].push(f),
                        Err(why) => notes[k] = Some(format!("no floor: {why}")),
                    }
                }
                Err(why) => {
                    notes[k] = Some(why);
                    out_bytes[k] = None;
                    stopped[k] = true;
                    walls[k].clear();
                    peaks[k].clear();
                    floors[k].clear();
                }
            }
            let _ = std::fs::remove_file(&out);
        }
    }
    let rows = PIPELINES
        .iter()
        .enumerate()
        .map(|(k, &(tool, input))| E2eRow {
            tool,
            input,
            wall_s: median(std::mem::take(&mut walls[k])),
            peak_kib: median(std::mem::take(&mut peaks[k])),
            out_bytes: out_bytes[k],
            floor_s: median(std::mem::take(&mut floors[k])),
            note: notes[k].take().unwrap_or_default(),
        })
        .collect();
    Ok(E2eReport { n, rows })
}

/// The table: wall time, ratio to scipy on the same input, the I/O floor
/// and the ratio to it, peak memory and bytes per particle.
pub fn table(r: &E2eReport) -> String {
    let mut out = format!(
        "N = {}, file -> answer -> file, whole processes (median); floor: read the input + write the answer's bytes\n  {:<26} {:>5} {:>8} {:>10} {:>8} {:>8} {:>9} {:>10}  note\n",
        r.n, "pipeline", "input", "wall s", "× scipy", "floor s", "× floor", "peak MiB", "B/particle"
    );
    let f = |v: Option<f64>, d: usize| v.map_or("—".into(), |x| format!("{x:.d$}"));
    for row in &r.rows {
        out.push_str(&format!(
            "  {:<26} {:>5} {:>8} {:>10} {:>8} {:>8} {:>9} {:>10}  {}\n",
            row.tool.name(),
            row.input.name(),
            f(row.wall_s, 2),
            f(r.vs_scipy(row), 2),
            f(row.floor_s, 3),
            f(r.vs_floor(row), 1),
            f(row.peak_kib.map(|k| k / 1024.0), 0),
            f(r.bytes_per_particle(row), 0),
            row.note
        ));
    }
    out
}

/// `sticky bench --e2e --json`: one object.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct E2eJson {
    /// N.
    pub n: usize,
    /// One row per pipeline and input.
    pub e2e: Vec<E2eRowJson>,
}

/// One pipeline on one input.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct E2eRowJson {
    /// The pipeline's name.
    pub pipeline: &'static str,
    /// The input's name.
    pub input: &'static str,
    /// Wall-clock seconds (`null`: not measured).
    pub wall_s: Option<Fixed<4>>,
    /// Its ratio to the SciPy pipeline.
    pub vs_scipy: Option<Fixed<4>>,
    /// The I/O floor of the same bytes, seconds (`null`: not measured).
    pub floor_s: Option<Fixed<4>>,
    /// Its ratio to the I/O floor.
    pub vs_floor: Option<Fixed<4>>,
    /// Peak resident bytes per particle.
    pub peak_bytes_per_particle: Option<Fixed<4>>,
    /// A remark.
    pub note: String,
}

/// [`E2eJson`] as one line.
pub fn json(r: &E2eReport) -> String {
    let e2e = r
        .rows
        .iter()
        .map(|row| E2eRowJson {
            pipeline: row.tool.name(),
            input: row.input.name(),
            wall_s: row.wall_s.map(Fixed),
            vs_scipy: r.vs_scipy(row).map(Fixed),
            floor_s: row.floor_s.map(Fixed),
            vs_floor: r.vs_floor(row).map(Fixed),
            peak_bytes_per_particle: r.bytes_per_particle(row).map(Fixed),
            note: row.note.clone(),
        })
        .collect();
    crate::json::to_string(&E2eJson { n: r.n, e2e })
}
