//! dem (see lib.rs for the architecture).
