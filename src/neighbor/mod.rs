//! neighbor (see lib.rs for the architecture).
