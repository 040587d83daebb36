//! Grids: a table of coloured markers (rows × columns of cells, each with
//! one square per outcome) with a colour legend.

use std::fmt;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::font::FAMILY;
use super::Grid;

const CELL_W: u32 = 150;
const CELL_H: u32 = 46;
const TITLE_H: u32 = 44;
const HEADER_H: u32 = 36;
const LEGEND_LINE: u32 = 26;
const MARGIN: u32 = 16;

/// Approximate text width in pixels (0.6 em per character).
pub(super) fn text_width(s: &str, size: u32) -> u32 {
    (s.chars().count() as u32 * size * 6).div_ceil(10)
}

fn label_width(grid: &Grid) -> u32 {
    grid.rows
        .iter()
        .map(|r| text_width(r, 14))
        .max()
        .unwrap_or(0)
        + 2 * MARGIN
}

fn legend_lines(grid: &Grid, width: u32) -> Vec<Vec<usize>> {
    let mut lines: Vec<Vec<usize>> = Vec::new();
    let mut used = width; // forces a first line
    for (i, (name, _)) in grid.legend.iter().enumerate() {
        let w = 24 + text_width(name, 14) + 24;
        if used + w > width.saturating_sub(2 * MARGIN) || lines.is_empty() {
            lines.push(Vec::new());
            used = 0;
        }
        used += w;
        if let Some(last) = lines.last_mut() {
            last.push(i);
        }
    }
    lines
}

pub(super) fn grid_size(grid: &Grid) -> (u32, u32) {
    let cols = grid.columns.len().max(1) as u32;
    let rows = grid.rows.len().max(1) as u32;
    let width =
        (label_width(grid) + cols * CELL_W + MARGIN).max(text_width(&grid.title, 20) + 2 * MARGIN);
    let legend = legend_lines(grid, width).len() as u32;
    let height = TITLE_H + HEADER_H + rows * CELL_H + MARGIN + legend * LEGEND_LINE + MARGIN;
    (width, height)
}

pub(super) fn grid_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    grid: &Grid,
) -> Result<(), String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (width, _) = grid_size(grid);
    let left = label_width(grid) as i32;
    let font = |size: u32, h: HPos, v: VPos| {
        TextStyle::from((FAMILY, size).into_font())
            .color(&BLACK)
            .pos(Pos::new(h, v))
    };
    root.draw(&Text::new(
        grid.title.clone(),
        (width as i32 / 2, (TITLE_H / 2) as i32),
        font(20, HPos::Center, VPos::Center),
    ))
    .map_err(|e| err(&e))?;
    let top = (TITLE_H + HEADER_H) as i32;
    let (cw, ch) = (CELL_W as i32, CELL_H as i32);
    for (j, name) in grid.columns.iter().enumerate() {
        let x = left + cw * j as i32 + cw / 2;
        root.draw(&Text::new(
            name.clone(),
            (x, (TITLE_H + HEADER_H / 2) as i32),
            font(14, HPos::Center, VPos::Center),
        ))
        .map_err(|e| err(&e))?;
    }
    let line = RGBColor(200, 200, 200);
    for (i, name) in grid.rows.iter().enumerate() {
        let y = top + ch * i as i32;
        root.draw(&Text::new(
            name.clone(),
            (left - MARGIN as i32 / 2, y + ch / 2),
            font(14, HPos::Right, VPos::Center),
        ))
        .map_err(|e| err(&e))?;
    }
    let (rows, cols) = (grid.rows.len() as i32, grid.columns.len() as i32);
    for i in 0..=rows {
        let y = top + ch * i;
        root.draw(&PathElement::new(
            vec![(left, y), (left + cw * cols, y)],
            line,
        ))
        .map_err(|e| err(&e))?;
    }
    for j in 0..=cols {
        let x = left + cw * j;
        root.draw(&PathElement::new(
            vec![(x, top), (x, top + ch * rows)],
            line,
        ))
        .map_err(|e| err(&e))?;
    }
    for cell in &grid.cells {
        if cell.row >= grid.rows.len() || cell.column >= grid.columns.len() {
            continue;
        }
        let x0 = left + cw * cell.column as i32;
        let y0 = top + ch * cell.row as i32;
        let k = cell.colors.len().max(1) as i32;
        let side = ((cw - 16) / k)
            .min(if cell.text.is_some() { 18 } else { 24 })
            .max(4);
        let total = side * k + 2 * (k - 1);
        let sy = if cell.text.is_some() {
            y0 + 5
        } else {
            y0 + (ch - side) / 2
        };
        for (m, c) in cell.colors.iter().enumerate() {
            let sx = x0 + (cw - total) / 2 + m as i32 * (side + 2);
            root.draw(&Rectangle::new(
                [(sx, sy), (sx + side, sy + side)],
                c.color().filled(),
            ))
            .map_err(|e| err(&e))?;
        }
        if let Some(t) = &cell.text {
            root.draw(&Text::new(
                t.clone(),
                (x0 + cw / 2, y0 + ch - 4),
                font(11, HPos::Center, VPos::Bottom),
            ))
            .map_err(|e| err(&e))?;
        }
    }
    let mut y = top + ch * rows + MARGIN as i32 + LEGEND_LINE as i32 / 2;
    for entries in legend_lines(grid, width) {
        let mut x = MARGIN as i32;
        for i in entries {
            let (name, c) = &grid.legend[i];
            root.draw(&Rectangle::new(
                [(x, y - 8), (x + 16, y + 8)],
                c.color().filled(),
            ))
            .map_err(|e| err(&e))?;
            root.draw(&Text::new(
                name.clone(),
                (x + 22, y),
                font(14, HPos::Left, VPos::Center),
            ))
            .map_err(|e| err(&e))?;
            x += 24 + text_width(name, 14) as i32 + 24;
        }
        y += LEGEND_LINE as i32;
    }
    Ok(())
}
