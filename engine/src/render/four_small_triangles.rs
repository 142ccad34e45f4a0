//! Set-up of four small triangles at once, one triangle per lane of `f32`
//! vectors (structure of arrays): culling, winding, edge functions, window
//! coverage and vertex weights for the common case of dense meshes, a pixel
//! box of at most [`WINDOW_COLUMNS`] x [`WINDOW_ROWS`] centres.
//!
//! Every lane runs the operations of [`SmallTriangle::set_up`], its window
//! coverage and [`VertexWeights::from_edges`] on the same exact whole numbers,
//! so a lane gives the same coverage and the same weights as the one-at-a-time
//! set-up (up to the sign of a zero weight, which no pixel shows); where
//! [`SmallTriangle`] keeps one triangle's three edges in the lanes of one
//! vector (one lane idle, and shuffles to combine them), here each operation
//! serves four triangles. A triangle outside the window, or too long for
//! exact `f32` edges, is left to the one-at-a-time set-up.
//!
//! [`SmallTriangle`]: super::small_triangle::SmallTriangle
//! [`SmallTriangle::set_up`]: super::small_triangle::SmallTriangle::set_up

use glam::{BVec4A, IVec4, Vec4};

use super::batch::CullMode;
use super::centre_box::{SpanLanes, whole_numbers};
use super::project::transpose_lanes;
use super::raster::{HALF, MASK_EXTENT, ONE, ScreenVertex, VertexWeights};
use super::small_triangle::{WINDOW_COLUMNS, WINDOW_ROWS, edge_lanes};

/// Four triangles set up together (lane `t` is triangle `t`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FourSmallTriangles {
    /// Bit `t` set: triangle `t` is not set up here (its box is larger than
    /// the window, or an edge is too long for exact `f32` edge functions).
    one_at_a_time: u32,
    /// Bit `t` set: triangle `t` runs counter-clockwise on screen and is
    /// drawn turned clockwise (vertices 1 and 2, and edges 1 and 2, swapped).
    turned: u32,
    /// The pixel centres each triangle covers, bit `8 * row + column`
    /// relative to its box's corner (none for dropped triangles).
    coverage: [i32; 4],
    /// Per triangle, the weights of the vertices opposite edges 1 and 2 as
    /// submitted (edge values over the doubled area): at the first centre,
    /// then per pixel right and down.
    weights: [[f32; 4]; 6],
}

/// The pixel spans of four triangles, one per lane: first column and row,
/// and their numbers of columns and rows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FourSpans {
    x0: Vec4,
    y0: Vec4,
    columns: Vec4,
    rows: Vec4,
    /// Bit `t` set: triangle `t`'s box fits the window.
    in_window: u32,
}

impl FourSpans {
    /// The spans of the four triangles whose span lanes are `spans`, each
    /// holding a pixel centre.
    #[inline(always)]
    pub fn of(spans: [SpanLanes; 4]) -> FourSpans {
        // Span lanes (x0, -x1, y0, -y1) per triangle, as lanes per coordinate.
        let [x0, minus_x1, y0, minus_y1] = transpose_lanes(spans.map(SpanLanes::lanes));
        let columns = Vec4::ONE - (minus_x1 + x0);
        let rows = Vec4::ONE - (minus_y1 + y0);
        // `fits_window`, per lane.
        let fits = columns.cmple(Vec4::splat(WINDOW_COLUMNS as f32))
            & rows.cmple(Vec4::splat(WINDOW_ROWS as f32));
        FourSpans {
            x0,
            y0,
            columns,
            rows,
            in_window: fits.bitmask(),
        }
    }

    /// Bit `t` set: triangle `t`'s box fits the window of
    /// [`FourSmallTriangles`].
    #[inline(always)]
    pub fn in_window(&self) -> u32 {
        self.in_window
    }
}

/// What [`FourSmallTriangles`] made of one of its triangles.
#[derive(Debug, Clone, Copy)]
pub(crate) enum FourSetUp<'v> {
    /// Not set up here: the one-at-a-time set-up applies.
    OneAtATime,
    /// Covers no pixel centre, has no area, or its facing is culled.
    Empty,
    /// A triangle to draw.
    Covered {
        /// The vertices, clockwise on screen.
        vertices: [&'v ScreenVertex; 3],
        /// The weights of vertices 1 and 2 over the box.
        weights: VertexWeights,
        /// The covered pixel centres, bit `8 * row + column` from the box's corner.
        mask: u64,
    },
}

