//! A 4-wide BVH with full-precision child boxes in structure-of-arrays form,
//! collapsed from an obvhs [`Bvh2`], and its ordered traversal, one ray at a
//! time or several interleaved.
//!
//! One node tests its four children's slabs at once with 4-lane vector
//! arithmetic (about 25 vector operations, no decompression), visits the
//! nearest hit child next and culls stacked children that start beyond the
//! closest hit found so far.
//!
//! A traversal is a [`Walk`]: a small state machine whose every step reads one
//! node or one leaf. [`WideBvh::traverse`] runs one walk to its end;
//! [`WideBvh::traverse_many`] runs [`BATCH_LANES`] walks round-robin and
//! prefetches what each will read next, so that the cache misses of
//! independent rays overlap instead of queueing. The two stack a node's
//! children in different orders (each the faster for its case), so they find
//! the same closest distance, bit for bit, but where two items are hit at
//! exactly that distance they may report different ones.

use std::cell::Cell;
use std::hint::select_unpredictable;

use glam::{BVec4A, Vec3A, Vec4};
use obvhs::bvh2::Bvh2;

use super::Ray;
use super::prefetch;
use super::triangle::Xyz;

/// Children per node.
const WIDTH: usize = 4;

/// Rays in flight in [`WideBvh::traverse_many`] (chosen by measurement: of
/// 2, 4, 6, 8, 12 and 16, 4 was the fastest or within noise of it on every
/// workload).
pub(crate) const BATCH_LANES: usize = 4;

/// Entries at the bottom of each traversal stack ([`Visit::FLOOR`]), and how
/// many entries a pop looks at together.
const FLOOR: usize = 4;

/// Bits of a [`Visit::child`] reference that hold a leaf's item count.
const COUNT_BITS: u32 = 4;

/// Evaluates `$body` with the const `$name: u8` set to the octant `$octant`
/// (0 to 7; anything else counts as 7), so that code generic over the octant
/// is chosen once per call instead of testing signs at every box.
macro_rules! for_octant {
    ($octant:expr, $name:ident => $body:expr) => {
        for_octant!(@arms $octant, $name, $body, [0 1 2 3 4 5 6], 7)
    };
    (@arms $octant:expr, $name:ident, $body:expr, [$($k:literal)*], $last:literal) => {
        match $octant {
            $($k => {
                const $name: u8 = $k;
                $body
            })*
            _ => {
                const $name: u8 = $last;
                $body
            }
        }
    };
}

thread_local! {
    /// Each thread's traversal stack, reused so that a cast neither allocates
    /// nor clears one. Taken out while in use: a nested cast (from inside a
    /// primitive test) finds it empty and simply grows its own.
    static STACK: Cell<Vec<Visit>> = const { Cell::new(Vec::new()) };
    /// Each thread's ray order of [`WideBvh::traverse_many`] (rays grouped
    /// by octant), reused the same way.
    static ORDER: Cell<Vec<usize>> = const { Cell::new(Vec::new()) };
}

/// A node: the boxes of up to four children (lane `k` is child `k`), two
/// cache lines.
///
/// Unused lanes have an empty box (`min = +inf`, `max = -inf`), which every
/// ray misses, so the traversal needs no lane mask.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    /// Per axis (x, y, z), the children's box minima (`[axis][0]`) and
    /// maxima (`[axis][1]`), so that a ray picks its entry and exit planes by
    /// index rather than by branch.
    planes: [[Vec4; 2]; 3],
    /// Per lane, the child as a [`Visit::child`] reference.
    child: [u32; WIDTH],
}

impl Node {
    const EMPTY: Node = Node {
        planes: [[Vec4::INFINITY, Vec4::NEG_INFINITY]; 3],
        child: [0; WIDTH],
    };
}

/// What the traversal visits next: a node or a leaf's item range, in eight
/// bytes.
#[derive(Clone, Copy, Debug, Default)]
struct Visit {
    /// Distance at which the ray enters the child's box.
    entry: f32,
    /// `first << COUNT_BITS | count`: node index `first` when `count` is 0,
    /// else the leaf's items `first..first + count`.
    child: u32,
}

