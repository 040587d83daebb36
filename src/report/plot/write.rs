//! Writing figures: every figure is drawn once per backend (SVG, then PNG
//! when a font was found), each file written whole under a temporary name
//! and renamed.

use std::fs;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::chart::chart_on;
use super::font::{notice_png_skipped, png_support, PngSupport};
use super::grid::{grid_on, grid_size};
use super::heatmap::{heatmap_on, heatmap_size};
use super::{Chart, Grid, Heatmap, PlotError, Written};

/// Writes `chart` as `dir/stem.svg` and `dir/stem.png` (PNG only when a font
/// was found); `dir` is created if needed.
pub fn write_chart(chart: &Chart, dir: &Path, stem: &str) -> Result<Written, PlotError> {
    write_figure(dir, stem, chart.size, |area| draw_chart(area, chart))
}

/// Writes `grid` as `dir/stem.svg` and `dir/stem.png` (PNG only when a font
/// was found); `dir` is created if needed.
pub fn write_grid(grid: &Grid, dir: &Path, stem: &str) -> Result<Written, PlotError> {
    let size = grid_size(grid);
    write_figure(dir, stem, size, |area| draw_grid(area, grid))
}

/// Writes `map` as `dir/stem.svg` and `dir/stem.png` (PNG only when a font
/// was found); `dir` is created if needed.
pub fn write_heatmap(map: &Heatmap, dir: &Path, stem: &str) -> Result<Written, PlotError> {
    write_figure(dir, stem, heatmap_size(map), |area| area.heatmap(map))
}

/// Writes `contents` to `path` whole: a temporary file in the same folder,
/// then a rename ([`crate::report::io::write_whole`], its one definition).
pub fn write_whole(path: &Path, contents: &[u8]) -> Result<(), PlotError> {
    crate::report::io::write_whole(path, contents).map_err(|e| PlotError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

pub(super) use crate::report::io::temporary;

fn write_figure<F>(dir: &Path, stem: &str, size: (u32, u32), draw: F) -> Result<Written, PlotError>
where
    F: Fn(&mut dyn FigureArea) -> Result<(), String>,
{
    if stem.is_empty() || stem.contains(['/', '\\']) || stem.starts_with('.') {
        return Err(PlotError::BadName {
            stem: stem.to_string(),
        });
    }
    fs::create_dir_all(dir).map_err(|e| PlotError::Io {
        path: dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let support = png_support();
    let svg = dir.join(format!("{stem}.svg"));
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        let mut area = Area(root);
        draw(&mut area).map_err(|message| PlotError::Draw {
            path: svg.clone(),
            message,
        })?;
        area.0.present().map_err(|e| PlotError::Draw {
            path: svg.clone(),
            message: e.to_string(),
        })?;
    }
    write_whole(&svg, text.as_bytes())?;
    let png = match support {
        PngSupport::Skipped(why) => {
            notice_png_skipped(why);
            None
        }
        PngSupport::Font(_) => {
            let path = dir.join(format!("{stem}.png"));
            let tmp = temporary(&path, "png");
            let drawn = {
                let root = BitMapBackend::new(&tmp, size).into_drawing_area();
                let mut area = Area(root);
                draw(&mut area).and_then(|()| area.0.present().map_err(|e| e.to_string()))
            };
            if let Err(message) = drawn {
                let _ = fs::remove_file(&tmp);
                return Err(PlotError::Draw { path, message });
            }
            fs::rename(&tmp, &path).map_err(|e| {
                let _ = fs::remove_file(&tmp);
                PlotError::Io {
                    path: path.clone(),
                    message: e.to_string(),
                }
            })?;
            Some(path)
        }
    };
    Ok(Written { svg, png })
}

/// The drawing area of one backend, behind a trait object so that one
/// drawing routine serves SVG and PNG.
trait FigureArea {
    fn chart(&mut self, chart: &Chart) -> Result<(), String>;
    fn grid(&mut self, grid: &Grid) -> Result<(), String>;
    fn heatmap(&mut self, map: &Heatmap) -> Result<(), String>;
}

struct Area<DB: DrawingBackend>(DrawingArea<DB, Shift>);

impl<DB: DrawingBackend> FigureArea for Area<DB> {
    fn chart(&mut self, chart: &Chart) -> Result<(), String> {
        chart_on(&self.0, chart)
    }
    fn grid(&mut self, grid: &Grid) -> Result<(), String> {
        grid_on(&self.0, grid)
    }
    fn heatmap(&mut self, map: &Heatmap) -> Result<(), String> {
        heatmap_on(&self.0, map)
    }
}

fn draw_chart(area: &mut dyn FigureArea, chart: &Chart) -> Result<(), String> {
    area.chart(chart)
}

fn draw_grid(area: &mut dyn FigureArea, grid: &Grid) -> Result<(), String> {
    area.grid(grid)
}
