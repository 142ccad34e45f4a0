//! Issue 22: `MeshBvh::build` stays near `n log n` on degenerate layouts (a
//! row of equal triangles: 45 s for 50k before; a fan of slivers covering one
//! huge polygon), and rays still find the nearest triangle.

use std::time::{Duration, Instant};

use engine::geom::{HitTarget, MeshBvh, Ray, TriMesh};
use glam::Vec3;

/// `n` unit right triangles side by side along +X.
fn row(n: usize) -> TriMesh {
    let mut positions = Vec::with_capacity(3 * n);
    let mut triangles = Vec::with_capacity(n);
    for k in 0..n {
        let x = k as f32;
        let b = positions.len() as u32;
        positions.extend([
            Vec3::new(x, 0.0, 0.0),
            Vec3::new(x, 0.0, 1.0),
            Vec3::new(x + 1.0, 0.0, 0.0),
        ]);
        triangles.push([b, b + 1, b + 2]);
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// One 100 m disc as a fan of `n` slivers around its centre.
fn fan(n: usize) -> TriMesh {
    let mut positions = vec![Vec3::ZERO];
    for k in 0..=n {
        let a = k as f32 / n as f32 * std::f32::consts::TAU;
        positions.push(Vec3::new(a.cos() * 100.0, 0.0, a.sin() * 100.0));
    }
    let triangles = (0..n as u32).map(|k| [0, k + 2, k + 1]).collect();
    TriMesh::new(positions, triangles).unwrap()
}

/// Build time; the limit is generous for a debug-profile test on a shared machine
/// (release: see NOTES-issue22b.md).
fn timed(mesh: &TriMesh) -> (MeshBvh, Duration) {
    let start = Instant::now();
    let bvh = MeshBvh::build(mesh).unwrap();
    let took = start.elapsed();
    eprintln!("{} triangles: built in {took:?}", mesh.triangles.len());
    (bvh, took)
}

#[test]
fn fifty_thousand_triangles_in_a_row_build_quickly_and_are_hit() {
    let (bvh, took) = timed(&row(50_000));
    assert!(took < Duration::from_secs(5), "{took:?}");
    for x in [0.25f32, 1234.5, 49_999.2] {
        let ray = Ray::new(Vec3::new(x, 5.0, 0.1), Vec3::NEG_Y).unwrap();
        let hit = bvh.cast(&ray, 100.0).expect("the row is under the ray");
        let HitTarget::Mesh { triangle, .. } = hit.target else {
            panic!("{hit:?}");
        };
        assert_eq!(triangle as usize, x as usize, "{x}");
        assert!((hit.distance - 5.0).abs() < 1e-4);
    }
}

#[test]
fn a_huge_polygon_as_a_fan_builds_quickly_and_is_hit() {
    let (bvh, took) = timed(&fan(50_000));
    assert!(took < Duration::from_secs(5), "{took:?}");
    let ray = Ray::new(Vec3::new(30.0, 10.0, 20.0), Vec3::NEG_Y).unwrap();
    let hit = bvh.cast(&ray, 100.0).expect("the disc is under the ray");
    assert!((hit.distance - 10.0).abs() < 1e-3);
}

#[test]
fn a_fan_with_one_far_vertex_builds_quickly() {
    // Found by the fuzz harness: a fan whose first rim vertex was moved to x = -7e26.
    let mut mesh = fan(20_000);
    mesh.positions[1].x = -7.18e26;
    let (_, took) = timed(&mesh);
    assert!(took < Duration::from_secs(5), "{took:?}");
}
