//! A 4-wide BVH with full-precision child boxes in structure-of-arrays form,
//! collapsed from an obvhs [`Bvh2`], and its ordered single-ray traversal.
//!
//! One node tests its four children's slabs at once with 4-lane vector
//! arithmetic (about 25 vector operations, no decompression), visits the
//! nearest hit child next and culls stacked children that start beyond the
//! closest hit found so far.

use std::cell::Cell;

use glam::{BVec4A, Vec3A, Vec4};
use obvhs::bvh2::Bvh2;

/// Children per node.
const WIDTH: usize = 4;

thread_local! {
    /// Each thread's traversal stack, reused so that a cast neither allocates
    /// nor clears one. Taken out while in use: a nested cast (from inside a
    /// primitive test) finds it empty and simply grows its own.
    static STACK: Cell<Vec<Visit>> = const { Cell::new(Vec::new()) };
}

/// A node: the boxes of up to four children (lane `k` is child `k`).
///
/// Unused lanes have an empty box (`min = +inf`, `max = -inf`), which every
/// ray misses, so the traversal needs no lane mask.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Per axis (x, y, z), the children's box minima.
    min: [Vec4; 3],
    /// Per axis, the children's box maxima.
    max: [Vec4; 3],
    /// Node index of an inner child, or first primitive slot of a leaf child.
    first: [u32; WIDTH],
    /// Primitive count of a leaf child, 0 for an inner child.
    count: [u32; WIDTH],
}

impl Node {
    const EMPTY: Node = Node {
        min: [Vec4::INFINITY; 3],
        max: [Vec4::NEG_INFINITY; 3],
        first: [0; WIDTH],
        count: [0; WIDTH],
    };
}

/// What the traversal visits next: a node or a leaf's primitive range.
#[derive(Clone, Copy, Debug, Default)]
struct Visit {
    /// Distance at which the ray enters the child's box.
    entry: f32,
    first: u32,
    count: u32,
}

impl Visit {
    /// The child in the lowest lane of `hits`, removed from `hits`.
    #[inline(always)]
    fn child(node: &Node, entry: &[f32; WIDTH], hits: &mut u32) -> Visit {
        let lane = hits.trailing_zeros() as usize % WIDTH;
        *hits &= *hits - 1;
        Visit {
            entry: entry[lane],
            first: node.first[lane],
            count: node.count[lane],
        }
    }
}

/// A 4-wide BVH over primitives in slot order (the slot order of the
/// [`Bvh2`] it was collapsed from: slot `s` is `bvh2.primitive_indices[s]`).
#[derive(Clone, Debug)]
pub(crate) struct WideBvh {
    nodes: Vec<Node>,
    /// Depth of the deepest node (the root is depth 1).
    depth: usize,
}

impl WideBvh {
    /// Collapses `bvh2` (root at index 0) into 4-wide nodes: each node takes a
    /// binary node's two children and keeps opening its largest inner child
    /// (by surface area) until it has four.
    pub(crate) fn from_bvh2(bvh2: &Bvh2) -> WideBvh {
        let mut wide = WideBvh {
            nodes: Vec::with_capacity(bvh2.nodes.len() / 2 + 1),
            depth: 0,
        };
        if let Some(root) = bvh2.nodes.first() {
            let children = if root.is_leaf() {
                vec![0]
            } else {
                vec![root.first_index as usize, root.first_index as usize + 1]
            };
            wide.emit(bvh2, children, 1);
        }
        wide
    }

