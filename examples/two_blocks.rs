//! Scene → initial data → trajectory → state at a time.
//!
//! Reads a scene written inline (the format of `scenes/*.toml`), computes the
//! whole sticky history exactly, and prints every collision and the state
//! after the last one.
//!
//! ```text
//! cargo run --example two_blocks
//! ```

use num_rational::BigRational;
use sticky::{Scalar, Trajectory};

const SCENE: &str = r#"
name = "two blocks"
[particles]
radius = "1/8"
positions  = ["0", "1/4", "1", "5/4"]
velocities = ["1", "1", "-1", "-1"]
"#;

fn main() -> Result<(), sticky::Error> {
    let scene = sticky::scene::parse(SCENE)?;
    let traj = Trajectory::new(scene.data.clone());
    for impulse in traj.impulses() {
        println!(
            "t = {}: particles {}..{} stick together ({} parts), velocity {}",
            impulse.t.render(),
            impulse.cluster.first + 1,
            impulse.cluster.end(),
            impulse.parts.len(),
            impulse.velocity.render(),
        );
    }
    // Every time and value is an exact rational (`sticky::rational::parse_exact`
    // reads "3/2", "0.125" or "1e-3" exactly from text).
    let t = BigRational::new(1.into(), 2.into());
    let state = traj.at(&t)?;
    let show = |v: &[_]| v.iter().map(Scalar::render).collect::<Vec<_>>().join(", ");
    println!("x({}) = [{}]", t.render(), show(&state.positions));
    println!("u({}) = [{}]", t.render(), show(&state.velocities));
    println!("λ({}) = [{}]", t.render(), show(&state.multipliers));
    Ok(())
}
