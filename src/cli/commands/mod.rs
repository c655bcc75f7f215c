//! One module per subcommand: each has `Args` (clap) and `run(Args)`.
pub mod analyze;
pub mod check_scene;
pub mod embed;
pub mod fit_frf;
pub mod fnn;
pub mod lyap_k;
pub mod mutual;
pub mod nrlazy;
pub mod plot;
pub mod poincare;
pub mod reproduce;
pub mod simulate;
pub mod spectrum;
pub mod surrogate_test;
pub mod surrogates;
pub mod sweep;
pub mod tradeoff;
