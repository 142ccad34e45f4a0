//! Running window jobs (smoothing, settling) in parallel with the result of
//! running them one after another: jobs whose windows overlap keep their
//! order, jobs whose windows are apart run side by side.

use std::collections::HashMap;

use engine::geom::GridRect;
use rayon::prelude::*;

use super::heightfield::Heightfield;

/// Jobs below this many in a wave run on the calling thread (spreading a
/// few small windows over threads costs more than it saves).
const MIN_PARALLEL_JOBS: usize = 4;

/// Resource: one set of work buffers per job of the largest wave run so far
/// (grown on demand, reused from step to step). Not part of any terrain's state.
#[derive(Debug, Default)]
pub struct ScratchPool<S>(pub Vec<S>);

/// Groups jobs into waves: job `k` goes one wave after the last earlier job
/// whose window overlaps its own (wave 0 when none does). Within a wave no
/// two windows overlap, and every job comes after the earlier jobs that
/// overlap it, so running the waves in order, each wave's jobs in any order
/// or at once, gives what running the jobs in list order gives.
///
/// A job reads and writes only inside its window, so windows that merely
/// touch are apart. Empty windows go to wave 0.
pub(crate) fn independent_waves(windows: &[GridRect]) -> Vec<Vec<usize>> {
    // Earlier jobs are found through square buckets as large as the largest
    // window, so each window meets at most four buckets' lists.
    let side = (windows.iter())
        .map(|w| w.width().max(w.height()))
        .max()
        .unwrap_or(1)
        .max(1);
    let mut buckets: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    let mut wave_of: Vec<usize> = Vec::with_capacity(windows.len());
    let mut waves: Vec<Vec<usize>> = Vec::new();
    for (k, w) in windows.iter().enumerate() {
        let keys: Vec<(usize, usize)> = if w.is_empty() {
            Vec::new()
        } else {
            let (bi, bj) = (
                w.i0 / side..=(w.i1 - 1) / side,
                w.j0 / side..=(w.j1 - 1) / side,
            );
            bj.flat_map(|j| bi.clone().map(move |i| (i, j))).collect()
        };
        let wave = (keys.iter())
            .filter_map(|key| buckets.get(key))
            .flatten()
            .filter(|&&e| !windows[e].intersect(w).is_empty())
            .map(|&e| wave_of[e] + 1)
            .max()
            .unwrap_or(0);
        for key in keys {
            buckets.entry(key).or_default().push(k);
        }
        wave_of.push(wave);
        if waves.len() <= wave {
            waves.resize_with(wave + 1, Vec::new);
        }
        waves[wave].push(k);
    }
    waves
}

/// Runs one job per window with the result of running them in list order;
/// the jobs of a wave ([`independent_waves`]) are computed in parallel on
/// the current rayon pool, in one contiguous share of the wave per thread.
///
/// `compute(hf, scratch, k)` reads the terrain (only inside window `k`) and
/// returns what it would write, owning it (the scratch holds only work
/// buffers); `commit(hf, scratch, k, result)` writes it back, on the calling
/// thread, in job order within the wave, with the scratch that computed it.
/// A wave too small to share (or a single thread) computes and commits job
/// after job in one scratch. `scratches` grows to one per share and is
/// reused from call to call. The result is the same bits on any number of
/// threads: each job sees the same heights whoever runs it.
pub(crate) fn run_in_waves<S, R>(
    hf: &mut Heightfield,
    windows: &[GridRect],
    scratches: &mut Vec<S>,
    compute: impl Fn(&Heightfield, &mut S, usize) -> R + Sync,
    mut commit: impl FnMut(&mut Heightfield, &mut S, usize, R),
) where
    S: Default + Send,
    R: Send,
{
    let threads = rayon::current_num_threads().max(1);
    for wave in independent_waves(windows) {
        let shares = if wave.len() < MIN_PARALLEL_JOBS {
            1
        } else {
            threads.min(wave.len())
        };
        if scratches.len() < shares {
            scratches.resize_with(shares, S::default);
        }
        if shares == 1 {
            let scratch = &mut scratches[0];
            for &k in &wave {
                let result = compute(hf, scratch, k);
                commit(hf, scratch, k, result);
            }
            continue;
        }
        let per_share = wave.len().div_ceil(shares);
        let terrain: &Heightfield = hf;
        let results: Vec<Vec<R>> = (wave.par_chunks(per_share))
            .zip(scratches.par_iter_mut())
            .map(|(jobs, scratch)| (jobs.iter().map(|&k| compute(terrain, scratch, k))).collect())
            .collect();
        for ((jobs, scratch), results) in wave
            .chunks(per_share)
            .zip(scratches.iter_mut())
            .zip(results)
        {
            for (&k, result) in jobs.iter().zip(results) {
                commit(hf, scratch, k, result);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_windows_keep_their_order_and_apart_ones_share_a_wave() {
        let windows = [
            GridRect::new(0, 0, 10, 10),
            GridRect::new(20, 0, 30, 10),
            // Overlaps the first: after it.
            GridRect::new(5, 5, 15, 15),
            // Touches the first (columns 10..12 after 0..10): apart.
            GridRect::new(10, 0, 12, 4),
            // Overlaps the third (wave 1): wave 2.
            GridRect::new(14, 14, 16, 16),
        ];
        let waves = independent_waves(&windows);
        assert_eq!(waves, vec![vec![0, 1, 3], vec![2], vec![4]]);
    }
}