/// Lane `t` is `f(t)`, converted exactly (whole numbers below `2^24`).
#[inline(always)]
fn lanes(f: impl Fn(usize) -> i32) -> Vec4 {
    IVec4::new(f(0), f(1), f(2), f(3)).as_vec4()
}

impl FourSmallTriangles {
    /// Sets up the triangles `v` (each in submitted order, inside the guard
    /// band) over their pixel spans `spans`, each holding a pixel centre.
    #[inline(always)]
    pub fn set_up(
        v: [[&ScreenVertex; 3]; 4],
        spans: &FourSpans,
        cull: CullMode,
    ) -> FourSmallTriangles {
        let one = ONE as f32;
        let FourSpans {
            x0,
            y0,
            columns,
            rows,
            ..
        } = *spans;
        // The first centre, and the vertices relative to it (exact: see
        // `SmallTriangle::set_up`); edge k runs from vertex k + 1 to k + 2.
        let (px, py) = (x0 * one + HALF as f32, y0 * one + HALF as f32);
        let x = [1, 2, 0].map(|k| lanes(|t| v[t][k].x) - px);
        let y = [1, 2, 0].map(|k| lanes(|t| v[t][k].y) - py);
        let dx = [x[1] - x[0], x[2] - x[1], x[0] - x[2]];
        let dy = [y[1] - y[0], y[2] - y[1], y[0] - y[2]];
        let extent = (0..3).fold(Vec4::ZERO, |m, k| m.max(dx[k].abs().max(dy[k].abs())));
        let exact = extent.cmplt(Vec4::splat(MASK_EXTENT as f32));
        let area = dy[2] * dx[1] - dx[2] * dy[1];
        // The winding rule of `SmallTriangle::set_up`: a negative area is
        // turned clockwise (each edge reversed), a positive one kept when
        // both sides are drawn.
        let turn = area.cmplt(Vec4::ZERO);
        let kept = turn | (area.cmpgt(Vec4::ZERO) & BVec4A::splat(cull == CullMode::None));
        let sign = Vec4::select(turn, Vec4::NEG_ONE, Vec4::ONE);
        let (dx, dy) = (dx.map(|d| d * sign), dy.map(|d| d * sign));
        let area = area * sign;
        // Each edge's value at the first centre with the top-left bias, and
        // its steps: `edge_lanes` with one edge of four triangles in the
        // lanes. (Turning also trades edges 1 and 2, which neither the
        // coverage nor these values depend on: the weights are traded with
        // the vertices in `lane`.)
        let edges: [[Vec4; 3]; 3] =
            std::array::from_fn(|k| edge_lanes(dy[k] * x[k] - dx[k] * y[k], dx[k], dy[k]));
        let [start, step_x, step_y] = [0, 1, 2].map(|part| edges.map(|edge| edge[part]));
        // Window coverage: centre (column c, row r) is covered when all
        // three edge values there are >= 0 (exact inside the box) and it
        // lies in the box.
        let second_row = kept & rows.cmpgt(Vec4::ONE);
        let mut first = start;
        let mut coverage = Vec4::ZERO;
        for c in 0..WINDOW_COLUMNS {
            let in_column = kept & columns.cmpgt(Vec4::splat(c as f32));
            let second: [Vec4; 3] = std::array::from_fn(|k| first[k] + step_y[k]);
            let inside = |e: [Vec4; 3]| e[0].min(e[1]).min(e[2]).cmpge(Vec4::ZERO);
            let bit = |row: u32| Vec4::splat((1u32 << (8 * row + c)) as f32);
            coverage += Vec4::select(inside(first) & in_column, bit(0), Vec4::ZERO);
            coverage += Vec4::select(inside(second) & in_column & second_row, bit(1), Vec4::ZERO);
            first = std::array::from_fn(|k| first[k] + step_x[k]);
        }
        // `VertexWeights::from_edges`: edge values over the doubled area.
        // (Written out: `array::map` here stayed out of line, in baseline
        // code.)
        let inv_area = Vec4::ONE / area;
        let weight = |e: Vec4| (e * inv_area).to_array();
        let weights = [
            weight(start[1]),
            weight(start[2]),
            weight(step_x[1]),
            weight(step_x[2]),
            weight(step_y[1]),
            weight(step_y[2]),
        ];
        FourSmallTriangles {
            one_at_a_time: !(spans.in_window & exact.bitmask()) & 0b1111,
            turned: turn.bitmask(),
            coverage: whole_numbers(coverage),
            weights,
        }
    }

