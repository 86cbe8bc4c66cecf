//! Problems located by file and line (`FileDiagnostic`), as this terminal shows them: in color
//! where the user wants color.

use crate::load::color;
use proclaim_syntax::FileDiagnostic;

/// One problem, ending in a newline.
pub fn shown(d: &FileDiagnostic) -> String {
    d.render(color())
}
