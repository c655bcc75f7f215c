//! impact (see lib.rs for the architecture).
