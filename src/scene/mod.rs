//! Scene files (TOML), docs/guide/scenes.md.
//!
//! A scene is one TOML document:
//!
//! ```toml
//! name = "two-blocks"                      # optional string
//! description = "Appendix C: two blocks"   # optional string
//! t_end = "2"                              # optional exact number ≥ 0
//!
//! [particles]                              # either this table ...
//! radius = "1/16"                          # optional, default 1/(2N)
//! positions  = ["0", "1/8", "1/2", "5/8"]  # x_{i+1} − x_i ≥ 2r (df:KN)
//! velocities = ["1", "1", "-1", "-1"]      # u_{i+1} ≥ u_i across contacts (def:velcone)
//! ```
//!
//! Big scenes keep their columns in a file beside the TOML:
//! `data = "particles.csv"` (header `position,velocity`, exact strings) or
//! `data = "particles.npy"` (`f64`, shape `(N, 2)`, every double read exactly)
//! instead of `positions`/`velocities` ([`crate::columns`]; read by [`load`]
//! or [`parse_in`], relative to the scene's folder).
//!
//! The streaming path reads inline columns of the plain shape above straight
//! into machine words ([`inline_scene`]) and leaves anything else to [`parse`].
//!
//! or, instead of `[particles]`, a macroscopic datum sampled at the quantiles
//! (paper §2.1, `thm:main`; see [`crate::quantile`]):
//!
//! ```toml
//! [macro]
//! particles = 64                           # N, an integer in 1 ..= 10_000_000
//! blocks = [
//!   { from = "0", to = "1/2", density = "1",   velocity = "1" },
//!   { from = "1", to = "2",   density = "1/2", velocity = ["-1", "0"] },  # affine
//! ]
//! ```
//!
//! **Exact numbers.** Every number is a TOML integer or a string holding an
//! integer (`"3"`), a fraction (`"-7/4"`), a decimal (`"0.125"`) or scientific
//! form (`"1.5e-3"`), read exactly by [`crate::rational::parse_exact`]. A TOML
//! float is refused ([`Error::Float`], the message says to quote it): nothing
//! is rounded silently.
//!
//! **Strictness.** Exactly one of `[particles]` and `[macro]`
//! ([`Error::SceneKind`]); a key the format does not know is an error
//! ([`Error::UnknownField`]: a typo is never silently ignored); so are a
//! missing required key ([`Error::MissingField`]) and a value of the wrong
//! TOML type ([`Error::WrongType`]).
//!
//! **Field names** in errors are dotted paths with **0-based** array indices,
//! as TOML tools show them: `particles.positions[3]`,
//! `macro.blocks[2].density`, `macro.blocks[0].velocity[1]`. Constraint
//! violations found after reading count from 0 the same way: particles
//! `positions[0] … positions[N-1]` (the paper's `x_1 … x_N`;
//! [`Error::Overlap`], [`Error::Approaching`]) and blocks `macro.blocks[k]`
//! ([`Error::Block`], [`Error::Density`]).
//!
//! **Robustness.** [`parse`] never panics. The only allocation whose size the
//! file chooses beyond its own length is the `[macro]` sample, bounded by
//! [`MAX_MACRO_PARTICLES`] particles and by [`MAX_SAMPLE_BYTES`] bytes of
//! estimated number storage; the numbers read are bounded in total by
//! [`MAX_NUMBER_BITS`] (a short scientific form can stand for a long
//! integer), the blocks by [`MAX_MACRO_BLOCKS`]; [`load`] refuses files
//! larger than [`MAX_SCENE_BYTES`].

mod lean;
mod macro_datum;
mod particles;
mod values;

use std::io::Read;
use std::path::Path;

use num_rational::BigRational;
use num_traits::Signed;
use toml::Table;

use crate::error::Error;
use crate::initial::InitialData;
use crate::quantile::{render_short, MacroDatum};
pub use macro_datum::macro_data;
use macro_datum::macro_table;
use particles::particles_table;
use values::{check_keys, exact, optional_string, toml_error, Budget};

pub use lean::{inline_scene, InlineScene};

/// The scenes shipped in `scenes/`, embedded in the library: `(name, text)`,
/// the name being the file stem. The one list the claims ledger, the
/// scaling and sampling checks and the atlas draw their scenes from.
pub const SHIPPED: [(&str, &str); 6] = [
    (
        "appendix-c-two-blocks",
        include_str!("../../scenes/appendix-c-two-blocks.toml"),
    ),
    (
        "three-cluster-simultaneous",
        include_str!("../../scenes/three-cluster-simultaneous.toml"),
    ),
    (
        "collision-cascade",
        include_str!("../../scenes/collision-cascade.toml"),
    ),
    (
        "riemann-compression",
        include_str!("../../scenes/riemann-compression.toml"),
    ),
    (
        "riemann-expansion-affine",
        include_str!("../../scenes/riemann-expansion-affine.toml"),
    ),
    ("random-1000", include_str!("../../scenes/random-1000.toml")),
];

