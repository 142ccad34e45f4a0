//! A top-down binned-SAH build of an obvhs binary BVH, for the layouts on
//! which obvhs's PLOC build degrades towards quadratic time, and the test that
//! recognises them.
//!
//! PLOC merges mutually nearest clusters; when many neighbours are equally
//! near (triangles in a row: each has two neighbours at the same distance) or
//! every box overlaps every other (a fan of slivers covering one huge
//! polygon), each round merges only a few clusters and the build takes
//! rounds in proportion to the triangle count. The binned build splits
//! each node at the cheapest of 16 planes per axis (surface area heuristic),
//! or at the median when that fails, so its time stays near `n log n`.

use obvhs::aabb::Aabb;
use obvhs::bvh2::{Bvh2, node::Bvh2Node};

/// Planes tried per axis.
const BINS: usize = 16;
/// Below this depth a node is split by SAH; deeper nodes at the median, so the tree stays shallow.
const MAX_SAH_DEPTH: usize = 48;
/// Meshes smaller than this always use PLOC (even its worst case is quick).
const MIN_PRIMITIVES: usize = 1024;
/// Boxes whose centres are sampled to measure overlap.
const OVERLAP_SAMPLES: usize = 64;
/// A layout where a sampled box centre lies, on average, inside more than this
/// many boxes overlaps heavily (a typical mesh: 1 to 4).
const OVERLAP_LIMIT: usize = 16;

/// True when PLOC would build slowly on `boxes`: heavily overlapping boxes, or
/// equally near neighbours along the longest axis for more than half of them.
pub(crate) fn ploc_degenerates(boxes: &[Aabb]) -> bool {
    let n = boxes.len();
    if n < MIN_PRIMITIVES {
        return false;
    }
    // Overlap: how many boxes contain the centres of a few evenly spaced boxes
    // (a count, so one far outlier vertex does not hide it).
    let step = n / OVERLAP_SAMPLES;
    let depth: usize = (0..OVERLAP_SAMPLES)
        .map(|k| {
            let p = boxes[k * step].center();
            boxes
                .iter()
                .filter(|b| p.cmpge(b.min).all() && p.cmple(b.max).all())
                .count()
        })
        .sum();
    if depth > OVERLAP_LIMIT * OVERLAP_SAMPLES {
        return true;
    }
    let mut centres = Aabb::INVALID;
    for b in boxes {
        centres.extend(b.center());
    }
    let axis = centres.diagonal().max_position();
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_unstable_by(|&a, &b| {
        let (a, b) = (&boxes[a as usize], &boxes[b as usize]);
        a.center_axis(axis).total_cmp(&b.center_axis(axis))
    });
    let merged = |a: u32, b: u32| boxes[a as usize].union(&boxes[b as usize]).half_area();
    let ties = order
        .windows(3)
        .filter(|w| {
            let (left, right) = (merged(w[0], w[1]), merged(w[1], w[2]));
            (left - right).abs() <= 1e-6 * left.max(right)
        })
        .count();
    ties * 2 > n
}

/// A binary BVH over `boxes` with leaves of at most `max_leaf` primitives.
pub(crate) fn build_binned(boxes: &[Aabb], max_leaf: usize) -> Bvh2 {
    let max_leaf = max_leaf.max(1);
    let mut indices: Vec<u32> = (0..boxes.len() as u32).collect();
    let mut nodes = vec![Bvh2Node::new(Aabb::INVALID, 0, 0)];
    // (node, first, end, depth)
    let mut stack = vec![(0usize, 0usize, boxes.len(), 0usize)];
    while let Some((node, first, end, depth)) = stack.pop() {
        let slice = &mut indices[first..end];
        let mut bounds = Aabb::INVALID;
        let mut centres = Aabb::INVALID;
        for &i in slice.iter() {
            bounds = bounds.union(&boxes[i as usize]);
            centres.extend(boxes[i as usize].center());
        }
        if slice.len() <= max_leaf {
            nodes[node] = Bvh2Node::new(bounds, slice.len() as u32, first as u32);
            continue;
        }
        let split = if depth < MAX_SAH_DEPTH {
            sah_split(boxes, slice, &centres)
        } else {
            None
        }
        .unwrap_or_else(|| median_split(boxes, slice, &centres));
        let left = nodes.len();
        nodes.push(Bvh2Node::new(Aabb::INVALID, 0, 0));
        nodes.push(Bvh2Node::new(Aabb::INVALID, 0, 0));
        nodes[node] = Bvh2Node::new(bounds, 0, left as u32);
        stack.push((left + 1, first + split, end, depth + 1));
        stack.push((left, first, first + split, depth + 1));
    }
    Bvh2 {
        nodes,
        primitive_indices: indices,
        ..Bvh2::default()
    }
}