impl Visit {
    /// The entries below every stack: never taken (their entry, NaN, is
    /// beyond any distance), so a pop may look at the top [`FLOOR`]
    /// entries without checking the stack's depth.
    const FLOOR: Visit = Visit {
        entry: f32::NAN,
        child: 0,
    };

    /// The child reference of a node (`count == 0`) or of a leaf's item range.
    fn reference(first: u32, count: u32) -> u32 {
        assert!(
            count < 1 << COUNT_BITS && first < 1 << (32 - COUNT_BITS),
            "a leaf holds at most 15 items and a tree at most 2^28 nodes or items"
        );
        first << COUNT_BITS | count
    }

    /// Node index or first leaf item.
    #[inline(always)]
    fn first(self) -> u32 {
        self.child >> COUNT_BITS
    }

    /// Leaf item count, 0 for a node.
    #[inline(always)]
    fn count(self) -> u32 {
        self.child & ((1 << COUNT_BITS) - 1)
    }
}

/// The items the leaves of a [`WideBvh`] hold (triangle packets for a mesh),
/// as the traversal sees them.
pub(crate) trait LeafItems {
    /// The nearest hit of `ray` on item `item` within `t_max`, as `(t, id)`
    /// with an id of the implementor's choosing (below `u32::MAX`); `t` is
    /// NaN when the item is missed (the id is then any value), so that the
    /// traversal keeps its best hit by selection rather than by a branch.
    fn nearest(&self, item: u32, ray: &WideRay, t_max: f32) -> (f32, u32);

    /// Where item `item` lies in memory, for prefetching: its first
    /// [`prefetch::SPAN`] bytes are hinted (the pointer is never
    /// dereferenced, so it may be computed without bounds checks).
    fn address(&self, item: u32) -> *const u8;
}

