//! Ray casts against brute force: every BVH answer is checked against a loop
//! over all triangles, on flat, sloped, bumpy and freshly edited grids, with
//! random, vertical, grazing and exactly-on-edge rays.

use engine::geom::{
    GridBvh, GridRect, HeightGrid, Hit, HitTarget, MeshBvh, Ray, RayScene, TriMesh, ray_triangle,
};
use engine::glam::{Vec2, Vec3, Vec3A};
use engine::rng::SplitMix64;

const TILE: usize = 8;
const CELL: f32 = 0.25;
const ORIGIN: Vec2 = Vec2::new(-3.0, 2.0);

fn grid(f: impl FnMut(f32, f32) -> f32) -> HeightGrid {
    // 41 x 37 samples: neither side a multiple of the tile size.
    HeightGrid::from_fn(ORIGIN, CELL, 41, 37, f).unwrap()
}

fn flat() -> HeightGrid {
    grid(|_, _| 0.5)
}
fn sloped() -> HeightGrid {
    grid(|x, z| 0.3 * x - 0.2 * z)
}
fn bumpy() -> HeightGrid {
    grid(|x, z| 0.4 * (1.7 * x).sin() * (1.3 * z).cos() + 0.1 * (5.0 * x + z).sin())
}
fn edited() -> HeightGrid {
    let mut g = bumpy();
    carve(&mut g, GridRect::new(10, 12, 22, 20), 0.3);
    g
}

/// Lowers a rectangle of samples by `depth` and raises its rim: a footprint.
fn carve(g: &mut HeightGrid, r: GridRect, depth: f32) {
    for (i, j) in r.iter() {
        let rim = i == r.i0 || j == r.j0 || i + 1 == r.i1 || j + 1 == r.j1;
        let h = g.height(i, j) + if rim { depth * 0.5 } else { -depth };
        g.set_height(i, j, h);
    }
}

/// The closest hit over every triangle of the grid: the reference.
fn brute(mesh: &TriMesh, ray: &Ray, max_t: f32) -> Option<(f32, u32)> {
    let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
    let mut best: Option<(f32, u32)> = None;
    for (k, t) in mesh.triangles.iter().enumerate() {
        let corners = t.map(|v| Vec3A::from(mesh.positions[v as usize]));
        let limit = best.map_or(max_t, |b| b.0);
        if let Some(t) = ray_triangle(o, d, corners, limit)
            && best.is_none_or(|b| t < b.0)
        {
            best = Some((t, k as u32));
        }
    }
    best
}

fn check_against_brute(g: &HeightGrid, rays: &[Ray], what: &str) {
    let bvh = GridBvh::build_with_tiles(g, TILE).unwrap();
    let mesh = g.to_tri_mesh();
    let mut hits = 0;
    for (k, ray) in rays.iter().enumerate() {
        let want = brute(&mesh, ray, 50.0);
        let got = bvh.cast(g, ray, 50.0);
        assert_eq!(
            got.is_some(),
            want.is_some(),
            "{what}: ray {k} {ray:?}: bvh {got:?}, brute {want:?}"
        );
        assert_eq!(bvh.any_hit(g, ray, 50.0), want.is_some(), "{what}: ray {k}");
        if let (Some(h), Some((t, _))) = (got, want) {
            hits += 1;
            assert!(
                (h.distance - t).abs() <= 1e-4 * (1.0 + t),
                "{what}: ray {k}: bvh t {} vs brute t {t}",
                h.distance
            );
            assert!(
                (h.point - ray.at(h.distance)).length() < 1e-3,
                "{what}: ray {k}"
            );
            let direct = g.intersect_ray(ray, 50.0).unwrap();
            assert!((direct.distance - h.distance).abs() <= 1e-5 * (1.0 + t));
        }
    }
    assert!(
        hits > rays.len() / 4,
        "{what}: only {hits} hits, the test is too weak"
    );
}

fn random_rays(g: &HeightGrid, rng: &mut SplitMix64, n: usize) -> Vec<Ray> {
    let ext = g.extent();
    (0..n)
        .map(|_| {
            let o = Vec3::new(
                rng.range(ORIGIN.x - 1.0, ORIGIN.x + ext.x + 1.0),
                rng.range(-1.0, 3.0),
                rng.range(ORIGIN.y - 1.0, ORIGIN.y + ext.y + 1.0),
            );
            let d = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 0.3),
                rng.range(-1.0, 1.0),
            );
            Ray::new(o, d).unwrap()
        })
        .collect()
}