/// Partitions `slice` at the cheapest binned SAH plane and returns the size of
/// the left part, or `None` when no plane separates the centres.
fn sah_split(boxes: &[Aabb], slice: &mut [u32], centres: &Aabb) -> Option<usize> {
    let extent = centres.diagonal();
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, plane)
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let bin_of = |i: u32| bin(&boxes[i as usize], centres, axis);
        let mut bin_boxes = [Aabb::INVALID; BINS];
        let mut bin_counts = [0usize; BINS];
        for &i in slice.iter() {
            let b = bin_of(i);
            bin_boxes[b] = bin_boxes[b].union(&boxes[i as usize]);
            bin_counts[b] += 1;
        }
        // Costs of the left parts, then swept from the right.
        let mut left_cost = [0.0f32; BINS];
        let (mut acc, mut count) = (Aabb::INVALID, 0usize);
        for p in 0..BINS - 1 {
            acc = acc.union(&bin_boxes[p]);
            count += bin_counts[p];
            left_cost[p] = if count == 0 {
                0.0
            } else {
                acc.half_area() * count as f32
            };
        }
        let (mut acc, mut count) = (Aabb::INVALID, 0usize);
        for p in (0..BINS - 1).rev() {
            acc = acc.union(&bin_boxes[p + 1]);
            count += bin_counts[p + 1];
            let left_count: usize = slice.len() - count;
            if count == 0 || left_count == 0 {
                continue;
            }
            let cost = left_cost[p] + acc.half_area() * count as f32;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, p));
            }
        }
    }
    let (_, axis, plane) = best?;
    let mut k = 0;
    for j in 0..slice.len() {
        if bin(&boxes[slice[j] as usize], centres, axis) <= plane {
            slice.swap(k, j);
            k += 1;
        }
    }
    (k > 0 && k < slice.len()).then_some(k)
}

/// The bin of a box's centre along `axis` of the centre bounds.
fn bin(b: &Aabb, centres: &Aabb, axis: usize) -> usize {
    let lo = centres.min[axis];
    let extent = centres.max[axis] - lo;
    let t = (b.center_axis(axis) - lo) / extent;
    ((t * BINS as f32) as usize).min(BINS - 1)
}

/// Splits `slice` in two halves by centre along the longest axis.
fn median_split(boxes: &[Aabb], slice: &mut [u32], centres: &Aabb) -> usize {
    let axis = centres.diagonal().max_position();
    let mid = slice.len() / 2;
    slice.select_nth_unstable_by(mid, |&a, &b| {
        boxes[a as usize]
            .center_axis(axis)
            .total_cmp(&boxes[b as usize].center_axis(axis))
    });
    mid
}

/// Whether `point` lies inside `b` (bounds included); for tests.
#[cfg(test)]
fn contains(b: &Aabb, point: glam::Vec3A) -> bool {
    point.cmpge(b.min).all() && point.cmple(b.max).all()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    fn row(n: usize) -> Vec<Aabb> {
        (0..n)
            .map(|k| {
                let x = k as f32;
                Aabb::new(Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 1.0, 1.0, 0.0))
            })
            .collect()
    }

    #[test]
    fn a_row_is_degenerate_and_a_grid_is_not() {
        assert!(ploc_degenerates(&row(5000)));
        let grid: Vec<Aabb> = (0..4096)
            .map(|k| {
                let (x, z) = ((k % 64) as f32, (k / 64) as f32);
                Aabb::new(Vec3A::new(x, 0.0, z), Vec3A::new(x + 1.0, 0.1, z + 1.0))
            })
            .collect();
        assert!(!ploc_degenerates(&grid));
        // A 100k-triangle terrain mesh: two triangles per cell, on a gentle slope.
        let side = 224;
        let terrain: Vec<Aabb> = (0..side * side * 2)
            .map(|k| {
                let cell = k / 2;
                let (x, z) = ((cell % side) as f32, (cell / side) as f32);
                let y = 0.01 * x;
                Aabb::new(Vec3A::new(x, y, z), Vec3A::new(x + 1.0, y + 0.01, z + 1.0))
            })
            .collect();
        assert!(!ploc_degenerates(&terrain));
        assert!(!ploc_degenerates(&row(100)), "small meshes keep PLOC");
    }

    #[test]
    fn every_primitive_is_in_one_leaf_inside_its_ancestors() {
        let boxes = row(1000);
        let bvh = build_binned(&boxes, 4);
        let mut seen = vec![0u32; boxes.len()];
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &bvh.nodes[n];
            if node.is_leaf() {
                assert!(node.prim_count <= 4);
                let first = node.first_index as usize;
                for &p in &bvh.primitive_indices[first..first + node.prim_count as usize] {
                    seen[p as usize] += 1;
                    assert!(contains(node.aabb(), boxes[p as usize].center()));
                }
            } else {
                stack.extend([node.first_index as usize, node.first_index as usize + 1]);
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
    }
}
