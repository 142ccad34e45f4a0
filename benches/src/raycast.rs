//! The `raycast` group of the peers harness: our tile BVH over the height grid
//! against a brute-force loop over every grid triangle and against a triangle
//! BVH ([`MeshBvh`]: obvhs PLOC build, 4-wide traversal) over all grid
//! triangles, on the paper's 512² terrain, same run.
//!
//! Times are nanoseconds per ray (per refit for `refit_40x40`).

use std::hint::black_box;

use engine::geom::{GridBvh, GridRect, HeightGrid, MeshBvh, Ray, TriMesh, ray_triangle};
use engine::glam::{Vec2, Vec3, Vec3A};

use crate::{Row, time_ns};
use engine::rng::SplitMix64;

const CELL: f32 = 10.0 / 511.0;
const RAYS: usize = 2048;
/// The brute-force loop is so slow that it runs on a few rays only.
const BRUTE_RAYS: usize = 8;
const BUDGET_MS: u64 = 300;

/// Runs the group and returns one row per workload.
pub fn run() -> Vec<Row> {
    let grid = HeightGrid::from_fn(Vec2::ZERO, CELL, 512, 512, |x, z| {
        0.3 * (0.9 * x).sin() * (0.7 * z).cos() + 0.05 * (4.0 * x + 3.0 * z).sin()
    })
    .expect("a valid grid");
    let ours = GridBvh::build(&grid);
    let mesh = grid.to_tri_mesh();
    let tri_bvh = MeshBvh::build(&mesh).expect("a valid mesh");
    let mut rng = SplitMix64::new(1);
    let vertical: Vec<Ray> = (0..RAYS)
        .map(|_| Ray::down(rng.range(4.0, 6.0), 5.0, rng.range(4.0, 6.0)).expect("finite"))
        .collect();
    let arbitrary: Vec<Ray> = (0..RAYS)
        .map(|_| {
            let o = Vec3::new(
                rng.range(0.0, 10.0),
                rng.range(1.0, 3.0),
                rng.range(0.0, 10.0),
            );
            let d = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, -0.1),
                rng.range(-1.0, 1.0),
            );
            Ray::new(o, d).expect("finite")
        })
        .collect();

    let mut rows = Vec::new();
    for (name, rays) in [
        ("vertical_ray_512", &vertical),
        ("arbitrary_ray_512", &arbitrary),
    ] {
        let ours_ns = per_ray(rays.len(), || {
            for r in rays.iter() {
                black_box(ours.cast(&grid, r, f32::INFINITY));
            }
        });
        let down_ns = (name == "vertical_ray_512").then(|| {
            per_ray(rays.len(), || {
                for r in rays.iter() {
                    let o = r.origin();
                    black_box(ours.cast_down(&grid, o.x, o.z, o.y));
                }
            })
        });
        let tri_bvh_ns = per_ray(rays.len(), || {
            for r in rays.iter() {
                black_box(tri_bvh.cast(r, f32::INFINITY));
            }
        });
        let brute_ns = per_ray(BRUTE_RAYS, || {
            for r in &rays[..BRUTE_RAYS] {
                black_box(brute(&mesh, r));
            }
        });
        rows.push(Row::new(
            name,
            vec![
                ("ours_ns", Some(ours_ns)),
                ("ours_cast_down_ns", down_ns),
                ("brute_ns", Some(brute_ns)),
                ("tri_bvh_ns", Some(tri_bvh_ns)),
            ],
        ));
    }

    let mut edited = grid.clone();
    let mut refitted = GridBvh::build(&edited);
    let rect = GridRect::new(200, 230, 241, 271);
    let mut depth = 0.001;
    let refit_ns = time_ns(BUDGET_MS, || {
        depth = -depth;
        for (i, j) in rect.iter() {
            let h = edited.height(i, j) + depth;
            edited.set_height(i, j, h);
        }
        refitted.refit(&edited, rect);
    });
    let rebuild_ns = time_ns(BUDGET_MS, || {
        black_box(GridBvh::build(&edited));
    });
    let tri_rebuild_ns = time_ns(BUDGET_MS, || {
        black_box(MeshBvh::build(&edited.to_tri_mesh()).expect("valid"));
    });
    rows.push(Row::new(
        "refit_40x40",
        vec![
            ("ours_ns", Some(refit_ns)),
            ("ours_rebuild_ns", Some(rebuild_ns)),
            ("tri_bvh_ns", Some(tri_rebuild_ns)),
        ],
    ));
    rows
}

fn per_ray(rays: usize, f: impl FnMut()) -> f64 {
    time_ns(BUDGET_MS, f) / rays as f64
}

/// The closest hit over every triangle.
fn brute(mesh: &TriMesh, ray: &Ray) -> Option<f32> {
    let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
    let mut best = f32::INFINITY;
    for t in &mesh.triangles {
        let corners = t.map(|v| Vec3A::from(mesh.positions[v as usize]));
        if let Some(t) = ray_triangle(o, d, corners, best) {
            best = t;
        }
    }
    best.is_finite().then_some(best)
}
