//! Crowd scenes generated from a few numbers: the built-in `crowd` scene and
//! the variants `softwalk bench` measures (walker count, field size, grid,
//! grass cover, lanes or crossing paths).

use std::fmt::Write;

/// How the walkers are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrowdLayout {
    /// Four groups enter from the four sides and cross the field.
    Crossing,
    /// Parallel lanes along +X, `spacing` metres apart, in rows when the
    /// lanes do not fit across the field.
    Lanes,
}

/// The numbers a crowd scene is made from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrowdSpec {
    /// Number of walkers.
    pub walkers: usize,
    /// Side of the square field, metres.
    pub size_m: f32,
    /// Samples along a side.
    pub resolution: u32,
    /// Fraction of the field covered by 0.9 m (`medium`) grass, in a band
    /// across the middle, on soil; `[0, 1]`.
    pub grass_fraction: f32,
    /// Sand, snow and soil bands (true) or sand alone (false).
    pub mixed_ground: bool,
    /// Layout of the paths.
    pub layout: CrowdLayout,
    /// Distance between neighbouring lanes, metres.
    pub spacing_m: f32,
    /// Simulated seconds.
    pub duration_s: f32,
}

impl Default for CrowdSpec {
    /// The built-in `crowd` scene: 240 walkers of four morphologies cross a
    /// 40 x 40 m field of sand, snow and grass on soil from its four sides.
    fn default() -> Self {
        CrowdSpec {
            walkers: 240,
            size_m: 40.0,
            resolution: 2048,
            grass_fraction: 0.2,
            mixed_ground: true,
            layout: CrowdLayout::Crossing,
            spacing_m: 0.6,
            duration_s: 12.0,
        }
    }
}

/// Body height (m) and mass (kg) of the morphologies, taken in turn.
const MORPHOLOGIES: [(f32, f32); 4] = [(1.0, 20.0), (1.4, 40.0), (1.75, 70.0), (1.9, 80.0)];
/// Distance kept from the field's edges, metres.
const MARGIN_M: f32 = 1.0;
/// Distance between the rows of one group along its walking direction, metres.
const ROW_GAP_M: f32 = 1.5;

/// One walker: start (x, z), heading in degrees, path length.
struct Walker {
    start: [f32; 2],
    heading_deg: f32,
    length: f32,
}

impl CrowdSpec {
    /// The scene as TOML (`name` and its description first).
    pub fn toml(&self, name: &str) -> String {
        let size = self.size_m;
        let mut s = String::new();
        let _ = writeln!(s, "name = \"{name}\"");
        let _ = writeln!(
            s,
            "description = \"{} walkers of mixed morphologies cross a {size} x {size} m field{}\"",
            self.walkers,
            if self.mixed_ground {
                " of sand, snow and grass"
            } else {
                " of sand"
            }
        );
        let _ = writeln!(
            s,
            "\n[terrain]\nsize_x = {size:.1}\nsize_z = {size:.1}\nresolution = {}\nmax_height = 10.0\nmaterial = \"sand\"\n\n[terrain.shape]\nkind = \"flat\"",
            self.resolution
        );
        let band = self.grass_band();
        if self.mixed_ground {
            let third = size / 3.0;
            let _ = writeln!(
                s,
                "\n[[terrain.regions]]\nmaterial = \"snow\"\nx = [{:.3}, {:.3}]",
                third,
                2.0 * third
            );
        }
        if let Some([z0, z1]) = band {
            let _ = writeln!(
                s,
                "\n[[terrain.regions]]\nmaterial = \"soil\"\nz = [{z0:.3}, {z1:.3}]"
            );
        }
        let _ = writeln!(
            s,
            "\n[sim]\nduration = {:.3}\ndt = 0.016666668\n\n[camera]\nfov_deg = 55.0\n\n[camera.mode]\nkind = \"fixed\"\neye = [{:.2}, {:.2}, {:.2}]\ntarget = [{:.2}, 0.0, {:.2}]",
            self.duration_s,
            0.5 * size,
            0.75 * size,
            -0.35 * size,
            0.5 * size,
            0.55 * size
        );
        let _ = writeln!(
            s,
            "\n[render]\nwidth = 960\nheight = 540\nevery = 4\noverlays = false\ngif = true\napng = false\ncontact_sheet_columns = 6"
        );
        if let Some([z0, z1]) = band {
            let _ = writeln!(
                s,
                "\n[[grass]]\nx = [0.0, {size:.3}]\nz = [{z0:.3}, {z1:.3}]\npreset = \"medium\""
            );
        }
        for (k, w) in self.walkers().iter().enumerate() {
            let (height, mass) = MORPHOLOGIES[k % MORPHOLOGIES.len()];
            let _ = writeln!(
                s,
                "\n[[characters]]\nname = \"w{k}\"\npath = {{ kind = \"straight\", start = [{:.3}, {:.3}], heading_deg = {:.1}, length = {:.3} }}\nbody = {{ height = {height}, mass = {mass} }}",
                w.start[0], w.start[1], w.heading_deg, w.length
            );
        }
        s
    }

