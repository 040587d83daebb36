//! The guards against hostile sizes (issue 13, part 4): a cap on the digits
//! of one number, and an up-front refusal of data whose common denominators
//! make the exact answer take too long. Small versions of the two hostile
//! inputs (a 2,000,000-digit position; 20,000 velocities with 4,000-digit
//! denominators) that go through the same guards, with the caps lowered by
//! their environment variables.

use std::path::PathBuf;
use std::process::{Command, Output};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::One;

use sticky::rational::{parse_exact, NumberError, MAX_DIGITS};
use sticky::solver::work::{check_work, work_estimate, MAX_WORK};
use sticky::InitialData;

const STICKY: &str = env!("CARGO_BIN_EXE_sticky");

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sticky-guards-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn sticky(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(STICKY);
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("sticky runs")
}

#[test]
fn a_number_past_the_digit_cap_is_refused() {
    let long = format!("1{}", "0".repeat(MAX_DIGITS));
    assert_eq!(
        parse_exact(&long),
        Err(NumberError::TooManyDigits {
            digits: MAX_DIGITS + 1,
            cap: MAX_DIGITS
        })
    );
    let half = "7".repeat(MAX_DIGITS / 2);
    assert!(parse_exact(&format!("{half}/{half}")).is_ok());
    assert!(parse_exact(&format!("{half}/{half}9")).is_err());
    let e = parse_exact(&long).unwrap_err().to_string();
    assert!(
        e.contains("100000") && e.contains("STICKY_MAX_DIGITS"),
        "{e}"
    );
}

#[test]
fn the_digit_cap_names_the_place_and_can_be_changed() {
    let d = dir("digits");
    // TOML: the field; CSV: line and column.
    let toml = d.join("t.toml");
    std::fs::write(
        &toml,
        "[particles]\nradius = \"1/4\"\npositions = [\"0\", \"1234567\"]\nvelocities = [\"1\", \"-1\"]\n",
    )
    .unwrap();
    std::fs::write(d.join("c.csv"), "position,velocity\n0,1\n1,-1/1234567\n").unwrap();
    let csv = d.join("c.toml");
    std::fs::write(&csv, "[particles]\nradius = \"1/4\"\ndata = \"c.csv\"\n").unwrap();
    let cap = [("STICKY_MAX_DIGITS", "6")];
    let o = sticky(
        &["run", toml.to_str().unwrap(), "--at", "1/3", "--json"],
        &cap,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(o.stdout.is_empty());
    assert!(
        err.contains("particles.positions[1]")
            && err.contains("7 digits")
            && err.contains("cap of 6"),
        "{err}"
    );
    let o = sticky(
        &["run", csv.to_str().unwrap(), "--at", "1/3", "--json"],
        &cap,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("line 3, column 3") && err.contains("cap of 6"),
        "{err}"
    );
    // Under the default cap both run.
    for p in [&toml, &csv] {
        let o = sticky(&["run", p.to_str().unwrap(), "--at", "1/3", "--json"], &[]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn huge_common_denominators_are_refused_up_front() {
    // Two particles with a denominator of 2^(64·16384): 2 · 16384² > 2^29.
    let q = |n: i64, bits: usize| BigRational::new(BigInt::from(n), BigInt::one() << bits);
    let big = InitialData::new(
        q(1, 2),
        vec![q(0, 0), q(1, 0)],
        vec![q(1, 64 * 16384), q(-1, 0)],
    )
    .unwrap();
    assert!(work_estimate(&big) > MAX_WORK);
    let e = check_work(&big).unwrap_err().to_string();
    assert!(e.contains("STICKY_MAX_WORK") && e.contains("N = 2"), "{e}");
    let fine = InitialData::new(
        q(1, 2),
        vec![q(0, 0), q(1, 0)],
        vec![q(1, 64 * 1000), q(-1, 0)],
    )
    .unwrap();
    assert!(check_work(&fine).is_ok());
    // The command line: `events` and `run` refuse, with the cap lowered to
    // what this small scene needs minus one; raised, they run.
    let d = dir("work");
    let mut csv = String::from("position,velocity\n");
    for i in 0..200 {
        csv.push_str(&format!(
            "{i},{}/{}{}\n",
            1 - 2 * (i % 2),
            i + 2,
            "0".repeat(40)
        ));
    }
    std::fs::write(d.join("w.csv"), csv).unwrap();
    let scene = d.join("w.toml");
    std::fs::write(&scene, "[particles]\nradius = \"1/4\"\ndata = \"w.csv\"\n").unwrap();
    let s = scene.to_str().unwrap();
    // 200 particles, denominators of 2 or 3 words each, but their common
    // denominator lcm(2, …, 201) · 10^40 has 431 bits (7 words), which the
    // integer engines scale to: 200 · 49 = 9800.
    // `run` with `--engine kernel` forces the common-denominator engine;
    // `events` has only the event merge. (With `auto`, `run` falls back to
    // the blockwise projection on local denominators: below.)
    for args in [
        vec!["events", s],
        vec!["run", s, "--at", "1", "--json", "--engine", "kernel"],
    ] {
        let o = sticky(&args, &[("STICKY_MAX_WORK", "9799")]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains("N = 200")
                && err.contains("common denominator of 431 bits")
                && err.contains("STICKY_MAX_WORK"),
            "{err}"
        );
        let o = sticky(&args, &[("STICKY_MAX_WORK", "9800")]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    // `auto`: the work check refuses the kernel, the Solver falls back to
    // the blockwise projection (200 particles over a largest single
    // denominator of 3 words: 200 · 9 = 1800), says so with `--explain`,
    // and answers the same bytes as the kernel; below 1800 both are
    // refused, with the kernel's message.
    let auto = ["run", s, "--at", "1", "--json", "--explain"];
    let kernel = sticky(
        &["run", s, "--at", "1", "--json", "--engine", "kernel"],
        &[("STICKY_MAX_WORK", "9800")],
    );
    let o = sticky(&auto, &[("STICKY_MAX_WORK", "9799")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.starts_with("engine: blockwise (N = 200,")
            && err.contains("the cost model chose kernel, which the work check refuses"),
        "{err}"
    );
    assert_eq!(o.stdout, kernel.stdout);
    let o = sticky(&auto, &[("STICKY_MAX_WORK", "1799")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("common denominator of 431 bits"), "{err}");
    assert!(sticky(&auto, &[("STICKY_MAX_WORK", "1800")])
        .status
        .success());
    std::fs::remove_dir_all(&d).unwrap();
}
