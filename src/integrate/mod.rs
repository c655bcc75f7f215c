//! integrate (see lib.rs for the architecture).
