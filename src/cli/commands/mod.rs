//! One module per subcommand: each has `Args` (clap) and `run(Args)`.
pub mod analyze;
pub mod cao;
pub mod check_scene;
pub mod d2;
pub mod embed;
pub mod fit_frf;
pub mod fnn;
pub mod lyap_k;
//TODO pub mod lyap_r;
pub mod mutual;
pub mod plot;
pub mod poincare;
pub mod reproduce;
//TODO pub mod rqa;
pub mod simulate;
pub mod spectrum;
pub mod sweep;
pub mod tradeoff;