/// A 4-wide BVH over leaf items.
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
    ///
    /// `leaf(first, count)` is called for each binary leaf (its primitive slot
    /// range), in depth-first order of the wide tree, and returns the leaf's
    /// item range `(first, count)` (`1 <= count <= 15`), so that the caller
    /// can lay out its items in traversal order.
    pub(crate) fn from_bvh2(bvh2: &Bvh2, mut leaf: impl FnMut(u32, u32) -> (u32, u32)) -> WideBvh {
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
            wide.emit(bvh2, children, 1, &mut leaf);
        }
        wide
    }

    /// Appends the node whose children are the binary nodes `children`
    /// (opened further up to four) and, depth first, its inner children.
    fn emit(
        &mut self,
        bvh2: &Bvh2,
        mut children: Vec<usize>,
        depth: usize,
        leaf: &mut impl FnMut(u32, u32) -> (u32, u32),
    ) -> u32 {
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
                node.planes[axis][0][lane] = aabb.min[axis];
                node.planes[axis][1][lane] = aabb.max[axis];
            }
            let (first, count) = if b.is_leaf() {
                let (first, count) = leaf(b.first_index, b.prim_count);
                debug_assert!(count >= 1);
                (first, count)
            } else {
                let pair = vec![b.first_index as usize, b.first_index as usize + 1];
                (self.emit(bvh2, pair, depth + 1, leaf), 0)
            };
            node.child[lane] = Visit::reference(first, count);
        }
        self.nodes[index] = node;
        index as u32
    }

    /// Stack entries one walk may need: the [`FLOOR`], then at most
    /// `WIDTH - 1` siblings per level, and a node writes all `WIDTH` lanes
    /// past the top.
    fn stack_size(&self) -> usize {
        FLOOR + (WIDTH - 1) * self.depth + WIDTH
    }

    /// The closest (or, with `ANY`, the first found) leaf item hit by the ray
    /// `origin + t * dir`, `0 <= t <= max_t`, as `(t, id)` from
    /// [`LeafItems::nearest`].
    ///
    /// Items are visited in an order fixed by the tree and the ray alone, so
    /// results are deterministic; an item hit at the same distance as the best
    /// so far replaces it.
    #[inline]
    pub(crate) fn traverse<const ANY: bool>(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        max_t: f32,
        items: &impl LeafItems,
    ) -> Option<(f32, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut stack = STACK.take();
        if stack.len() < self.stack_size() {
            stack.resize(self.stack_size(), Visit::default());
        }
        stack[..FLOOR].fill(Visit::FLOOR);
        let walk = Walk::new(origin, dir, max_t);
        let best = for_octant!(octant(dir), O => walk.run::<ANY, O>(self, items, &mut stack));
        STACK.set(stack);
        best
    }

    /// [`WideBvh::traverse`] for each of `rays`, [`BATCH_LANES`] at a time
    /// interleaved step by step, with prefetching where the CPU has it.
    /// `found(k, hit)` receives ray `k`'s answer: `traverse`'s distance, bit
    /// for bit (the item may be another one hit at exactly that distance);
    /// rays finish out of order.
    pub(crate) fn traverse_many<const ANY: bool>(
        &self,
        rays: &[Ray],
        max_t: f32,
        items: &impl LeafItems,
        found: impl FnMut(usize, Option<(f32, u32)>),
    ) {
        if prefetch::available() {
            self.interleave::<ANY, true, BATCH_LANES>(rays, max_t, items, found);
        } else {
            self.interleave::<ANY, false, BATCH_LANES>(rays, max_t, items, found);
        }
    }

    /// [`WideBvh::traverse_many`] with `LANES` walks in flight, prefetching or
    /// not. The rays are grouped by direction octant first (a counting sort
    /// of their indices), so that each group's walks know at compile time
    /// through which plane of each axis a ray enters a box.
    fn interleave<const ANY: bool, const PREFETCH: bool, const LANES: usize>(
        &self,
        rays: &[Ray],
        max_t: f32,
        items: &impl LeafItems,
        mut found: impl FnMut(usize, Option<(f32, u32)>),
    ) {
        if self.nodes.is_empty() {
            (0..rays.len()).for_each(|k| found(k, None));
            return;
        }
        let octant_of = |k: usize| usize::from(octant(rays[k].dir().into()));
        let mut ends = [0; OCTANTS + 1];
        for k in 0..rays.len() {
            ends[octant_of(k) + 1] += 1;
        }
        for o in 0..OCTANTS {
            ends[o + 1] += ends[o];
        }
        // Reused from call to call (taken, so that a nested batch gets its own).
        let mut order = ORDER.take();
        order.resize(rays.len(), 0);
        let mut fill = ends;
        for k in 0..rays.len() {
            let o = octant_of(k);
            order[fill[o]] = k;
            fill[o] += 1;
        }
        for o in 0..OCTANTS {
            let mut batch = Batch {
                bvh: self,
                items,
                rays,
                order: &order[ends[o]..ends[o + 1]],
                max_t,
                next: 0,
                busy: 0,
                found: &mut found,
            };
            for_octant!(o, O => batch.run::<ANY, PREFETCH, LANES, O>());
        }
        ORDER.set(order);
    }

    /// Hints that `visit`'s node or first leaf item will be read soon (see
    /// [`prefetch::span`]), choosing between the two without a branch:
    /// interleaved walks mix unrelated rays, so a branch on the kind of visit
    /// would mispredict often.
    #[inline(always)]
    fn prefetch(&self, visit: Visit, items: &impl LeafItems) {
        let node = self.nodes.as_ptr().wrapping_add(visit.first() as usize);
        let leaf = items.address(visit.first());
        prefetch::span(if visit.count() == 0 {
            node.cast()
        } else {
            leaf
        });
    }
}

/// The shared state of [`WideBvh::interleave`] for one group of rays: what
/// every lane reads, the group's rays (indices into `rays`), the next of them
/// to start, how many lanes are still walking, and where answers go.
struct Batch<'a, I, F> {
    bvh: &'a WideBvh,
    items: &'a I,
    rays: &'a [Ray],
    order: &'a [usize],
    max_t: f32,
    next: usize,
    busy: usize,
    found: F,
}

