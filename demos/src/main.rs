//! The `softwalk` command-line program; all the work is in the `softwalk_app` library.

#![forbid(unsafe_code)]

use std::process::ExitCode;

use clap::Parser;
use softwalk_app::cli::{Cli, error_line};
use softwalk_app::commands::execute;

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