/// The text of the shipped scene `name` ([`SHIPPED`]), if there is one.
pub fn shipped(name: &str) -> Option<&'static str> {
    SHIPPED
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

/// The default scene, embedded in the binary: Appendix C (`app:uniqueness`)
/// of the paper, two congested blocks colliding at `t* = η/2 = 1/8`
/// (`scenes/appendix-c-two-blocks.toml`).
pub const DEFAULT_SCENE: &str = SHIPPED[0].1;

/// Largest scene file [`load`] reads: 64 MiB.
pub const MAX_SCENE_BYTES: u64 = 64 * 1024 * 1024;

/// Largest column file a scene may name, in bytes.
pub const MAX_DATA_BYTES: u64 = 4 * 1024 * 1024 * 1024;

/// Largest particle count a `[macro]` scene may ask for.
pub const MAX_MACRO_PARTICLES: usize = 10_000_000;

/// Upper bound on the estimated storage of the digits of a `[macro]` sample
/// (positions and velocities), 4 GiB: a file with huge numbers and many
/// particles is refused before sampling rather than exhausting memory.
/// [`MAX_MACRO_PARTICLES`] particles with small numbers fit.
pub const MAX_SAMPLE_BYTES: u64 = 4 * 1024 * 1024 * 1024;

/// Largest number of blocks a `[macro]` scene may give (the exact masses
/// of many blocks with unrelated denominators grow quickly).
pub const MAX_MACRO_BLOCKS: usize = 10_000;

/// Upper bound on the total size of the exact numbers of one scene, in bits
/// (numerators and denominators; 1 GiB). Text such as `"1e4096"` is short
/// but stands for a 13 607-bit integer: without this bound a 64 MiB file
/// could ask for tens of gigabytes.
pub const MAX_NUMBER_BITS: u64 = 8 * 1024 * 1024 * 1024;

/// Longest offending text quoted verbatim in an [`Error::Number`]; longer
/// texts are cut (with `…`) so that messages stay readable.
const MAX_QUOTED_CHARS: usize = 64;

/// A parsed and validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The `name` field, if given.
    pub name: Option<String>,
    /// The `description` field, if given.
    pub description: Option<String>,
    /// The `t_end` field (a horizon for plots and studies), if given; `≥ 0`.
    pub t_end: Option<BigRational>,
    /// Whether the scene gave particles or a macroscopic datum.
    pub kind: SceneKind,
    /// The validated initial data: given directly by `[particles]`, or the
    /// quantile sampling of `[macro]` (radius `1/(2N)`).
    pub data: InitialData<BigRational>,
}

impl Scene {
    /// A `[particles]` scene with no name around validated `data`.
    pub fn particles(data: InitialData<BigRational>) -> Scene {
        Scene {
            name: None,
            description: None,
            t_end: None,
            kind: SceneKind::Particles,
            data,
        }
    }

    /// Number of particles N.
    pub fn n(&self) -> usize {
        self.data.n()
    }
}

/// Where a scene's initial data came from.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneKind {
    /// A `[particles]` table: positions and velocities given one by one.
    Particles,
    /// A `[macro]` table: a macroscopic datum `(ρ⁰, u⁰)` and the particle
    /// count N of its quantile sampling (`thm:main` (i)).
    Macro {
        /// The validated macroscopic datum.
        datum: MacroDatum,
        /// The particle count N.
        particles: usize,
    },
}

/// Parses and validates a scene from TOML text. Never panics; every failure
/// is an [`Error`] naming the field (see the module documentation for the
/// field-path and numbering conventions).
pub fn parse(text: &str) -> Result<Scene, Error> {
    parse_in(text, None)
}

