//! Scene files: TOML → validated scene (owned by the impact/scene issue).

pub mod dem;
