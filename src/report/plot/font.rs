//! Fonts: plotters' `ab_glyph` backend has no font of its own, so one is
//! registered before the first figure (a TrueType file found on the machine,
//! else an in-memory metrics-only font that lets SVG be laid out); whether
//! PNG files can be written follows from it.

use std::fs;
use std::path::PathBuf;
use std::sync::OnceLock;

use plotters::style::FontStyle;

/// Where a TrueType font is looked for, after `$STICKY_FONT`.
pub const FONT_PATHS: [&str; 12] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/liberation-sans/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
    "/usr/share/fonts/noto/NotoSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "/Library/Fonts/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

/// The font family name registered with plotters.
pub(super) const FAMILY: &str = "sans-serif";

/// Whether PNG files can be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PngSupport {
    /// A TrueType font was found and registered: PNGs are written.
    Font(PathBuf),
    /// No usable font: only SVGs are written; the reason.
    Skipped(String),
}

static FONT: OnceLock<PngSupport> = OnceLock::new();

static NOTICE: OnceLock<()> = OnceLock::new();

/// Says on standard error, once per process, that a PNG was skipped and how
/// to get PNGs (called when a figure's PNG is skipped: an omission is never
/// silent).
pub(super) fn notice_png_skipped(why: &str) {
    NOTICE.get_or_init(|| eprintln!("sticky: {why}"));
}

/// Finds and registers a font, once per process; says whether PNGs can be
/// written.
pub fn png_support() -> &'static PngSupport {
    FONT.get_or_init(register_font)
}

fn register_font() -> PngSupport {
    let mut candidates: Vec<PathBuf> = Vec::new();
    let chosen = std::env::var_os("STICKY_FONT");
    let disabled = chosen.as_ref().is_some_and(|p| p == "none");
    if let Some(p) = chosen.filter(|_| !disabled) {
        candidates.push(PathBuf::from(p));
    }
    if !disabled {
        candidates.extend(FONT_PATHS.iter().map(PathBuf::from));
    }
    for path in candidates {
        let Ok(bytes) = fs::read(&path) else {
            continue;
        };
        // plotters keeps `&'static` font data: one font per process is
        // leaked on purpose (the registration happens once).
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        if plotters::style::register_font(FAMILY, FontStyle::Normal, bytes).is_ok() {
            return PngSupport::Font(path);
        }
    }
    let metrics: &'static [u8] = Box::leak(metrics_only_font().into_boxed_slice());
    let why = if plotters::style::register_font(FAMILY, FontStyle::Normal, metrics).is_ok() {
        "no TrueType font found: PNG charts skipped, SVG written (install one, e.g. \
         `apt-get install fonts-dejavu-core`, or set STICKY_FONT to a .ttf file)"
    } else {
        "no TrueType font found and the built-in metrics font was refused: PNG charts \
         skipped (install one, e.g. `apt-get install fonts-dejavu-core`, or set \
         STICKY_FONT to a .ttf file)"
    };
    PngSupport::Skipped(why.to_string())
}

/// A minimal TrueType font with one empty glyph 0.6 em wide (tables `head`,
/// `hhea`, `hmtx`, `maxp`): enough for plotters to measure text, so that SVG
/// files can be laid out without a real font. Every character maps to the
/// empty glyph.
pub(super) fn metrics_only_font() -> Vec<u8> {
    fn be16(v: &mut Vec<u8>, x: u16) {
        v.extend_from_slice(&x.to_be_bytes());
    }
    fn be32(v: &mut Vec<u8>, x: u32) {
        v.extend_from_slice(&x.to_be_bytes());
    }
    const UNITS: u16 = 1000;
    let mut head = Vec::with_capacity(54);
    be32(&mut head, 0x0001_0000); // version
    be32(&mut head, 0x0001_0000); // fontRevision
    be32(&mut head, 0); // checkSumAdjustment
    be32(&mut head, 0x5F0F_3CF5); // magicNumber
    be16(&mut head, 0); // flags
    be16(&mut head, UNITS); // unitsPerEm
    head.extend_from_slice(&[0; 16]); // created, modified
    for v in [0u16, (-236i16) as u16, 600, 928] {
        be16(&mut head, v); // xMin, yMin, xMax, yMax
    }
    be16(&mut head, 0); // macStyle
    be16(&mut head, 8); // lowestRecPPEM
    be16(&mut head, 2); // fontDirectionHint
    be16(&mut head, 0); // indexToLocFormat
    be16(&mut head, 0); // glyphDataFormat
    let mut hhea = Vec::with_capacity(36);
    be32(&mut hhea, 0x0001_0000);
    be16(&mut hhea, 928); // ascender
    be16(&mut hhea, (-236i16) as u16); // descender
    be16(&mut hhea, 0); // lineGap
    be16(&mut hhea, 600); // advanceWidthMax
    hhea.extend_from_slice(&[0; 22]); // minLSB … metricDataFormat
    be16(&mut hhea, 1); // numberOfHMetrics
    let mut hmtx = Vec::new();
    be16(&mut hmtx, 600); // advanceWidth
    be16(&mut hmtx, 0); // lsb
    let mut maxp = Vec::new();
    be32(&mut maxp, 0x0000_5000);
    be16(&mut maxp, 1); // numGlyphs
    let tables: [(&[u8; 4], Vec<u8>); 4] = [
        (b"head", head),
        (b"hhea", hhea),
        (b"hmtx", hmtx),
        (b"maxp", maxp),
    ];
    let mut out = Vec::new();
    be32(&mut out, 0x0001_0000);
    be16(&mut out, tables.len() as u16);
    be16(&mut out, 64); // searchRange
    be16(&mut out, 2); // entrySelector
    be16(&mut out, 0); // rangeShift
    let mut offset = 12 + 16 * tables.len();
    let mut body = Vec::new();
    for (tag, data) in &tables {
        let checksum = data
            .chunks(4)
            .map(|c| {
                let mut w = [0u8; 4];
                w[..c.len()].copy_from_slice(c);
                u32::from_be_bytes(w)
            })
            .fold(0u32, u32::wrapping_add);
        out.extend_from_slice(&tag[..]);
        be32(&mut out, checksum);
        be32(&mut out, offset as u32);
        be32(&mut out, data.len() as u32);
        body.extend_from_slice(data);
        while body.len() % 4 != 0 {
            body.push(0);
        }
        offset = 12 + 16 * tables.len() + body.len();
    }
    out.extend_from_slice(&body);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metrics_font_parses() {
        let bytes: &'static [u8] = Box::leak(metrics_only_font().into_boxed_slice());
        assert!(
            plotters::style::register_font("sticky-test-metrics", FontStyle::Normal, bytes).is_ok()
        );
    }
}
