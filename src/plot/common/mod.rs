//! Shared machinery of the figures: bundled font, output backends, styling, input checks.
//!
//! Files: rendering ([`render`]), styling (palette, fonts), axes and data checks, and the
//! side legend; their items are re-exported here.

mod axes;
mod render;
mod side_legend;
mod style;

pub use axes::*;
pub use render::*;
pub use side_legend::*;
pub use style::*;
