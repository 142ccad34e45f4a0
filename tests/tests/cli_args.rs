//! The `softwalk` command line as a library: argument parsing, scene resolution,
//! the output-folder check, listing and dumping scenes, and the files a run writes.

use std::fs;
use std::path::Path;

use softwalk_app::cli::{ArgsError, Cli, CliError, Command, error_line};
use softwalk_app::commands::execute;
use softwalk_app::output::metrics_header;
use softwalk_app::scene::{Scene, builtin_scenes};

fn parse(args: &[&str]) -> Result<Cli, ArgsError> {
    Cli::parse_args(std::iter::once("softwalk").chain(args.iter().copied()))
}

fn execute_args(args: &[&str]) -> (Result<(), CliError>, String) {
    let cli = parse(args).expect("arguments should parse");
    let mut out = Vec::new();
    let result = execute(cli, &mut out);
    (result, String::from_utf8(out).unwrap())
}

#[test]
fn run_defaults_to_the_default_scene() {
    let Command::Run(run) = parse(&["run", "--out", "o"]).unwrap().command else {
        panic!("not a run command");
    };
    assert_eq!(run.scene.scene, "default");
    assert_eq!(run.out, Path::new("o"));
    assert!(!run.no_render && !run.hash);
    assert_eq!(
        (run.scene.steps, run.scene.seconds, run.scene.threads),
        (None, None, None)
    );
}

#[test]
fn run_accepts_every_option() {
    let cli = parse(&[
        "run",
        "sand-up",
        "--out",
        "o",
        "--no-render",
        "--threads",
        "3",
        "--hash",
        "--steps",
        "12",
        "--width",
        "320",
        "--height",
        "200",
    ])
    .unwrap();
    let Command::Run(run) = cli.command else {
        panic!("not a run command");
    };
    assert_eq!(run.scene.scene, "sand-up");
    assert_eq!(run.scene.steps, Some(12));
    assert_eq!(run.scene.threads, Some(3));
    assert_eq!((run.width, run.height), (Some(320), Some(200)));
    assert!(run.no_render && run.hash);
}

#[test]
fn bad_arguments_are_refused_by_the_parser() {
    match parse(&["run"])
        .expect("`softwalk run` alone runs the default scene")
        .command
    {
        Command::Run(args) => assert_eq!(
            args.out,
            std::path::PathBuf::from("out"),
            "--out defaults to `out`"
        ),
        other => panic!("parsed as {other:?}"),
    }
    assert!(parse(&["run", "--out", "o", "--steps", "3", "--seconds", "1"]).is_err());
    assert!(parse(&["run", "--out", "o", "--threads", "0"]).is_err());
    assert!(parse(&["run", "--out", "o", "--seconds", "nan"]).is_err());
    assert!(parse(&["run", "--out", "o", "--seconds", "-1"]).is_err());
    assert!(parse(&["run", "--out", "o", "--width", "100000"]).is_err());
    assert!(parse(&["run", "--out", "o", "--frobnicate"]).is_err());
    assert!(parse(&["fly"]).is_err());
}

#[test]
fn scenes_lists_every_builtin_with_a_description() {
    let (result, out) = execute_args(&["scenes"]);
    result.unwrap();
    let lines: Vec<&str> = out.lines().collect();
    let all = builtin_scenes();
    assert_eq!(lines.len(), all.len());
    for (line, b) in lines.iter().zip(&all) {
        let (name, description) = line
            .split_once("  ")
            .expect("name, two spaces, description");
        assert_eq!(name, b.name);
        assert_eq!(
            description.trim(),
            Scene::builtin(&b.name).unwrap().description
        );
    }
}

#[test]
fn dump_round_trips() {
    let (result, out) = execute_args(&["scenes", "--dump", "controller-compare"]);
    result.unwrap();
    let parsed = Scene::from_toml_str(&out, Path::new("")).unwrap();
    assert_eq!(parsed, Scene::builtin("controller-compare").unwrap());
    let (result, _) = execute_args(&["scenes", "--dump", "nope"]);
    assert!(error_line(&result.unwrap_err()).starts_with("unknown scene \"nope\""));
}

