//! The report layer's file helpers: writing a file whole (a temporary name
//! in the same folder, then a rename, so a reader never sees half a file)
//! and quoting a CSV field.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// Writes `contents` to `path` whole: a hidden temporary file in the same
/// folder (`.NAME.partial-PID.tmp`), then a rename; the temporary file is
/// removed when the rename fails. The folder must exist.
pub fn write_whole(path: &Path, contents: &[u8]) -> io::Result<()> {
    let tmp = temporary(path, "tmp");
    fs::write(&tmp, contents)?;
    fs::rename(&tmp, path).inspect_err(|_| {
        let _ = fs::remove_file(&tmp);
    })
}

/// `dir/.NAME.partial-PID.EXT`: a hidden sibling of `path` ending in `ext`
/// (a chart encoder picks its format from the extension).
pub fn temporary(path: &Path, ext: &str) -> PathBuf {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.partial-{}.{ext}", std::process::id()))
}

/// One CSV field (RFC 4180): quoted, with its quotes doubled, when it holds
/// a comma, a quote or a line break (`\n` or `\r`); as is otherwise.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::{csv_field, write_whole};

    #[test]
    fn fields_are_quoted_when_rfc_4180_says_so() {
        assert_eq!(csv_field("plain"), "plain");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
        assert_eq!(csv_field("a\nb"), "\"a\nb\"");
        assert_eq!(csv_field("a\rb"), "\"a\rb\"");
    }

    #[test]
    fn a_file_is_written_whole_and_no_temporary_is_left() {
        let dir = std::env::temp_dir().join(format!("sticky-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("x.csv");
        write_whole(&path, b"a,b\n").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"a,b\n");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
