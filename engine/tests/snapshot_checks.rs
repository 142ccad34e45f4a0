//! Golden-image checks: exact and tolerant matches, failure artifacts, the
//! update and CI settings, and an overlay golden under `tests/snapshots/`.

use engine::canvas::{LinePlot, Overlay, Series};
use engine::glam::{Vec2, Vec3};
use engine::snapshot::{Outcome, Snapshot, SnapshotEnv, SnapshotError, Tolerance};
use image::{Rgba, RgbaImage};

const WHITE: Rgba<u8> = Rgba([255, 255, 255, 255]);
const BLACK: Rgba<u8> = Rgba([0, 0, 0, 255]);
const LOCAL: SnapshotEnv = SnapshotEnv {
    update: false,
    ci: false,
};
const CI: SnapshotEnv = SnapshotEnv {
    update: false,
    ci: true,
};
const UPDATE: SnapshotEnv = SnapshotEnv {
    update: true,
    ci: true,
};

/// A white image with a crisp black square at (8..24, 8..24).
fn square() -> RgbaImage {
    RgbaImage::from_fn(32, 32, |x, y| {
        if (8..24).contains(&x) && (8..24).contains(&y) {
            BLACK
        } else {
            WHITE
        }
    })
}

/// A snapshot in fresh temporary golden and artifact directories, with its golden written.
fn with_golden(name: &str, golden: &RgbaImage) -> (tempfile::TempDir, Snapshot) {
    let dir = tempfile::tempdir().unwrap();
    let snap = Snapshot::in_dirs(
        name,
        dir.path().join("goldens"),
        dir.path().join("artifacts"),
    );
    assert!(matches!(
        snap.check_with(golden, LOCAL).unwrap(),
        Outcome::Created(_)
    ));
    (dir, snap)
}

#[test]
fn identical_pixels_pass_exactly() {
    let (_dir, snap) = with_golden("same", &square());
    assert_eq!(snap.check_with(&square(), CI).unwrap(), Outcome::Identical);
    assert!(!snap.artifact_path().exists());
}

#[test]
fn one_anti_aliased_edge_pixel_is_forgiven() {
    let (_dir, snap) = with_golden("aa_edge", &square());
    let mut actual = square();
    actual.put_pixel(24, 15, Rgba([128, 128, 128, 255]));
    match snap.check_with(&actual, CI).unwrap() {
        Outcome::WithinTolerance {
            diff_pixels,
            aa_pixels,
            ..
        } => assert_eq!((diff_pixels, aa_pixels), (0, 1)),
        other => panic!("expected a tolerated difference, got {other:?}"),
    }
}

#[test]
fn small_colour_drift_is_under_the_threshold() {
    let (_dir, snap) = with_golden("drift", &square());
    let drifted = RgbaImage::from_fn(32, 32, |x, y| {
        let p = square().get_pixel(x, y).0;
        Rgba([p[0].saturating_sub(3), p[1], p[2].saturating_add(2), 255])
    });
    assert!(matches!(
        snap.check_with(&drifted, CI).unwrap(),
        Outcome::WithinTolerance { diff_pixels: 0, .. }
    ));
    let strict = snap.clone().tolerance(Tolerance::EXACT);
    assert!(matches!(
        strict.check_with(&drifted, CI),
        Err(SnapshotError::Mismatch(_))
    ));
}

#[test]
fn a_changed_image_fails_and_writes_actual_expected_and_diff() {
    let (_dir, snap) = with_golden("changed", &square());
    let mut actual = square();
    for y in 0..4 {
        for x in 0..5 {
            actual.put_pixel(26 + x, 26 + y, Rgba([255, 0, 0, 255]));
        }
    }
    let err = snap.check_with(&actual, CI).unwrap_err();
    let SnapshotError::Mismatch(report) = &err else {
        panic!("expected a mismatch, got {err}");
    };
    let (a, e, d) = (&report.actual, &report.expected, &report.diff);
    assert_eq!(report.diff_pixels, 20);
    let message = err.to_string();
    assert!(message.contains("20 pixels differ"), "{message}");
    for path in [a, e, d] {
        assert!(path.exists(), "{} written", path.display());
        assert!(message.contains(&path.display().to_string()), "{message}");
    }
    assert_eq!(image::open(a).unwrap().into_rgba8(), actual);
    assert_eq!(image::open(e).unwrap().into_rgba8(), square());
    let diff = image::open(d).unwrap().into_rgba8();
    assert_eq!(
        diff.get_pixel(27, 27),
        &Rgba([230, 20, 20, 255]),
        "differing pixels are red"
    );
    // Enough allowance lets it pass, and stale artifacts are cleared.
    let lenient = snap.clone().tolerance(Tolerance {
        threshold: 0.1,
        max_diff_pixels: 20,
    });
    assert!(lenient.check_with(&actual, CI).is_ok());
    assert!(!snap.artifact_path().exists());
}

