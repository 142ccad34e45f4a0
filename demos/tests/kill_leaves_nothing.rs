//! Issue 22: a run killed with `kill -9` left hidden temporary files named by
//! process id (`.animation.gif.tmp7637-0`, `.metrics.csv.tmp…`) that no later
//! run removed. Partial files now have fixed names (`.NAME.partial`) and the
//! next run into the same folder removes them.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Every hidden file under `dir`, recursively.
fn hidden_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let path = entry.path();
        if entry.file_type().unwrap().is_dir() {
            found.extend(hidden_files(&path));
        } else if entry.file_name().to_string_lossy().starts_with('.') {
            found.push(path);
        }
    }
    found
}

fn softwalk(args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_softwalk"));
    command
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    command
}

#[test]
fn a_rerun_after_kill_9_leaves_no_hidden_files() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let out_arg = out.to_str().unwrap();
    let mut child = softwalk(&[
        "run",
        "default",
        "--out",
        out_arg,
        "--steps",
        "100000",
        "--threads",
        "1",
        "--width",
        "64",
        "--height",
        "48",
    ])
    .spawn()
    .unwrap();
    // Kill once a few frames are on disk: metrics and the GIF are half written.
    let frames = out.join("frames");
    let start = Instant::now();
    while fs::read_dir(&frames).map_or(0, |d| d.count()) < 3 {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no frames after 2 minutes"
        );
        assert!(child.try_wait().unwrap().is_none(), "the run ended early");
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap(); // SIGKILL on Unix: no destructor runs.
    child.wait().unwrap();
    // A frame being written at the kill, and the names earlier versions used.
    fs::write(frames.join(".frame_099998.png.partial"), b"half").unwrap();
    fs::write(out.join(".animation.gif.tmp7637-0"), b"old").unwrap();
    let left = hidden_files(&out);
    assert!(
        left.iter().any(|p| p.ends_with(".metrics.csv.partial")),
        "the killed run left its partial files: {left:?}"
    );

    let rerun = softwalk(&[
        "run",
        "default",
        "--out",
        out_arg,
        "--steps",
        "3",
        "--no-render",
    ])
    .status()
    .unwrap();
    assert!(rerun.success());
    assert_eq!(hidden_files(&out), Vec::<PathBuf>::new());
    assert!(out.join("metrics.csv").is_file());
}

#[test]
fn an_output_path_that_is_a_folder_is_refused_before_the_run() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    fs::create_dir_all(out.join("summary.json")).unwrap();
    let started = Instant::now();
    let result = softwalk(&[
        "run",
        "default",
        "--out",
        out.to_str().unwrap(),
        "--no-render",
    ])
    .stderr(Stdio::piped())
    .output()
    .unwrap();
    assert!(!result.status.success());
    let stderr = String::from_utf8(result.stderr).unwrap();
    assert!(stderr.contains("summary.json\" is a folder"), "{stderr}");
    assert!(!out.join("metrics.csv").exists(), "nothing ran");
    assert!(started.elapsed() < Duration::from_secs(30));
}
