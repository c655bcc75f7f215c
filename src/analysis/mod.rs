//! analysis (see lib.rs for the architecture).
