//! `softwalk paper`: reproduce the paper's claims and write `paper-results.md`.

use std::io::Write;
use std::time::Instant;

use crate::cli::{CliError, PaperArgs};
use crate::out_dir::prepare_output_dir;
use crate::paper::{self, PaperOptions};

/// Runs every reproduction scene, writes the report and gallery into `--out`,
/// and prints the tally.
pub fn paper(args: &PaperArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let dir = prepare_output_dir(&args.out)?;
    let options = PaperOptions {
        quick: args.quick,
        progress: true,
    };
    let start = Instant::now();
    let report = paper::write_report(&dir, &options).map_err(|e| CliError::Paper(Box::new(e)))?;
    let (claims, passing) = report.tally();
    writeln!(
        out,
        "{passing} of {claims} claims pass ({:.0} s); report in {}",
        start.elapsed().as_secs_f64(),
        dir.join("paper-results.md").display()
    )
    .map_err(CliError::Stdout)
}
