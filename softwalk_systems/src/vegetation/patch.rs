//! `GrassPatch`: blades scattered over a rectangle, pushed by feet through the
//! paper's deformation field, recovering in closed form, breaking when trodden.

use std::collections::VecDeque;
use std::ops::Range;

use glam::{Vec2, Vec3, Vec3Swizzles};

use super::area::XzRect;
use super::blade::{Bend, Blade, BladeState};
use super::columns::{BladeColumns, Marker};
use super::error::VegetationError;
use super::field_batch::FieldBatch;
use super::field_memo::FieldMemo;
use super::foot_motion::FootMotion;
use super::grid::BladeGrid;
use super::recovery::time_to_settle;
use super::settings::GrassSettings;
use super::state_columns::StateColumns;
use crate::foot::FootState;
use crate::ground::Ground;
use engine::rng::SplitMix64;

/// Most blades one patch may hold.
pub const MAX_BLADES: usize = 1 << 26;

/// Colour a broken blade fades towards (dry straw, linear RGB).
const STRAW: [f32; 3] = [0.55, 0.48, 0.25];

/// A blade ready to draw: a thin strip tapering from `width` at the root to a
/// point at the tip, through the three points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BladePolyline {
    /// Root, middle and tip (world).
    pub points: [Vec3; 3],
    /// Width at the root (metres).
    pub width: f32,
    /// Linear RGB colour.
    pub colour: [f32; 3],
}

/// What one deformation step did (for tests and benchmarks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DeformStats {
    /// Blades whose root the grid query returned (candidates).
    pub visited: usize,
    /// Blades the field pushed this step.
    pub pushed: usize,
    /// Reached blades whose field was reused from the previous step, not
    /// recomputed: only feet that did not move reach them.
    pub reused: usize,
    /// Blades that settled and left the active list this step.
    pub retired: usize,
}

/// A patch of grass: the component the `grass_deform` system updates.
#[derive(Debug, Clone)]
pub struct GrassPatch {
    area: XzRect,
    settings: GrassSettings,
    blades: Vec<Blade>,
    /// Hot copy of the blades' roots and heights for the candidate test.
    columns: BladeColumns,
    /// Per blade state, in a column every push touches and one of bends.
    states: StateColumns,
    /// Per blade, the bend of the field of the last step that reached it
    /// (valid for the blades the previous step reached).
    field_bends: Vec<Bend>,
    /// Per blade, the size of that field, apart: most pushes read only it.
    field_sizes: Vec<f32>,
    grid: BladeGrid,
    /// Lowest root and highest tip, to skip feet far above or below.
    y_range: (f32, f32),
    /// Lowest upright middle point (as the candidate test computes it).
    lowest_mid: f32,
    clock: f64,
    active_count: usize,
    /// Recovering blades with the time they may settle (lazy: re-queued when pushed again).
    retire_queue: VecDeque<(u32, f64)>,
    motion: FootMotion,
    /// Scratch buffers kept to avoid allocating each step.
    scratch: StepScratch,
}

/// Buffers one deformation step fills, kept between steps so a step does not
/// allocate.
#[derive(Debug, Clone, Default)]
struct StepScratch {
    /// Sole centres of the feet given to [`GrassPatch::deform`].
    sole_centres: Vec<Vec3>,
    /// The feet and previous foot positions the candidate test measures against.
    markers: Vec<Marker>,
    /// Grid ranges near each marker, with the marker's index.
    marker_ranges: Vec<(usize, Range<usize>)>,
    /// `(merged range, marker)` pairs whose ranges meet, sorted.
    range_markers: Vec<(usize, usize)>,
    /// The markers that can reach the blades of one range.
    relevant: Vec<Marker>,
    /// Merged grid ranges near the feet.
    ranges: Vec<Range<usize>>,
    /// Blades some foot reaches, in storage order.
    reached: Vec<u32>,
    /// Of them, the blades whose field must be computed anew, in storage order.
    fresh: Vec<u32>,
    /// The fresh blades' upright geometry for the batched field.
    batch: FieldBatch,
}

impl GrassPatch {
    /// Scatters `density * area` blades over `area`, roots on `ground`.
    pub fn new(
        area: XzRect,
        settings: GrassSettings,
        ground: &dyn Ground,
    ) -> Result<Self, VegetationError> {
        Self::with_height_fn(area, settings, |x, z| {
            ground.cast_down(x, z, f32::MAX).map(|h| h.point.y)
        })
    }