impl<I: LeafItems, F: FnMut(usize, Option<(f32, u32)>)> Batch<'_, I, F> {
    /// Walks every ray of the group (all in direction octant `OCTANT`),
    /// `LANES` at a time interleaved step by step.
    #[inline(always)]
    fn run<const ANY: bool, const PREFETCH: bool, const LANES: usize, const OCTANT: u8>(&mut self) {
        const { assert!(LANES.is_multiple_of(4), "lanes are stepped four at a time") };
        if self.order.is_empty() {
            return;
        }
        let size = self.bvh.stack_size();
        let mut stack = STACK.take();
        if stack.len() < LANES * size {
            stack.resize(LANES * size, Visit::default());
        }
        for chunk in stack.chunks_exact_mut(size) {
            chunk[..FLOOR].fill(Visit::FLOOR);
        }
        let count = self.order.len();
        (self.next, self.busy) = (LANES.min(count), LANES.min(count));
        // Lane `l` walks ray `ray_of[l]` (`usize::MAX` once the rays run out).
        let mut ray_of: [usize; LANES] =
            std::array::from_fn(|l| if l < count { self.order[l] } else { usize::MAX });
        let mut walks: [Walk; LANES] =
            std::array::from_fn(|l| self.start(self.order[if l < count { l } else { 0 }]));
        let stacks: [&mut [Visit]; LANES] = {
            let mut chunks = stack.chunks_exact_mut(size);
            std::array::from_fn(|_| chunks.next().expect("the stack holds LANES chunks"))
        };
        // While rays remain to be started at the start of a round, every lane
        // is busy (a lane goes idle only at its own step, once none remain),
        // so the lanes are stepped without checking, written out four at a
        // time: each lane's state then sits at a fixed place and its
        // branches have their own history.
        while self.next < count {
            for base in (0..LANES).step_by(4) {
                let mut lane = |l: usize| {
                    self.advance::<ANY, PREFETCH, OCTANT>(&mut walks[l], stacks[l], &mut ray_of[l])
                };
                lane(base);
                lane(base + 1);
                lane(base + 2);
                lane(base + 3);
            }
        }
        // Then the lanes finish one by one.
        while self.busy > 0 {
            for lane in 0..LANES {
                if ray_of[lane] != usize::MAX {
                    self.advance::<ANY, PREFETCH, OCTANT>(
                        &mut walks[lane],
                        stacks[lane],
                        &mut ray_of[lane],
                    );
                }
            }
        }
        STACK.set(stack);
    }

    /// A walk of ray `k` from the root.
    #[inline(always)]
    fn start(&self, k: usize) -> Walk {
        let ray = &self.rays[k];
        Walk::new(ray.origin().into(), ray.dir().into(), self.max_t)
    }

    /// Steps the walk of ray `*ray` once; when it ends, reports its answer
    /// and starts the group's next ray in its place, or marks the lane idle
    /// (`usize::MAX`) when none remain.
    #[inline(always)]
    fn advance<const ANY: bool, const PREFETCH: bool, const OCTANT: u8>(
        &mut self,
        walk: &mut Walk,
        stack: &mut [Visit],
        ray: &mut usize,
    ) {
        if walk.step::<ANY, PREFETCH, true, OCTANT>(self.bvh, self.items, stack) {
            (self.found)(*ray, walk.best());
            if self.next < self.order.len() {
                *ray = self.order[self.next];
                *walk = self.start(*ray);
                self.next += 1;
            } else {
                *ray = usize::MAX;
                self.busy -= 1;
            }
        }
    }
}

/// Direction octants: bit `axis` set when the direction's component on that
/// axis is negative (sign bit set, as for `-0.0`).
const OCTANTS: usize = 8;

/// The octant of `dir` (see [`OCTANTS`]).
#[inline]
fn octant(dir: Vec3A) -> u8 {
    dir.is_negative_bitmask() as u8
}

