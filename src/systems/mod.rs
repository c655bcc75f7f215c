//! systems (see lib.rs for the architecture).

pub mod bouncing_ball;
