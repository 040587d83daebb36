//! One test per kind of bad scene: each checks the exact `Error` variant and
//! that the message is a single line naming the problem (the field, or the
//! first offending pair or block).

use std::path::PathBuf;

use sticky::rational::NumberError;
use sticky::scene::{self, MAX_MACRO_PARTICLES};
use sticky::Error;

/// Parses `text`, which must fail, and checks the message is one line
/// containing every one of `needles`.
fn err(text: &str, needles: &[&str]) -> Error {
    let e = match scene::parse(text) {
        Ok(s) => panic!("scene was accepted: {s:?}\n--- text ---\n{text}"),
        Err(e) => e,
    };
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "message is not one line: {msg:?}");
    assert!(!msg.is_empty());
    for n in needles {
        assert!(msg.contains(n), "message {msg:?} does not mention {n:?}");
    }
    e
}

/// A `[particles]` scene.
fn particles(radius: Option<&str>, positions: &str, velocities: &str) -> String {
    let radius = radius
        .map(|r| format!("radius = {r}\n"))
        .unwrap_or_default();
    format!("[particles]\n{radius}positions = {positions}\nvelocities = {velocities}\n")
}

/// A `[macro]` scene with `particles = n` and the given block lines.
fn macro_scene(n: &str, blocks: &[&str]) -> String {
    format!(
        "[macro]\nparticles = {n}\nblocks = [\n{}\n]\n",
        blocks
            .iter()
            .map(|b| format!("  {b},"))
            .collect::<Vec<_>>()
            .join("\n")
    )
}

const HALF_A: &str = r#"{ from = "0", to = "1/2", density = "1", velocity = "0" }"#;
const HALF_B: &str = r#"{ from = "1", to = "3/2", density = "1", velocity = "0" }"#;

// ------------------------------------------------------------ particles

