//! Every shipped scene parses and validates (with its key facts checked
//! exactly), the quantile sampling of `thm:main` (i) is exact and admissible,
//! and `scene::parse` never panics on arbitrary or mutated input.

use std::path::{Path, PathBuf};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;

use sticky::quantile::{Block, BlockVelocity, MacroDatum};
use sticky::scene::{self, Scene, SceneKind};
use sticky::{Error, InitialData};

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

fn int(n: i64) -> BigRational {
    q(n, 1)
}

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn scene_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/ exists")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

fn load(name: &str) -> Scene {
    let path = scenes_dir().join(name);
    scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `x_{i+1} − x_i ≥ 2r`, and equal-or-separating velocities across contacts.
fn assert_admissible(data: &InitialData<BigRational>) {
    let two_r = data.two_r();
    let x = data.positions();
    let u = data.velocities();
    for i in 1..x.len() {
        let gap = &x[i] - &x[i - 1];
        assert!(gap >= two_r, "x_{} - x_{} = {gap} < 2r", i + 1, i);
        if gap == two_r {
            assert!(u[i] >= u[i - 1], "contact {i}/{} approaches", i + 1);
        }
    }
}

// ------------------------------------------------------------ shipped scenes

#[test]
fn every_shipped_scene_parses_and_is_documented() {
    let files = scene_files();
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for required in [
        "appendix-c-two-blocks.toml",
        "three-cluster-simultaneous.toml",
        "random-1000.toml",
        "riemann-compression.toml",
        "riemann-expansion-affine.toml",
        "collision-cascade.toml",
    ] {
        assert!(names.iter().any(|n| n == required), "missing {required}");
    }
    for path in &files {
        let scene = scene::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let stem = path.file_stem().unwrap().to_string_lossy();
        assert_eq!(scene.name.as_deref(), Some(&*stem), "{}", path.display());
        let description = scene.description.as_deref().unwrap_or("");
        assert!(
            description.len() > 40,
            "{}: description too short",
            path.display()
        );
        let t_end = scene.t_end.clone().expect("t_end given");
        assert!(t_end > BigRational::zero(), "{}", path.display());
        assert_admissible(&scene.data);
        if let SceneKind::Macro { datum, particles } = &scene.kind {
            assert_eq!(scene.n(), *particles);
            assert_eq!(*scene.data.radius(), q(1, 2 * *particles as i64));
            let n = int(*particles as i64);
            for (k, x) in scene.data.positions().iter().enumerate() {
                let w = int(k as i64 + 1) / &n;
                assert_eq!(*x, datum.x0(&w));
                assert_eq!(datum.cdf(x), w, "F(x_i) = i/N");
            }
        }
    }
}

#[test]
fn appendix_c_scene_is_the_papers_datum() {
    let scene = load("appendix-c-two-blocks.toml");
    assert_eq!(scene.n(), 16);
    assert_eq!(*scene.data.radius(), q(1, 32));
    assert_eq!(scene.t_end, Some(q(1, 2)));
    let SceneKind::Macro { datum, particles } = &scene.kind else {
        panic!("macro scene expected");
    };
    assert_eq!(*particles, 16);
    assert_eq!(datum.blocks().len(), 2);
    for i in 1..=16i64 {
        let k = (i - 1) as usize;
        let (x, u) = if i <= 8 {
            (q(i, 16), int(1))
        } else {
            (q(i, 16) + q(1, 4), int(-1))
        };
        assert_eq!(scene.data.positions()[k], x, "x_{i}");
        assert_eq!(scene.data.velocities()[k], u, "u_{i}");
    }
    // X⁰(w) = w on [0, 1/2], w + η on (1/2, 1] with η = 1/4 (app:uniqueness).
    for (w, x) in [
        (q(1, 4), q(1, 4)),
        (q(1, 2), q(1, 2)),
        (q(3, 4), int(1)),
        (int(1), q(5, 4)),
    ] {
        assert_eq!(datum.x0(&w), x, "X0({w})");
    }
    // Collision time t* = η/2: gap x_9 − x_8 − 2r closes at speed 2.
    let gap = &scene.data.positions()[8] - &scene.data.positions()[7] - scene.data.two_r();
    assert_eq!(gap / int(2), q(1, 8));
    // The embedded default scene is this one.
    assert_eq!(scene::default_scene().unwrap(), scene);
    assert_eq!(
        scene::DEFAULT_SCENE,
        std::fs::read_to_string(scenes_dir().join("appendix-c-two-blocks.toml")).unwrap()
    );
}

#[test]
fn riemann_compression_spacing_is_two_over_n() {
    let scene = load("riemann-compression.toml");
    assert_eq!(scene.n(), 64);
    assert_eq!(*scene.data.radius(), q(1, 128));
    for i in 1..=64i64 {
        let k = (i - 1) as usize;
        assert_eq!(scene.data.positions()[k], q(i, 32), "x_{i} = 2i/N");
        assert_eq!(
            scene.data.velocities()[k],
            int(if i <= 32 { 1 } else { -1 })
        );
    }
}

#[test]
fn riemann_expansion_affine_has_exact_affine_velocities() {
    let scene = load("riemann-expansion-affine.toml");
    assert_eq!(scene.n(), 32);
    let SceneKind::Macro { datum, .. } = &scene.kind else {
        panic!("macro scene expected");
    };
    assert!(matches!(
        datum.blocks()[0].velocity,
        BlockVelocity::Affine(..)
    ));
    assert!(matches!(
        datum.blocks()[1].velocity,
        BlockVelocity::Constant(..)
    ));
    for i in 1..=32i64 {
        let k = (i - 1) as usize;
        let (x, u) = if i <= 16 {
            (q(i, 16), int(-1) + q(i, 8))
        } else {
            (q(3, 2) + q(i - 16, 32), q(-1, 2))
        };
        assert_eq!(scene.data.positions()[k], x, "x_{i}");
        assert_eq!(scene.data.velocities()[k], u, "u_{i}");
    }
    // First collision, particles 16 and 17, at t = 1/3.
    let x = scene.data.positions();
    let u = scene.data.velocities();
    let t = (&x[16] - &x[15] - scene.data.two_r()) / (&u[15] - &u[16]);
    assert_eq!(t, q(1, 3));
}

/// Shifted positions and velocities of the particles `range` (0-based).
fn cluster_motion(
    data: &InitialData<BigRational>,
    range: std::ops::Range<usize>,
) -> (BigRational, BigRational) {
    let xt = data.shifted_positions();
    let n = int(range.len() as i64);
    let mut sx = BigRational::zero();
    let mut su = BigRational::zero();
    for i in range {
        sx += &xt[i];
        su += &data.velocities()[i];
    }
    (sx / &n, su / n)
}

#[test]
fn three_clusters_meet_at_one_instant() {
    let scene = load("three-cluster-simultaneous.toml");
    let data = &scene.data;
    assert_eq!(data.n(), 8);
    assert_eq!(*data.radius(), q(1, 2));
    assert_eq!(scene.kind, SceneKind::Particles);
    // Clusters A = 1..3, B = 4..5, C = 6..7 in contact with equal velocities.
    let xt = data.shifted_positions();
    let u = data.velocities();
    for (a, b) in [(0, 1), (1, 2), (3, 4), (5, 6)] {
        assert_eq!(xt[a], xt[b]);
        assert_eq!(u[a], u[b]);
    }
    let meet =
        |l: (BigRational, BigRational), r: (BigRational, BigRational)| (r.0 - l.0) / (l.1 - r.1);
    let a = cluster_motion(data, 0..3);
    let b = cluster_motion(data, 3..5);
    let c = cluster_motion(data, 5..7);
    let d = cluster_motion(data, 7..8);
    let t1 = meet(a.clone(), b.clone());
    assert_eq!(t1, q(1, 2));
    assert_eq!(meet(b, c.clone()), q(1, 2), "simultaneous");
    // C and D move at the same velocity: D cannot reach C before t1.
    assert_eq!(c.1, d.1);
    assert!(d.0 > c.0);
    let abc = cluster_motion(data, 0..7);
    assert_eq!(abc.1, int(1));
    assert_eq!(meet(abc, d), int(2));
    assert_eq!(cluster_motion(data, 0..8).1, q(3, 4));
}

#[test]
fn collision_cascade_has_a_separating_contact() {
    let scene = load("collision-cascade.toml");
    let data = &scene.data;
    assert_eq!(data.n(), 6);
    let x = data.positions();
    let u = data.velocities();
    assert_eq!(&x[5] - &x[4], data.two_r());
    assert!(u[5] > u[4]);
    // Exactly one initial contact.
    let contacts = (1..6)
        .filter(|&i| &x[i] - &x[i - 1] == data.two_r())
        .count();
    assert_eq!(contacts, 1);
}

#[test]
fn random_1000_scene() {
    let scene = load("random-1000.toml");
    let data = &scene.data;
    assert_eq!(data.n(), 1000);
    assert_eq!(*data.radius(), q(1, 2000));
    let x = data.positions();
    let u = data.velocities();
    let contacts: Vec<usize> = (1..1000)
        .filter(|&i| &x[i] - &x[i - 1] == data.two_r())
        .collect();
    assert!(contacts.len() > 50, "{} initial contacts", contacts.len());
    for &i in &contacts {
        assert_eq!(u[i], u[i - 1], "initial clusters move together");
    }
    let eighth = int(8);
    for v in u {
        assert!((v * &eighth).is_integer() && v.abs() <= int(5));
    }
}

// ------------------------------------------------------------ particles scenes

#[test]
fn default_radius_is_one_over_two_n() {
    let s = scene::parse("[particles]\npositions = [0, \"1/2\", 2]\nvelocities = [1, 2, \"-3\"]\n")
        .unwrap();
    assert_eq!(*s.data.radius(), q(1, 6));
    assert_eq!(s.data.positions(), &[int(0), q(1, 2), int(2)]);
    assert_eq!(s.data.velocities(), &[int(1), int(2), int(-3)]);
    assert_eq!(s.name, None);
    assert_eq!(s.t_end, None);
}

#[test]
fn every_number_form_is_read_exactly() {
    let s = scene::parse(
        "t_end = 0\n[particles]\nradius = \"1e-3\"\npositions = [\"-7/4\", \"1.5e-3\", \"0.125\", \"+2\", 3]\nvelocities = [\"0\", \"0\", \"0\", \"0\", \"0\"]\n",
    )
    .unwrap();
    assert_eq!(*s.data.radius(), q(1, 1000));
    assert_eq!(
        s.data.positions(),
        &[q(-7, 4), q(3, 2000), q(1, 8), int(2), int(3)]
    );
    assert_eq!(s.t_end, Some(int(0)));
}

#[test]
fn blocks_as_array_of_tables_are_accepted() {
    let s = scene::parse(
        "[macro]\nparticles = 4\n[[macro.blocks]]\nfrom = 0\nto = 1\ndensity = 1\nvelocity = 0\n",
    )
    .unwrap();
    assert_eq!(s.data.positions(), &[q(1, 4), q(1, 2), q(3, 4), int(1)]);
}

// ------------------------------------------------------------ quantile

fn constant(from: BigRational, to: BigRational, density: BigRational, u: BigRational) -> Block {
    Block {
        from,
        to,
        density,
        velocity: BlockVelocity::Constant(u),
    }
}

/// Blocks with a gap: [0, 1/4) density 1 (u = 2), gap, [1, 2) density 1/4
/// (u affine 0 → 4), [2, 3) density 1/2 (u = −1), touching the previous one.
fn gapped() -> MacroDatum {
    MacroDatum::new(vec![
        constant(int(0), q(1, 4), int(1), int(2)),
        Block {
            from: int(1),
            to: int(2),
            density: q(1, 4),
            velocity: BlockVelocity::Affine(int(0), int(4)),
        },
        constant(int(2), int(3), q(1, 2), int(-1)),
    ])
    .unwrap()
}

#[test]
fn mass_breakpoints_accumulate() {
    assert_eq!(
        gapped().mass_breakpoints(),
        vec![int(0), q(1, 4), q(1, 2), int(1)]
    );
}

#[test]
fn x0_and_u0_at_breakpoints_are_left_continuous() {
    let d = gapped();
    // m_1 = 1/4: the end of block 1 (not the start of block 2 after the gap).
    assert_eq!(d.x0(&q(1, 4)), q(1, 4));
    assert_eq!(d.u0(&q(1, 4)), int(2));
    // Just after m_1 the map has jumped over the gap [1/4, 1).
    assert_eq!(d.x0(&(q(1, 4) + q(1, 1000))), int(1) + q(4, 1000));
    // m_2 = 1/2: the end of block 2, where the affine velocity is 4.
    assert_eq!(d.x0(&q(1, 2)), int(2));
    assert_eq!(d.u0(&q(1, 2)), int(4));
    // X⁰(1) = the end of the last block.
    assert_eq!(d.x0(&int(1)), int(3));
    assert_eq!(d.u0(&int(1)), int(-1));
}

#[test]
fn x0_and_u0_inside_blocks() {
    let d = gapped();
    assert_eq!(d.x0(&q(1, 8)), q(1, 8));
    assert_eq!(d.u0(&q(1, 8)), int(2));
    // Block 2: X⁰(w) = 1 + (w − 1/4)·4, u = 4(x − 1).
    assert_eq!(d.x0(&q(3, 8)), int(1) + q(1, 2));
    assert_eq!(d.u0(&q(3, 8)), int(2));
    assert_eq!(d.x0(&q(5, 16)), q(5, 4));
    assert_eq!(d.u0(&q(5, 16)), int(1));
    // Block 3: X⁰(w) = 2 + 2(w − 1/2).
    assert_eq!(d.x0(&q(3, 4)), q(5, 2));
    assert_eq!(d.u0(&q(3, 4)), int(-1));
}

#[test]
fn eulerian_view_is_consistent() {
    let d = gapped();
    assert_eq!(d.density_at(&q(1, 2)), int(0));
    assert_eq!(d.density_at(&int(1)), q(1, 4));
    assert_eq!(d.density_at(&int(3)), int(0));
    assert_eq!(d.velocity_at(&q(3, 2)), Some(int(2)));
    assert_eq!(d.velocity_at(&int(-1)), None);
    assert_eq!(d.cdf(&int(-1)), int(0));
    assert_eq!(d.cdf(&q(1, 2)), q(1, 4));
    assert_eq!(d.cdf(&int(10)), int(1));
    for k in 1..=64 {
        let w = q(k, 64);
        assert_eq!(d.cdf(&d.x0(&w)), w, "F(X0(w)) = w");
    }
}

#[test]
fn sampling_is_admissible_with_spacing_at_least_one_over_n() {
    let d = gapped();
    for n in [1usize, 2, 3, 4, 7, 16, 100, 257] {
        let data = d.sample(n).unwrap();
        assert_eq!(data.n(), n);
        assert_eq!(*data.radius(), q(1, 2 * n as i64));
        let inv_n = q(1, n as i64);
        for i in 1..n {
            assert!(&data.positions()[i] - &data.positions()[i - 1] >= inv_n);
        }
        for (k, (x, u)) in data.positions().iter().zip(data.velocities()).enumerate() {
            let w = q(k as i64 + 1, n as i64);
            assert_eq!(*x, d.x0(&w));
            assert_eq!(*u, d.u0(&w));
        }
    }
    assert_eq!(d.sample(0).unwrap_err(), Error::NoParticles);
}

#[test]
fn sampling_the_riemann_datum() {
    let d = MacroDatum::new(vec![
        constant(int(0), int(1), q(1, 2), int(1)),
        constant(int(1), int(2), q(1, 2), int(-1)),
    ])
    .unwrap();
    for n in [2i64, 10, 64, 65] {
        let data = d.sample(n as usize).unwrap();
        assert_eq!(data.n(), n as usize);
        for (k, x) in data.positions().iter().enumerate() {
            let i = k as i64 + 1;
            assert_eq!(*x, q(2 * i, n), "x_{i} = 2i/N");
            let expected = if 2 * i <= n { 1 } else { -1 };
            assert_eq!(data.velocities()[k], int(expected));
        }
    }
}

#[test]
fn macro_datum_errors() {
    let ok = |u| constant(int(0), int(1), int(1), u);
    assert!(matches!(MacroDatum::new(vec![]), Err(Error::Mass { .. })));
    assert!(matches!(
        MacroDatum::new(vec![constant(int(0), int(2), q(3, 2), int(0))]),
        Err(Error::Density { block: 0, .. })
    ));
    assert!(matches!(
        MacroDatum::new(vec![ok(int(0)), constant(int(-1), int(0), int(1), int(0))]),
        Err(Error::Block { block: 1, reason }) if reason.contains("unsorted")
    ));
    assert!(matches!(
        MacroDatum::new(vec![Block {
            from: int(0),
            to: int(1),
            density: int(1),
            velocity: BlockVelocity::Affine(int(0), int(1)),
        }]),
        Err(Error::Block { block: 0, reason }) if reason.contains("hyp:u0")
    ));
    // An "affine" velocity with equal end values is constant: allowed.
    let d = MacroDatum::new(vec![Block {
        from: int(0),
        to: int(1),
        density: int(1),
        velocity: BlockVelocity::Affine(int(3), int(3)),
    }])
    .unwrap();
    assert_eq!(d.u0(&q(1, 2)), int(3));
    assert!(MacroDatum::new(vec![ok(int(0))]).is_ok());
}

// ------------------------------------------------------------ properties

/// A small random rational p/q, q in 1..=12.
fn small_rational() -> impl Strategy<Value = BigRational> {
    (-40i64..=40, 1i64..=12).prop_map(|(p, d)| q(p, d))
}

/// Random valid-shaped blocks: positive lengths and gaps, densities in
/// (0, 1], lengths rescaled so that the total mass is exactly 1.
fn random_blocks() -> impl Strategy<Value = Vec<Block>> {
    prop::collection::vec(
        (
            1i64..=8,
            0i64..=3,
            1i64..=6,
            any::<bool>(),
            small_rational(),
            small_rational(),
        ),
        1..6,
    )
    .prop_map(|raw| {
        // density = k/6, length = len, gap before = gap.
        let mass: BigRational = raw
            .iter()
            .map(|(len, _, k, _, _, _)| q(*k, 6) * int(*len))
            .fold(BigRational::zero(), |a, b| a + b);
        let scale = BigRational::one() / mass;
        let mut at = int(-3);
        raw.into_iter()
            .map(|(len, gap, k, affine, a, b)| {
                let from = &at + int(gap) * &scale;
                let to = &from + int(len) * &scale;
                at = to.clone();
                let density = q(k, 6);
                let velocity = if affine && k < 6 {
                    BlockVelocity::Affine(a, b)
                } else {
                    BlockVelocity::Constant(a)
                };
                Block {
                    from,
                    to,
                    density,
                    velocity,
                }
            })
            .collect()
    })
}

fn toml_number(x: &BigRational) -> String {
    format!("\"{x}\"")
}

fn blocks_toml(blocks: &[Block], n: usize) -> String {
    let mut s = format!("name = \"random\"\nt_end = \"1\"\n[macro]\nparticles = {n}\nblocks = [\n");
    for b in blocks {
        let v = match &b.velocity {
            BlockVelocity::Constant(c) => toml_number(c),
            BlockVelocity::Affine(a, c) => format!("[{}, {}]", toml_number(a), toml_number(c)),
        };
        s += &format!(
            "  {{ from = {}, to = {}, density = {}, velocity = {v} }},\n",
            toml_number(&b.from),
            toml_number(&b.to),
            toml_number(&b.density)
        );
    }
    s + "]\n"
}

/// The macro particle count a (mutated) text asks for, if it is a valid
/// TOML integer.
fn macro_particles(text: &str) -> Option<i64> {
    let table = text.parse::<toml::Table>().ok()?;
    table.get("macro")?.get("particles")?.as_integer()
}

fn shipped_texts() -> Vec<String> {
    scene_files()
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

/// One edit of a text: delete, insert or replace a short byte range
/// (applied at char boundaries).
#[derive(Debug, Clone)]
enum Edit {
    Delete(usize, usize),
    Insert(usize, String),
    Replace(usize, usize, String),
}

fn edit() -> impl Strategy<Value = Edit> {
    let snippet = prop_oneof![
        "[-0-9./eE+\"\\[\\]{}=,# a-z\n]{1,6}",
        Just("0.5".to_string()),
        Just("\"1/0\"".to_string()),
        Just("[particles]\n".to_string()),
        Just("[macro]\n".to_string()),
        Just("velocity = [\"1\", \"2\"]".to_string()),
        Just("density = \"2\"".to_string()),
        any::<String>().prop_map(|s| s.chars().take(4).collect()),
    ];
    prop_oneof![
        (any::<usize>(), 1usize..40).prop_map(|(at, len)| Edit::Delete(at, len)),
        (any::<usize>(), snippet.clone()).prop_map(|(at, s)| Edit::Insert(at, s)),
        (any::<usize>(), 1usize..8, snippet).prop_map(|(at, len, s)| Edit::Replace(at, len, s)),
    ]
}

fn floor_boundary(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn apply(text: &str, e: &Edit) -> String {
    let mut s = text.to_string();
    match e {
        Edit::Delete(at, len) | Edit::Replace(at, len, _) => {
            let a = floor_boundary(&s, at % (s.len() + 1));
            let b = floor_boundary(&s, a + len);
            let insert = match e {
                Edit::Replace(_, _, r) => r.as_str(),
                _ => "",
            };
            s.replace_range(a..b, insert);
        }
        Edit::Insert(at, ins) => {
            let a = floor_boundary(&s, at % (s.len() + 1));
            s.insert_str(a, ins);
        }
    }
    s
}

fn check_parse_result(text: &str) {
    match scene::parse(text) {
        Ok(s) => assert_admissible(&s.data),
        Err(e) => {
            let msg = e.to_string();
            assert!(!msg.is_empty());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn parse_never_panics_on_arbitrary_strings(text in any::<String>()) {
        check_parse_result(&text);
    }

    #[test]
    fn parse_never_panics_on_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        check_parse_result(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn parse_never_panics_on_toml_like_text(
        text in "([a-z_.\\[\\]]{0,12} ?= ?(\"[-0-9/.e]{0,6}\"|[-0-9.e]{1,5}|\\[[-0-9\", /]{0,16}\\]|\\{[a-z =\",0-9/]{0,30}\\})?\n){0,8}"
    ) {
        check_parse_result(&text);
    }

    #[test]
    fn parse_never_panics_on_mutated_scenes(
        which in any::<prop::sample::Index>(),
        edits in prop::collection::vec(edit(), 1..4),
    ) {
        let texts = shipped_texts();
        let mut text = texts[which.index(texts.len())].clone();
        for e in &edits {
            text = apply(&text, e);
        }
        // Keep the test fast: a mutation may legitimately ask for millions
        // of particles, which is valid but slow to sample.
        prop_assume!(!matches!(macro_particles(&text), Some(n) if n > 100_000));
        check_parse_result(&text);
    }

    #[test]
    fn random_macro_data_sample_exactly(blocks in random_blocks(), n in 1usize..40) {
        let text = blocks_toml(&blocks, n);
        let datum = MacroDatum::new(blocks).expect("valid by construction");
        match scene::parse(&text) {
            Ok(scene) => {
                prop_assert_eq!(scene.n(), n);
                prop_assert_eq!(scene.data.radius().clone(), q(1, 2 * n as i64));
                let inv_n = q(1, n as i64);
                let x = scene.data.positions();
                for i in 1..n {
                    prop_assert!(&x[i] - &x[i - 1] >= inv_n);
                }
                for (k, (xi, ui)) in x.iter().zip(scene.data.velocities()).enumerate() {
                    let w = q(k as i64 + 1, n as i64);
                    prop_assert_eq!(xi, &datum.x0(&w));
                    prop_assert_eq!(ui, &datum.u0(&w));
                    prop_assert_eq!(datum.cdf(xi), w);
                }
                prop_assert_eq!(scene.kind, SceneKind::Macro { datum, particles: n });
            }
            // A block touching a congested block on its left with a faster
            // velocity at the junction: u⁰ jumps down where ρ⁰ becomes 1,
            // and the sampling reports the approaching contact.
            Err(Error::Approaching { .. }) => {
                let jump_into_congestion = datum.blocks().windows(2).any(|w| {
                    w[0].to == w[1].from
                        && w[1].density == BigRational::one()
                        && w[0].velocity_at(&w[0].to) > w[1].velocity_at(&w[1].from)
                });
                prop_assert!(jump_into_congestion);
            }
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }
}
