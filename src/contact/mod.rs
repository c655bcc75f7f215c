//! contact (see lib.rs for the architecture).
