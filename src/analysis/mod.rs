//! analysis (see lib.rs for the architecture).
pub mod frf_fit;
pub mod optimum;
