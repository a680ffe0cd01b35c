//! Explicit inputs given as a list or a file: `--params 0,0.3,1` or `--params params.txt`.

use std::path::Path;

use anyhow::Result;

use crate::context::Context;
use crate::exit::bad_input;
use crate::values::numbers;

/// The numbers of `text`: a comma-separated list, or, when `text` names an existing file (or
/// `-`), the numbers of that file, one value per line (a one-column points file).
pub(crate) fn parameters(cx: &Context, text: &str, what: &str) -> Result<Vec<f64>> {
    let path = Path::new(text);
    if text == "-" || path.is_file() {
        let (pts, name) = crate::items::read_points(cx, path)?;
        if pts.dim() != 1 {
            return bad_input(format!(
                "{name}: {what} needs one value per line; found {} columns",
                pts.dim()
            ));
        }
        return Ok(pts.as_slice().to_vec());
    }
    numbers(text, what)
}
