//! analysis (see lib.rs for the architecture).
pub mod poincare;
pub mod regime;
pub mod spectrum;
pub mod zero_one_test;
