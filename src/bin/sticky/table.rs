//! Plain-text tables shared by the commands that print for a person.

use std::io::{self, Write};

use num_rational::BigRational;

use sticky::cluster::Cluster;
use sticky::trajectory::Trajectory;
use sticky::Scalar;

pub fn range_1based(c: &Cluster) -> String {
    if c.size == 1 {
        format!("{}", c.first + 1)
    } else {
        format!("{}–{}", c.first + 1, c.end())
    }
}

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
    writeln!(out, "{n} collision{}", if n == 1 { "" } else { "s" })?;
    if n == 0 {
        return Ok(());
    }
    let rows: Vec<Vec<String>> = traj
        .impulses()
        .iter()
        .map(|i| {
            vec![
                i.t.render(),
                range_1based(&i.cluster),
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
