//! `sticky bench` smoke test: every method measured on a small N, JSON keys
//! as documented (timings are reports, never asserted).

use num_rational::BigRational;
use sticky::report::bench::{json, run, scene, BenchOptions};

#[test]
fn bench_reports_every_method() {
    let opts = BenchOptions {
        n: 2000,
        reps: 1,
        peers: false,
        events: true,
        memory: false,
    };
    let t = BigRational::new(1.into(), 100.into());
    let scripts = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
    let r = run(&opts, &t, &scripts);
    let text = json(&r);
    let v: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    assert_eq!(v["n"], 2000);
    for key in [
        "f64",
        "exact_int",
        "exact_bigint",
        "bigrational_naive",
        "adaptive",
        "events",
    ] {
        assert!(v["ns_per_particle"].get(key).is_some(), "missing {key}");
    }
    for key in [
        "f64",
        "exact_int",
        "exact_int_lowest",
        "exact_bigint",
        "exact_bigint_100",
        "bigrational_naive",
        "adaptive",
        "adaptive_bigdata",
        "events",
        "events_lowest",
        "events_generic",
    ] {
        assert!(
            v["ns_per_particle"][key].as_f64().is_some_and(|x| x > 0.0),
            "{key} not measured"
        );
    }
    // The bench scene is admissible and exactly N particles.
    assert_eq!(scene(777, 3).n(), 777);
}
