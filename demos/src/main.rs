//! The `softwalk` command-line program; all the work is in the `demos` library.

use std::process::ExitCode;

use clap::Parser;
use demos::cli::{Cli, error_line, execute};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli, &mut std::io::stdout().lock()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", error_line(&e));
            ExitCode::FAILURE
        }
    }
}