    /// The grass band `[z0, z1]` across the middle, or `None` without grass.
    fn grass_band(&self) -> Option<[f32; 2]> {
        let f = self.grass_fraction.clamp(0.0, 1.0);
        (f > 0.0).then(|| {
            let half = 0.5 * f * self.size_m;
            let mid = 0.5 * self.size_m;
            [mid - half, mid + half]
        })
    }

    fn walkers(&self) -> Vec<Walker> {
        match self.layout {
            CrowdLayout::Crossing => self.crossing(),
            CrowdLayout::Lanes => self.lanes(),
        }
    }

    /// Four groups, one per side, each in lanes `spacing_m` apart and rows
    /// [`ROW_GAP_M`] apart, walking across to the opposite side. The lanes
    /// keep clear of the corners, where the other groups' rows start.
    fn crossing(&self) -> Vec<Walker> {
        let size = self.size_m;
        let per_group = self.walkers.div_ceil(4).max(1);
        let spacing = self.spacing_m.max(0.01);
        // The fewest rows whose lanes, between corners as deep as the rows,
        // hold the group; on a field too small for that, the most walkers
        // per row (spawn points may then overlap: the scene warns).
        let usable_for =
            |rows: usize| (size - 2.0 * (MARGIN_M + rows as f32 * ROW_GAP_M)).max(spacing);
        let lanes_in = |usable: f32| ((usable / spacing) as usize).clamp(1, per_group);
        let max_rows = ((0.5 * size / ROW_GAP_M) as usize).max(1);
        let rows = (1..=max_rows)
            .find(|&r| r * lanes_in(usable_for(r)) >= per_group)
            .unwrap_or(1);
        let usable = usable_for(rows);
        let lanes = lanes_in(usable);
        let corner = (size - usable) / 2.0;
        let mut out = Vec::with_capacity(self.walkers);
        for k in 0..self.walkers {
            let (group, slot) = (k % 4, k / 4);
            let (lane, row) = (slot % lanes, slot / lanes);
            // Lanes of each group are offset by a quarter of the spacing, so
            // the groups' lanes interleave instead of meeting head-on.
            let across = corner
                + (lane as f32 + 0.5) * usable / lanes as f32
                + 0.25 * group as f32 * self.spacing_m.min(usable / lanes as f32);
            let along = MARGIN_M + row as f32 * ROW_GAP_M;
            let length = (size - along - MARGIN_M).max(1.0);
            let (start, heading_deg) = match group {
                0 => ([along, across], 0.0),
                1 => ([across, along], 90.0),
                2 => ([size - along, across], 180.0),
                _ => ([across, size - along], 270.0),
            };
            out.push(Walker {
                start: start.map(|v| v.clamp(0.0, size)),
                heading_deg,
                length,
            });
        }
        out
    }

    /// Parallel lanes along +X starting at the west edge, `spacing_m` apart
    /// and centred across the field; extra walkers in rows further east.
    fn lanes(&self) -> Vec<Walker> {
        let size = self.size_m;
        let usable = (size - 2.0 * MARGIN_M).max(0.0);
        let fit = ((usable / self.spacing_m.max(0.01)) as usize + 1).max(1);
        let lanes = fit.min(self.walkers.max(1));
        let width = (lanes - 1) as f32 * self.spacing_m;
        let z0 = 0.5 * (size - width);
        let rows = self.walkers.div_ceil(lanes).max(1);
        let row_gap = (usable / rows as f32).max(ROW_GAP_M);
        (0..self.walkers)
            .map(|k| {
                let (lane, row) = (k % lanes, k / lanes);
                let x = MARGIN_M + row as f32 * row_gap;
                Walker {
                    start: [x.min(size), z0 + lane as f32 * self.spacing_m],
                    heading_deg: 0.0,
                    length: (size - x - MARGIN_M).max(1.0),
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn the_builtin_crowd_parses_with_its_walkers_on_the_field() {
        let spec = CrowdSpec::default();
        let scene = Scene::from_toml_str(&spec.toml("crowd"), std::path::Path::new(".")).unwrap();
        assert!(scene.characters.len() >= 200);
        assert_eq!(scene.grass.len(), 1);
    }

    #[test]
    fn lanes_are_spaced_and_centred() {
        let spec = CrowdSpec {
            walkers: 2,
            size_m: 100.0,
            resolution: 257,
            layout: CrowdLayout::Lanes,
            spacing_m: 60.0,
            grass_fraction: 0.0,
            mixed_ground: false,
            ..CrowdSpec::default()
        };
        let w = spec.lanes();
        assert_eq!(w.len(), 2);
        assert!((w[1].start[1] - w[0].start[1] - 60.0).abs() < 1e-4);
        assert!((w[0].start[1] - 20.0).abs() < 1e-4);
        Scene::from_toml_str(&spec.toml("two"), std::path::Path::new(".")).unwrap();
    }
}
