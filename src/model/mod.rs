//! model (see lib.rs for the architecture).
