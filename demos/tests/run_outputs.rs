//! Issue 22 regressions of `softwalk run`'s outputs: a plot never aborts a
//! run, and more threads than cores are clamped with a warning.

use std::fs;
use std::process::Command;

fn softwalk(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_softwalk"))
        .args(args)
        .output()
        .expect("the softwalk binary runs")
}

/// `snow-flat`, `mud-flat` and `snow-down` with `alpha = 1.0e-45` (inside the
/// allowed range) panicked in the plot's axis formatting.
#[test]
fn a_subnormal_alpha_still_writes_every_plot() {
    let tmp = tempfile::tempdir().unwrap();
    for scene in ["snow-flat", "mud-flat", "snow-down"] {
        let dump = softwalk(&["scenes", "--dump", scene]);
        assert!(dump.status.success());
        let toml = String::from_utf8(dump.stdout).unwrap();
        let alpha = toml
            .lines()
            .find(|l| l.starts_with("alpha = "))
            .expect("the scene sets alpha");
        let file = tmp.path().join(format!("{scene}.toml"));
        fs::write(&file, toml.replace(alpha, "alpha = 1.0e-45")).unwrap();
        let out = tmp.path().join(scene);
        let run = softwalk(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--seconds",
            "1",
            "--no-render",
        ]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{scene}: {stderr}");
        assert!(!stderr.contains("panicked"), "{scene}: {stderr}");
        for plot in ["tilt", "torque", "pelvis", "knees", "feet"] {
            assert!(
                out.join(format!("plots/{plot}.png")).is_file(),
                "{scene}: {plot}"
            );
        }
    }
}

#[test]
fn threads_above_the_cores_are_clamped_with_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let run = softwalk(&[
        "run",
        "sand-flat",
        "--out",
        out.to_str().unwrap(),
        "--steps",
        "2",
        "--no-render",
        "--threads",
        "1000",
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    assert!(
        stderr.contains(&format!(
            "warning: --threads 1000 is more than the {cores} core"
        )),
        "{stderr}"
    );
    let summary = fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(
        summary.contains(&format!("\"threads\": {cores},")),
        "{summary}"
    );
}
