//! packing (see lib.rs for the architecture).