fn grazing_rays(g: &HeightGrid, rng: &mut SplitMix64, n: usize) -> Vec<Ray> {
    let ext = g.extent();
    (0..n)
        .map(|_| {
            let x = rng.range(ORIGIN.x, ORIGIN.x + ext.x);
            let z = rng.range(ORIGIN.y, ORIGIN.y + ext.y);
            let y = g.height_at(x, z).unwrap() + rng.range(0.001, 0.05);
            let a = rng.range(0.0, std::f32::consts::TAU);
            Ray::new(Vec3::new(x, y, z), Vec3::new(a.cos(), -0.01, a.sin())).unwrap()
        })
        .collect()
}

/// Rays lying exactly on cell edges and tile borders, along the axes and the diagonals.
fn edge_rays(g: &HeightGrid) -> Vec<Ray> {
    let mut rays = Vec::new();
    let (nx, nz) = (g.nx(), g.nz());
    for k in 0..nx.max(nz) {
        let x = ORIGIN.x + (k.min(nx - 1)) as f32 * CELL;
        let z = ORIGIN.y + (k.min(nz - 1)) as f32 * CELL;
        let starts = [
            Vec3::new(x, 3.0, ORIGIN.y - 0.5),
            Vec3::new(ORIGIN.x - 0.5, 3.0, z),
        ];
        rays.push(Ray::new(starts[0], Vec3::new(0.0, -0.4, 1.0)).unwrap());
        rays.push(Ray::new(starts[1], Vec3::new(1.0, -0.4, 0.0)).unwrap());
        rays.push(Ray::new(Vec3::new(x, 3.0, z), Vec3::new(0.0, -1.0, 0.0)).unwrap());
        let corner = g.sample_position(k.min(nx - 1), (k * 7) % nz) + Vec3::Y * 2.0;
        rays.push(Ray::new(corner, Vec3::new(1.0, -1.0, 1.0)).unwrap());
        rays.push(Ray::new(corner, Vec3::new(-1.0, -1.5, -1.0)).unwrap());
    }
    rays
}

#[test]
fn random_grazing_and_edge_rays_match_brute_force_on_every_grid() {
    let mut rng = SplitMix64::new(7);
    for (name, g) in [
        ("flat", flat()),
        ("sloped", sloped()),
        ("bumpy", bumpy()),
        ("edited", edited()),
    ] {
        let mut rays = random_rays(&g, &mut rng, 300);
        rays.extend(grazing_rays(&g, &mut rng, 150));
        rays.extend(edge_rays(&g));
        check_against_brute(&g, &rays, name);
    }
}

#[test]
fn vertical_rays_hit_height_at_exactly_also_on_cell_edges_and_tile_borders() {
    let g = edited();
    let bvh = GridBvh::build_with_tiles(&g, TILE).unwrap();
    let mesh = g.to_tri_mesh();
    let mut rng = SplitMix64::new(11);
    let mut points: Vec<(f32, f32)> = (0..500)
        .map(|_| (rng.range(-3.0, 7.0), rng.range(2.0, 11.0)))
        .collect();
    // Every sample position: cell edges, tile borders, grid corners and borders.
    for j in 0..g.nz() {
        for i in 0..g.nx() {
            let p = g.sample_position(i, j);
            points.push((p.x, p.z));
            points.push((p.x + 0.5 * CELL, p.z));
        }
    }
    let mut hits = 0;
    for (x, z) in points {
        let from_y = 5.0;
        let fast = bvh.cast_down(&g, x, z, from_y);
        let ray = Ray::down(x, from_y, z).unwrap();
        let walked = bvh.cast(&g, &ray, f32::INFINITY);
        assert_eq!(fast, walked, "at ({x}, {z})");
        match g.height_at(x, z) {
            Some(h) => {
                hits += 1;
                let hit = fast.unwrap_or_else(|| panic!("lost vertical hit at ({x}, {z})"));
                assert_eq!(hit.point.y, h, "at ({x}, {z})");
                let (t, _) = brute(&mesh, &ray, f32::INFINITY).unwrap();
                assert!((t - hit.distance).abs() < 1e-5, "at ({x}, {z})");
            }
            None => assert!(fast.is_none(), "off-grid hit at ({x}, {z})"),
        }
    }
    assert!(hits > 1000);
    // A ray starting below the surface going down meets nothing; NaN input is refused quietly.
    let h = g.height_at(0.1, 5.0).unwrap();
    assert_eq!(bvh.cast_down(&g, 0.1, 5.0, h - 0.01), None);
    assert_eq!(bvh.cast_down(&g, f32::NAN, 5.0, 3.0), None);
    assert_eq!(bvh.cast_down(&g, 0.1, f32::INFINITY, 3.0), None);
    assert_eq!(bvh.cast_down(&g, 0.1, 5.0, f32::INFINITY), None);
    assert_eq!(bvh.cast_down(&g, 0.1, 5.0, f32::NAN), None);
    assert_eq!(
        bvh.cast_down(&g, 0.1, 5.0, h).map(|hit| hit.distance),
        Some(0.0)
    );
}