    /// Appends the node whose children are the binary nodes `children`
    /// (opened further up to four) and, depth first, its inner children.
    fn emit(&mut self, bvh2: &Bvh2, mut children: Vec<usize>, depth: usize) -> u32 {
        while children.len() < WIDTH {
            let widest = children
                .iter()
                .enumerate()
                .filter(|&(_, &c)| !bvh2.nodes[c].is_leaf())
                .max_by(|a, b| {
                    let area = |c: usize| bvh2.nodes[c].aabb().half_area();
                    area(*a.1).total_cmp(&area(*b.1))
                })
                .map(|(k, _)| k);
            let Some(k) = widest else { break };
            let left = bvh2.nodes[children[k]].first_index as usize;
            children[k] = left;
            children.push(left + 1);
        }
        self.depth = self.depth.max(depth);
        let index = self.nodes.len();
        self.nodes.push(Node::EMPTY);
        let mut node = Node::EMPTY;
        for (lane, &c) in children.iter().enumerate() {
            let b = &bvh2.nodes[c];
            let aabb = b.aabb();
            for axis in 0..3 {
                node.min[axis][lane] = aabb.min[axis];
                node.max[axis][lane] = aabb.max[axis];
            }
            if b.is_leaf() {
                node.first[lane] = b.first_index;
                node.count[lane] = b.prim_count;
            } else {
                let pair = vec![b.first_index as usize, b.first_index as usize + 1];
                node.first[lane] = self.emit(bvh2, pair, depth + 1);
            }
        }
        self.nodes[index] = node;
        index as u32
    }

    /// The closest (or, with `ANY`, the first found) primitive hit by the ray
    /// `origin + t * dir`, `0 <= t <= max_t`, as `(t, slot)`.
    ///
    /// `hit(slot, t_max)` intersects one primitive and returns its distance
    /// when it is at most `t_max`. Primitives are visited in an order fixed by
    /// the tree and the ray alone, so results are deterministic; among equally
    /// distant primitives the first visited wins.
    #[inline]
    pub(crate) fn traverse<const ANY: bool>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        max_t: f32,
        hit: impl FnMut(usize, f32) -> Option<f32>,
    ) -> Option<(f32, usize)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut stack = STACK.take();
        // Each level leaves at most WIDTH - 1 siblings on the stack.
        let needed = (WIDTH - 1) * self.depth + 1;
        if stack.len() < needed {
            stack.resize(needed, Visit::default());
        }
        let found = self.traverse_with::<ANY>(&mut stack, origin, dir, max_t, hit);
        STACK.set(stack);
        found
    }

    /// [`WideBvh::traverse`] with a stack of at least `(WIDTH - 1) * depth + 1` entries.
    #[inline(always)]
    fn traverse_with<const ANY: bool>(
        &self,
        stack: &mut [Visit],
        origin: Vec3A,
        dir: Vec3A,
        max_t: f32,
        mut hit: impl FnMut(usize, f32) -> Option<f32>,
    ) -> Option<(f32, usize)> {
        let slabs = Slabs::new(origin, dir);
        let mut best: Option<(f32, usize)> = None;
        let mut t_max = max_t;
        let mut top = 0;
        let mut next = Visit {
            entry: 0.0,
            first: 0,
            count: 0,
        };
        loop {
            if next.count == 0 {
                let node = &self.nodes[next.first as usize];
                let (entry, mut hits) = slabs.enter(node, t_max);
                if hits != 0 {
                    // Visit the nearest child next; stack the others.
                    next = Visit::child(node, &entry, &mut hits);
                    while hits != 0 {
                        let mut other = Visit::child(node, &entry, &mut hits);
                        if other.entry < next.entry {
                            std::mem::swap(&mut other, &mut next);
                        }
                        stack[top] = other;
                        top += 1;
                    }
                    continue;
                }
            } else {
                let slots = next.first as usize..(next.first + next.count) as usize;
                for slot in slots {
                    if let Some(t) = hit(slot, t_max) {
                        best = Some((t, slot));
                        if ANY {
                            return best;
                        }
                        t_max = t;
                    }
                }
            }
            // Pop the nearest stacked child that still starts before the best hit.
            loop {
                if top == 0 {
                    return best;
                }
                top -= 1;
                if stack[top].entry <= t_max {
                    next = stack[top];
                    break;
                }
            }
        }
    }
}

/// A ray prepared for slab tests against a node's four boxes.
struct Slabs {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    /// Per axis, whether the ray runs towards negative coordinates (it then
    /// enters a box through its max plane).
    negative: [bool; 3],
}

