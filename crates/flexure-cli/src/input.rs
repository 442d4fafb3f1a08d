//! Reading the files a command is given: bounded, so that `/dev/zero` or a
//! runaway file is refused with its size rather than read until memory
//! runs out.

use std::io::Read;
use std::path::Path;

/// The largest file any option reads (64 MiB): a mechanism file, an
/// `--input` CSV. The library refuses larger texts too
/// ([`flexure::mechanism::file::MAX_TEXT_BYTES`]).
pub const MAX_BYTES: u64 = flexure::mechanism::file::MAX_TEXT_BYTES as u64;

/// The text of `path`, read to at most [`MAX_BYTES`]; errors name `what`
/// (the option or the file's role) and the path.
pub fn read_text(path: &Path, what: &str) -> Result<String, String> {
    let shown = path.display();
    let file = std::fs::File::open(path).map_err(|e| format!("{what}{shown}: {e}"))?;
    let mut bytes = Vec::new();
    file.take(MAX_BYTES + 1).read_to_end(&mut bytes).map_err(|e| format!("{what}{shown}: {e}"))?;
    if bytes.len() as u64 > MAX_BYTES {
        return Err(format!(
            "{what}{shown}: larger than {} MiB, the most a file may hold here; nothing past that was read",
            MAX_BYTES >> 20
        ));
    }
    String::from_utf8(bytes)
        .map_err(|e| format!("{what}{shown}: not UTF-8 text (invalid byte at {})", e.utf8_error().valid_up_to()))
}

/// The mechanism of either dimension that the file at `path` describes,
/// read, parsed and built once, warning of each number it gives that is
/// implausible as written ([`flexure::mechanism::file::habits`]), placed
/// in the file.
pub fn read_model(path: &Path) -> Result<flexure::model::Model, String> {
    let text = read_text(path, "")?;
    let document = flexure::mechanism::file::Document::parse(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    for h in flexure::mechanism::file::habits(&document) {
        crate::options::warn(format!("{}: {h}", path.display()));
    }
    flexure::model::Model::from_document(document).map_err(|e| format!("{}: {e}", path.display()))
}
