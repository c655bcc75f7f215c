//! One module per subcommand: each has `Args` (clap) and `run(Args)`.
pub mod simulate;
pub mod sweep;
pub mod check_scene;
pub mod tradeoff;
pub mod mutual;
pub mod fnn;
pub mod embed;
pub mod spectrum;
pub mod poincare;
pub mod lyap_k;
pub mod analyze;
pub mod fit_frf;
pub mod plot;
pub mod reproduce;
