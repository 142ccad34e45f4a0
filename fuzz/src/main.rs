//! `cargo run --release -p fuzz -- --minutes 10 [--threads 2] [--seed 1] [--save DIR]`:
//! a fuzz campaign; exits with 1 when it finds a panic, a hang or a scene
//! that passed validation and failed mid-run (their inputs saved to `--save`).
#![forbid(unsafe_code)]

use std::path::PathBuf;
use std::time::Duration;

use fuzz::campaign::{Config, run};

fn main() {
    let mut config = Config {
        duration: Duration::from_secs(60),
        threads: 2,
        seed: 1,
        save_dir: Some(PathBuf::from("fuzz-findings")),
        corpus_dir: Some(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus")),
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut k = 0;
    while k < args.len() {
        let value = args.get(k + 1).cloned().unwrap_or_default();
        let number = || -> f64 {
            value.parse().unwrap_or_else(|_| {
                eprintln!("{}: \"{value}\" is not a number", args[k]);
                std::process::exit(2)
            })
        };
        match args[k].as_str() {
            "--minutes" => config.duration = Duration::from_secs_f64(60.0 * number()),
            "--seconds" => config.duration = Duration::from_secs_f64(number()),
            "--threads" => config.threads = number() as usize,
            "--seed" => config.seed = number() as u64,
            "--save" => config.save_dir = Some(PathBuf::from(&value)),
            other => {
                eprintln!(
                    "unknown argument {other}; use --minutes N, --seconds N, --threads N, --seed N, --save DIR"
                );
                std::process::exit(2);
            }
        }
        k += 2;
    }
    let report = run(&config);
    print!("{}", report.summary());
    if !(report.panics.is_empty() && report.hangs.is_empty() && report.failed_mid_run.is_empty()) {
        if let Some(dir) = &config.save_dir {
            println!("inputs saved in {}", dir.display());
        }
        std::process::exit(1);
    }
}
