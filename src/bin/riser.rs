//! `riser` — the engine of the FMU on the command line.
//!
//! `riser statics SCENE [--set name=value]... [--json] [--out DIR]`

use clap::{Parser, Subcommand};
use riser::scene::{PARAMETER_NAMES, Scene};
use riser::statics::report::{StaticReport, solve_scene};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "riser", version, about = "Nonlinear statics and dynamics of marine risers (Cosserat rod)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Static equilibrium under gravity and buoyancy (and the current if the scene's static_current is true).
    Statics {
        /// Built-in scene (catenary, lazy_wave) or path to a scene file (TOML).
        scene: String,
        /// Override a parameter by name, e.g. --set n_elements=120 (see `riser params`).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Print one JSON object instead of the text summary.
        #[arg(long)]
        json: bool,
        /// Write shape.csv (S, x, y, z, tension) into this directory.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// List the parameter names accepted by --set (the FMU's parameters).
    Params,
    /// Print a scene file (built-in or path, after --set overrides) as TOML.
    Scene {
        scene: String,
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
    },
}

fn load(scene: &str, set: &[String]) -> Result<Scene, riser::RiserError> {
    Ok(Scene::load(scene)?.with_overrides(set)?)
}

fn write_shape_csv(dir: &Path, report: &StaticReport) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("shape.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path)?);
    writeln!(f, "S,x,y,z,tension")?;
    for r in &report.shape {
        writeln!(f, "{},{},{},{},{}", r.s, r.x, r.y, r.z, r.tension)?;
    }
    f.flush()?;
    Ok(path)
}

fn statics(scene: &str, set: &[String], json: bool, out: Option<PathBuf>) -> Result<(), String> {
    let scene = load(scene, set).map_err(|e| e.to_string())?;
    let t0 = std::time::Instant::now();
    let (_rod, rep) = solve_scene(&scene).map_err(|e| e.to_string())?;
    let wall = t0.elapsed().as_secs_f64();
    let csv = match &out {
        Some(dir) => Some(write_shape_csv(dir, &rep).map_err(|e| format!("cannot write {}: {e}", dir.display()))?),
        None => None,
    };
    if json {
        let v = serde_json::json!({
            "scene": scene.name,
            "n_elements": scene.analysis.n_elements,
            "top_tension": rep.top_tension,
            "bottom_tension": rep.bottom_tension,
            "top_force": [rep.top_force.x, rep.top_force.y, rep.top_force.z],
            "bottom_force": [rep.bottom_force.x, rep.bottom_force.y, rep.bottom_force.z],
            "min_tension": rep.min_tension,
            "iterations": rep.iterations,
            "continuation_steps": rep.continuation_steps,
            "residual": rep.residual,
            "wall_time": wall,
            "shape": rep.shape.iter().map(|r| [r.s, r.x, r.y, r.z, r.tension]).collect::<Vec<_>>(),
        });
        println!("{v}");
    } else {
        let kn = |v: f64| v / 1e3;
        println!(
            "riser statics: scene '{}' ({} elements, EA {:.4e} N, EI {:.4e} N m^2)",
            scene.name, scene.analysis.n_elements, scene.line.axial_stiffness, scene.line.bending_stiffness
        );
        println!(
            "  Newton: {} iterations, {} continuation step(s), relative residual {:.2e}, {:.1} ms",
            rep.iterations,
            rep.continuation_steps,
            rep.residual,
            wall * 1e3
        );
        println!("  top tension     {:10.3} kN", kn(rep.top_tension));
        println!(
            "  force on vessel ({:.3}, {:.3}, {:.3}) kN",
            kn(rep.top_force.x),
            kn(rep.top_force.y),
            kn(rep.top_force.z)
        );
        println!("  bottom tension  {:10.3} kN", kn(rep.bottom_tension));
        println!("  min tension     {:10.3} kN", kn(rep.min_tension));
        let low = rep.shape.iter().fold(f64::INFINITY, |m, r| m.min(r.z));
        println!("  lowest point    {:10.3} m", low);
        if let Some(p) = csv {
            println!("  wrote {}", p.display());
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Statics { scene, set, json, out } => statics(&scene, &set, json, out),
        Command::Params => {
            for (n, u) in PARAMETER_NAMES {
                println!("{n:22} {u}");
            }
            Ok(())
        }
        Command::Scene { scene, set } => {
            load(&scene, &set).map(|s| print!("{}", s.to_toml())).map_err(|e| e.to_string())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("riser: error: {msg}");
            ExitCode::FAILURE
        }
    }
}
