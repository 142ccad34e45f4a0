//! `softwalk view`: without a display it fails in one line; under Xvfb
//! (`xvfb-run`), a short input script and `--screenshot-after` give a
//! screenshot matching its golden, and the session's recording replays
//! headless (`run --inputs`) to the live world hash. Where `xvfb-run` is
//! missing, the window test says it was skipped.

use std::path::{Path, PathBuf};
use std::process::Command;

use engine::snapshot::Tolerance;

/// Steps before the screenshot (2.5 s at 60 Hz).
const SCREENSHOT_AFTER: &str = "150";
/// Room for last-bit float differences between machines, far below a real change.
const TOLERANCE: Tolerance = Tolerance {
    threshold: 0.1,
    max_diff_pixels: 40,
};

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/inputs/turns_stop_snow.toml")
}

#[test]
fn view_without_a_display_fails_in_one_line() {
    let out = Command::new(env!("CARGO_BIN_EXE_softwalk"))
        .args(["view", "--steps", "10"])
        .env_remove("DISPLAY")
        .output()
        .expect("the softwalk binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert_eq!(
        stderr.trim_end(),
        "error: cannot open a window: no X display (DISPLAY is not set)"
    );
}

fn xvfb_run() -> Option<PathBuf> {
    let paths = std::env::var_os("PATH")?;
    std::env::split_paths(&paths)
        .map(|dir| dir.join("xvfb-run"))
        .find(|p| p.is_file())
}

#[test]
fn view_under_xvfb_matches_its_golden() {
    let Some(xvfb) = xvfb_run() else {
        println!("skipped: xvfb-run is not installed, so no window can be opened");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("shot.png");
    let record = dir.path().join("recorded.toml");
    let out = Command::new(xvfb)
        .args(["-a", "-s", "-screen 0 640x480x24"])
        .arg(env!("CARGO_BIN_EXE_softwalk"))
        .args([
            "view",
            "--width",
            "240",
            "--height",
            "136",
            "--threads",
            "1",
        ])
        .arg("--inputs")
        .arg(script())
        .args(["--screenshot-after", SCREENSHOT_AFTER])
        .arg("--screenshot")
        .arg(&shot)
        .arg("--record")
        .arg(&record)
        .output()
        .expect("xvfb-run runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "softwalk view failed: {stderr}");
    println!("{}", String::from_utf8_lossy(&out.stdout).trim_end());
    let image = image::open(&shot).expect("a screenshot").to_rgba8();
    assert_eq!(image.dimensions(), (240, 136));
    engine::snapshot!("live_view_after_150_steps")
        .tolerance(TOLERANCE)
        .assert_matches(&image);
    let recorded = std::fs::read_to_string(&record).unwrap();
    assert!(recorded.contains("velocity = [0.85, -0.85]"), "{recorded}");
    let live_hash = hash_line(&out.stdout);
    let replay = Command::new(env!("CARGO_BIN_EXE_softwalk"))
        .args(["run", "--no-render", "--hash", "--steps", SCREENSHOT_AFTER])
        .arg("--out")
        .arg(dir.path().join("replay"))
        .arg("--inputs")
        .arg(&record)
        .output()
        .expect("the softwalk binary runs");
    assert!(replay.status.success());
    assert_eq!(
        hash_line(&replay.stdout),
        live_hash,
        "replay differs from live"
    );
}

/// The `world hash: ...` line of a command's output.
fn hash_line(stdout: &[u8]) -> String {
    let text = String::from_utf8_lossy(stdout);
    text.lines()
        .find(|l| l.starts_with("world hash: "))
        .unwrap_or_else(|| panic!("no world hash in:\n{text}"))
        .to_string()
}
