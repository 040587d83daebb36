//! Plain-text tables shared by the commands that print for a person.

use std::io::{self, Write};

use num_rational::BigRational;

use sticky::cluster::Cluster;
use sticky::trajectory::Trajectory;
use sticky::Scalar;

/// The particles of a cluster, indexed from 0 and inclusive: `3` or `0–6`.
pub fn particle_range(c: &Cluster) -> String {
    if c.size == 1 {
        format!("{}", c.first)
    } else {
        format!("{}–{}", c.first, c.end() - 1)
    }
}

/// What every text output that prints particle indices says about them.
pub const INDICES_FROM_0: &str = "(particle indices from 0)";

/// Left-aligned columns, two spaces apart.
pub fn write_table(out: &mut impl Write, header: &[&str], rows: &[Vec<String>]) -> io::Result<()> {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: Vec<&str>| -> String {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c}{}", " ".repeat(w - c.chars().count())))
            .collect();
        format!("  {}", padded.join("  ").trim_end())
    };
    writeln!(out, "{}", line(header.to_vec()))?;
    for row in rows {
        writeln!(out, "{}", line(row.iter().map(String::as_str).collect()))?;
    }
    Ok(())
}

pub fn write_events_table(out: &mut impl Write, traj: &Trajectory<BigRational>) -> io::Result<()> {
    let n = traj.impulses().len();
    if n == 0 {
        return writeln!(out, "0 collisions");
    }
    writeln!(
        out,
        "{n} collision{}   {INDICES_FROM_0}",
        if n == 1 { "" } else { "s" }
    )?;
    let rows: Vec<Vec<String>> = traj
        .impulses()
        .iter()
        .map(|i| {
            vec![
                i.t.render(),
                particle_range(&i.cluster),
                i.cluster.size.to_string(),
                i.parts
                    .iter()
                    .map(|p| p.size.to_string())
                    .collect::<Vec<_>>()
                    .join(" + "),
                i.velocity.render(),
            ]
        })
        .collect();
    write_table(
        out,
        &["t", "particles", "size", "parts", "velocity after"],
        &rows,
    )
}

pub fn abbreviate(items: &[String], keep: usize) -> String {
    if items.len() <= keep {
        items.join(" ")
    } else {
        format!(
            "{} … {} ({} clusters)",
            items[..keep / 2].join(" "),
            items[items.len() - keep / 2..].join(" "),
            items.len()
        )
    }
}
