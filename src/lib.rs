//! # pdamp — particle (granular) vibration dampers
//!
//! A toolkit that simulates particle dampers on a one-degree-of-freedom primary system and
//! analyses the nonlinear dynamics of the grains. The physics and the estimators are written up
//! in `docs/PHYSICS.md`; equation numbers such as (2.1.21) are the source thesis's (Sánchez
//! 2012), and "SPEC §n" in a doc comment is the part of that document marked §n.
//!
//! ## Architecture (dependencies point one way)
//! ```text
//! (binary: cli) → prelude → systems → study → tradeoff → sweep → plot → io → setup (scene → resolved objects)
//!   → choice → scene → dem / impact → observe / contact / neighbor / integrate / packing → files → model → analysis → simd → units / error
//! ```
//! A module imports only modules to its right, never one beside it (`dem` and `impact` know
//! nothing of each other), and no two files import each other. `tests/design_module_graph.rs`
//! reads the `use`/path graph of `src/` from the syntax tree and holds the code to this order
//! (its list of exceptions names what is left: a few `mod.rs` ↔ child-file pairs in `scene`).
//! `dem`, `impact` and `model` never see a scene; `analysis` knows nothing of the simulators
//! (the primary's FRF (2.1.21) it fits is its own,
//! [`analysis::frf_fit::base_excitation_amplitude`], and [`model`] evaluates it from there).
//! - [`scene`]: TOML scene files → validated [`scene::Scene`].
//! - [`setup`]: the resolve step, [`scene::Scene::resolve`] → the engine's objects
//!   ([`impact::ImpactSetup`], [`setup::DemSetup`]); `dem`, `impact` and `model` never see a scene.
//! - [`model`]: equations of the primary system (2.1.2), its analytic FRF (2.1.21).
//! - [`impact`]: event-driven one-particle impact damper (SPEC §3).
//! - [`contact`], [`neighbor`], [`integrate`], [`dem`], [`packing`]: the discrete element model (SPEC §2, §5).
//! - [`sweep`]: parallel, resumable parameter sweeps.
//! - [`analysis`]: delay embedding, mutual information, false nearest neighbours, spectra,
//!   Poincaré sections, Kantz's Lyapunov exponent, regime classification, FRF fits (SPEC §4).
//! - [`systems`]: logistic, Hénon, Lorenz, Rössler, bouncing ball — literature references.
//! - [`plot`]: headless PNG figures (SPEC §7), and the table → figure adapters of `pdamp plot`
//!   ([`plot::from_table`]).
//! - [`tradeoff`]: speed against accuracy of the models and settings, measured.
//! - [`choice`]: the ladder of shortcuts and `kind = "auto"`'s pick from the measured table.
//! - [`io`]: series and CSV input/output, the run directory.
//! - [`files`]: atomic writes and CSV text, beneath the observers (re-exported by [`io`]).
//! - [`prelude`]: the common types in one `use pdamp::prelude::*;` (see
//!   `examples/end_to_end.rs`: scene → simulate with an observer → analyse → figure).
//!
//! The `pdamp` command line is not part of the library: it lives in the binary (`src/main.rs`,
//! `src/cli/`, cargo feature `cli`, on by default). `cargo build --lib --no-default-features`
//! builds the library without clap, anyhow or indicatif.
#![warn(missing_docs)]
// every `unsafe` block says why it is sound, and every `unsafe fn` when it may be called (issue 40)
#![warn(clippy::undocumented_unsafe_blocks, clippy::missing_safety_doc)]

pub mod analysis;
pub mod choice;
pub mod contact;
pub mod dem;
pub mod error;
pub mod files;
pub mod impact;
pub mod integrate;
pub mod io;
pub mod model;
pub mod neighbor;
pub mod observe;
pub mod packing;
pub mod plot;
pub mod prelude;
pub mod scene;
pub mod setup;
pub mod simd;
pub mod study;
pub mod sweep;
pub mod systems;
pub mod tradeoff;
pub mod units;
