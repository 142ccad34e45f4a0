//! A short fuzz campaign inside `cargo test`: a few seconds on two threads,
//! no panic, no hang, no scene that passes validation and fails mid-run.

use std::time::Duration;

use fuzz::campaign::{Config, run};

#[test]
fn a_few_seconds_of_fuzzing_find_nothing() {
    let config = Config {
        duration: Duration::from_secs(4),
        threads: 2,
        seed: 22,
        save_dir: None,
        corpus_dir: Some(concat!(env!("CARGO_MANIFEST_DIR"), "/corpus").into()),
    };
    let report = run(&config);
    let summary = report.summary();
    eprint!("{summary}");
    assert!(report.tried > 20, "{summary}");
    assert!(
        report.accepted > 0,
        "some inputs must get through to the steps: {summary}"
    );
    assert!(report.panics.is_empty(), "{summary}");
    assert!(report.hangs.is_empty(), "{summary}");
    assert!(report.failed_mid_run.is_empty(), "{summary}");
}