#[test]
fn an_output_folder_under_a_regular_file_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("plain-file");
    fs::write(&file, "x").unwrap();
    let out = file.join("run");
    let (result, stdout) = execute_args(&["run", "sand-flat", "--out", out.to_str().unwrap()]);
    let e = result.unwrap_err();
    assert!(matches!(e, CliError::OutputDir(_)), "{e:?}");
    let line = error_line(&e);
    assert!(line.starts_with("output folder \""), "{line}");
    assert!(
        line.contains("plain-file/run\" cannot be created: "),
        "{line}"
    );
    assert!(stdout.is_empty(), "nothing ran");
}

#[test]
fn a_scene_file_error_names_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    let text = Scene::builtin("sand-flat")
        .unwrap()
        .to_toml_string()
        .unwrap()
        .replacen("dt = ", "dt = -", 1);
    fs::write(&scene, text).unwrap();
    let out = dir.path().join("out");
    let (result, _) = execute_args(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let line = error_line(&result.unwrap_err());
    assert!(line.contains("bad.toml\": sim.dt: -0.01"), "{line}");
    assert!(line.contains("must be > 0"), "{line}");
    assert!(line.ends_with("(line 16)"), "{line}");
    assert!(
        !out.exists(),
        "the scene is checked before the output folder is made"
    );
}

#[test]
fn run_writes_metrics_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nested/out");
    let (result, stdout) = execute_args(&[
        "run",
        "morphology",
        "--out",
        out.to_str().unwrap(),
        "--seconds",
        "0.5",
        "--threads",
        "1",
        "--no-render",
    ]);
    result.unwrap();
    let metrics = fs::read_to_string(out.join("metrics.csv")).unwrap();
    assert_eq!(metrics.lines().next(), Some(metrics_header().as_str()));
    let columns = metrics_header().split(',').count();
    assert!(
        metrics.lines().all(|l| l.split(',').count() == columns),
        "every row has one cell per column"
    );
    let cell = |row: &str, name: &str| -> f32 {
        let k = softwalk_app::output::metric_column(name).unwrap();
        row.split(',').nth(k).unwrap().parse().unwrap()
    };
    let last = metrics.lines().last().unwrap();
    for side in ["l", "r"] {
        let ground = cell(last, &format!("{side}ground_y"));
        let heel = cell(last, &format!("{side}heel_y"));
        assert!(
            (heel - ground).abs() < 1.0,
            "{side}: heel {heel} near ground {ground}"
        );
    }
    let summary = fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"scene\": \"morphology\""), "{summary}");
    assert!(
        summary.contains("\"steps\": 30,"),
        "0.5 s at 60 Hz: {summary}"
    );
    for name in ["small", "medium", "tall"] {
        assert!(
            summary.contains(&format!("\"name\": \"{name}\"")),
            "{summary}"
        );
    }
    assert!(summary.contains("\"threads\": 1"), "{summary}");
    assert!(!out.join("frames").exists(), "--no-render writes no frames");
    assert!(stdout.starts_with("scene morphology: 30 steps"), "{stdout}");
    let leftovers: Vec<_> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