    /// Scatters blades over `area` with roots at `ground_height(x, z)`
    /// (`None` or a non-finite height is an error naming the point).
    ///
    /// ```
    /// use glam::Vec2;
    /// use softwalk_systems::vegetation::{GrassPatch, GrassSettings, XzRect};
    /// let area = XzRect::new(Vec2::ZERO, Vec2::splat(2.0));
    /// let patch = GrassPatch::with_height_fn(area, GrassSettings::small(), |_, _| Some(0.0)).unwrap();
    /// assert_eq!(patch.blade_count(), 4000);
    /// assert_eq!(patch.height_at(1.0, 1.0), 0.5);
    /// assert_eq!(patch.height_at(3.0, 1.0), 0.0);
    /// ```
    pub fn with_height_fn(
        area: XzRect,
        settings: GrassSettings,
        ground_height: impl Fn(f32, f32) -> Option<f32>,
    ) -> Result<Self, VegetationError> {
        settings.validate()?;
        if !area.is_valid() {
            return Err(VegetationError::BadArea {
                min: area.min.to_array(),
                max: area.max.to_array(),
            });
        }
        let requested = settings.density as f64 * area.area() as f64;
        if requested.is_nan() || requested > MAX_BLADES as f64 {
            return Err(VegetationError::TooManyBlades {
                requested,
                limit: MAX_BLADES,
            });
        }
        let count = requested.round() as usize;
        let mut rng = SplitMix64::new(settings.seed);
        let mut scattered = Vec::with_capacity(count);
        for _ in 0..count {
            let x = rng.range(area.min.x, area.max.x);
            let z = rng.range(area.min.y, area.max.y);
            let y = ground_height(x, z)
                .filter(|y| y.is_finite())
                .ok_or(VegetationError::NoGround { x, z })?;
            let shade = rng.range(0.8, 1.1);
            scattered.push(Blade {
                root: Vec3::new(x, y, z),
                height: rng.around(settings.height, settings.height_variation),
                width: rng.around(settings.blade_width, 0.25),
                stiffness: rng.around(1.0, settings.stiffness_variation),
                colour: settings.colour.map(|c| (c * shade).min(1.0)),
            });
        }
        let xz: Vec<Vec2> = scattered.iter().map(|b| b.root.xz()).collect();
        // Cells of half the field radius: a foot's query square then wastes
        // less than with radius-sized cells, and rows stay contiguous slices.
        let (grid, order) = BladeGrid::build(area, 0.5 * settings.field.radius(), &xz);
        let blades: Vec<Blade> = order.iter().map(|&i| scattered[i as usize]).collect();
        let y_range = blades
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.root.y), hi.max(b.root.y + b.height))
            });
        let columns = BladeColumns::new(&blades);
        let lowest_mid = columns.lowest_mid();
        Ok(Self {
            area,
            settings,
            states: StateColumns::new(blades.len()),
            field_bends: vec![Bend::ZERO; blades.len()],
            field_sizes: vec![0.0; blades.len()],
            columns,
            blades,
            grid,
            y_range,
            lowest_mid,
            clock: 0.0,
            active_count: 0,
            retire_queue: VecDeque::new(),
            motion: FootMotion::default(),
            scratch: StepScratch::default(),
        })
    }

    /// The rectangle the patch covers.
    pub fn area(&self) -> XzRect {
        self.area
    }

    /// The patch's parameters.
    pub fn settings(&self) -> &GrassSettings {
        &self.settings
    }

    /// The paper's `t_max` for this patch.
    pub fn t_max(&self) -> f32 {
        self.settings.field.t_max
    }

    /// The paper's `gamma` for this patch.
    pub fn gamma(&self) -> f32 {
        self.settings.field.gamma
    }

    /// Vegetation height sensed at `(x, z)`: the nominal height inside the
    /// patch, 0 outside.
    pub fn height_at(&self, x: f32, z: f32) -> f32 {
        if self.area.contains(x, z) {
            self.settings.height
        } else {
            0.0
        }
    }

    /// Number of blades.
    pub fn blade_count(&self) -> usize {
        self.blades.len()
    }

    /// The blades (sorted by grid cell; the order is fixed at creation).
    pub fn blades(&self) -> &[Blade] {
        &self.blades
    }

    /// The per-blade states, parallel to [`GrassPatch::blades`].
    pub fn states(&self) -> impl ExactSizeIterator<Item = BladeState> + '_ {
        (0..self.blades.len()).map(|i| self.states.get(i))
    }

    /// The state of blade `index`.
    pub fn state(&self, index: usize) -> BladeState {
        self.states.get(index)
    }

    /// The spatial grid over the blades.
    pub fn grid(&self) -> &BladeGrid {
        &self.grid
    }

    /// The patch clock: seconds of simulated time so far.
    pub fn time(&self) -> f64 {
        self.clock
    }

    /// Blades currently bent and recovering.
    pub fn active_count(&self) -> usize {
        self.active_count
    }

    /// Current bend of blade `index` (displacement of its middle and tip).
    pub fn bend(&self, index: usize) -> Bend {
        let omega = self.settings.recovery_omega * self.blades[index].stiffness;
        self.states.get(index).bend_at(self.clock, omega)
    }

    /// Root, middle and tip of blade `index` as it looks now.
    pub fn blade_points(&self, index: usize) -> [Vec3; 3] {
        self.blades[index].points(self.bend(index))
    }

    /// Every blade ready to draw, in storage order.
    pub fn blade_polylines(&self) -> impl Iterator<Item = BladePolyline> + '_ {
        (0..self.blades.len()).map(|i| {
            let blade = &self.blades[i];
            let colour = if self.states.push[i].broken {
                std::array::from_fn(|c| 0.4 * blade.colour[c] + 0.6 * STRAW[c])
            } else {
                blade.colour
            };
            BladePolyline {
                points: self.blade_points(i),
                width: blade.width,
                colour,
            }
        })
    }

    /// One `grass_deform` step: advances the clock by `dt` and pushes blades
    /// with every foot. The foot position `p_f` is the sole centre.
    pub fn deform(&mut self, feet: &[FootState], dt: f32) -> DeformStats {
        let mut centres = std::mem::take(&mut self.scratch.sole_centres);
        centres.clear();
        centres.extend(feet.iter().map(|f| f.sole.center()));
        let stats = self.deform_points(&centres, dt);
        self.scratch.sole_centres = centres;
        stats
    }

    /// One step with explicit foot positions `p_f` (world).
    ///
    /// Each blade within reach of a foot gets the combined field of all feet
    /// at its upright middle and tip. Its bend becomes the larger (by
    /// `|mid| + |tip|`) of the field and its current recovering bend; a larger
    /// field re-anchors the recovery at this time, and so does the field that
    /// already holds the blade. Blades not reached are not visited: their
    /// recovery is evaluated in closed form when read.
    ///
    /// Feet are matched across steps by their index in `feet`. A blade that
    /// only feet standing still reach (a planted stance foot) was reached by
    /// exactly these feet at the same places in the previous step: its field
    /// is reused from then, not recomputed.
    pub fn deform_points(&mut self, feet: &[Vec3], dt: f32) -> DeformStats {
        self.clock += dt as f64;
        let mut stats = DeformStats {
            retired: self.retire_settled(),
            ..DeformStats::default()
        };
        let mut scratch = std::mem::take(&mut self.scratch);
        let mut motion = std::mem::take(&mut self.motion);
        let radius = self.settings.field.radius();
        motion.update(feet, |p| self.within_reach(p, radius));
        stats.visited = self.find_reached(&motion, &mut scratch);
        stats.reused = scratch.reached.len() - scratch.fresh.len();
        // Fields first (they depend on the upright blades and the feet only),
        // then the pushes in storage order.
        scratch.batch.clear();
        for &i in &scratch.fresh {
            scratch.batch.push(self.columns.upright(i as usize));
        }
        let mut fresh = scratch.fresh.iter();
        scratch
            .batch
            .evaluate(&self.settings.field, &motion.feet, |memo| {
                let i = *fresh.next().expect("one result per fresh blade") as usize;
                self.field_bends[i] = memo.bend;
                self.field_sizes[i] = memo.size;
            });
        for &i in &scratch.reached {
            if self.push(i as usize) {
                stats.pushed += 1;
            }
        }
        self.motion = motion;
        self.scratch = scratch;
        stats
    }

    /// Fills `scratch.reached` with the blades some foot of `motion` reaches
    /// and `scratch.fresh` with those of them a moved foot, or the previous
    /// position of one, reaches (the others get the field of the previous
    /// step again). Returns how many blades the grid query returned.
    fn find_reached(&self, motion: &FootMotion, scratch: &mut StepScratch) -> usize {
        let radius = self.settings.field.radius();
        let StepScratch {
            markers,
            marker_ranges,
            range_markers,
            relevant,
            ranges,
            reached,
            fresh,
            ..
        } = scratch;
        // A blade a moved foot, or the previous position of one, reaches must
        // have its field computed anew; otherwise it is reached by exactly the
        // feet of the previous step, at the same places.
        markers.clear();
        for (&at, &moved) in motion.feet.iter().zip(&motion.moved) {
            markers.push(Marker {
                at,
                reaches: true,
                disturbs: moved,
            });
        }
        let departed = motion.departed.iter().map(|&at| Marker {
            at,
            reaches: false,
            disturbs: true,
        });
        markers.extend(departed);
        // Each marker's own grid ranges: the blades it can reach at all.
        marker_ranges.clear();
        for (k, m) in markers.iter().enumerate() {
            let near = self
                .grid
                .ranges_near(m.at.xz(), self.reach_xz(m.at, radius));
            marker_ranges.extend(near.filter(|r| !r.is_empty()).map(|r| (k, r)));
        }
        // The blades to visit: those of the feet (a departed foot only
        // matters for blades a foot reaches now).
        ranges.clear();
        let of_feet = marker_ranges.iter().filter(|(k, _)| markers[*k].reaches);
        ranges.extend(of_feet.map(|(_, r)| r.clone()));
        merge_ranges(ranges);
        reached.clear();
        fresh.clear();
        // Only the markers whose own ranges meet a merged range can reach its
        // blades: pair each marker range with the merged ranges it meets (they
        // are sorted and disjoint), then read the pairs range by range, the
        // markers in index order.
        range_markers.clear();
        for (k, r) in marker_ranges.iter() {
            let first = ranges.partition_point(|m| m.end <= r.start);
            let meeting = ranges[first..].iter().take_while(|m| m.start < r.end);
            range_markers.extend((first..).zip(meeting).map(|(q, _)| (q, *k)));
        }
        range_markers.sort_unstable();
        range_markers.dedup();
        let mut pairs = range_markers.iter().peekable();
        for (q, range) in ranges.iter().enumerate() {
            relevant.clear();
            while let Some(&(_, k)) = pairs.next_if(|(rq, _)| *rq == q) {
                relevant.push(markers[k]);
            }
            self.columns
                .collect_reached(range.clone(), relevant, radius, reached, fresh);
        }
        ranges.iter().map(|r| r.len()).sum()
    }

    /// Horizontal distance from a foot at `p` beyond which no blade's upright
    /// middle or tip is within `radius` of it: every middle is at least
    /// `lowest_mid` high and every tip at most the highest tip, so a foot
    /// below the middles (a foot on the ground in tall grass) or above the
    /// tips reaches less far horizontally than `radius`.
    fn reach_xz(&self, p: Vec3, radius: f32) -> f32 {
        let dy = (self.lowest_mid - p.y).max(p.y - self.y_range.1).max(0.0);
        // Shrunk far beyond rounding: the candidate test decides exactly
        // which blades are reached; this only bounds where it looks.
        let dy = dy * (1.0 - 1e-3);
        (radius * radius - dy * dy).max(0.0).sqrt()
    }

    /// True when a foot at `p` can reach some blade of the patch.
    fn within_reach(&self, p: Vec3, radius: f32) -> bool {
        let (lo, hi) = self.y_range;
        p.is_finite()
            && p.y - radius < hi
            && p.y + radius > lo
            && p.x + radius > self.area.min.x
            && p.x - radius < self.area.max.x
            && p.z + radius > self.area.min.y
            && p.z - radius < self.area.max.y
    }

    /// Pushes blade `i` with its field of this step; true if it was pushed
    /// (non-zero field).
    fn push(&mut self, i: usize) -> bool {
        let size = self.field_sizes[i];
        if size <= 0.0 {
            return false;
        }
        let now = self.clock;
        let state = &mut self.states.push[i];
        let new_tread = state.count_tread(now, self.settings.tread_gap);
        let was_active = state.active;
        // Most pushes end here: a field below the floor loses to the
        // recovering bend, and is not the field holding the blade (that one
        // has the held bend's size, above the floor). An unknown (NaN) floor
        // decides nothing here.
        let below_floor = size < state.floor;
        let bend_changed = !below_floor && self.take_over(i, size);
        // Damage depends on the held bend and the treads only.
        if bend_changed || new_tread {
            self.apply_damage(i);
        }
        if !was_active {
            self.states.push[i].active = true;
            self.active_count += 1;
            let omega = self.settings.recovery_omega * self.blades[i].stiffness;
            let deadline = self.states.bends[i].anchor_time + time_to_settle(omega) as f64;
            self.retire_queue.push_back((i as u32, deadline));
        }
        true
    }

    /// Lets the field of size `size` take blade `i` over if it is the field
    /// already holding the blade or at least as large as its recovering bend
    /// (re-anchoring the recovery now); true if the held bend changed.
    fn take_over(&mut self, i: usize, size: f32) -> bool {
        let field = FieldMemo {
            bend: self.field_bends[i],
            size,
        };
        let s = &self.settings;
        let now = self.clock;
        // Read only when needed: most pushes do not look at the recovery.
        let omega = || s.recovery_omega * self.blades[i].stiffness;
        let state = self.states.get(i);
        let ceiling = self.states.ceiling(i);
        let states = &mut self.states;
        if !field.takes_over(&state, ceiling, || states.floor(i), now, omega) {
            return false;
        }
        let record = &mut self.states.bends[i];
        let changed = record.held != field.bend;
        record.held = field.bend;
        record.anchor_time = now;
        if changed {
            let rest_size = record.rest_size;
            self.states.set_sizes(i, size, rest_size);
        }
        changed
    }

    /// Breaks blade `i` if its held bend or its treads say so, and gives a
    /// broken blade its permanent residual bend.
    fn apply_damage(&mut self, i: usize) {
        let blade = &self.blades[i];
        let s = &self.settings;
        let StateColumns { push, bends } = &mut self.states;
        let (state, record) = (&mut push[i], &mut bends[i]);
        let break_at = s.break_bend * blade.stiffness * blade.height;
        let bent_too_far = record.held.tip.length_squared() > break_at * break_at;
        if bent_too_far || state.treads >= s.treads_to_break {
            state.broken = true;
        }
        if state.broken {
            let residual = record.held.scaled(s.broken_residual);
            if residual.size() > record.rest_size {
                record.rest = residual;
                self.states.resize(i);
            }
        }
    }

    /// Takes settled blades off the active list; returns how many.
    fn retire_settled(&mut self) -> usize {
        let mut retired = 0;
        while let Some(&(i, deadline)) = self.retire_queue.front() {
            if deadline > self.clock {
                break;
            }
            self.retire_queue.pop_front();
            let i = i as usize;
            let omega = self.settings.recovery_omega * self.blades[i].stiffness;
            let record = &mut self.states.bends[i];
            let settle_at = record.anchor_time + time_to_settle(omega) as f64;
            if settle_at > self.clock {
                self.retire_queue.push_back((i as u32, settle_at));
            } else {
                record.held = record.rest;
                self.states.push[i].active = false;
                self.states.resize(i);
                self.active_count -= 1;
                retired += 1;
            }
        }
        retired
    }
}