/// [`parse`] for a scene that lives in the folder `dir`: a `[particles]`
/// table may then name a column file beside it (`data = "particles.csv"` or
/// `"particles.npy"`, see [`crate::columns`]), read relative to `dir`.
/// Without a folder (`None`), a `data` field is an error that says so.
pub fn parse_in(text: &str, dir: Option<&Path>) -> Result<Scene, Error> {
    let table: Table = text.parse::<Table>().map_err(|e| toml_error(text, &e))?;
    check_keys(
        &table,
        "",
        &["name", "description", "t_end", "particles", "macro"],
    )?;
    let budget = Budget::new();
    let name = optional_string(&table, "name")?;
    let description = optional_string(&table, "description")?;
    let t_end = match table.get("t_end") {
        None => None,
        Some(v) => {
            let t = exact(v, "t_end", &budget)?;
            if t.is_negative() {
                return Err(Error::NegativeTime {
                    t: render_short(&t),
                });
            }
            Some(t)
        }
    };
    let (kind, data) = match (table.get("particles"), table.get("macro")) {
        (Some(_), Some(_)) => return Err(Error::SceneKind {
            message:
                "a scene must have exactly one of [particles] and [macro], but this one has both"
                    .to_string(),
        }),
        (None, None) => return Err(Error::SceneKind {
            message:
                "a scene must have exactly one of [particles] and [macro], but this one has neither"
                    .to_string(),
        }),
        (Some(p), None) => (SceneKind::Particles, particles_table(p, &budget, dir)?),
        (None, Some(m)) => macro_table(m, &budget)?,
    };
    Ok(Scene {
        name,
        description,
        t_end,
        kind,
        data,
    })
}

/// Reads a scene file and parses it with [`parse`]. I/O failures (with the
/// operating system's message and the path), files larger than
/// [`MAX_SCENE_BYTES`] and text that is not UTF-8 are reported as
/// [`Error::Io`].
pub fn load(path: &Path) -> Result<Scene, Error> {
    let io = |e: std::io::Error| Error::Io {
        message: format!("{}: {e}", path.display()),
    };
    let too_big = || Error::Io {
        message: format!(
            "{}: the file is larger than the {} MiB limit for scene files",
            path.display(),
            MAX_SCENE_BYTES / (1024 * 1024)
        ),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    if let Ok(meta) = file.metadata() {
        if meta.is_file() && meta.len() > MAX_SCENE_BYTES {
            return Err(too_big());
        }
    }
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big());
    }
    let text = String::from_utf8(bytes).map_err(|e| Error::Io {
        message: format!(
            "{}: not UTF-8 text (invalid byte at offset {})",
            path.display(),
            e.utf8_error().valid_up_to()
        ),
    })?;
    parse_in(&text, path.parent())
}

/// A `[particles]` scene whose columns live in a file (`data = "…"`), read
/// up to the columns: what the streaming path of [`crate::fast::stream`]
/// needs before it reads the file itself.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnScene {
    /// The `radius` field, if given (else `1/(2N)`, as for [`parse`]).
    pub radius: Option<BigRational>,
    /// The column file, relative to the current folder.
    pub data: std::path::PathBuf,
    /// The bits [`MAX_NUMBER_BITS`] is charged for before the columns
    /// (`t_end` and `radius`).
    pub charged_bits: u64,
}

/// The scene at `path` as a [`ColumnScene`], when it is a valid
/// `[particles]` scene with a `data` file of a known kind and nothing in it
/// before the columns is wrong; `None` otherwise (then [`load`] is the path
/// that reads it, or says what is wrong, with the message of record).
pub fn column_scene(path: &Path) -> Option<ColumnScene> {
    let meta = std::fs::metadata(path).ok()?;
    if !meta.is_file() || meta.len() > MAX_SCENE_BYTES {
        return None;
    }
    let text = std::fs::read_to_string(path).ok()?;
    // Cheap refusal before parsing a big inline scene: a `data` key is
    // spelled out (an escaped spelling is left to the general path).
    if !text.contains("data") {
        return None;
    }
    let table: Table = text.parse::<Table>().ok()?;
    check_keys(
        &table,
        "",
        &["name", "description", "t_end", "particles", "macro"],
    )
    .ok()?;
    if table.contains_key("macro") {
        return None;
    }
    let budget = Budget::new();
    optional_string(&table, "name").ok()?;
    optional_string(&table, "description").ok()?;
    let mut charged_bits = 0;
    if let Some(v) = table.get("t_end") {
        let t = exact(v, "t_end", &budget).ok()?;
        if t.is_negative() {
            return None;
        }
        charged_bits += values::bits(&t) + 64;
    }
    let particles = values::as_table(table.get("particles")?, "particles").ok()?;
    check_keys(particles, "particles", &["radius", "data"]).ok()?;
    let toml::Value::String(file) = particles.get("data")? else {
        return None;
    };
    let radius = match particles.get("radius") {
        Some(r) => {
            let r = exact(r, "particles.radius", &budget).ok()?;
            charged_bits += values::bits(&r) + 64;
            Some(r)
        }
        None => None,
    };
    let data = path.parent()?.join(file);
    let meta = std::fs::metadata(&data).ok()?;
    let known = matches!(
        data.extension().and_then(|e| e.to_str()),
        Some("csv" | "npy")
    );
    (known && meta.len() <= MAX_DATA_BYTES).then_some(ColumnScene {
        radius,
        data,
        charged_bits,
    })
}

