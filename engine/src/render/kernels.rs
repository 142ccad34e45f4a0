//! Which machine code runs the renderer's hot kernels (a batch's vertex pass
//! and triangle set-up, a band's clear and fill).
//!
//! Each kernel is written once, `#[inline(always)]`, and reached through a
//! wrapper compiled twice by [`multiversion`]: for the baseline `x86_64`
//! (SSE2) and with AVX2 enabled, picked at run time from the CPU's features
//! (no `unsafe` here; the crate checks the features before calling the AVX2
//! copy). The AVX2 copy runs the same IEEE operations in the same order (Rust
//! never fuses a multiply and an add on its own, and float reductions are not
//! reordered), so both give the same bits; tests check whole frames.

/// The machine code a frame runs its hot kernels with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Kernels {
    /// The best copy for the CPU the program runs on (AVX2 where present).
    #[default]
    Dispatched,
    /// The baseline copy, whatever the CPU (tests compare it with the other).
    #[cfg_attr(not(test), allow(dead_code))]
    Baseline,
}

/// Runs `kernel` (an `#[inline(always)]` kernel called in a closure) in the
/// baseline machine code, out of line like the dispatched copies, so that
/// neither changes how the other's caller is compiled.
#[inline(never)]
pub(crate) fn run_baseline<R>(kernel: impl FnOnce() -> R) -> R {
    kernel()
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use super::Kernels;
    use crate::render::test_ground::ground;
    use crate::render::{
        Camera, CullMode, FrameScene, GrassBlade, Lighting, MeshInstance, Renderer,
    };
    use crate::rng::SplitMix64;

    #[test]
    fn baseline_and_dispatched_kernels_draw_the_same_bytes() {
        let (terrain, mesh) = ground(129);
        let lighting = Lighting::default();
        // The dense mesh above the terrain, both sides drawn, lit each frame
        // (fog included); a pre-lit copy of it lower down.
        let mut lit = MeshInstance::new(
            &mesh,
            Mat4::from_translation(Vec3::Y * 0.3),
            Vec3::new(0.5, 0.6, 0.4),
        );
        lit.cull = CullMode::None;
        let baked: Vec<Vec3> = (0..mesh.positions.len())
            .map(|k| Vec3::new((k % 7) as f32 / 7.0, 0.5, (k % 5) as f32 / 5.0))
            .collect();
        let pre_lit = MeshInstance::new(&mesh, Mat4::from_translation(-Vec3::Y * 0.1), Vec3::ONE)
            .with_vertex_colors(&baked);
        let mut rng = SplitMix64::new(11);
        let blades: Vec<GrassBlade> = (0..3000)
            .map(|_| {
                let root = Vec3::new(rng.next_f32() * 4.0 - 2.0, 0.3, rng.next_f32() * 4.0 - 2.0);
                GrassBlade {
                    root,
                    mid: root + Vec3::new(0.01, 0.05, 0.0),
                    tip: root + Vec3::new(0.03, 0.1, 0.01),
                    width: 0.01,
                    color: Vec3::new(0.3, 0.6, 0.2),
                }
            })
            .collect();
        let meshes = [lit, pre_lit];
        let scene = FrameScene {
            terrain: Some(&terrain),
            meshes: &meshes,
            blades: &blades,
            lighting,
        };
        // Close enough that the near plane cuts the ground and blades.
        let camera = Camera::perspective(1.0, 320, 180, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 0.5, -2.1), Vec3::new(0.0, 0.0, 1.0), Vec3::Y);
        let render = |kernels: Kernels, threads: usize| {
            Renderer::new(320, 180)
                .and_then(|r| r.with_threads(threads))
                .unwrap()
                .with_kernels(kernels)
                .render_with_stats(&scene, &camera)
        };
        let (baseline, stats) = render(Kernels::Baseline, 1);
        assert!(stats.triangles > 20_000, "{stats:?}");
        let sky = *baseline.get_pixel(160, 0);
        assert!(baseline.pixels().filter(|&&p| p != sky).count() > 30_000);
        // One thread draws triangles as they are set up, two bin them by
        // bands first: the same pixels and counts.
        for threads in [1, 2] {
            let (dispatched, dispatched_stats) = render(Kernels::Dispatched, threads);
            assert!(dispatched == baseline, "{threads} threads");
            assert_eq!(dispatched_stats, stats, "{threads} threads");
        }
        assert!(render(Kernels::Baseline, 2) == (baseline, stats));
    }
}