/// Sorts `ranges` and merges overlapping or touching ones, so that every
/// blade index appears in at most one of them.
fn merge_ranges(ranges: &mut Vec<Range<usize>>) {
    ranges.retain(|r| !r.is_empty());
    ranges.sort_unstable_by_key(|r| (r.start, r.end));
    let mut merged = 0;
    for k in 0..ranges.len() {
        if merged > 0 && ranges[k].start <= ranges[merged - 1].end {
            ranges[merged - 1].end = ranges[merged - 1].end.max(ranges[k].end);
        } else {
            ranges[merged] = ranges[k].clone();
            merged += 1;
        }
    }
    ranges.truncate(merged);
}

/// The vegetation height sensed at `(x, z)` over several patches (the tallest).
pub fn vegetation_height_at(patches: &[GrassPatch], x: f32, z: f32) -> f32 {
    patches
        .iter()
        .map(|p| p.height_at(x, z))
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ground::FlatGround;

    fn patch(seed: u64) -> GrassPatch {
        let settings = GrassSettings {
            seed,
            density: 400.0,
            ..GrassSettings::small()
        };
        let area = XzRect::new(Vec2::new(-1.0, -1.0), Vec2::new(2.0, 1.5));
        GrassPatch::new(area, settings, &FlatGround(0.25)).unwrap()
    }

    #[test]
    fn scattering_is_deterministic_and_inside_the_area() {
        let a = patch(9);
        let b = patch(9);
        let c = patch(10);
        assert_eq!(a.blades(), b.blades());
        assert_ne!(a.blades(), c.blades());
        assert_eq!(a.blade_count(), 3000);
        let s = a.settings();
        for blade in a.blades() {
            assert!(a.area().contains(blade.root.x, blade.root.z));
            assert_eq!(blade.root.y, 0.25);
            let h = blade.height / s.height;
            assert!((0.8..1.2).contains(&h), "{h}");
        }
        let mean = a.blades().iter().map(|b| b.height).sum::<f32>() / 3000.0;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let area = XzRect::new(Vec2::ZERO, Vec2::ONE);
        let flat = FlatGround(0.0);
        let empty = XzRect::new(Vec2::ZERO, Vec2::new(1.0, 0.0));
        assert!(matches!(
            GrassPatch::new(empty, GrassSettings::small(), &flat),
            Err(VegetationError::BadArea { .. })
        ));
        let dense = GrassSettings {
            density: 1e12,
            ..GrassSettings::small()
        };
        assert!(matches!(
            GrassPatch::new(area, dense, &flat),
            Err(VegetationError::TooManyBlades { .. })
        ));
        let err = GrassPatch::with_height_fn(area, GrassSettings::small(), |x, _| {
            (x < 0.5).then_some(0.0)
        })
        .unwrap_err();
        assert!(matches!(err, VegetationError::NoGround { x, .. } if x >= 0.5));
    }

    #[test]
    fn foot_far_above_touches_nothing_and_no_nan() {
        let mut p = patch(3);
        let stats = p.deform_points(&[Vec3::new(0.0, 5.0, 0.0)], 0.1);
        assert_eq!(stats, DeformStats::default());
        // A foot exactly at a blade's middle point: finite result.
        let mid = p.blades()[10].rest_mid();
        p.deform_points(&[mid], 0.1);
        for i in 0..p.blade_count() {
            assert!(p.blade_points(i).iter().all(|v| v.is_finite()));
        }
        assert!(p.active_count() > 0);
    }

    /// The grid query narrowed by the foot's height still finds every blade
    /// the field pushes, and visits fewer blades for a foot below the
    /// middles than for one among them.
    #[test]
    fn feet_at_any_height_push_exactly_the_blades_the_field_reaches() {
        let area = XzRect::new(Vec2::new(-1.0, -1.0), Vec2::new(1.0, 1.0));
        let fresh = GrassPatch::with_height_fn(area, GrassSettings::medium(), |x, _| Some(0.1 * x))
            .unwrap();
        let field = fresh.settings().field;
        let mut visited = Vec::new();
        for y in [-0.5, -0.1, 0.0, 0.15, 0.45, 0.8, 1.1, 1.4, 1.7] {
            let foot = Vec3::new(0.1, y, -0.05);
            let mut p = fresh.clone();
            let stats = p.deform_points(&[foot], 0.01);
            let brute: Vec<usize> = (0..p.blade_count())
                .filter(|&i| {
                    let b = &p.blades()[i];
                    let [mid, tip] = field.on_upright_blade(b.root, b.height, &[foot]);
                    mid.length() + tip.length() > 0.0
                })
                .collect();
            let pushed: Vec<usize> = (0..p.blade_count())
                .filter(|&i| p.state(i).treads > 0)
                .collect();
            assert_eq!(pushed, brute, "foot at height {y}");
            assert_eq!(stats.pushed, brute.len());
            visited.push(stats.visited);
        }
        assert!(visited[2] < visited[4], "{visited:?}");
        assert!(visited[8] < visited[6], "{visited:?}");
    }

    #[test]
    fn sensed_height_takes_the_tallest_patch() {
        let small = patch(1);
        let medium = GrassPatch::with_height_fn(
            XzRect::new(Vec2::ZERO, Vec2::ONE),
            GrassSettings::medium(),
            |_, _| Some(0.0),
        )
        .unwrap();
        let patches = [small, medium];
        assert_eq!(vegetation_height_at(&patches, 0.5, 0.5), 0.9);
        assert_eq!(vegetation_height_at(&patches, -0.5, 0.5), 0.5);
        assert_eq!(vegetation_height_at(&patches, 5.0, 5.0), 0.0);
    }
}
