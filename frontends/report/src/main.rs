//! `voxtrace-report`: measures voxtrace with the CLI's own code path and
//! writes the tables (markdown) and plots (PNG) the README shows.
//!
//! `cargo run --release -p voxtrace-report -- speed [--quick] [--vs-binary PATH]`
//! `cargo run --release -p voxtrace-report -- accuracy [--quick | --full]`
//! `cargo run --release -p voxtrace-report -- embree-input [--size N]`

mod accuracy;
mod common_args;
mod convergence;
mod embree_input;
mod geometric;
mod measure;
mod naive_dda;
mod path_accuracy;
mod plot;
mod speed;
mod speed_data;
mod speed_tables;
mod speed_vs;
mod surface;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Measure voxtrace and write the README's tables and plots.
#[derive(Debug, Parser)]
#[command(name = "voxtrace-report", version, about)]
struct Cli {
    #[command(subcommand)]
    report: Report,
}

#[derive(Debug, Subcommand)]
enum Report {
    /// Render and build times per backend and scene size, beside the seed
    /// paper's table; storage bytes; octree scaling to size 2048; with
    /// --vs-binary, a "speedup vs" table against another voxtrace binary.
    Speed(speed::SpeedArgs),
    /// Render time, rays and error against a converged reference for each
    /// setting of each accuracy axis (samples, AO rays, shadows), and of
    /// spp x bounces on path-traced material scenes; then the
    /// exact walk against a textbook float-accumulating one (time, pixels
    /// whose hit voxel differs) at the paper's sizes.
    Accuracy(accuracy::AccuracyArgs),
    /// The terrain as a triangle mesh, the paper camera's rays and the
    /// octree's hits, for `benches/embree/run.sh` (Intel Embree on the
    /// same rays).
    EmbreeInput(embree_input::EmbreeInputArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.report {
        Report::Speed(args) => speed::run(args),
        Report::Accuracy(args) => accuracy::run(args),
        Report::EmbreeInput(args) => embree_input::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => voxtrace_cli::atomic::exit_with_error(&message),
    }
}