    /// What became of triangle `t`, whose vertices in submitted order are `v`.
    #[inline(always)]
    pub fn lane<'v>(&self, t: usize, v: [&'v ScreenVertex; 3]) -> FourSetUp<'v> {
        if self.one_at_a_time & (1 << t) != 0 {
            return FourSetUp::OneAtATime;
        }
        let mask = self.coverage[t] as u64;
        if mask == 0 {
            return FourSetUp::Empty;
        }
        let w = |k: usize| self.weights[k][t];
        let (start, step_x, step_y) = ([w(0), w(1)], [w(2), w(3)], [w(4), w(5)]);
        let (vertices, weights) = if self.turned & (1 << t) != 0 {
            let swap = |[a, b]: [f32; 2]| [b, a];
            let weights = VertexWeights {
                start: swap(start),
                step_x: swap(step_x),
                step_y: swap(step_y),
            };
            ([v[0], v[2], v[1]], weights)
        } else {
            let weights = VertexWeights {
                start,
                step_x,
                step_y,
            };
            (v, weights)
        };
        FourSetUp::Covered {
            vertices,
            weights,
            mask,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::centre_box::{centre_box, screen_limits};
    use crate::render::small_triangle::{SmallSetUp, SmallTriangle, fits_window};
    use crate::rng::SplitMix64;

    /// Random small triangles, four at a time, against the one-at-a-time
    /// set-up: the same decision, coverage, vertices and weights.
    #[test]
    fn four_at_a_time_agrees_with_one_at_a_time() {
        let mut rng = SplitMix64::new(0x3c6e_f372_fe94_f82b);
        let (width, height) = (48, 40);
        let limits = screen_limits(width, height);
        let mut outcomes = [0usize; 3];
        // A random small triangle whose span holds a pixel centre (the
        // set-up's precondition), and that span.
        let mut triangle = || loop {
            let centre = (rng.range(0.0, 48.0), rng.range(0.0, 40.0));
            let size = 0.5 + 12.0 * rng.next_f32() * rng.next_f32();
            let v: [ScreenVertex; 3] = std::array::from_fn(|_| ScreenVertex {
                x: ((centre.0 + rng.range(-size, size) * 0.5) * ONE as f32) as i32,
                y: ((centre.1 + rng.range(-size, size) * 0.5) * ONE as f32) as i32,
                inv_w: 1.0,
                color_w: Vec3::ZERO,
            });
            let [a, b, c] = v.each_ref().map(centre_box);
            let lanes = SpanLanes::of(a, b, c, limits);
            if !lanes.is_empty() {
                return (v, lanes);
            }
        };
        for group in 0..3000 {
            let picked: [([ScreenVertex; 3], SpanLanes); 4] = std::array::from_fn(|_| triangle());
            let (triangles, lanes) = (picked.map(|p| p.0), picked.map(|p| p.1));
            let cull = if group % 3 == 0 {
                CullMode::Back
            } else {
                CullMode::None
            };
            let vertices = triangles.each_ref().map(|t| t.each_ref());
            let four = FourSmallTriangles::set_up(vertices, &FourSpans::of(lanes), cull);
            for t in 0..4 {
                let span = lanes[t].span();
                let (columns, rows) = span.size();
                let fits = fits_window(columns, rows);
                let one = SmallTriangle::set_up(vertices[t], span, cull);
                match (four.lane(t, vertices[t]), one) {
                    (FourSetUp::OneAtATime, one) => {
                        assert!(!fits || matches!(one, SmallSetUp::TooBig), "{span:?}");
                        outcomes[0] += 1;
                    }
                    (FourSetUp::Empty, SmallSetUp::Dropped) => outcomes[1] += 1,
                    (FourSetUp::Empty, SmallSetUp::Kept { triangle, .. }) => {
                        assert!(fits);
                        assert_eq!(triangle.coverage(span), 0);
                        outcomes[1] += 1;
                    }
                    (
                        FourSetUp::Covered {
                            vertices,
                            weights,
                            mask,
                        },
                        SmallSetUp::Kept {
                            vertices: want_vertices,
                            area,
                            triangle,
                        },
                    ) => {
                        assert!(fits);
                        assert_eq!(mask, triangle.coverage(span));
                        assert_eq!(vertices, want_vertices);
                        assert_eq!(weights, triangle.weights(area));
                        outcomes[2] += 1;
                    }
                    (lane, one) => panic!("{span:?}: {lane:?} against {one:?}"),
                }
            }
        }
        assert!(outcomes.iter().all(|&n| n > 500), "{outcomes:?}");
    }
}
