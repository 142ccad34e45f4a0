use super::grid_bvh::closer;
use super::{GeomError, GridBvh, GridRect, HeightGrid, Hit, MeshBvh, MeshId, Ray, TriMesh};

/// Everything rays can hit: static meshes (in world space) and at most one
/// deformable height grid, through their BVHs.
///
/// The grid's heights are not owned: queries take `Option<&HeightGrid>`
/// (`None` leaves the ground out). A grid whose shape differs from the one
/// the ground BVH was built for is still answered exactly, by a direct walk.
///
/// ```
/// use engine::geom::{HeightGrid, RayScene, TriMesh};
/// use engine::glam::{Vec2, Vec3};
/// let ground = HeightGrid::new(Vec2::ZERO, 0.1, 33, 33, 0.0).unwrap();
/// let mut scene = RayScene::new();
/// scene.set_grid(&ground);
/// let rock = TriMesh::new(
///     vec![Vec3::new(1.0, 0.5, 1.0), Vec3::new(2.0, 0.5, 1.0), Vec3::new(1.0, 0.5, 2.0)],
///     vec![[0, 2, 1]],
/// ).unwrap();
/// let rock_id = scene.add_mesh(rock).unwrap();
/// let on_rock = scene.cast_down(Some(&ground), 1.2, 1.2, 5.0).unwrap();
/// assert!((on_rock.point.y - 0.5).abs() < 1e-6);
/// let beside = scene.cast_down(Some(&ground), 2.5, 2.5, 5.0).unwrap();
/// assert!(beside.point.y.abs() < 1e-6);
/// # let _ = rock_id;
/// ```
#[derive(Debug, Clone, Default)]
pub struct RayScene {
    meshes: Vec<MeshBvh>,
    grid: Option<GridBvh>,
}

impl RayScene {
    /// An empty scene.
    pub fn new() -> RayScene {
        RayScene::default()
    }

    /// Adds a static mesh, already in world space; refuses an invalid mesh.
    pub fn add_mesh(&mut self, mesh: TriMesh) -> Result<MeshId, GeomError> {
        let id = MeshId(self.meshes.len() as u32);
        self.meshes.push(MeshBvh::build(&mesh)?.with_id(id));
        Ok(id)
    }

    /// The BVH of mesh `id`.
    pub fn mesh(&self, id: MeshId) -> Option<&MeshBvh> {
        self.meshes.get(id.0 as usize)
    }

    /// Number of meshes.
    pub fn mesh_count(&self) -> usize {
        self.meshes.len()
    }

    /// Uses `grid` as the ground (builds its [`GridBvh`], replacing any previous one).
    pub fn set_grid(&mut self, grid: &HeightGrid) {
        self.grid = Some(GridBvh::build(grid));
    }

    /// Removes the ground.
    pub fn clear_grid(&mut self) {
        self.grid = None;
    }

    /// The ground's BVH, if any.
    pub fn grid_bvh(&self) -> Option<&GridBvh> {
        self.grid.as_ref()
    }

    /// Refits the ground after the samples in `changed` were edited (builds it
    /// when none is set or when the grid changed shape).
    pub fn refit_grid(&mut self, grid: &HeightGrid, changed: GridRect) {
        match &mut self.grid {
            Some(bvh) if bvh.matches(grid) => bvh.refit(grid, changed),
            _ => self.set_grid(grid),
        }
    }

    /// The ground BVH when it was built for `grid`'s shape.
    fn ground_for(&self, grid: &HeightGrid) -> Option<&GridBvh> {
        self.grid.as_ref().filter(|bvh| bvh.matches(grid))
    }

    /// The closest hit over every mesh and the ground within `max_t`.
    pub fn cast(&self, grid: Option<&HeightGrid>, ray: &Ray, max_t: f32) -> Option<Hit> {
        let mut best = self.cast_ground(grid, ray, max_t);
        for mesh in &self.meshes {
            let limit = best.map_or(max_t, |b| b.distance);
            if mesh.bounds().ray_interval(ray, limit).is_none() {
                continue;
            }
            if let Some(h) = mesh.cast(ray, limit)
                && best.is_none_or(|b| closer(&h, &b))
            {
                best = Some(h);
            }
        }
        best
    }

    /// True when `ray` meets anything within `max_t`.
    pub fn any_hit(&self, grid: Option<&HeightGrid>, ray: &Ray, max_t: f32) -> bool {
        let ground = grid.is_some_and(|g| match self.ground_for(g) {
            Some(bvh) => bvh.any_hit(g, ray, max_t),
            None => g.intersect_ray(ray, max_t).is_some(),
        });
        ground
            || self
                .meshes
                .iter()
                .any(|m| m.bounds().ray_interval(ray, max_t).is_some() && m.any_hit(ray, max_t))
    }

    /// The closest hit of a ray going straight down from `(x, from_y, z)`:
    /// the ground through its vertical fast path, meshes through their BVHs.
    pub fn cast_down(&self, grid: Option<&HeightGrid>, x: f32, z: f32, from_y: f32) -> Option<Hit> {
        let mut best = grid.and_then(|g| match self.ground_for(g) {
            Some(bvh) => bvh.cast_down(g, x, z, from_y),
            None => g.cast_down(x, z, from_y),
        });
        if self.meshes.is_empty() {
            return best;
        }
        let ray = Ray::down(x, from_y, z).ok()?;
        for mesh in &self.meshes {
            let limit = best.map_or(f32::INFINITY, |b| b.distance);
            if let Some(h) = mesh.cast(&ray, limit)
                && best.is_none_or(|b| closer(&h, &b))
            {
                best = Some(h);
            }
        }
        best
    }

    fn cast_ground(&self, grid: Option<&HeightGrid>, ray: &Ray, max_t: f32) -> Option<Hit> {
        let grid = grid?;
        match self.ground_for(grid) {
            Some(bvh) => bvh.cast(grid, ray, max_t),
            None => grid.intersect_ray(ray, max_t),
        }
    }
}