#[test]
fn overlapping_positions_name_the_pair() {
    let text = particles(
        Some(r#""1/32""#),
        r#"["0", "1/8", "1/4", "3/10"]"#,
        r#"["0", "0", "0", "0"]"#,
    );
    let e = err(&text, &[]);
    assert_eq!(
        e,
        Error::Overlap {
            i: 2,
            gap: "1/20".into(),
            two_r: "1/16".into()
        }
    );
    assert_eq!(
        e.to_string(),
        "positions[2] and positions[3] overlap: gap 1/20 < 2r = 1/16"
    );
}

#[test]
fn velocities_outside_the_cone() {
    // 2r = 1/8: particles 1 and 2 (from 0) touch and approach (1 > -1).
    let text = particles(
        Some(r#""1/16""#),
        r#"["0", "1/2", "5/8", "1"]"#,
        r#"["0", "1", "-1", "0"]"#,
    );
    let e = err(
        &text,
        &[
            "particles 1 and 2 (indices from 0)",
            "velocities[1] = 1 > velocities[2] = -1",
        ],
    );
    assert_eq!(
        e,
        Error::Approaching {
            i: 1,
            left: "1".into(),
            right: "-1".into()
        }
    );
}

#[test]
fn float_radius_is_refused() {
    let text = particles(Some("0.5"), r#"["0", "2"]"#, r#"["0", "0"]"#);
    let e = err(&text, &["particles.radius", "\"0.5\"", "quoted"]);
    assert_eq!(
        e,
        Error::Float {
            field: "particles.radius".into(),
            value: "0.5".into()
        }
    );
}

#[test]
fn float_inside_positions_is_refused() {
    let text = particles(None, r#"["0", 0.25, "1"]"#, r#"["0", "0", "0"]"#);
    let e = err(&text, &["particles.positions[1]", "0.25"]);
    assert_eq!(
        e,
        Error::Float {
            field: "particles.positions[1]".into(),
            value: "0.25".into()
        }
    );
}

#[test]
fn float_in_scientific_form_is_refused() {
    let text = particles(None, r#"["0"]"#, "[1e-7]");
    let e = err(&text, &["particles.velocities[0]", "1e-7"]);
    assert!(matches!(e, Error::Float { .. }), "{e:?}");
}

#[test]
fn infinite_float_is_a_wrong_type() {
    let text = particles(None, r#"["0"]"#, "[inf]");
    let e = err(&text, &["particles.velocities[0]"]);
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
}

#[test]
fn unparsable_numbers() {
    for bad in ["abc", "1/", "", "1..2", "0x10"] {
        let text = particles(None, &format!("[\"0\", \"{bad}\"]"), r#"["0", "0"]"#);
        let e = err(&text, &["particles.positions[1]"]);
        assert!(
            matches!(
                &e,
                Error::Number { field, text, reason: NumberError::Malformed | NumberError::Empty }
                    if field == "particles.positions[1]" && text == bad
            ),
            "{bad:?}: {e:?}"
        );
    }
}

#[test]
fn zero_denominator() {
    let text = particles(None, r#"["0"]"#, r#"["1/0"]"#);
    let e = err(&text, &["particles.velocities[0]", "zero denominator"]);
    assert_eq!(
        e,
        Error::Number {
            field: "particles.velocities[0]".into(),
            text: "1/0".into(),
            reason: NumberError::ZeroDenominator
        }
    );
}

#[test]
fn huge_exponent() {
    let text = particles(None, r#"["1e999999"]"#, r#"["0"]"#);
    let e = err(&text, &["particles.positions[0]", "exponent"]);
    assert_eq!(
        e,
        Error::Number {
            field: "particles.positions[0]".into(),
            text: "1e999999".into(),
            reason: NumberError::ExponentTooLarge
        }
    );
}

#[test]
fn length_mismatch() {
    let text = particles(None, r#"["0", "1", "2"]"#, r#"["0", "0"]"#);
    let e = err(&text, &["3 positions", "2 velocities"]);
    assert_eq!(
        e,
        Error::LengthMismatch {
            positions: 3,
            velocities: 2
        }
    );
}

#[test]
fn no_particles() {
    let e = err(&particles(None, "[]", "[]"), &["no particles"]);
    assert_eq!(e, Error::NoParticles);
    let e = err(&particles(Some(r#""1""#), "[]", "[]"), &["no particles"]);
    assert_eq!(e, Error::NoParticles);
}

#[test]
fn zero_radius() {
    let e = err(
        &particles(Some(r#""0""#), r#"["0"]"#, r#"["0"]"#),
        &["radius", "0"],
    );
    assert_eq!(e, Error::NonPositiveRadius { radius: "0".into() });
}

#[test]
fn negative_radius() {
    let e = err(
        &particles(Some(r#""-1/2""#), r#"["0"]"#, r#"["0"]"#),
        &["radius", "-1/2"],
    );
    assert_eq!(
        e,
        Error::NonPositiveRadius {
            radius: "-1/2".into()
        }
    );
    // A negative TOML integer too.
    let e = err(&particles(Some("-1"), r#"["0"]"#, r#"["0"]"#), &["radius"]);
    assert_eq!(
        e,
        Error::NonPositiveRadius {
            radius: "-1".into()
        }
    );
}

// ------------------------------------------------------------ macro

#[test]
fn density_above_one() {
    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "1/2", density = "2", velocity = "0" }"#],
    );
    let e = err(&text, &["macro.blocks[0]", "density 2"]);
    assert_eq!(
        e,
        Error::Density {
            block: 0,
            density: "2".into()
        }
    );
}

#[test]
fn density_zero_or_negative() {
    for (d, shown) in [("\"0\"", "0"), ("\"-1/2\"", "-1/2"), ("0", "0")] {
        let text = macro_scene(
            "4",
            &[
                r#"{ from = "0", to = "1", density = "1", velocity = "0" }"#,
                &format!(r#"{{ from = "2", to = "3", density = {d}, velocity = "0" }}"#),
            ],
        );
        let e = err(&text, &["macro.blocks[1]", shown]);
        assert_eq!(
            e,
            Error::Density {
                block: 1,
                density: shown.into()
            }
        );
    }
}

#[test]
fn total_mass_not_one() {
    let text = macro_scene(
        "4",
        &[
            HALF_A,
            r#"{ from = "1", to = "2", density = "1/4", velocity = "0" }"#,
        ],
    );
    let e = err(&text, &["total mass 3/4"]);
    assert_eq!(e, Error::Mass { mass: "3/4".into() });
}

#[test]
fn empty_block_list_has_mass_zero() {
    let e = err("[macro]\nparticles = 4\nblocks = []\n", &["total mass 0"]);
    assert_eq!(e, Error::Mass { mass: "0".into() });
}

#[test]
fn empty_block() {
    let text = macro_scene(
        "4",
        &[r#"{ from = "1", to = "1", density = "1", velocity = "0" }"#],
    );
    let e = err(&text, &["macro.blocks[0]", "empty"]);
    assert!(matches!(e, Error::Block { block: 0, .. }), "{e:?}");
}

#[test]
fn unsorted_blocks() {
    let text = macro_scene("4", &[HALF_B, HALF_A]);
    let e = err(&text, &["macro.blocks[1]", "unsorted"]);
    assert!(matches!(e, Error::Block { block: 1, .. }), "{e:?}");
}

#[test]
fn overlapping_blocks() {
    let text = macro_scene(
        "4",
        &[
            HALF_A,
            r#"{ from = "1/4", to = "3/4", density = "1", velocity = "0" }"#,
        ],
    );
    let e = err(&text, &["macro.blocks[1]", "overlaps macro.blocks[0]"]);
    assert!(matches!(e, Error::Block { block: 1, .. }), "{e:?}");
}

#[test]
fn affine_velocity_on_a_congested_block() {
    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "1", density = "1", velocity = ["0", "1"] }"#],
    );
    let e = err(&text, &["macro.blocks[0]", "hyp:u0", "constant"]);
    assert!(matches!(e, Error::Block { block: 0, .. }), "{e:?}");
}

#[test]
fn touching_congested_blocks_that_collide_give_approaching_particles() {
    // hyp:u0 is violated across the touching point; the sampling has two
    // particles in contact approaching each other.
    let text = macro_scene(
        "4",
        &[
            r#"{ from = "0", to = "1/2", density = "1", velocity = "1" }"#,
            r#"{ from = "1/2", to = "1", density = "1", velocity = "-1" }"#,
        ],
    );
    let e = err(&text, &["particles 1 and 2 (indices from 0)"]);
    assert!(matches!(e, Error::Approaching { i: 1, .. }), "{e:?}");
}

#[test]
fn macro_particles_zero() {
    let e = err(&macro_scene("0", &[HALF_A, HALF_B]), &["no particles"]);
    assert_eq!(e, Error::NoParticles);
}

#[test]
fn macro_particles_negative_or_fractional() {
    for n in ["-3", "\"3/2\"", "\"abc\"", "true"] {
        let e = err(&macro_scene(n, &[HALF_A, HALF_B]), &["macro.particles"]);
        match (n, &e) {
            ("\"abc\"", Error::Number { .. }) => {}
            (_, Error::WrongType { field, .. }) if field == "macro.particles" => {}
            _ => panic!("{n}: {e:?}"),
        }
    }
    let e = err(
        &macro_scene("64.0", &[HALF_A, HALF_B]),
        &["macro.particles"],
    );
    assert!(matches!(e, Error::Float { .. }), "{e:?}");
}

#[test]
fn macro_particles_absurdly_large() {
    let n = (MAX_MACRO_PARTICLES + 1).to_string();
    let e = err(
        &macro_scene(&n, &[HALF_A, HALF_B]),
        &["macro.particles", &n],
    );
    assert!(matches!(e, Error::Unsupported { .. }), "{e:?}");
    let e = err(
        &macro_scene("\"1e4000\"", &[HALF_A, HALF_B]),
        &["macro.particles"],
    );
    assert!(matches!(e, Error::Unsupported { .. }), "{e:?}");
}

#[test]
fn macro_sample_with_huge_numbers_is_refused_before_sampling() {
    let text = macro_scene(
        "1000000",
        &[r#"{ from = "0", to = "1e4000", density = "1e-4000", velocity = "0" }"#],
    );
    let e = err(&text, &["macro.particles", "MiB"]);
    assert!(matches!(e, Error::Unsupported { .. }), "{e:?}");
}

#[test]
fn affine_velocity_with_three_values() {
    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "2", density = "1/2", velocity = ["0", "1", "2"] }"#],
    );
    let e = err(&text, &["macro.blocks[0].velocity"]);
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
}

#[test]
fn float_in_a_block() {
    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "2", density = 0.5, velocity = "0" }"#],
    );
    let e = err(&text, &["macro.blocks[0].density", "0.5"]);
    assert_eq!(
        e,
        Error::Float {
            field: "macro.blocks[0].density".into(),
            value: "0.5".into()
        }
    );
    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "2", density = "1/2", velocity = ["0", 1.5] }"#],
    );
    let e = err(&text, &["macro.blocks[0].velocity[1]"]);
    assert!(matches!(e, Error::Float { .. }), "{e:?}");
}

// ------------------------------------------------------------ structure

#[test]
fn both_tables() {
    let text = format!(
        "{}\n{}",
        particles(None, r#"["0"]"#, r#"["0"]"#),
        macro_scene("4", &[HALF_A, HALF_B])
    );
    let e = err(&text, &["[particles]", "[macro]", "both"]);
    assert!(matches!(e, Error::SceneKind { .. }), "{e:?}");
}

#[test]
fn neither_table() {
    let e = err("name = \"empty\"\n", &["[particles]", "[macro]", "neither"]);
    assert!(matches!(e, Error::SceneKind { .. }), "{e:?}");
    let e = err("", &["neither"]);
    assert!(matches!(e, Error::SceneKind { .. }), "{e:?}");
}

#[test]
fn unknown_fields() {
    let base = particles(None, r#"["0"]"#, r#"["0"]"#);
    let e = err(
        &format!("t_ned = \"1\"\n{base}"),
        &["unknown field", "t_ned"],
    );
    assert_eq!(
        e,
        Error::UnknownField {
            field: "t_ned".into()
        }
    );

    let e = err(&format!("{base}radus = \"1\"\n"), &["particles.radus"]);
    assert_eq!(
        e,
        Error::UnknownField {
            field: "particles.radus".into()
        }
    );

    // A misspelt table is reported as unknown, not as "neither table".
    let e = err(
        "[particle]\npositions = [\"0\"]\nvelocities = [\"0\"]\n",
        &["particle"],
    );
    assert_eq!(
        e,
        Error::UnknownField {
            field: "particle".into()
        }
    );

    let text = macro_scene(
        "4",
        &[r#"{ from = "0", to = "1", densty = "1", velocity = "0" }"#],
    );
    let e = err(&text, &["macro.blocks[0].densty"]);
    assert_eq!(
        e,
        Error::UnknownField {
            field: "macro.blocks[0].densty".into()
        }
    );
}

#[test]
fn missing_fields() {
    let e = err(
        "[particles]\npositions = [\"0\"]\n",
        &["missing", "particles.velocities"],
    );
    assert_eq!(
        e,
        Error::MissingField {
            field: "particles.velocities".into()
        }
    );
    let e = err("[macro]\nparticles = 4\n", &["macro.blocks"]);
    assert_eq!(
        e,
        Error::MissingField {
            field: "macro.blocks".into()
        }
    );
    let e = err(
        &macro_scene("4", &[r#"{ from = "0", density = "1", velocity = "0" }"#]),
        &["macro.blocks[0].to"],
    );
    assert_eq!(
        e,
        Error::MissingField {
            field: "macro.blocks[0].to".into()
        }
    );
}

#[test]
fn wrong_types() {
    let e = err(
        &particles(None, "\"0\"", r#"["0"]"#),
        &["particles.positions", "array"],
    );
    assert!(
        matches!(&e, Error::WrongType { field, .. } if field == "particles.positions"),
        "{e:?}"
    );
    let e = err(
        &particles(None, r#"["0", true]"#, r#"["0", "1"]"#),
        &["particles.positions[1]", "exact number"],
    );
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
    let e = err(
        &format!("name = 3\n{}", particles(None, r#"["0"]"#, r#"["0"]"#)),
        &["`name`", "string"],
    );
    assert_eq!(
        e,
        Error::WrongType {
            field: "name".into(),
            expected: "a string"
        }
    );
    let e = err("particles = 3\n", &["`particles`", "table"]);
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
    let e = err(
        "[macro]\nparticles = 4\nblocks = \"none\"\n",
        &["macro.blocks"],
    );
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
    let e = err(
        "[macro]\nparticles = 4\nblocks = [\"0\"]\n",
        &["macro.blocks[0]"],
    );
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
    let e = err(
        &macro_scene(
            "4",
            &[r#"{ from = "0", to = "1", density = "1", velocity = true }"#],
        ),
        &["macro.blocks[0].velocity"],
    );
    assert!(matches!(e, Error::WrongType { .. }), "{e:?}");
}

#[test]
fn invalid_toml_syntax() {
    let e = err(
        "[particles\npositions = [\"0\"]\n",
        &["not valid TOML", "line 1"],
    );
    assert!(matches!(e, Error::Toml { .. }), "{e:?}");
    let e = err(
        "name = \"x\"\n[particles]\npositions = [\"0\",\nvelocities = 3\n",
        &["not valid TOML", "line"],
    );
    assert!(matches!(e, Error::Toml { .. }), "{e:?}");
    // A duplicated key is a TOML error too.
    let e = err("name = \"a\"\nname = \"b\"\n", &["line 2"]);
    assert!(matches!(e, Error::Toml { .. }), "{e:?}");
}

#[test]
fn negative_t_end() {
    let text = format!(
        "t_end = \"-1\"\n{}",
        particles(None, r#"["0"]"#, r#"["0"]"#)
    );
    let e = err(&text, &["-1", "negative"]);
    assert_eq!(e, Error::NegativeTime { t: "-1".into() });
    let text = format!("t_end = 1.5\n{}", particles(None, r#"["0"]"#, r#"["0"]"#));
    let e = err(&text, &["t_end"]);
    assert!(matches!(e, Error::Float { .. }), "{e:?}");
}

#[test]
fn long_offending_text_is_shortened() {
    let long = "9".repeat(500) + "x";
    let text = particles(None, &format!("[\"{long}\"]"), r#"["0"]"#);
    let e = err(&text, &["particles.positions[0]", "…"]);
    assert!(e.to_string().len() < 400, "{e}");
    assert!(matches!(e, Error::Number { .. }), "{e:?}");
}

// ------------------------------------------------------------ files

fn temp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sticky-scene-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn missing_file() {
    let path = temp_path("does-not-exist.toml");
    let e = scene::load(&path).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
    assert!(msg.contains("does-not-exist.toml"), "{msg}");
    assert!(msg.contains("No such file"), "{msg}");
    assert!(!msg.contains('\n'));
}

#[test]
fn file_too_large() {
    let path = temp_path("huge.toml");
    let file = std::fs::File::create(&path).unwrap();
    // Sparse: no 64 MiB actually written.
    file.set_len(scene::MAX_SCENE_BYTES + 1).unwrap();
    drop(file);
    let e = scene::load(&path).unwrap_err();
    let _ = std::fs::remove_file(&path);
    let msg = e.to_string();
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
    assert!(msg.contains("64 MiB"), "{msg}");
}

#[test]
fn file_not_utf8() {
    let path = temp_path("latin1.toml");
    std::fs::write(&path, b"name = \"caf\xe9\"\n").unwrap();
    let e = scene::load(&path).unwrap_err();
    let _ = std::fs::remove_file(&path);
    let msg = e.to_string();
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
    assert!(msg.contains("UTF-8"), "{msg}");
}

#[test]
fn directory_is_not_a_scene() {
    let e = scene::load(&std::env::temp_dir()).unwrap_err();
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
}
