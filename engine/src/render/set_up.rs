//! The triangle set-up every batch shares: triangles culled by their
//! outcodes and facing, clipped where they cross the near plane or the guard
//! band, wound clockwise on screen and kept when they cover a pixel centre,
//! into a [`TriangleSink`]: a [`super::batch::ScreenBatch`] keeps them binned
//! by bands to draw later, a [`super::at_once::DrawnAtOnce`] draws them as
//! they come.

use glam::Vec4;
use multiversion::multiversion;

use super::batch::{CullMode, TriangleGroup, Viewport};
use super::centre_box::{SpanLanes, screen_limits, triangle_span};
use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle};
use super::four_small_triangles::{FourSetUp, FourSmallTriangles, FourSpans};
use super::kernels::{Kernels, run_baseline};
use super::project::{ClipSource, ProjectedVertex, VertexShader, project_vertices};
use super::raster::{
    BigTriangle, Dot, Edges, PixelSpan, Planes, ScreenVertex, Triangle, signed_area,
};
use super::small_triangle::{SmallSetUp, SmallTriangle};

/// Sets up every triangle of `groups` over the vertices of `positions`,
/// coloured four at a time by `shader`, into `sink`, with the machine code
/// `kernels` selects. `projected` is scratch for the projected vertices
/// (kept by the caller for its capacity).
pub(crate) fn set_up<P: ClipSource, S: VertexShader>(
    sink: &mut impl TriangleSink,
    projected: &mut Vec<ProjectedVertex>,
    positions: P,
    shader: S,
    groups: &[TriangleGroup<'_>],
    vp: Viewport,
    kernels: Kernels,
) {
    match kernels {
        Kernels::Dispatched => build_dispatched(sink, projected, positions, shader, groups, vp),
        Kernels::Baseline => {
            run_baseline(|| build_batch(sink, projected, positions, shader, groups, vp))
        }
    }
}

/// Where set-up triangles go. The provided methods are the set-up itself,
/// compiled into every sink's copy of [`set_up`]; a sink says what keeping a
/// triangle means.
pub(crate) trait TriangleSink {
    /// The edge functions that the coverage of big triangles refers to.
    fn edges(&mut self) -> &mut Vec<Edges>;

    /// Keeps a set-up triangle whose box is `span`.
    fn triangle(&mut self, tri: Triangle, span: PixelSpan);

    /// Keeps a triangle that covers a single pixel centre, as that pixel.
    fn dot(&mut self, dot: Dot);

    /// Culls, orients, sets up and keeps one triangle if it covers a pixel
    /// centre.
    #[inline(always)]
    fn push(&mut self, projected: &[ProjectedVertex], tri: [u32; 3], cull: CullMode, limits: Vec4) {
        let [a, b, c] = tri.map(|k| k as usize);
        // Most sub-pixel triangles have no pixel centre in their box: drop them
        // first (the box does not depend on the winding).
        let (pa, pb, pc) = (&projected[a], &projected[b], &projected[c]);
        let Some(span) = triangle_span(pa.centre_box, pb.centre_box, pc.centre_box, limits) else {
            return;
        };
        self.push_in_span([&pa.screen, &pb.screen, &pc.screen], cull, span);
    }

    /// [`TriangleSink::push`] for a triangle whose pixel span `span` is known
    /// to hold a pixel centre.
    #[inline(always)]
    fn push_in_span(&mut self, v: [&ScreenVertex; 3], cull: CullMode, span: PixelSpan) {
        let (vertices, area, small) = match SmallTriangle::set_up(v, span, cull) {
            SmallSetUp::Kept {
                vertices,
                area,
                triangle,
            } => (vertices, area, triangle),
            SmallSetUp::Dropped => return,
            SmallSetUp::TooBig => {
                let Some((v, area)) = clockwise(v, cull) else {
                    return;
                };
                let tri = BigTriangle::of(v, span).triangle(v, area, self.edges());
                self.triangle(tri, span);
                return;
            }
        };
        let mask = small.coverage(span);
        if mask != 0 {
            self.push_covered(small.planes(vertices, area), span, mask);
        }
    }

    /// Sets up four triangles that need no clipping, whose pixel spans hold
    /// a pixel centre, together where they are small enough
    /// ([`FourSmallTriangles`]), and keeps them in order.
    #[inline(always)]
    fn push_four(&mut self, kept: &[KeptTriangle<'_>; 4], cull: CullMode) {
        let spans = FourSpans::of(kept.map(|k| k.lanes));
        if spans.in_window().count_ones() < FOUR_AT_A_TIME_MIN {
            for k in kept {
                self.push_in_span(k.screen(), cull, k.lanes.span());
            }
            return;
        }
        let four = FourSmallTriangles::set_up(kept.map(|k| k.screen()), &spans, cull);
        // Each triangle's vertices read again from `kept` (keeping the twelve
        // in registers for the loop costs more).
        for (t, k) in kept.iter().enumerate() {
            match four.lane(t, k.screen()) {
                FourSetUp::OneAtATime => self.push_in_span(k.screen(), cull, k.lanes.span()),
                FourSetUp::Empty => {}
                FourSetUp::Covered {
                    vertices,
                    weights,
                    mask,
                } => self.push_covered(
                    Planes::from_weights(vertices, weights),
                    k.lanes.span(),
                    mask,
                ),
            }
        }
    }

    /// Keeps a small triangle with attribute planes `planes` over box `span`
    /// that covers the centres of `mask` (not empty; see
    /// [`Triangle::masked`]): as a [`Dot`] when that is a single centre.
    #[inline(always)]
    fn push_covered(&mut self, planes: Planes, span: PixelSpan, mask: u64) {
        if mask.is_power_of_two() {
            self.dot(Dot::in_box(&planes, span, mask));
        } else {
            self.triangle(Triangle::masked(planes, span, mask), span);
        }
    }
}

/// The triangle `v` wound clockwise on screen with its positive doubled area,
/// or `None` when it has no area or `cull` drops its facing.
#[inline]
fn clockwise(v: [&ScreenVertex; 3], cull: CullMode) -> Option<([&ScreenVertex; 3], i64)> {
    let [a, b, c] = v;
    let area = signed_area(a, b, c);
    // Counter-clockwise in the world, seen from the front, projects to a
    // negative area on the y-down screen. (`SmallTriangle::set_up` applies
    // the same rule to its exact `f32` area; shared through one function, the
    // rule cost the hot loop 1.5 % more instructions, so it is written twice.)
    if area < 0 {
        Some(([a, c, b], -area))
    } else if area > 0 && cull == CullMode::None {
        Some((v, area))
    } else {
        None
    }
}

/// [`build_batch`] in the best machine code for the CPU (see [`Kernels`]).
#[multiversion(targets("x86_64+avx2"))]
fn build_dispatched<K: TriangleSink, P: ClipSource, S: VertexShader>(
    sink: &mut K,
    projected: &mut Vec<ProjectedVertex>,
    positions: P,
    shader: S,
    groups: &[TriangleGroup<'_>],
    vp: Viewport,
) {
    build_batch(sink, projected, positions, shader, groups, vp);
}

/// Sets up `groups` over the vertices of `positions` coloured by `shader`
/// into `sink` (see [`set_up`]); inlined into each copy of its callers.
#[inline(always)]
fn build_batch(
    sink: &mut impl TriangleSink,
    projected: &mut Vec<ProjectedVertex>,
    positions: impl ClipSource,
    shader: impl VertexShader,
    groups: &[TriangleGroup<'_>],
    vp: Viewport,
) {
    project_vertices(&positions, &shader, vp, projected);
    let projected: &[ProjectedVertex] = projected;
    // What clipping needs of a vertex (the projected ones keep neither):
    // vertex k of the sources is projected vertex k.
    let first_projected = projected.as_ptr() as usize;
    let clip_vertex = |v: &ProjectedVertex| {
        let k = (v as *const ProjectedVertex as usize - first_projected)
            / std::mem::size_of::<ProjectedVertex>();
        ClipVertex {
            pos: positions.clip(k),
            color: shader.color(k),
        }
    };
    let mut polygon = Vec::with_capacity(9);
    let limits = screen_limits(vp.width, vp.height);
    // The vertices of the polygon being clipped.
    let mut clipped = Vec::with_capacity(9);
    // One selected triangle on its own: set up, or clipped first.
    let mut push_kept = |sink: &mut _, kept: &KeptTriangle<'_>, cull: CullMode| {
        if !kept.clip {
            TriangleSink::push_in_span(sink, kept.screen(), cull, kept.lanes.span());
            return;
        }
        clip_triangle(kept.vertices.map(clip_vertex), &mut polygon);
        if polygon.is_empty() {
            return;
        }
        // Not clipped again: no outcode needed.
        clipped.clear();
        clipped.extend(
            polygon
                .iter()
                .map(|v| ProjectedVertex::new(vp.project(v), 0)),
        );
        for k in 1..clipped.len() as u32 - 1 {
            TriangleSink::push(sink, &clipped, [0, k, k + 1], cull, limits);
        }
    };
    let mut kept = [KeptTriangle::UNUSED; KEEP_CHUNK];
    for group in groups {
        for chunk in group.triangles.chunks(KEEP_CHUNK) {
            // First the triangles that may draw, in order, selected without
            // branches (whether a small triangle's box holds a pixel centre is
            // data-random), then their set-up.
            let mut count = 0;
            for &tri in chunk {
                let vertices = tri.map(|k| &projected[(k - group.first_vertex) as usize]);
                let [pa, pb, pc] = vertices;
                let (ca, cb, cc) = (pa.code, pb.code, pc.code);
                let lanes = SpanLanes::of(pa.centre_box, pb.centre_box, pc.centre_box, limits);
                let clip = (ca | cb | cc) & (OUT_NEAR | OUT_GUARD) != 0;
                let visible = ca & cb & cc & OUT_FRUSTUM == 0;
                // `count` is below the chunk's length: the mask only spares
                // the bounds check.
                kept[count & (KEEP_CHUNK - 1)] = KeptTriangle {
                    vertices,
                    lanes,
                    clip,
                };
                count += usize::from(visible & (clip | !lanes.is_empty()));
            }
            // Four at a time where none needs clipping, in order.
            let (fours, rest) = kept[..count].as_chunks::<4>();
            for four in fours {
                if four.iter().any(|k| k.clip) {
                    for k in four {
                        push_kept(sink, k, group.cull);
                    }
                } else {
                    sink.push_four(four, group.cull);
                }
            }
            for k in rest {
                push_kept(sink, k, group.cull);
            }
        }
    }
}

/// Of four triangles, at least this many must fit the window of
/// [`FourSmallTriangles`] for the four to be set up together (the others are
/// set up again one at a time).
const FOUR_AT_A_TIME_MIN: u32 = 2;

/// Triangles selected at a time before their set-up (a power of two).
const KEEP_CHUNK: usize = 256;

/// A triangle that may draw: not outside the frustum, and either to be
/// clipped or with a pixel centre in its box.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KeptTriangle<'a> {
    /// Its projected vertices.
    vertices: [&'a ProjectedVertex; 3],
    /// Its pixel span.
    lanes: SpanLanes,
    /// Whether it crosses the near plane or the guard band.
    clip: bool,
}

impl<'a> KeptTriangle<'a> {
    /// A placeholder for the slots of a chunk not yet selected.
    const UNUSED: KeptTriangle<'static> = KeptTriangle {
        vertices: [&ProjectedVertex::UNUSED; 3],
        lanes: SpanLanes::EMPTY,
        clip: false,
    };

    /// The screen vertices of its projected vertices.
    #[inline(always)]
    fn screen(&self) -> [&'a ScreenVertex; 3] {
        self.vertices.map(|v| &v.screen)
    }
}