/// A ray prepared for 4-lane tests: its origin, direction and inverse
/// direction splatted over the lanes.
pub(crate) struct WideRay {
    /// The origin, each component in all four lanes.
    pub(crate) origin: Xyz<Vec4>,
    /// The direction, each component in all four lanes.
    pub(crate) dir: Xyz<Vec4>,
    inv_dir: [Vec4; 3],
}

impl WideRay {
    fn new(origin: Vec3A, dir: Vec3A) -> WideRay {
        // A zero component gives an infinite inverse: the slab then holds for
        // every t or for none, and a ray lying exactly in a box's face plane
        // (the product is NaN) can only touch primitives padded inside it.
        let inv = dir.recip();

        WideRay {
            origin: Xyz::from(origin),
            dir: Xyz::from(dir),
            inv_dir: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
        }
    }

    /// Entry distances of the ray, whose direction lies in octant `OCTANT`,
    /// into the four child boxes of `node`, and which of them it meets within
    /// `0..=t_max`. A ray running towards negative coordinates on an axis
    /// enters a box through its maximum plane ([`Node::planes`] index 1).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // one index picks the axis in four arrays
    fn enter<const OCTANT: u8>(&self, node: &Node, t_max: f32) -> (Vec4, BVec4A) {
        let origin = [self.origin.x, self.origin.y, self.origin.z];
        let mut t_in = Vec4::ZERO;
        let mut t_out = Vec4::splat(t_max);
        for axis in 0..3 {
            let near = usize::from(OCTANT >> axis & 1);
            let (o, inv) = (origin[axis], self.inv_dir[axis]);
            t_in = t_in.max((node.planes[axis][near] - o) * inv);
            t_out = t_out.min((node.planes[axis][near ^ 1] - o) * inv);
        }
        (t_in, t_in.cmple(t_out))
    }
}

/// One ray's traversal in progress: what it visits next, how deep its stack
/// is (the stack itself is lent to each step), and the best hit so far.
struct Walk {
    ray: WideRay,
    next: Visit,
    top: usize,
    t_max: f32,
    /// The item hit at `t_max` (`u32::MAX` while none is).
    best_item: u32,
}

impl Walk {
    /// A walk that starts at the root.
    fn new(origin: Vec3A, dir: Vec3A, max_t: f32) -> Walk {
        Walk {
            ray: WideRay::new(origin, dir),
            next: Visit::default(),
            top: FLOOR,
            t_max: max_t,
            best_item: u32::MAX,
        }
    }

    /// Steps the walk to its end, one ray alone, and returns its answer.
    #[inline(always)]
    fn run<const ANY: bool, const OCTANT: u8>(
        mut self,
        bvh: &WideBvh,
        items: &impl LeafItems,
        stack: &mut [Visit],
    ) -> Option<(f32, u32)> {
        while !self.step::<ANY, false, false, OCTANT>(bvh, items, stack) {}
        self.best()
    }

    /// The answer so far: the best hit as `(t, id)`.
    #[inline(always)]
    fn best(&self) -> Option<(f32, u32)> {
        (self.best_item != u32::MAX).then_some((self.t_max, self.best_item))
    }

