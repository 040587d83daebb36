//! Replays every committed fuzz input (`tests/fuzz_inputs/<target>/*`)
//! through the same code the fuzz targets run (`sticky::claims::fuzz`). A crash
//! found by `cargo fuzz` is copied here once fixed, so it stays fixed.

use std::fs;
use std::path::Path;

fn replay(target: &str, f: fn(&[u8])) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_inputs")
        .join(target);
    let mut count = 0;
    for entry in fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("directory entry").path();
        if path.is_file() && path.file_name().is_some_and(|n| n != ".gitkeep") {
            let bytes = fs::read(&path).expect("readable input");
            f(&bytes);
            count += 1;
        }
    }
    count
}

#[test]
fn replay_claims_inputs() {
    let n = replay("claims", sticky::claims::fuzz::claims);
    eprintln!("replayed {n} claims inputs");
}

#[test]
fn replay_scene_parser_inputs() {
    let n = replay("scene_parser", sticky::claims::fuzz::scene_parser);
    eprintln!("replayed {n} scene_parser inputs");
}

#[test]
fn replay_kernels_inputs() {
    let n = replay("kernels", sticky::claims::fuzz::kernels);
    eprintln!("replayed {n} kernels inputs");
}

#[test]
fn replay_lean_toml_inputs() {
    let n = replay("lean_toml", sticky::claims::fuzz::lean_toml);
    assert!(n > 0, "no lean_toml seeds");
    eprintln!("replayed {n} lean_toml inputs");
}