impl Slabs {
    fn new(origin: Vec3A, dir: Vec3A) -> Slabs {
        // A zero component gives an infinite inverse: the slab then holds for
        // every t or for none, and a ray lying exactly in a box's face plane
        // (the product is NaN) can only touch primitives padded inside it.
        let inv = dir.recip();
        Slabs {
            origin: [
                Vec4::splat(origin.x),
                Vec4::splat(origin.y),
                Vec4::splat(origin.z),
            ],
            inv_dir: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
            negative: [
                dir.x.is_sign_negative(),
                dir.y.is_sign_negative(),
                dir.z.is_sign_negative(),
            ],
        }
    }

    /// Entry distances of the ray into the four child boxes of `node`, and
    /// the lane bit mask of those it meets within `0..=t_max`.
    #[inline(always)]
    fn enter(&self, node: &Node, t_max: f32) -> ([f32; WIDTH], u32) {
        let mut t_in = Vec4::ZERO;
        let mut t_out = Vec4::splat(t_max);
        for axis in 0..3 {
            let (near, far) = if self.negative[axis] {
                (node.max[axis], node.min[axis])
            } else {
                (node.min[axis], node.max[axis])
            };
            t_in = t_in.max((near - self.origin[axis]) * self.inv_dir[axis]);
            t_out = t_out.min((far - self.origin[axis]) * self.inv_dir[axis]);
        }
        let hits: BVec4A = t_in.cmple(t_out);
        (t_in.to_array(), hits.bitmask())
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::bvh2::builder::build_bvh2;

    use super::*;

    /// Unit cubes at x = 0, 2, 4, ...: a ray along +x meets them in order.
    fn cubes(n: usize) -> (Bvh2, Vec<Aabb>) {
        let boxes: Vec<Aabb> = (0..n)
            .map(|k| {
                let x = 2.0 * k as f32;
                Aabb::new(Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 1.0, 1.0, 1.0))
            })
            .collect();
        let bvh2 = build_bvh2(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        (bvh2, boxes)
    }

    fn cast<const ANY: bool>(
        wide: &WideBvh,
        bvh2: &Bvh2,
        boxes: &[Aabb],
        o: Vec3A,
        d: Vec3A,
    ) -> Option<(f32, u32)> {
        let ray = obvhs::ray::Ray::new(o, d, 0.0, f32::INFINITY);
        wide.traverse::<ANY>(o, d, f32::INFINITY, |slot, t_max| {
            let t = boxes[bvh2.primitive_indices[slot] as usize].intersect_ray(&ray);
            (t <= t_max).then_some(t)
        })
        .map(|(t, slot)| (t, bvh2.primitive_indices[slot]))
    }

    #[test]
    fn finds_the_closest_box_from_either_side() {
        for n in [1, 3, 200] {
            let (bvh2, boxes) = cubes(n);
            let wide = WideBvh::from_bvh2(&bvh2);
            let (o, d) = (Vec3A::new(-1.0, 0.5, 0.5), Vec3A::X);
            assert_eq!(cast::<false>(&wide, &bvh2, &boxes, o, d), Some((1.0, 0)));
            let far = Vec3A::new(2.0 * n as f32 + 1.0, 0.5, 0.5);
            let last = (n - 1) as u32;
            assert_eq!(
                cast::<false>(&wide, &bvh2, &boxes, far, -d),
                Some((2.0, last))
            );
            assert!(cast::<true>(&wide, &bvh2, &boxes, o, d).is_some());
            let above = Vec3A::new(-1.0, 2.0, 0.5);
            assert_eq!(cast::<false>(&wide, &bvh2, &boxes, above, d), None);
        }
    }

    #[test]
    fn a_cast_nested_in_a_primitive_test_gets_its_own_stack() {
        let (bvh2, boxes) = cubes(500);
        let wide = WideBvh::from_bvh2(&bvh2);
        let o = Vec3A::new(-1.0, 0.5, 0.5);
        let alone = cast::<false>(&wide, &bvh2, &boxes, o, Vec3A::X);
        let mut inner = Vec::new();
        let outer = wide.traverse::<false>(o, Vec3A::X, f32::INFINITY, |_, _| {
            inner.push(cast::<false>(&wide, &bvh2, &boxes, o, Vec3A::X));
            None
        });
        assert_eq!(outer, None);
        assert!(!inner.is_empty() && inner.iter().all(|&c| c == alone));
        assert_eq!(alone, Some((1.0, 0)));
    }
}
