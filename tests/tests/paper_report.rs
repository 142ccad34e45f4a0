//! The paper report's machinery on one tiny scene: a headless trace, a claim
//! measured from it, the Markdown it renders, a gallery frame, the command line.

use softwalk_app::cli::{Cli, Command};
use softwalk_app::paper::gait_section::{GAIT_SECTION_TITLE, gait_quality_claim};
use softwalk_app::paper::gallery::render_at;
use softwalk_app::paper::gallery_strip::render_strip;
use softwalk_app::paper::measure::stance_errors;
use softwalk_app::paper::trace::trace;
use softwalk_app::paper::{Check, Claim, GalleryImage, Report, character};

#[test]
fn a_tiny_slope_walk_becomes_a_claim_table_in_the_markdown() {
    let mut scene = character::slope_scene(10.0).unwrap();
    scene.terrain.resolution = 101;
    scene.sim.duration = 1.5;
    let t = trace(&scene, scene.steps() as usize, |_| {}).unwrap();
    assert_eq!(t.walkers.len(), 3);
    assert!(t.walkers.iter().all(|w| w.len() == 90));
    assert_eq!(
        t.initial.heights(),
        t.last.heights(),
        "rigid ground stays put"
    );
    let (drift, gap) = stance_errors(t.walkers[0].iter().map(|m| &m.character), &t.last);
    let claim = Claim {
        title: "Stance feet neither slide nor float".into(),
        statement: "no sliding".into(),
        method: "tiny scene".into(),
        checks: vec![
            Check::new("drift", format!("{drift:.4} m"), "≤ 0.01 m", drift <= 0.01),
            Check::new("gap", format!("{gap:.4} m"), "≤ 0.01 m", gap <= 0.01),
        ],
    };
    assert!(claim.passes(), "{claim:?}");
    let report = Report {
        sections: vec![("Character".into(), vec![claim])],
        gallery: vec![GalleryImage {
            name: "sand-flat".into(),
            caption: "prints".into(),
        }],
        provenance: "test".into(),
    };
    let md = report.to_markdown();
    let lines: Vec<&str> = md.lines().collect();
    assert_eq!(lines[0], "# Paper results");
    assert!(lines.contains(&"**1 of 1 claims pass.**"));
    assert!(lines.contains(&"| Character | Stance feet neither slide nor float | pass |"));
    assert!(lines.contains(&"## Character"));
    assert!(lines.contains(&"### Stance feet neither slide nor float"));
    assert!(lines.contains(&"| quantity | measured | threshold | verdict |"));
    assert_eq!(
        lines.iter().filter(|l| l.starts_with("| drift |")).count(),
        1
    );
    assert!(lines.contains(&"![sand-flat](gallery/sand-flat.png)"));
}

#[test]
fn a_gallery_frame_has_the_asked_size() {
    let mut scene = softwalk_app::scene::Scene::builtin("sand-flat").unwrap();
    scene.terrain.resolution = 65;
    let image = render_at(&scene, 0.1, 64, 36).unwrap();
    assert_eq!(image.dimensions(), (64, 36));
}

#[test]
fn the_gait_quality_section_checks_every_goal_of_every_character() {
    let mut scene = softwalk_app::scene::Scene::builtin("morphology").unwrap();
    scene.terrain.resolution = 101;
    let claim = gait_quality_claim(&scene, 1.5).unwrap();
    assert_eq!(claim.title, "Gait quality: morphology");
    let figures = [
        "pelvis step",
        "knee step",
        "stance knee reversals",
        "stance knee mean",
        "knee max",
        "sole below ground",
    ];
    assert_eq!(claim.checks.len(), 3 * figures.len(), "{claim:?}");
    for (k, character) in ["small", "medium", "tall"].iter().enumerate() {
        for (g, figure) in figures.iter().enumerate() {
            let check = &claim.checks[k * figures.len() + g];
            assert_eq!(check.quantity, format!("{character}: {figure}"));
            assert!(check.threshold.starts_with("≤ "), "{check:?}");
        }
    }
    let report = Report {
        sections: vec![(GAIT_SECTION_TITLE.into(), vec![claim.clone()])],
        gallery: Vec::new(),
        provenance: "test".into(),
    };
    let md = report.to_markdown();
    let verdict = if claim.passes() { "pass" } else { "**FAIL**" };
    assert!(
        md.contains(&format!(
            "| Gait quality | Gait quality: morphology | {verdict} |"
        )),
        "{md}"
    );
    assert!(md.contains("| small: pelvis step | "), "{md}");
}

#[test]
fn the_snow_strip_is_eight_consecutive_frames_side_by_side() {
    let mut scene = softwalk_app::scene::Scene::builtin("snow-flat").unwrap();
    scene.terrain.resolution = 65;
    let strip = render_strip(&scene, 0.2, 8, 20, 15).unwrap();
    assert_eq!(strip.dimensions(), (160, 15));
    let frame = |k: u32| image::imageops::crop_imm(&strip, 20 * k, 0, 20, 15).to_image();
    assert!(
        (0..8).all(|k| frame(k).pixels().any(|p| p.0 != [0, 0, 0, 0])),
        "every slot holds a rendered frame"
    );
}

#[test]
fn the_paper_command_parses_its_options() {
    let cli = Cli::parse_args(["softwalk", "paper", "--quick", "--out", "somewhere"]).unwrap();
    let Command::Paper(args) = cli.command else {
        panic!("not the paper command");
    };
    assert!(args.quick);
    assert_eq!(args.out, std::path::PathBuf::from("somewhere"));
    let defaults = Cli::parse_args(["softwalk", "paper"]).unwrap();
    let Command::Paper(args) = defaults.command else {
        panic!("not the paper command");
    };
    assert!(!args.quick);
    assert_eq!(args.out, std::path::PathBuf::from("docs"));
}
