//! `[particles] data = "…"`: column files beside the scene (docs/guide/scenes.md),
//! read exactly, with the same validation and clear errors.

use std::path::{Path, PathBuf};

use num_rational::BigRational;
use sticky::columns::{f64_exact, write_csv, write_npy};
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::scene::{self, particles_toml};
use sticky::{Error, Scalar};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sticky-scene-data-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn write(dir: &Path, file: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(file);
    std::fs::write(&p, bytes).expect("write");
    p
}

fn scene_with(dir: &Path, file: &str, radius: &str) -> PathBuf {
    write(
        dir,
        "scene.toml",
        format!("name = \"s\"\n[particles]\nradius = \"{radius}\"\ndata = \"{file}\"\n").as_bytes(),
    )
}

#[test]
fn csv_scene_equals_the_toml_scene() {
    let d = dir("csv");
    let mut rng = SplitMix64::new(5);
    for k in 0..20 {
        let data = initial_data(&rng.bytes(64 + 16 * k), Limits::default());
        let from_toml = scene::parse(&particles_toml(&data, None)).expect("toml");
        write(
            &d,
            "p.csv",
            write_csv(data.positions(), data.velocities()).as_bytes(),
        );
        let path = scene_with(&d, "p.csv", &data.radius().render());
        let from_csv = scene::load(&path).expect("csv scene");
        assert_eq!(from_csv.data, from_toml.data);
    }
}

#[test]
fn npy_scene_reads_every_double_exactly() {
    let d = dir("npy");
    let rows = [(0.1, 1.0), (0.5, 1.0), (2.0, -0.75)];
    write(&d, "p.npy", &write_npy(&rows));
    let s = scene::load(&scene_with(&d, "p.npy", "1/8")).expect("npy scene");
    let want: Vec<BigRational> = rows
        .iter()
        .map(|r| f64_exact(r.0).expect("finite"))
        .collect();
    assert_eq!(s.data.positions(), want.as_slice());
    assert_eq!(
        s.data.velocities()[2],
        BigRational::new((-3).into(), 4.into())
    );
    // A file numpy itself wrote, when numpy is there.
    let py = d.join("mk.py");
    std::fs::write(
        &py,
        format!(
            "import numpy as np\nnp.save({:?}, np.array([[0.1, 1.0], [0.5, 1.0], [2.0, -0.75]]))\n",
            d.join("np.npy").display().to_string()
        ),
    )
    .expect("script");
    match std::process::Command::new("python3").arg(&py).status() {
        Ok(st) if st.success() => {
            let s2 = scene::load(&scene_with(&d, "np.npy", "1/8")).expect("numpy's file");
            assert_eq!(s2.data, s.data);
        }
        _ => eprintln!("numpy not available: the numpy-written file was not checked"),
    }
}

#[test]
fn errors_name_the_file_and_the_place() {
    let d = dir("errors");
    write(&d, "bad.csv", b"position,velocity\n0,1\n1,zz\n");
    let e = scene::load(&scene_with(&d, "bad.csv", "1/8")).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, Error::DataFile { .. }), "{msg}");
    assert!(
        msg.contains("bad.csv") && msg.contains("line 3, column 3"),
        "{msg}"
    );

    let e = scene::load(&scene_with(&d, "missing.csv", "1/8")).unwrap_err();
    assert!(e.to_string().contains("missing.csv"), "{e}");

    write(&d, "p.txt", b"position,velocity\n0,1\n");
    let e = scene::load(&scene_with(&d, "p.txt", "1/8")).unwrap_err();
    assert!(e.to_string().contains(".csv"), "{e}");

    write(&d, "nan.npy", &write_npy(&[(0.0, 1.0), (f64::NAN, 1.0)]));
    let e = scene::load(&scene_with(&d, "nan.npy", "1/8")).unwrap_err();
    assert!(
        e.to_string()
            .contains("particle 1 (from 0) has a non-finite position"),
        "{e}"
    );

    // The constraints are those of every scene.
    write(&d, "overlap.csv", b"position,velocity\n0,0\n1/10,0\n");
    let e = scene::load(&scene_with(&d, "overlap.csv", "1/8")).unwrap_err();
    assert!(matches!(e, Error::Overlap { i: 0, .. }), "{e}");

    // One source of columns, and a folder to read it from.
    let both = "[particles]\ndata = \"p.csv\"\npositions = [\"0\"]\n";
    let e = scene::parse_in(both, Some(&d)).unwrap_err();
    assert!(e.to_string().contains("both `data` and `positions`"), "{e}");
    let e = scene::parse("[particles]\ndata = \"p.csv\"\n").unwrap_err();
    assert!(e.to_string().contains("load the scene from a file"), "{e}");
    let e = scene::parse_in("[particles]\ndata = 3\n", Some(&d)).unwrap_err();
    assert!(matches!(e, Error::WrongType { .. }), "{e}");
}