#[test]
fn hits_name_the_cell_and_an_upward_normal() {
    let g = sloped();
    let bvh = GridBvh::build_with_tiles(&g, TILE).unwrap();
    let x = ORIGIN.x + 3.3 * CELL;
    let z = ORIGIN.y + 7.6 * CELL;
    let hit = bvh.cast_down(&g, x, z, 10.0).unwrap();
    assert_eq!(hit.target, HitTarget::Grid { i: 3, j: 7 });
    let want = Vec3::new(-0.3, 1.0, 0.2).normalize();
    assert!((hit.normal - want).length() < 1e-5, "{:?}", hit.normal);
}

#[test]
fn refit_after_edits_answers_like_a_rebuild() {
    let mut g = bumpy();
    let mut bvh = GridBvh::build_with_tiles(&g, TILE).unwrap();
    let mut rng = SplitMix64::new(3);
    // Several edits, some on tile borders, one digging deep and one raising a wall.
    let edits = [
        (GridRect::new(7, 7, 10, 10), 0.5),
        (GridRect::new(15, 0, 25, 6), -1.5),
        (GridRect::new(30, 28, 41, 37), 0.8),
        (GridRect::new(0, 16, 3, 18), 2.0),
    ];
    for (rect, depth) in edits {
        carve(&mut g, rect, depth);
        bvh.refit(&g, rect);
        let fresh = GridBvh::build_with_tiles(&g, TILE).unwrap();
        assert_eq!(bvh.tiling(), fresh.tiling());
        let random = random_rays(&g, &mut rng, 200);
        for ray in &random {
            assert_eq!(
                bvh.cast(&g, ray, 50.0),
                fresh.cast(&g, ray, 50.0),
                "{ray:?}"
            );
        }
        // A ray running exactly along a cell edge may name either neighbour cell
        // (the tie depends on tree order); the hit itself must agree.
        for ray in random.iter().chain(&edge_rays(&g)) {
            let a: Option<Hit> = bvh.cast(&g, ray, 50.0);
            let b = fresh.cast(&g, ray, 50.0);
            assert_eq!(a.is_some(), b.is_some(), "{ray:?}");
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a.distance - b.distance).abs() <= 1e-5 * (1.0 + a.distance));
                assert!((a.point - b.point).length() <= 1e-4, "{ray:?}");
            }
            let direct = g.intersect_ray(ray, 50.0).map(|h| h.distance);
            let close = match (a.map(|h| h.distance), direct) {
                (Some(x), Some(y)) => (x - y).abs() <= 1e-5 * (1.0 + x),
                (x, y) => x == y,
            };
            assert!(close, "{ray:?}: {a:?} vs {direct:?}");
        }
    }
    check_against_brute(&g, &random_rays(&g, &mut rng, 200), "after refits");
}

#[test]
fn max_distance_is_honoured() {
    let g = flat();
    let bvh = GridBvh::build_with_tiles(&g, TILE).unwrap();
    let ray = Ray::down(0.0, 2.5, 5.0).unwrap();
    assert!(bvh.cast(&g, &ray, 1.9).is_none());
    assert!(!bvh.any_hit(&g, &ray, 1.9));
    assert_eq!(bvh.cast(&g, &ray, 2.0).map(|h| h.distance), Some(2.0));
    assert!(bvh.cast(&g, &ray, f32::NAN).is_none());
}

