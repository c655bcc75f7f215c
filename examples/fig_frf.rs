//! Writes `figures/frf.png` (+ `figures/frf.csv`): a synthetic damped FRF of scene B (SPEC §6)
//! with the (2.1.21) reference curves for M and M + m_p (SPEC §7, first figure).
//!
//! Replace the synthetic curve by a real sweep with
//! `pdamp plot frf DIR/sweep.csv -o frf.png --mass 2.37 --particle-mass 0.227 --stiffness 21500 --damping 7.6 --base-amplitude 4.5e-3`.

use pdamp::analysis::frf_fit::sdof_amplitude;
use pdamp::plot::frf::{FrfFigure, FrfReference};
use pdamp::plot::{render, FigureOptions, Series};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (m, mp, k, c, u) = (2.37, 0.227, 21500.0, 7.6, 4.5e-3);
    let f: Vec<f64> = (1..=60).map(|i| 0.5 * i as f64).collect();
    // stand-in for a granular damper: M_ef between M and M + m_p, C_ef ≈ 3 C
    let z: Vec<f64> = f
        .iter()
        .map(|&f| sdof_amplitude(f, m + 0.12, 3.0 * c, k, u))
        .collect();
    std::fs::create_dir_all("figures")?;
    let mut csv = String::from("frequency_hz,amplitude_m\n");
    for (f, z) in f.iter().zip(&z) {
        csv += &format!("{f},{z}\n");
    }
    std::fs::write("figures/frf.csv", csv)?;
    let fig = FrfFigure {
        series: vec![Series {
            label: "synthetic damped FRF",
            x: &f,
            y: &z,
        }],
        reference: Some(FrfReference {
            mass_kg: m,
            particle_mass_kg: Some(mp),
            stiffness_n_per_m: k,
            damping_ns_per_m: c,
            base_amplitude_m: u,
        }),
    };
    render(&fig, "figures/frf.png".as_ref(), &FigureOptions::default())?;
    println!("wrote figures/frf.png");
    Ok(())
}
