//! Replays every file of `fuzz/corpus` (inputs that once crashed, hung or
//! passed validation and failed mid-run, plus hand-made edge cases): none
//! panics, and none is accepted by validation and then fails.

use std::path::Path;

use fuzz::campaign::check_caught;
use fuzz::oracle::{Input, Outcome};

#[test]
fn every_corpus_file_is_refused_cleanly_or_runs() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus");
    let mut paths: Vec<_> = std::fs::read_dir(&corpus)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    paths.sort();
    let scratch = tempfile::tempdir().unwrap();
    let mut replayed = 0;
    for path in paths {
        let Some(input) = Input::from_file(&path) else {
            continue;
        };
        let outcome = check_caught(&input, scratch.path());
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        match outcome {
            Err(panic) => panic!("{name}: panicked: {panic}"),
            Ok(Outcome::FailedMidRun(e)) => panic!("{name}: accepted, then failed: {e}"),
            Ok(outcome) => {
                let expected = if name.starts_with("ok-") {
                    Outcome::Accepted
                } else {
                    Outcome::Rejected
                };
                if name.starts_with("ok-") || name.starts_with("bad-") {
                    assert_eq!(outcome, expected, "{name}");
                }
            }
        }
        replayed += 1;
    }
    assert!(replayed >= 5, "{replayed} files replayed");
}