#[test]
fn a_size_change_is_a_clear_failure() {
    let (_dir, snap) = with_golden("size", &square());
    let err = snap
        .check_with(&RgbaImage::from_pixel(31, 32, WHITE), CI)
        .unwrap_err();
    assert!(
        matches!(
            err,
            SnapshotError::SizeMismatch {
                actual_width: 31,
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string().contains("golden is 32x32, actual is 31x32"),
        "{err}"
    );
}

#[test]
fn missing_goldens_fail_on_ci_and_are_created_locally() {
    let dir = tempfile::tempdir().unwrap();
    let snap = Snapshot::in_dirs(
        "fresh",
        dir.path().join("goldens"),
        dir.path().join("artifacts"),
    );
    let err = snap.check_with(&square(), CI).unwrap_err();
    assert!(matches!(err, SnapshotError::MissingGolden { .. }), "{err}");
    assert!(err.to_string().contains("fresh.png"));
    assert!(!snap.golden_path().exists());
    assert_eq!(
        snap.check_with(&square(), LOCAL).unwrap(),
        Outcome::Created(snap.golden_path())
    );
    assert_eq!(
        image::open(snap.golden_path()).unwrap().into_rgba8(),
        square()
    );
}

#[test]
fn update_mode_refreshes_a_differing_golden() {
    let (_dir, snap) = with_golden("refresh", &square());
    let new = RgbaImage::from_pixel(20, 10, BLACK);
    assert_eq!(
        snap.check_with(&new, UPDATE).unwrap(),
        Outcome::Updated(snap.golden_path())
    );
    assert_eq!(snap.check_with(&new, CI).unwrap(), Outcome::Identical);
}

#[test]
fn update_mode_keeps_a_golden_that_still_passes() {
    let (_dir, snap) = with_golden("kept", &square());
    let mut within = square();
    within.put_pixel(24, 15, Rgba([128, 128, 128, 255]));
    assert!(matches!(
        snap.check_with(&within, UPDATE).unwrap(),
        Outcome::WithinTolerance { .. }
    ));
    assert_eq!(
        image::open(snap.golden_path()).unwrap().into_rgba8(),
        square(),
        "a golden within tolerance is not rewritten"
    );
    let mut failing = square();
    for x in 0..6 {
        failing.put_pixel(x, 0, BLACK);
    }
    assert_eq!(
        snap.check_with(&failing, UPDATE).unwrap(),
        Outcome::Updated(snap.golden_path())
    );
    assert_eq!(
        image::open(snap.golden_path()).unwrap().into_rgba8(),
        failing
    );
}

#[test]
fn names_that_are_not_plain_file_names_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["", "../escape", "a b"] {
        let snap = Snapshot::in_dirs(name, dir.path(), dir.path());
        assert!(matches!(
            snap.check_with(&square(), LOCAL),
            Err(SnapshotError::InvalidName { .. })
        ));
    }
}

#[test]
fn a_corrupt_golden_is_a_read_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("broken.png"), b"not a png").unwrap();
    let snap = Snapshot::in_dirs("broken", dir.path(), dir.path().join("artifacts"));
    let err = snap.check_with(&square(), CI).unwrap_err();
    assert!(
        matches!(err, SnapshotError::ReadGolden { .. }) && err.to_string().contains("broken.png"),
        "{err}"
    );
}

/// Balance overlays as a demo draws them: support segment, centre of mass,
/// torque arrow, foot rays and a label.
fn overlay_scene() -> RgbaImage {
    let mut img = RgbaImage::from_fn(128, 96, |x, y| {
        Rgba([150 + (x / 4) as u8, 140 + (y / 4) as u8, 110, 255])
    });
    let project = |p: Vec3| (p.z <= 0.0).then(|| Vec2::new(64.0 + p.x * 30.0, 80.0 - p.y * 30.0));
    let mut overlay = Overlay::new(&mut img);
    overlay.world_line(
        &project,
        Vec3::new(-1.2, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        WHITE,
        2.0,
    );
    overlay.world_circle(
        &project,
        Vec3::new(0.2, 1.5, 0.0),
        5.0,
        Rgba([230, 30, 30, 255]),
        2.0,
    );
    overlay.world_point(
        &project,
        Vec3::new(0.2, 1.5, 0.0),
        Rgba([230, 30, 30, 255]),
        3.0,
    );
    overlay.world_arrow(
        &project,
        Vec3::new(0.2, 1.5, 0.0),
        Vec3::new(1.2, 2.0, 0.0),
        Rgba([255, 210, 0, 255]),
        2.0,
    );
    for x in [-1.0, 0.8] {
        overlay.world_arrow(
            &project,
            Vec3::new(x, 2.4, 0.0),
            Vec3::new(x, 0.0, 0.0),
            Rgba([60, 190, 255, 255]),
            1.0,
        );
    }
    overlay.world_point(&project, Vec3::new(-1.0, 0.0, 1.0), BLACK, 6.0);
    overlay.text(Vec2::new(3.0, 2.0), 11.0, WHITE, "tau = 1.25");
    drop(overlay);
    img
}

#[test]
fn overlay_markers_match_their_golden() {
    engine::snapshot!("overlay_markers")
        .tolerance(Tolerance {
            threshold: 0.1,
            max_diff_pixels: 8,
        })
        .assert_matches(&overlay_scene());
}

#[test]
fn small_plot_matches_its_golden() {
    let plot = LinePlot {
        title: "Tilt".into(),
        x_label: "t (s)".into(),
        y_label: "rad".into(),
        series: vec![Series {
            name: "pitch".into(),
            points: (0..60)
                .map(|i| (i as f32 * 0.05, 0.1 * (i as f32 * 0.3).sin()))
                .collect(),
            color: Rgba([200, 60, 40, 255]),
        }],
    };
    engine::snapshot!("plot_small")
        .tolerance(Tolerance {
            threshold: 0.1,
            max_diff_pixels: 12,
        })
        .assert_matches(&plot.render(200, 128));
}