    /// Reads the next node (stacking the farther hit children, with
    /// [`Walk::push_branchless`] or else [`Walk::push_sorting`]) or leaf,
    /// then chooses what to read after it (and with `PREFETCH` hints it to
    /// the CPU). Returns true when the walk is over; [`Walk::best`] is then its
    /// answer.
    /// `stack` must hold [`WideBvh::stack_size`] entries and be the same at
    /// every step.
    #[inline(always)]
    fn step<const ANY: bool, const PREFETCH: bool, const BRANCHLESS: bool, const OCTANT: u8>(
        &mut self,
        bvh: &WideBvh,
        items: &impl LeafItems,
        stack: &mut [Visit],
    ) -> bool {
        let (first, count) = (self.next.first(), self.next.count());
        if count == 0 {
            let node = &bvh.nodes[first as usize];
            let (entry, hits) = self.ray.enter::<OCTANT>(node, self.t_max);
            if hits.any() {
                self.next = if BRANCHLESS {
                    Walk::push_branchless(node, entry, hits, stack, &mut self.top)
                } else {
                    Walk::push_sorting(node, entry, hits, stack, &mut self.top)
                };
                if PREFETCH {
                    bvh.prefetch(self.next, items);
                }
                return false;
            }
        } else {
            // A leaf holds at least one item (a mesh leaf exactly one); the
            // first is tested outside the loop, which spares copying the ray
            // for it.
            if self.test::<ANY, BRANCHLESS>(first, items) {
                return true;
            }
            for item in first + 1..first + count {
                if self.test::<ANY, BRANCHLESS>(item, items) {
                    return true;
                }
            }
        }
        if BRANCHLESS {
            self.pop_window(stack)
        } else {
            self.pop_one_by_one(stack)
        }
        .is_none_or(|next| {
            self.next = next;
            if PREFETCH {
                bvh.prefetch(next, items);
            }
            false
        })
    }

    /// Tests leaf item `item`, keeping it if it is hit no farther than the
    /// best hit so far (interleaved, by selection rather than by a branch:
    /// whether a leaf is hit is then unpredictable); true if the walk is to
    /// stop there (with `ANY`, on a hit).
    #[inline(always)]
    fn test<const ANY: bool, const BRANCHLESS: bool>(
        &mut self,
        item: u32,
        items: &impl LeafItems,
    ) -> bool {
        let (t, id) = items.nearest(item, &self.ray, self.t_max);
        // Every hit lies within `t_max`; a miss is NaN.
        let hit = t <= self.t_max;
        (self.t_max, self.best_item) = if BRANCHLESS {
            select_unpredictable(hit, (t, id), (self.t_max, self.best_item))
        } else if hit {
            (t, id)
        } else {
            (self.t_max, self.best_item)
        };
        ANY && hit
    }

    /// Pops the nearest stacked child that still starts before the best hit
    /// (`None` when none is left), one entry after another: cheapest when
    /// the culling branch predicts well, as for one ray after another.
    #[inline(always)]
    fn pop_one_by_one(&mut self, stack: &[Visit]) -> Option<Visit> {
        while self.top > FLOOR {
            self.top -= 1;
            if stack[self.top].entry <= self.t_max {
                return Some(stack[self.top]);
            }
        }
        None
    }

    /// [`Walk::pop_one_by_one`] looking at the top [`FLOOR`] entries at once,
    /// so that a culled entry costs no branch of its own (faster when walks
    /// are interleaved, as whether an entry is culled is then unpredictable).
    /// The floor's entries are never taken.
    #[inline(always)]
    fn pop_window(&mut self, stack: &[Visit]) -> Option<Visit> {
        loop {
            let window: &[Visit; FLOOR] = stack[self.top - FLOOR..self.top]
                .try_into()
                .expect("the top is at or above the floor");
            let entries = Vec4::from_array(window.map(|v| v.entry));
            let open = entries.cmple(Vec4::splat(self.t_max)).bitmask();
            if open != 0 {
                let k = (u32::BITS - 1 - open.leading_zeros()) as usize % FLOOR;
                self.top -= FLOOR - k;
                return Some(window[k]);
            }
            if self.top <= 2 * FLOOR {
                self.top = FLOOR;
                return None;
            }
            self.top -= FLOOR;
        }
    }

    /// Stacks the hit children of `node` but the nearest, which it returns,
    /// by compare and swap in lane order: the nearer of each pair goes on,
    /// so the stack top is often the second nearest. Cheapest when the
    /// branches predict well, as for one ray after another.
    #[inline(always)]
    fn push_sorting(
        node: &Node,
        entry: Vec4,
        hits: BVec4A,
        stack: &mut [Visit],
        top: &mut usize,
    ) -> Visit {
        let entry = entry.to_array();
        let mut hits = hits.bitmask();
        let mut take = || {
            let lane = hits.trailing_zeros() as usize % WIDTH;
            hits &= hits - 1;
            let visit = Visit {
                entry: entry[lane],
                child: node.child[lane],
            };
            (visit, hits != 0)
        };
        let (mut next, mut more) = take();
        while more {
            let (mut other, left) = take();
            if other.entry < next.entry {
                std::mem::swap(&mut other, &mut next);
            }
            stack[*top] = other;
            *top += 1;
            more = left;
        }
        next
    }