/// A closed, bumpy, sphere-like mesh of `2 * n * n` triangles.
fn blob(n: usize) -> TriMesh {
    let mut positions = Vec::new();
    for a in 0..=n {
        for b in 0..n {
            let theta = std::f32::consts::PI * a as f32 / n as f32;
            let phi = std::f32::consts::TAU * b as f32 / n as f32;
            let r = 1.0 + 0.2 * (3.0 * phi).sin() * (2.0 * theta).sin();
            positions.push(
                r * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ),
            );
        }
    }
    let mut triangles = Vec::new();
    for a in 0..n as u32 {
        for b in 0..n as u32 {
            let n32 = n as u32;
            let (p, q) = (a * n32 + b, a * n32 + (b + 1) % n32);
            triangles.push([p, q, q + n32]);
            triangles.push([p, q + n32, p + n32]);
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn mesh_bvh_matches_brute_force() {
    let mesh = blob(40);
    let bvh = MeshBvh::build(&mesh).unwrap();
    let mut rng = SplitMix64::new(5);
    let mut hits = 0;
    for k in 0..600 {
        let o = Vec3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        let toward = Vec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        let d = if k % 3 == 0 {
            Vec3::new(rng.range(-1.0, 1.0), 0.3, rng.range(-1.0, 1.0))
        } else {
            toward - o
        };
        let Ok(ray) = Ray::new(o, d) else { continue };
        let want = brute(&mesh, &ray, 10.0);
        let got = bvh.cast(&ray, 10.0);
        assert_eq!(got.is_some(), want.is_some(), "ray {k}");
        assert_eq!(bvh.any_hit(&ray, 10.0), want.is_some(), "ray {k}");
        if let (Some(h), Some((t, tri))) = (got, want) {
            hits += 1;
            assert!((h.distance - t).abs() < 1e-5, "ray {k}");
            if let HitTarget::Mesh { triangle, .. } = h.target {
                let same = triangle == tri || (h.distance - t).abs() == 0.0;
                assert!(same, "ray {k}: triangle {triangle} vs {tri}");
            }
        }
    }
    assert!(hits > 300);
}

/// The lost-hit pitfall: exactly axis-aligned rays on shared triangle edges and
/// box faces of a triangulated terrain must all hit.
#[test]
fn mesh_bvh_keeps_axis_aligned_rays_on_shared_edges() {
    let g = bumpy();
    let mesh = g.to_tri_mesh();
    let bvh = MeshBvh::build(&mesh).unwrap();
    for j in 0..g.nz() {
        for i in 0..g.nx() {
            let p = g.sample_position(i, j);
            for (dx, dz) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)] {
                let (x, z) = (p.x + dx * CELL, p.z + dz * CELL);
                let Some(h) = g.height_at(x, z) else { continue };
                let ray = Ray::down(x, 5.0, z).unwrap();
                let hit = bvh.cast(&ray, f32::INFINITY);
                let hit = hit.unwrap_or_else(|| panic!("lost hit at ({x}, {z})"));
                assert!((hit.point.y - h).abs() < 1e-5);
            }
        }
    }
}

#[test]
fn scene_returns_the_closest_of_ground_and_meshes() {
    let mut g = bumpy();
    let mut scene = RayScene::new();
    scene.set_grid(&g);
    let mut rock = blob(12);
    for p in &mut rock.positions {
        *p = *p * 0.5 + Vec3::new(1.0, 0.6, 6.0);
    }
    let rock_id = scene.add_mesh(rock.clone()).unwrap();
    let rock_bvh = MeshBvh::build(&rock).unwrap();
    let ground = GridBvh::build(&g);
    let mut rng = SplitMix64::new(9);
    for ray in random_rays(&g, &mut rng, 300) {
        let a = ground.cast(&g, &ray, 50.0);
        let b = rock_bvh.cast(&ray, 50.0);
        let want = match (a, b) {
            (Some(a), Some(b)) => Some(if a.distance <= b.distance {
                a.distance
            } else {
                b.distance
            }),
            (a, b) => a.or(b).map(|h| h.distance),
        };
        assert_eq!(scene.cast(Some(&g), &ray, 50.0).map(|h| h.distance), want);
        assert_eq!(scene.any_hit(Some(&g), &ray, 50.0), want.is_some());
        assert_eq!(
            scene.cast(None, &ray, 50.0).map(|h| h.distance),
            b.map(|h| h.distance)
        );
    }
    let on_rock = scene.cast_down(Some(&g), 1.0, 6.0, 5.0).unwrap();
    assert!(matches!(on_rock.target, HitTarget::Mesh { mesh, .. } if mesh == rock_id));
    // Edits reach the scene through refit_grid.
    let rect = GridRect::new(0, 0, 6, 6);
    carve(&mut g, rect, 1.0);
    scene.refit_grid(&g, rect);
    let p = g.sample_position(2, 2);
    let hit = scene.cast_down(Some(&g), p.x, p.z, 5.0).unwrap();
    assert_eq!(hit.point.y, p.y);
    // A grid of another shape is answered exactly (no panic), and a refit rebuilds for it.
    let other = flat();
    let x = ORIGIN.x + 1.3;
    assert_eq!(
        scene.cast_down(Some(&other), x, 3.0, 5.0).unwrap().point.y,
        0.5
    );
    let ray = Ray::down(x, 5.0, 3.0).unwrap();
    assert_eq!(scene.cast(Some(&other), &ray, 50.0).unwrap().distance, 4.5);
    assert!(scene.any_hit(Some(&other), &ray, 50.0));
    scene.refit_grid(&other, other.full_rect());
    assert!(scene.grid_bvh().unwrap().matches(&other));
}

#[test]
fn invalid_meshes_and_tile_sizes_are_refused_not_panicked_on() {
    let mut scene = RayScene::new();
    let bad = TriMesh {
        positions: vec![Vec3::ZERO, Vec3::X],
        normals: vec![],
        triangles: vec![[0, 1, 5]],
        parts: vec![],
    };
    assert!(scene.add_mesh(bad).is_err());
    assert!(MeshBvh::build(&TriMesh::default()).is_err());
    assert!(GridBvh::build_with_tiles(&flat(), 0).is_err());
    assert_eq!(scene.mesh_count(), 0);
}