/// The embedded [`DEFAULT_SCENE`], parsed.
pub fn default_scene() -> Result<Scene, Error> {
    parse(DEFAULT_SCENE)
}

/// Writes `data` as a `[particles]` scene (with an optional `name`): the
/// radius, positions and velocities as quoted exact strings (`"p/q"` in
/// lowest terms), so that [`parse`] reads back identical data.
pub fn particles_toml(data: &InitialData<BigRational>, name: Option<&str>) -> String {
    use crate::rational::render_exact;
    let list = |v: &[BigRational]| -> String {
        let items: Vec<String> = v
            .iter()
            .map(|q| format!("\"{}\"", render_exact(q)))
            .collect();
        format!("[{}]", items.join(", "))
    };
    let mut out = String::new();
    if let Some(name) = name {
        out.push_str("name = ");
        // A JSON string literal (with DEL escaped) is a valid TOML basic string.
        out.push_str(&crate::text::string(name));
        out.push('\n');
    }
    out.push_str("\n[particles]\n");
    out.push_str(&format!("radius = \"{}\"\n", render_exact(data.radius())));
    out.push_str(&format!("positions = {}\n", list(data.positions())));
    out.push_str(&format!("velocities = {}\n", list(data.velocities())));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn default_scene_parses() {
        let scene = default_scene().unwrap();
        assert_eq!(scene.n(), 16);
        assert!(matches!(scene.kind, SceneKind::Macro { particles: 16, .. }));
    }

    #[test]
    fn module_doc_examples_parse() {
        let head =
            "name = \"two-blocks\"\ndescription = \"Appendix C: two blocks\"\nt_end = \"2\"\n";
        let particles = format!(
            "{head}[particles]\nradius = \"1/16\"\npositions  = [\"0\", \"1/8\", \"1/2\", \"5/8\"]\nvelocities = [\"1\", \"1\", \"-1\", \"-1\"]\n"
        );
        assert_eq!(parse(&particles).unwrap().n(), 4);
        let macro_ = "[macro]\nparticles = 64\nblocks = [\n  { from = \"0\", to = \"1/2\", density = \"1\",   velocity = \"1\" },\n  { from = \"1\", to = \"2\",   density = \"1/2\", velocity = [\"-1\", \"0\"] },  # affine\n]\n";
        assert_eq!(parse(macro_).unwrap().n(), 64);
    }

    #[test]
    fn toml_errors_are_one_line() {
        let e = parse("a = \n[").unwrap_err();
        assert!(matches!(e, Error::Toml { .. }));
        assert!(!e.to_string().contains('\n'), "{e}");
        assert!(e.to_string().contains("line "), "{e}");
    }

    #[test]
    fn too_many_blocks() {
        let blocks = vec!["{ from = 0, to = 1, density = 1, velocity = 0 }"; MAX_MACRO_BLOCKS + 1];
        let text = format!("[macro]\nparticles = 2\nblocks = [{}]\n", blocks.join(","));
        let e = parse(&text).unwrap_err();
        assert!(matches!(e, Error::Unsupported { .. }), "{e:?}");
        assert!(e.to_string().contains("macro.blocks"), "{e}");
    }

    #[test]
    fn long_number_text_is_cut() {
        let long = "x".repeat(1000);
        let e = parse(&format!(
            "[particles]\npositions = [\"{long}\"]\nvelocities = [0]"
        ))
        .unwrap_err();
        assert!(e.to_string().len() < 400, "{e}");
    }

    #[test]
    fn particles_toml_round_trips() {
        use crate::generate::{initial_data, Limits, SplitMix64};
        let mut rng = SplitMix64::new(2024);
        for len in [0, 1, 7, 40, 300, 2000] {
            let data = initial_data(&rng.bytes(len), Limits::default());
            for name in [None, Some("round \"trip\" \\ é\n\t\u{1}")] {
                let text = particles_toml(&data, name);
                let scene = parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
                assert_eq!(scene.data, data, "{text}");
                assert_eq!(scene.name.as_deref(), name);
                assert_eq!(scene.kind, SceneKind::Particles);
            }
        }
        // Negative numbers, a radius different from 1/(2N), large integers.
        let big = BigRational::new(BigInt::from(10).pow(40) + 1u32, BigInt::from(3));
        let data = InitialData::new(
            BigRational::new(BigInt::from(1), BigInt::from(7)),
            vec![
                -big.clone(),
                BigRational::from_integer(BigInt::from(-1)),
                big.clone(),
            ],
            vec![
                BigRational::new(BigInt::from(-5), BigInt::from(2)),
                BigRational::from_integer(BigInt::from(0)),
                big,
            ],
        )
        .unwrap();
        assert_eq!(parse(&particles_toml(&data, None)).unwrap().data, data);
    }
}