    /// Stacks the hit children of `node` but the nearest (the lowest lane
    /// among equally near ones), which it returns, without branches: every
    /// lane is written past the top, which moves past the hit ones only.
    /// Faster when walks are interleaved, as branch history then mixes
    /// unrelated rays.
    #[inline(always)]
    fn push_branchless(
        node: &Node,
        entry: Vec4,
        hits: BVec4A,
        stack: &mut [Visit],
        top: &mut usize,
    ) -> Visit {
        let entered = Vec4::select(hits, entry, Vec4::INFINITY);
        let nearest = entered.min_element();
        let lane = entered
            .cmpeq(Vec4::splat(nearest))
            .bitmask()
            .trailing_zeros() as usize
            % WIDTH;
        let others = hits.bitmask() & !(1 << lane);
        let pushed: &mut [Visit; WIDTH] = (&mut stack[*top..*top + WIDTH])
            .try_into()
            .expect("the stack holds WIDTH entries past any reachable top");
        let mut count = 0;
        for (k, (&entry, &child)) in entry.to_array().iter().zip(&node.child).enumerate() {
            pushed[count % WIDTH] = Visit { entry, child };
            count += (others >> k) as usize & 1;
        }
        *top += count;
        Visit {
            entry: nearest,
            child: node.child[lane],
        }
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::bvh2::builder::build_bvh2;

    use super::*;

    /// Boxes as leaf items, in slot order.
    struct Boxes {
        bvh2: Bvh2,
        boxes: Vec<Aabb>,
    }

    impl LeafItems for Boxes {
        fn nearest(&self, item: u32, ray: &WideRay, t_max: f32) -> (f32, u32) {
            let lane0 = |v: &Xyz<Vec4>| Vec3A::new(v.x.x, v.y.x, v.z.x);
            let r = obvhs::ray::Ray::new(lane0(&ray.origin), lane0(&ray.dir), 0.0, f32::INFINITY);
            let k = self.bvh2.primitive_indices[item as usize];
            let t = self.boxes[k as usize].intersect_ray(&r);
            if t <= t_max { (t, k) } else { (f32::NAN, 0) }
        }

        fn address(&self, item: u32) -> *const u8 {
            self.boxes.as_ptr().wrapping_add(item as usize).cast()
        }
    }

    /// Unit cubes at x = 0, 2, 4, ...: a ray along +x meets them in order.
    fn cubes(n: usize) -> (WideBvh, Boxes) {
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
        let wide = WideBvh::from_bvh2(&bvh2, |first, count| (first, count));
        (wide, Boxes { bvh2, boxes })
    }

    fn cast<const ANY: bool>(
        wide: &WideBvh,
        boxes: &Boxes,
        o: Vec3A,
        d: Vec3A,
    ) -> Option<(f32, u32)> {
        wide.traverse::<ANY>(o, d, f32::INFINITY, boxes)
    }

    #[test]
    fn finds_the_closest_box_from_either_side() {
        for n in [1, 3, 200] {
            let (wide, boxes) = cubes(n);
            let (o, d) = (Vec3A::new(-1.0, 0.5, 0.5), Vec3A::X);
            assert_eq!(cast::<false>(&wide, &boxes, o, d), Some((1.0, 0)));
            let far = Vec3A::new(2.0 * n as f32 + 1.0, 0.5, 0.5);
            let last = (n - 1) as u32;
            assert_eq!(cast::<false>(&wide, &boxes, far, -d), Some((2.0, last)));
            assert!(cast::<true>(&wide, &boxes, o, d).is_some());
            let above = Vec3A::new(-1.0, 2.0, 0.5);
            assert_eq!(cast::<false>(&wide, &boxes, above, d), None);
        }
    }

    #[test]
    fn interleaved_walks_answer_like_single_ones_with_and_without_prefetch() {
        let (wide, boxes) = cubes(300);
        let rays: Vec<Ray> = (0..100)
            .map(|k| {
                // Every direction octant, with zero components of both signs
                // (`-0.3 * 0.0` is `-0.0`); the upward rays start below the cubes.
                let up = k % 5 == 0;
                let y = if up { -2.0 } else { 3.0 };
                let o = glam::Vec3::new(-5.0 + k as f32 * 7.0, y, 0.5 + (k % 3) as f32);
                let dy = if up { 1.0 } else { -1.0 };
                let d = glam::Vec3::new(
                    (k % 7) as f32 - 3.0,
                    dy,
                    -0.3 * (k % 4) as f32 + 0.2 * (k % 3) as f32,
                );
                Ray::new(o, d).unwrap()
            })
            .collect();
        let single = |any: bool| -> Vec<Option<(f32, u32)>> {
            rays.iter()
                .map(|r| {
                    let (o, d) = (r.origin().into(), r.dir().into());
                    if any {
                        cast::<true>(&wide, &boxes, o, d)
                    } else {
                        cast::<false>(&wide, &boxes, o, d)
                    }
                })
                .collect()
        };
        let (closest, first) = (single(false), single(true));
        assert!(closest.iter().filter(|h| h.is_some()).count() > 20);
        let octants: std::collections::BTreeSet<u8> =
            rays.iter().map(|r| octant(r.dir().into())).collect();
        assert_eq!(octants.len(), 8, "rays in every octant");
        let mut got = vec![None; rays.len()];
        wide.interleave::<false, true, 8>(&rays, f32::INFINITY, &boxes, |k, h| got[k] = h);
        assert_eq!(got, closest);
        got.fill(None);
        wide.interleave::<false, false, 8>(&rays, f32::INFINITY, &boxes, |k, h| got[k] = h);
        assert_eq!(got, closest);
        got.fill(None);
        wide.traverse_many::<true>(&rays, f32::INFINITY, &boxes, |k, h| got[k] = h);
        assert_eq!(got, first);
        // Fewer rays than lanes, and none.
        wide.traverse_many::<false>(&rays[..3], f32::INFINITY, &boxes, |k, h| {
            assert_eq!(h, closest[k])
        });
        wide.traverse_many::<false>(&[], f32::INFINITY, &boxes, |_, _| unreachable!());
    }

    #[test]
    fn a_cast_nested_in_a_primitive_test_gets_its_own_stack() {
        /// Casts the same ray again from inside every item test, and misses.
        struct Nested<'a> {
            wide: &'a WideBvh,
            boxes: &'a Boxes,
            inner: std::cell::RefCell<Vec<Option<(f32, u32)>>>,
        }
        impl LeafItems for Nested<'_> {
            fn nearest(&self, _: u32, _: &WideRay, _: f32) -> (f32, u32) {
                let o = Vec3A::new(-1.0, 0.5, 0.5);
                self.inner
                    .borrow_mut()
                    .push(cast::<false>(self.wide, self.boxes, o, Vec3A::X));
                (f32::NAN, 0)
            }
            fn address(&self, _: u32) -> *const u8 {
                std::ptr::null()
            }
        }
        let (wide, boxes) = cubes(500);
        let o = Vec3A::new(-1.0, 0.5, 0.5);
        let alone = cast::<false>(&wide, &boxes, o, Vec3A::X);
        let nested = Nested {
            wide: &wide,
            boxes: &boxes,
            inner: Default::default(),
        };
        let outer = wide.traverse::<false>(o, Vec3A::X, f32::INFINITY, &nested);
        assert_eq!(outer, None);
        let inner = nested.inner.into_inner();
        assert!(!inner.is_empty() && inner.iter().all(|&c| c == alone));
        assert_eq!(alone, Some((1.0, 0)));
    }
}
