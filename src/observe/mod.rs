//! observe (see lib.rs for the architecture).
