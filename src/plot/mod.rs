//! plot (see lib.rs for the architecture).
