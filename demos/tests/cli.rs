//! The built `softwalk` binary: exit codes, one-line errors, scene listing and dumps.

use std::fs;
use std::process::{Command, Output};

fn softwalk(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_softwalk"))
        .args(args)
        .output()
        .expect("the softwalk binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8(bytes.to_vec()).unwrap()
}

#[test]
fn scenes_prints_one_scene_per_line() {
    let out = softwalk(&["scenes"]);
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    let names: Vec<&str> = stdout
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert_eq!(names.first(), Some(&"default"));
    for name in [
        "sand-flat",
        "snow-down",
        "grass-small",
        "grass-medium",
        "morphology",
        "controller-compare",
        "mixed",
    ] {
        assert!(names.contains(&name), "{name} not listed:\n{stdout}");
    }
    assert!(stdout.lines().all(|l| {
        l.split_once("  ")
            .is_some_and(|(_, d)| !d.trim().is_empty())
    }));
}

#[test]
fn dump_output_loads_back_as_a_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = softwalk(&["scenes", "--dump", "mixed"]);
    assert!(out.status.success());
    let scene_file = dir.path().join("mixed.toml");
    fs::write(&scene_file, &out.stdout).unwrap();
    let scene = softwalk_app::scene::Scene::load(&scene_file).unwrap();
    assert_eq!(scene.name, "mixed");
}

#[test]
fn errors_are_one_line_and_exit_non_zero() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("file");
    fs::write(&file, "x").unwrap();
    let under_file = file.join("out");
    for (args, expected) in [
        (
            vec!["run", "quicksand", "--out", "o"],
            "error: unknown scene \"quicksand\"",
        ),
        (
            vec!["run", "sand-flat", "--out", under_file.to_str().unwrap()],
            "error: output folder \"",
        ),
        (
            vec!["run", "missing.toml", "--out", "o"],
            "error: cannot read scene file \"missing.toml\": ",
        ),
    ] {
        let out = softwalk(&args);
        assert!(!out.status.success(), "{args:?} succeeded");
        let stderr = text(&out.stderr);
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.starts_with(expected), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    assert!(!dir.path().join("o").exists());
}

#[test]
fn run_writes_outputs_and_prints_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let out = softwalk(&[
        "run",
        "sand-flat",
        "--out",
        out_dir.to_str().unwrap(),
        "--steps",
        "4",
        "--hash",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).starts_with("scene sand-flat: 4 steps"));
    assert!(text(&out.stdout).contains("world hash"));
    assert!(out_dir.join("metrics.csv").is_file());
    assert!(out_dir.join("summary.json").is_file());
    assert!(out_dir.join("frames").is_dir());
    assert!(
        out.stderr.is_empty(),
        "no progress bar when stderr is not a terminal"
    );
}

#[test]
fn bench_prints_per_step_cost() {
    let out = softwalk(&[
        "bench",
        "soil-up",
        "--steps",
        "5",
        "--threads",
        "1",
        "--repeats",
        "3",
    ]);
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with("scene soil-up: 1 walkers, 5 steps on 1 thread(s), 3 run(s)"),
        "{stdout}"
    );
    for line in [
        "set-up (ms)",
        "step, wall (us)",
        "sum of systems (us/step)",
        "carve",
    ] {
        assert!(stdout.contains(line), "{line} missing: {stdout}");
    }
    assert!(stdout.contains(": same in every run"), "{stdout}");
    let crowd = softwalk(&["bench", "soil-up", "--walkers", "3", "--repeats", "1"]);
    assert!(!crowd.status.success());
    assert!(text(&crowd.stderr).contains("crowd scene only"));
    let refused = softwalk(&["bench", "soil-up", "--repeats", "0"]);
    assert!(!refused.status.success());
    assert!(text(&refused.stderr).contains("--repeats"));
}
