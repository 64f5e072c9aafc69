//! `contactwave run SCENARIO --out DIR`: simulate one scenario and print its summary.
//!
//! A half-space scenario writes summary.json, timeseries.csv, probe.csv, spectrum.csv and
//! SVG plots into DIR; a bar-stack scenario (thesis chapter 4) writes the files of the
//! hammer test (FRF and modes) or of its incident wave, with a progress bar on a terminal.

use super::{check_out_dir, progress_bar, read_table, EXIT_OK, STEPS_TEMPLATE};
use contactwave::output;
use contactwave::scenario::bar_stack::BarStackScenario;
use contactwave::scenario::Scenario;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Simulate one scenario and write summary.json, timeseries.csv, probe.csv,
/// spectrum.csv and SVG plots into DIR (SI units: s, m, Pa, m/s, Hz).
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (TOML; see docs/scenario.md).
    scenario: PathBuf,
    /// Output folder (created if needed; files in it are replaced).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

pub fn run(args: Args) -> contactwave::Result<u8> {
    let (path, out) = (args.scenario.as_path(), args.out.as_path());
    let table = read_table(path)?;
    if BarStackScenario::is_bar_stack(&table) {
        return run_bar_stack(table, path, out);
    }
    let scenario = Scenario::from_table(table, path)?;
    check_out_dir(out)?;
    let t0 = Instant::now();
    let result = contactwave::simulate(&scenario)?;
    let wall = t0.elapsed();
    let files = output::run_files(&result, &scenario)?;
    output::write_files(out, &files)?;
    let s = &result.summary;
    let get = |k: &str| s.get(k).unwrap_or(f64::NAN);
    println!("scenario               {}", path.display());
    println!("xi                     {:.6}", get("xi"));
    println!("A1/Ainc                {:.6e}", get("A1_over_Ainc"));
    println!("A2/Ainc                {:.6e}", get("A2_over_Ainc"));
    println!("A2/A1                  {:.6e}", get("A2_over_A1"));
    println!("beta_end               {:.6}", get("beta_end"));
    println!("contact loss fraction  {:.6}", get("contact_loss_fraction"));
    println!("energy closure error   {:.3e}", get("energy_closure_error"));
    println!("wall time              {:.1} ms", wall.as_secs_f64() * 1e3);
    println!("wrote {} files to {}", files.len(), out.display());
    Ok(EXIT_OK)
}

/// `run` on a bar-stack scenario: the hammer test, FRF and modes (thesis chapter 4).
fn run_bar_stack(table: toml::Table, path: &Path, out: &Path) -> contactwave::Result<u8> {
    let scenario = BarStackScenario::from_table(table, path)?;
    check_out_dir(out)?;
    let t0 = Instant::now();
    // long runs report progress on a terminal
    let bar = progress_bar(STEPS_TEMPLATE, 0);
    let b = bar.clone();
    let progress = contactwave::solver::barstack::StepProgress(std::sync::Arc::new(
        move |done: usize, total: usize| {
            b.set_length(total as u64);
            b.set_position(done as u64);
        },
    ));
    let result = contactwave::simulate_bar_stack_with_progress(&scenario, Some(progress));
    bar.finish_and_clear();
    let result = result?;
    let wall = t0.elapsed();
    let files = output::bar_stack_files(&result, &path.display().to_string())?;
    output::write_files(out, &files)?;
    let get = |k: &str| result.summary.get(k).unwrap_or(f64::NAN);
    println!("scenario               {}", path.display());
    for (i, p) in scenario.static_pressure.iter().enumerate() {
        let closure = get(&format!("static_interface_closure_{i}"));
        println!("static pressure [{i}]    {p:.6e} Pa (closure {closure:.4e} m)");
    }
    if scenario.incident.is_some() {
        println!("xi (first interface)   {:.6}", get("xi"));
        println!("A1/Ainc (reflected)    {:.6e}", get("A1_over_Ainc"));
        println!("A2/Ainc (reflected)    {:.6e}", get("A2_over_Ainc"));
        if result.summary.get("transmitted_A1_over_Ainc").is_some() {
            println!(
                "A1/Ainc (transmitted)  {:.6e}",
                get("transmitted_A1_over_Ainc")
            );
            println!(
                "A2/Ainc (transmitted)  {:.6e}",
                get("transmitted_A2_over_Ainc")
            );
        }
        println!(
            "energy R / T           {:.6} / {:.6}",
            get("energy_reflected_fraction"),
            result
                .summary
                .get("energy_transmitted_fraction")
                .unwrap_or(0.0)
        );
    } else {
        println!("first mode             {:.2} Hz", get("first_mode_hz"));
        println!("second harmonic        {:.2} Hz", get("second_harmonic_hz"));
        println!("A2/A1                  {:.4e}", get("A2_over_A1"));
        println!("guide mode             {:.1} Hz", get("guide_mode_hz"));
    }
    println!(
        "min contact pressure   {:.4e} Pa",
        get("min_contact_pressure")
    );
    println!("wall time              {:.1} ms", wall.as_secs_f64() * 1e3);
    println!("wrote {} files to {}", files.len(), out.display());
    Ok(EXIT_OK)
}
