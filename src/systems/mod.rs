//! systems (see lib.rs for the architecture).
