//! io (see lib.rs for the architecture).