#[test]
fn snapshot_blesses_checks_and_reports_failing_frames() {
    let dir = tempfile::tempdir().unwrap();
    let golden = dir.path().join("golden");
    let failures = dir.path().join("failures");
    let args = |extra: &[&str]| {
        let mut a = vec![
            "snapshot",
            "sand-flat",
            "--steps",
            "4",
            "--width",
            "96",
            "--height",
            "54",
            "--golden",
            golden.to_str().unwrap(),
            "--out",
            failures.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(str::to_owned).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let owned = args(extra);
        let refs: Vec<&str> = owned.iter().map(String::as_str).collect();
        execute_args(&refs)
    };

    // No goldens yet: every frame fails, nothing is written into the goldens.
    let (result, out) = run(&[]);
    assert!(
        matches!(
            result,
            Err(CliError::Snapshot {
                failed: 2,
                total: 2
            })
        ),
        "{out}"
    );
    assert!(!golden.exists());

    let (result, out) = run(&["--bless"]);
    assert!(result.is_ok(), "{out}");
    assert!(out.contains("2 created"), "{out}");
    let (result, out) = run(&[]);
    assert!(result.is_ok(), "{out}");
    assert!(out.contains("2 identical"), "{out}");

    // A golden painted over fails, with actual, expected and diff written.
    let first = golden.join("frame_000000.png");
    let mut image = image::open(&first).unwrap().into_rgba8();
    for y in 0..20 {
        for x in 0..20 {
            image.put_pixel(x, y, image::Rgba([255, 0, 255, 255]));
        }
    }
    image.save(&first).unwrap();
    let (result, out) = run(&[]);
    assert!(
        matches!(
            result,
            Err(CliError::Snapshot {
                failed: 1,
                total: 2
            })
        ),
        "{out}"
    );
    for artifact in ["actual.png", "expected.png", "diff.png"] {
        assert!(
            failures.join("frame_000000").join(artifact).exists(),
            "{artifact}"
        );
    }
    // Blessing rewrites only the failing golden.
    let untouched = std::fs::read(golden.join("frame_000002.png")).unwrap();
    let (result, out) = run(&["--bless"]);
    assert!(result.is_ok(), "{out}");
    assert!(
        out.contains("1 identical") && out.contains("1 updated"),
        "{out}"
    );
    assert_eq!(
        std::fs::read(golden.join("frame_000002.png")).unwrap(),
        untouched
    );
}

fn repo_file(relative: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(relative)
        .to_string_lossy()
        .into_owned()
}

#[test]
fn inspect_prints_the_default_humans_rig_and_leg_chains() {
    let file = repo_file("assets/characters/human.glb");
    let (result, out) = execute_args(&["inspect", &file]);
    result.unwrap();
    assert!(out.contains("glTF model"), "{out}");
    assert!(
        out.contains("mesh: 6002 vertices, 12000 triangles"),
        "{out}"
    );
    assert!(out.contains("clips: none"), "{out}");
    assert!(out.contains("bone names: GameEngine"), "{out}");
    assert!(
        out.contains("left leg: hip thigh_l, knee calf_l, ankle foot_l, toe ball_l"),
        "{out}"
    );
    assert!(
        out.contains("spine: pelvis -> spine_01 -> spine_02 -> spine_03 -> neck_01 -> head"),
        "{out}"
    );
}

#[test]
fn inspect_prints_a_bvh_clip_and_says_what_is_missing() {
    let file = repo_file("engine/tests/data/walk_small.bvh");
    let (result, out) = execute_args(&["inspect", &file]);
    result.unwrap();
    assert!(out.contains("BVH mocap, 2 frames at 2.0 fps"), "{out}");
    assert!(out.contains("bone names: Bvh"), "{out}");
    assert!(out.contains("right leg: hip RightUpLeg"), "{out}");
    assert!(out.contains("not a walk clip"), "{out}");
    let (result, out) = execute_args(&["inspect", &repo_file("assets/clips/walk.bvh")]);
    result.unwrap();
    assert!(out.contains("walk cycle: 1.100 s (109 steps/min)"), "{out}");

    let dir = tempfile::tempdir().unwrap();
    let renamed = dir.path().join("renamed.bvh");
    let text = fs::read_to_string(&file)
        .unwrap()
        .replace("LeftFoot", "LeftPaw");
    fs::write(&renamed, text).unwrap();
    let (result, out) = execute_args(&["inspect", renamed.to_str().unwrap()]);
    result.unwrap();
    assert!(out.contains("leg chains not found"), "{out}");
    assert!(out.contains("FootL (looked for LeftFoot"), "{out}");
}

#[test]
fn inspect_refuses_bad_and_unknown_files() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.glb");
    fs::write(&bad, b"glTF nonsense").unwrap();
    let (result, _) = execute_args(&["inspect", bad.to_str().unwrap()]);
    let error = result.unwrap_err();
    assert!(
        error_line(&error).contains("bad.glb"),
        "{}",
        error_line(&error)
    );
    let (result, _) = execute_args(&["inspect", "model.fbx"]);
    assert!(matches!(result, Err(CliError::UnknownFileKind { .. })));
    assert!(parse(&["inspect"]).is_err());
}
