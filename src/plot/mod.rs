//! Headless figures (SPEC §7): plotters with the bundled DejaVu Sans font, PNG output, one file
//! per figure kind. Every figure is a struct of borrowed slices implementing [`Figure`];
//! [`render`] writes it to a file and [`render_rgb`] to memory.
//! [`from_table`] draws each figure kind of `pdamp plot` from the CSV tables of the output
//! contract (the command line only turns its flags into [`from_table::TableFigureOptions`]).

pub mod bed_motion;
pub mod bifurcation;
pub mod common;
pub mod correlation_dimension;
pub mod decay;
pub mod effective;
pub mod energy;
pub mod fnn;
pub mod frequency_panel;
pub mod frf;
pub mod from_table;
pub mod kantz;
pub mod labels;
pub mod lines;
pub mod mutual;
pub mod pareto;
pub mod poincare;
pub mod reconstruction;
pub mod recurrence;
pub mod regime_frf;
pub mod regime_map;
pub mod resonance;
pub mod spectrum;
pub mod table;

pub use common::{render, render_rgb, Figure, FigureOptions, Series};
