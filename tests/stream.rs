//! The streaming path (`fast::stream`, issue 13 part 2) against the general
//! path (`scene::load` + the kernel + `report::json::state`), byte for byte,
//! on random CSV and NPY column scenes: fractions, decimals, scientific forms
//! with exponents, signs and spaces, negative values, and data whose
//! denominators or values leave machine words (the streaming path must then
//! decline, and the general path answers).

use std::path::{Path, PathBuf};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use sticky::columns::{write_npy, CSV_HEADER};
use sticky::fast::kernel::{state_at, IntegerData};
use sticky::fast::stream::Lean;
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::initial::InitialData;
use sticky::report::json;

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sticky-stream-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The general answer: the scene read with `scene::load`, the kernel, the
/// contract's JSON line.
fn general(path: &Path, t: &BigRational) -> String {
    let scene = sticky::scene::load(path).unwrap_or_else(|e| panic!("{e}"));
    let d = IntegerData::new(&scene.data);
    format!(
        "{}\n",
        json::state(&state_at(&d, t).unwrap(), scene.data.radius())
    )
}

/// The streaming answer, when the streaming path takes the scene and `t`.
fn streamed(path: &Path, t: &BigRational) -> Option<String> {
    let lean = Lean::load(path)?;
    let b = lean.blocks_at(t)?;
    let mut out = Vec::new();
    json::write_lean_state(&mut out, &b, lean.radius()).unwrap();
    Some(String::from_utf8(out).unwrap())
}

/// The events JSON both ways; `false` when the streaming path declined.
fn events_agree(path: &Path) -> bool {
    let scene = sticky::scene::load(path).unwrap_or_else(|e| panic!("{e}"));
    let want = format!(
        "{}\n",
        json::events(sticky::fast::merge::trajectory(&scene.data).impulses())
    );
    let Some(h) = Lean::load(path).and_then(|l| l.history()) else {
        return false;
    };
    let mut out = Vec::new();
    json::write_word_events(&mut out, &h).unwrap();
    assert_eq!(String::from_utf8(out).unwrap(), want, "{}", path.display());
    true
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

/// A value as text in one of the exact forms `parse_exact` reads, chosen by
/// `style`: fraction, decimal, scientific (with a signed exponent), with an
/// explicit `+`, or padded with spaces.
fn text(v: &BigRational, style: u64) -> String {
    let plain = sticky::rational::render_exact(v);
    // A decimal form exists when the denominator divides a power of ten.
    let mut den = v.denom().clone();
    let mut k = 0u32;
    let ten = BigInt::from(10);
    while !(&ten.pow(k) % &den).is_zero() && k < 12 {
        k += 1;
    }
    if !(&ten.pow(k) % &den).is_zero() {
        den = BigInt::zero();
    }
    match style % 5 {
        1 if !den.is_zero() => {
            // digits · 10^-k as "int.frac".
            let scaled = v * BigRational::from_integer(ten.pow(k));
            let m = scaled.to_integer();
            let (sign, m) = if m.is_negative() { ("-", -m) } else { ("", m) };
            let s = format!("{:0>width$}", m.to_string(), width = k as usize + 1);
            let (a, b) = s.split_at(s.len() - k as usize);
            if k == 0 {
                format!("{sign}{a}")
            } else {
                format!("{sign}{a}.{b}")
            }
        }
        2 if !den.is_zero() => {
            // digits e-(k+2), the mantissa padded by two zeros.
            let m = (v * BigRational::from_integer(ten.pow(k + 2))).to_integer();
            format!("{m}e-{}", k + 2)
        }
        3 if !v.is_negative() => format!("+{plain}"),
        4 => format!("  {plain} "),
        _ => plain,
    }
}

fn write_csv_scene(
    dir: &Path,
    name: &str,
    radius: Option<&str>,
    rows: &[(String, String)],
) -> PathBuf {
    let mut csv = format!("{CSV_HEADER}\n");
    for (x, u) in rows {
        csv.push_str(&format!("{x},{u}\n"));
    }
    std::fs::write(dir.join(format!("{name}.csv")), csv).unwrap();
    let radius = radius.map_or(String::new(), |r| format!("radius = \"{r}\"\n"));
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!("name = \"{name}\"\n[particles]\n{radius}data = \"{name}.csv\"\n"),
    )
    .unwrap();
    path
}

