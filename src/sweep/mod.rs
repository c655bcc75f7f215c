//! sweep (see lib.rs for the architecture).
