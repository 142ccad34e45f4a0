//! OBJ loading and saving: parts, normals, round trips and every bad input.

use std::path::Path;

use engine::asset::{AssetError, load_obj, load_obj_from_str, save_grid_obj, save_obj};
use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Vec2, Vec3};

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

#[test]
fn objects_and_groups_become_named_parts() {
    let mesh = load_obj(&data("walker_parts.obj")).unwrap();
    let names: Vec<&str> = mesh.parts.iter().map(|p| p.name.as_str()).collect();
    // The material change inside `foot_l` does not split the part; the missing MTL is ignored.
    assert_eq!(names, ["pelvis", "foot_l", "foot_r"]);
    assert_eq!(
        mesh.part("pelvis").unwrap().triangles,
        0..2,
        "the quad is fan-triangulated"
    );
    assert_eq!(mesh.part("foot_l").unwrap().triangles, 2..4);
    assert_eq!(mesh.part("foot_r").unwrap().triangles, 4..5);
    assert_eq!(mesh.normals.len(), mesh.positions.len());
    // No normals in most of the file: computed from the faces (pelvis faces up).
    let pelvis_vertex = mesh.triangles[0][0] as usize;
    assert!((mesh.normals[pelvis_vertex] - Vec3::Y).length() < 1e-5);
    mesh.validate().unwrap();
}

#[test]
fn normals_from_the_file_are_kept() {
    let mesh =
        load_obj_from_str("v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\n").unwrap();
    assert!(mesh.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
}

#[test]
fn saved_meshes_load_back_identical() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = load_obj(&data("walker_parts.obj")).unwrap();
    let path = dir.path().join("walker.obj");
    save_obj(&mesh, &path).unwrap();
    let back = load_obj(&path).unwrap();
    assert_eq!(back.parts, mesh.parts);
    assert_eq!(back.triangles.len(), mesh.triangles.len());
    for (a, b) in back.triangles.iter().zip(&mesh.triangles) {
        let pa = a.map(|v| back.positions[v as usize]);
        let pb = b.map(|v| mesh.positions[v as usize]);
        assert_eq!(pa, pb);
    }
}

#[test]
fn a_carved_grid_exports_as_its_own_surface() {
    let mut grid =
        HeightGrid::from_fn(Vec2::new(1.0, -2.0), 0.1, 12, 9, |x, z| x * 0.3 + z * z).unwrap();
    grid.set_height(5, 4, -1.0);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("terrain.obj");
    save_grid_obj(&grid, &path).unwrap();
    let mesh = load_obj(&path).unwrap();
    assert_eq!(mesh.triangles.len(), 2 * 11 * 8);
    let want = grid.to_tri_mesh();
    for (a, b) in mesh.triangles.iter().zip(&want.triangles) {
        let pa = a.map(|v| mesh.positions[v as usize]);
        let pb = b.map(|v| want.positions[v as usize]);
        assert_eq!(pa, pb, "the exported corners are exact");
    }
    // Faces point up, like the grid's normals.
    let t = mesh.triangles[0].map(|v| mesh.positions[v as usize]);
    assert!((t[1] - t[0]).cross(t[2] - t[0]).y > 0.0);
}

fn err(text: &str) -> AssetError {
    load_obj_from_str(text).expect_err("bad input must be refused")
}

#[test]
fn bad_obj_input_gives_typed_errors_naming_the_file() {
    let missing = load_obj(Path::new("no/such/file.obj")).unwrap_err();
    assert!(matches!(missing, AssetError::Missing { .. }), "{missing}");
    assert!(missing.to_string().contains("no/such/file.obj"));

    let e = err("v 0 0 0\nv 1 x 0\nv 0 0 1\nf 1 2 3\n");
    assert!(matches!(e, AssetError::MalformedObj { .. }), "{e}");
    assert!(e.to_string().contains("<string>"));

    let e = err("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 9\n");
    assert!(matches!(e, AssetError::IndexOutOfRange { .. }), "{e}");

    let e = err("v 0 0 0\nv 1 0 0\nv 0 0 1\n");
    assert!(matches!(e, AssetError::EmptyMesh { .. }), "{e}");
    let e = err("");
    assert!(matches!(e, AssetError::EmptyMesh { .. }), "{e}");

    let e = err("o hip\nv 0 0 0\nv NaN 0 0\nv 0 0 1\nf 1 2 3\n");
    assert!(matches!(e, AssetError::NonFinite { .. }), "{e}");
    assert!(e.to_string().contains("hip"), "{e}");
    let e = err("v 0 0 0\nv inf 0 0\nv 0 0 1\nf 1 2 3\n");
    assert!(matches!(e, AssetError::NonFinite { .. }), "{e}");
}

#[test]
fn a_failed_save_leaves_the_old_file_alone() {
    let mesh = TriMesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Z], vec![[0, 2, 1]]).unwrap();
    let e = save_obj(&mesh, Path::new("/nonexistent-dir/mesh.obj")).unwrap_err();
    assert!(matches!(e, AssetError::Write(_)), "{e}");
    assert!(e.to_string().contains("nonexistent-dir"));
}