/// A random scene (N ≤ 60, varied denominators) shifted by a negative
/// offset, as column strings in every spelling `text` knows.
fn random_rows(
    rng: &mut SplitMix64,
    case: usize,
) -> (InitialData<BigRational>, Vec<(String, String)>) {
    let data = initial_data(
        &rng.bytes(300),
        Limits {
            max_n: 1 + case % 60,
            max_den: [8, 10, 1000, 40][case % 4],
            max_speed: 16,
        },
    );
    // Shift every position by a negative offset (negative values).
    let offset = q(
        -((rng.next_u64() % 1000) as i64),
        1 + (rng.next_u64() % 50) as i64,
    );
    let rows = data
        .positions()
        .iter()
        .zip(data.velocities())
        .map(|(x, u)| {
            (
                text(&(x + &offset), rng.next_u64()),
                text(u, rng.next_u64()),
            )
        })
        .collect();
    (data, rows)
}

#[test]
fn csv_scenes_give_the_same_bytes() {
    let d = dir("csv");
    let mut rng = SplitMix64::new(1313);
    let mut taken = 0;
    let mut events_taken = 0;
    for case in 0..120 {
        let (data, rows) = random_rows(&mut rng, case);
        let radius = sticky::rational::render_exact(data.radius());
        let path = write_csv_scene(&d, &format!("c{case}"), Some(&radius), &rows);
        events_taken += usize::from(events_agree(&path));
        for t in [q(0, 1), q(1, 3), q(5, 2), q(7, 1), q(1, 1_000_003)] {
            let want = general(&path, &t);
            if let Some(got) = streamed(&path, &t) {
                assert_eq!(got, want, "case {case}, t = {t}");
                taken += 1;
            }
        }
    }
    // The streaming path must take (nearly) all of these small scenes.
    assert!(taken >= 400, "streaming path taken {taken} times of 600");
    assert!(
        events_taken >= 80,
        "streaming events taken {events_taken} times of 120"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn off_words_the_streaming_path_declines_or_agrees() {
    let d = dir("big");
    // Denominators whose lcm overflows words, a 30-digit value, values
    // with exponents, a default radius.
    let primes = [1009i64, 1013, 1019, 1021, 1031];
    let rows: Vec<(String, String)> = (0..5)
        .map(|i| {
            (
                format!("{}/{}", 3 * i, 1),
                format!("1/{}", primes[i as usize]),
            )
        })
        .collect();
    let a = write_csv_scene(&d, "lcm", Some("1/4"), &rows);
    let rows = vec![
        (
            "-123456789012345678901234567890".to_string(),
            "1".to_string(),
        ),
        ("0".to_string(), "-1".to_string()),
    ];
    let b = write_csv_scene(&d, "long", Some("1/4"), &rows);
    let rows = vec![
        ("-1.5e3".to_string(), "2.5E-2".to_string()),
        ("1e2".to_string(), "-3e+0".to_string()),
        ("123e10".to_string(), "0".to_string()),
    ];
    let c = write_csv_scene(&d, "exp", None, &rows);
    // Overflows words only at late times (a big numerator of t).
    let big_t = BigRational::from_integer(BigInt::one() << 100u32);
    for path in [&a, &b, &c] {
        for t in [q(0, 1), q(1, 7), q(9, 4), big_t.clone()] {
            let want = general(path, &t);
            if let Some(got) = streamed(path, &t) {
                assert_eq!(got, want, "{}, t = {t}", path.display());
            }
        }
    }
    assert!(Lean::load(&a).is_some(), "lcm of five primes fits words");
    assert!(Lean::load(&b).is_none(), "a 30-digit value is off words");
    assert!(streamed(&c, &q(1, 1)).is_some(), "exponents on words");
    assert!(streamed(&c, &big_t).is_none(), "t = 2^100 is off words");
    // An invalid scene: the streaming path declines (the general path
    // names the error).
    let rows = vec![
        ("1".to_string(), "0".to_string()),
        ("1".to_string(), "0".to_string()),
    ];
    let e = write_csv_scene(&d, "overlap", Some("1/4"), &rows);
    assert!(Lean::load(&e).is_none());
    assert!(sticky::scene::load(&e).is_err());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn npy_scenes_give_the_same_bytes() {
    let d = dir("npy");
    let mut rng = SplitMix64::new(77);
    let mut taken = 0;
    for case in 0..60 {
        let n = 1 + case % 50;
        let mut x = -((rng.next_u64() % 1000) as f64) / 8.0;
        let mut rows = Vec::new();
        let mut contact_u = f64::NEG_INFINITY;
        for _ in 0..n {
            // In contact with the previous particle: not approaching it.
            let u = (((rng.next_u64() % 64) as f64 - 32.0) / [1.0, 4.0, 1024.0][case % 3])
                .max(contact_u);
            rows.push((x, u));
            // Gaps of exactly 2r = 1/32, or more.
            let extra = (rng.next_u64() % 4) as f64 / [2.0, 64.0, 4096.0][case % 3];
            x += 1.0 / 32.0 + extra;
            contact_u = if extra == 0.0 { u } else { f64::NEG_INFINITY };
        }
        if case % 10 == 9 {
            // A value off words: a huge double, or a tiny one.
            rows[n - 1].0 = if case % 20 == 9 { 1e300 } else { x + 1.0 };
            if case % 20 == 19 {
                rows[n - 1].1 = f64::from_bits(1);
            }
        }
        let name = format!("n{case}");
        std::fs::write(d.join(format!("{name}.npy")), write_npy(&rows)).unwrap();
        let path = d.join(format!("{name}.toml"));
        std::fs::write(
            &path,
            format!("[particles]\nradius = \"1/64\"\ndata = \"{name}.npy\"\n"),
        )
        .unwrap();
        events_agree(&path);
        for t in [q(0, 1), q(1, 3), q(3, 1)] {
            let want = general(&path, &t);
            if let Some(got) = streamed(&path, &t) {
                assert_eq!(got, want, "case {case}, t = {t}");
                taken += 1;
            }
        }
    }
    assert!(taken >= 150, "streaming path taken {taken} times of 180");
    std::fs::remove_dir_all(&d).unwrap();
}

const STICKY: &str = env!("CARGO_BIN_EXE_sticky");

fn cli(args: &[&str]) -> Vec<u8> {
    let o = std::process::Command::new(STICKY)
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o.stdout
}

/// `run --format csv|npy`: the streaming and the general path write the
/// same bytes; the CSV holds the JSON's exact strings; NPY needs `--lossy`
/// and holds their nearest doubles, shape (T, N, 3).
#[test]
fn csv_and_npy_output() {
    let d = dir("format");
    let mut rng = SplitMix64::new(4242);
    for case in 0..6 {
        let data = initial_data(&rng.bytes(400), Limits::default());
        let rows: Vec<(String, String)> = data
            .positions()
            .iter()
            .zip(data.velocities())
            .map(|(x, u)| (text(x, rng.next_u64()), text(u, rng.next_u64())))
            .collect();
        let radius = sticky::rational::render_exact(data.radius());
        let path = write_csv_scene(&d, &format!("f{case}"), Some(&radius), &rows);
        let p = path.to_str().unwrap();
        let at = ["--at", "0", "--at", "7/3"];
        let with = |extra: &[&str]| {
            let mut a = vec!["run", p];
            a.extend_from_slice(&at);
            a.extend_from_slice(extra);
            cli(&a)
        };
        let csv = with(&["--format", "csv"]);
        assert_eq!(csv, with(&["--format", "csv", "--engine", "kernel"]));
        let npy = with(&["--format", "npy", "--lossy"]);
        assert_eq!(
            npy,
            with(&["--format", "npy", "--lossy", "--engine", "kernel"])
        );
        let json = String::from_utf8(with(&["--json"])).unwrap();
        // Every CSV row against the JSON line of its time.
        let csv = String::from_utf8(csv).unwrap();
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("t,i,position,velocity,multiplier"));
        let n = data.n();
        let mut doubles = Vec::new();
        for (k, obj) in json.lines().enumerate() {
            let field = |key: &str| -> Vec<String> {
                let start = obj.find(&format!("\"{key}\": [")).unwrap() + key.len() + 5;
                let end = start + obj[start..].find(']').unwrap();
                obj[start..end]
                    .split(", ")
                    .filter(|s| !s.is_empty())
                    .map(|s| s.trim_matches('"').to_string())
                    .collect()
            };
            let (x, u, l) = (
                field("positions"),
                field("velocities"),
                field("multipliers"),
            );
            for i in 0..n {
                let lam = l.get(i).cloned().unwrap_or_default();
                let t = ["0", "7/3"][k];
                assert_eq!(
                    lines.next().unwrap(),
                    format!("{t},{i},{},{},{lam}", x[i], u[i])
                );
                for v in [
                    &x[i],
                    &u[i],
                    &if lam.is_empty() {
                        "0".to_string()
                    } else {
                        lam.clone()
                    },
                ] {
                    let q = sticky::rational::parse_exact(v).unwrap();
                    doubles.push(sticky::Scalar::to_f64_lossy(&q));
                }
            }
        }
        assert_eq!(lines.next(), None);
        let header = sticky::columns::npy_header(&[2, n, 3]);
        assert_eq!(&npy[..header.len()], &header[..]);
        let body: Vec<f64> = npy[header.len()..]
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(body, doubles);
    }
    let o = std::process::Command::new(STICKY)
        .args([
            "run",
            "scenes/collision-cascade.toml",
            "--at",
            "1",
            "--format",
            "npy",
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--lossy"));
    std::fs::remove_dir_all(&d).unwrap();
}

/// Writes a `[particles]` scene with inline columns in one of several
/// layouts (`style`): one line each, one value per line with comments and
/// a trailing comma, CRLF line ends, padded strings, top-level fields.
fn write_inline_scene(
    dir: &Path,
    name: &str,
    radius: Option<&str>,
    rows: &[(String, String)],
    style: u64,
) -> PathBuf {
    let nl = if style % 4 == 2 { "\r\n" } else { "\n" };
    let array = |v: Vec<&String>| -> String {
        // Some styles write the integer values as TOML integers.
        let bare = |s: &str| style % 7 == 5 && s.parse::<i64>().is_ok_and(|v| v.to_string() == s);
        let items: Vec<String> = v
            .iter()
            .map(|s| {
                if bare(s) {
                    s.to_string()
                } else {
                    format!("\"{s}\"")
                }
            })
            .collect();
        match style % 4 {
            1 => format!(
                "[{nl}  {},{nl}] # end",
                items.join(&format!(", # a comment{nl}  "))
            ),
            3 => format!("[ {} , ]", items.join(" ,\t")),
            _ => format!("[{}]", items.join(", ")),
        }
    };
    let mut text = String::new();
    if style % 3 == 0 {
        text.push_str(&format!(
            "# a scene{nl}name = \"{name}\"{nl}description = \"inline, style {style}\"{nl}t_end = \"3/2\"{nl}{nl}"
        ));
    }
    text.push_str(&format!("[ particles ]{nl}"));
    if let Some(r) = radius {
        text.push_str(&format!("radius = \"{r}\"{nl}"));
    }
    let xs = array(rows.iter().map(|r| &r.0).collect());
    let us = array(rows.iter().map(|r| &r.1).collect());
    if style % 2 == 0 {
        text.push_str(&format!("positions = {xs}{nl}velocities = {us}{nl}"));
    } else {
        text.push_str(&format!("velocities = {us}{nl}positions = {xs}"));
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// TOML scenes with inline columns (`scene::inline_scene`, issue 13 part 2):
/// the streaming path gives the general path's bytes on random scenes in
/// every layout, and the shipped `[particles]` scenes (all three).
#[test]
fn inline_toml_scenes_give_the_same_bytes() {
    let d = dir("toml");
    let mut rng = SplitMix64::new(2626);
    let mut taken = 0;
    let mut events_taken = 0;
    for case in 0..120u64 {
        let (data, rows) = random_rows(&mut rng, case as usize);
        let radius = sticky::rational::render_exact(data.radius());
        let radius = (case % 5 != 4).then_some(radius.as_str());
        let path = write_inline_scene(&d, &format!("t{case}"), radius, &rows, case);
        // Without its radius (the default 1/(2N)) a scene may overlap:
        // then the streaming path declines and the general path says so.
        if sticky::scene::load(&path).is_err() {
            assert!(radius.is_none(), "case {case}: every layout is TOML");
            assert!(Lean::load(&path).is_none(), "case {case}");
            continue;
        }
        events_taken += usize::from(events_agree(&path));
        for t in [q(0, 1), q(1, 3), q(5, 2), q(7, 1)] {
            let want = general(&path, &t);
            if let Some(got) = streamed(&path, &t) {
                assert_eq!(got, want, "case {case}, t = {t}");
                taken += 1;
            }
        }
    }
    assert!(taken >= 350, "streaming path taken {taken} times of 480");
    assert!(
        events_taken >= 90,
        "streaming events taken {events_taken} times of 120"
    );
    let mut shipped = 0;
    for (name, text) in sticky::scene::SHIPPED {
        let path = d.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        if Lean::load(&path).is_some() {
            shipped += 1;
            events_agree(&path);
            for t in [q(0, 1), q(1, 8), q(1, 1), q(10, 1)] {
                if let Some(got) = streamed(&path, &t) {
                    assert_eq!(got, general(&path, &t), "{name}, t = {t}");
                }
            }
        }
    }
    assert!(
        shipped >= 3,
        "{shipped} shipped scenes on the streaming path"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// What the inline reader does not hold, the streaming path declines and
/// the general path reads or refuses with its own message (the CLI prints
/// the same error with or without the streaming path in front).
#[test]
fn inline_toml_off_words_or_invalid_declines() {
    let d = dir("toml-off");
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let pair =
        |x: &[&str], u: &[&str]| -> Vec<(String, String)> { s(x).into_iter().zip(s(u)).collect() };
    // A 30-digit value: off words, the general path answers.
    let long = write_inline_scene(
        &d,
        "long",
        Some("1/4"),
        &pair(&["-123456789012345678901234567890", "0"], &["1", "-1"]),
        0,
    );
    assert!(Lean::load(&long).is_none());
    assert!(sticky::scene::load(&long).is_ok());
    // Plain TOML integers are read; an integer with `_` and escapes are
    // valid TOML the reader leaves to the general path.
    let ints = d.join("ints.toml");
    std::fs::write(
        &ints,
        "[particles]\npositions = [0, 1]\nvelocities = [\"1\", \"0\"]\n",
    )
    .unwrap();
    assert!(Lean::load(&ints).is_some());
    assert_eq!(streamed(&ints, &q(1, 1)), Some(general(&ints, &q(1, 1))));
    let underscored = d.join("underscored.toml");
    std::fs::write(
        &underscored,
        "[particles]\npositions = [0, 1_0]\nvelocities = [\"1\", \"0\"]\n",
    )
    .unwrap();
    assert!(Lean::load(&underscored).is_none());
    assert!(sticky::scene::load(&underscored).is_ok());
    let esc = d.join("esc.toml");
    std::fs::write(
        &esc,
        "[particles]\npositions = [\"\\u0030\", \"1\"]\nvelocities = [\"1\", \"0\"]\n",
    )
    .unwrap();
    assert!(Lean::load(&esc).is_none());
    assert_eq!(
        general(&esc, &q(1, 1)),
        general(&ints, &q(1, 1)),
        "\\u0030 is 0"
    );
    // Invalid scenes: an overlap, a bad number, a negative radius, unequal
    // columns. The streaming path declines; the CLI's error is the general
    // path's.
    for (name, rows, radius) in [
        ("overlap", pair(&["1", "1"], &["0", "0"]), "1/4"),
        ("badnum", pair(&["1", "2/0"], &["0", "0"]), "1/4"),
        ("negr", pair(&["0", "1"], &["0", "0"]), "-1/4"),
        ("approach", pair(&["0", "1/2"], &["1", "0"]), "1/4"),
    ] {
        let path = write_inline_scene(&d, name, Some(radius), &rows, 0);
        assert!(Lean::load(&path).is_none(), "{name}");
        let err = sticky::scene::load(&path).unwrap_err();
        let o = std::process::Command::new(STICKY)
            .args(["run", path.to_str().unwrap(), "--at", "1", "--json"])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{name}");
        assert_eq!(
            String::from_utf8_lossy(&o.stderr).trim(),
            format!("error: {}: {err}", path.display()),
            "{name}"
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// `run --explain` on a column scene the streaming path reads says so and
/// projects the peak memory from the NPY header (16 B/particle of columns,
/// the worst-case PAVA stack); over `STICKY_MAX_MEMORY` the run is refused
/// up front with that projection, and just at it the run answers.
#[test]
fn explain_projects_memory_and_the_limit_refuses() {
    let d = dir("memory");
    let rows = [(0.0, 1.0), (0.5, -0.25), (3.0, 0.0)];
    std::fs::write(d.join("m.npy"), write_npy(&rows)).unwrap();
    let path = d.join("m.toml");
    std::fs::write(&path, "[particles]\nradius = \"1/8\"\ndata = \"m.npy\"\n").unwrap();
    let p = path.to_str().unwrap();
    let run = |limit: &str| {
        std::process::Command::new(STICKY)
            .args(["run", p, "--at", "1", "--json", "--explain"])
            .env("STICKY_MAX_MEMORY", limit)
            .output()
            .unwrap()
    };
    // 3 particles: 48 B of columns, 4 MiB of buffer, 3 blocks at most.
    let o = run("5");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.starts_with("engine: streaming (N = 3,"), "{err}");
    assert!(
        err.contains("memory: at most 4.0 MiB (N = 3, file 0.0 MiB)"),
        "{err}"
    );
    assert_eq!(o.stdout, general(&path, &q(1, 1)).into_bytes());
    let o = run("4");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("would need at most 4.0 MiB (N = 3")
            && err.contains("over the memory limit of 4.0 MiB")
            && err.contains("STICKY_MAX_MEMORY"),
        "{err}"
    );
    assert!(o.stdout.is_empty());
    std::fs::remove_dir_all(&d).unwrap();
}

/// The state formatted in pieces on several threads gives the bytes of the
/// general path whatever the pieces' size: one piece (all on one thread),
/// or many small pieces, each shorter than some blocks, on 1 to 3 workers
/// (the core count of the machine decides, the result must not).
#[test]
fn pieces_on_several_threads_give_the_same_bytes() {
    let d = dir("pieces");
    sticky::report::bench::e2e::write_inputs(&d, 3000, 7).unwrap();
    for scene in ["dec.toml", "dyadic.toml"] {
        let path = d.join(scene);
        let lean = Lean::load(&path).expect("the streaming path takes it");
        for t in [q(1, 1000), q(1, 97), q(1, 1)] {
            let want = general(&path, &t);
            let b = lean.blocks_at(&t).unwrap();
            // Many pieces early on; blocks longer than the smallest pieces
            // (fewer pieces than particles) always.
            let pieces = b.pieces(7).len();
            assert!(pieces < b.n() / 7, "{scene} at {t}: {pieces}");
            assert!(t > q(1, 100) || pieces > 100, "{scene} at {t}: {pieces}");
            for piece in [1, 7, 500, usize::MAX] {
                let mut out = Vec::new();
                json::write_lean_state_in_pieces(&mut out, &b, lean.radius(), piece).unwrap();
                assert_eq!(
                    String::from_utf8(out).unwrap(),
                    want,
                    "{scene} at {t}, {piece}"
                );
            }
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}
