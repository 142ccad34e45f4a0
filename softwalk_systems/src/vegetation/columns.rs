//! Structure-of-arrays copy of the blades' roots and heights: the candidate
//! test of a deformation step scans contiguous grid slices of these columns,
//! a loop without branches that the compiler vectorises.

use std::ops::Range;

use glam::Vec3;

use super::blade::Blade;

/// Root coordinates and heights of the blades, one column each, in storage order.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct BladeColumns {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
    height: Vec<f32>,
}

impl BladeColumns {
    /// The columns of `blades`.
    pub(crate) fn new(blades: &[Blade]) -> Self {
        Self {
            x: blades.iter().map(|b| b.root.x).collect(),
            y: blades.iter().map(|b| b.root.y).collect(),
            z: blades.iter().map(|b| b.root.z).collect(),
            height: blades.iter().map(|b| b.height).collect(),
        }
    }

    /// ORs `bits` into `flags[k]` for every blade `blades.start + k` whose
    /// upright middle or tip is closer than `radius` to `p`: exactly the blades
    /// a foot at `p` pushes (same arithmetic as
    /// [`DeformationField::on_upright_blade`](super::DeformationField::on_upright_blade)).
    /// `flags` has one entry per blade of the range.
    pub(crate) fn mark_near(
        &self,
        blades: Range<usize>,
        p: Vec3,
        radius: f32,
        bits: u8,
        flags: &mut [u8],
    ) {
        let r2 = radius * radius;
        let roots = self.x[blades.clone()]
            .iter()
            .zip(&self.y[blades.clone()])
            .zip(&self.z[blades.clone()])
            .zip(&self.height[blades]);
        for (flag, (((&x, &y), &z), &h)) in flags.iter_mut().zip(roots) {
            let (dx, dz) = (x - p.x, z - p.z);
            let (mid, tip) = (y + 0.5 * h - p.y, y + h - p.y);
            let near = (dx * dx + mid * mid + dz * dz < r2) | (dx * dx + tip * tip + dz * dz < r2);
            *flag |= bits & u8::from(near).wrapping_neg();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_blades_whose_middle_or_tip_is_within_the_radius() {
        let blade = |x: f32, y: f32, height: f32| Blade {
            root: Vec3::new(x, y, 0.0),
            height,
            width: 0.01,
            stiffness: 1.0,
            colour: [0.0; 3],
        };
        // Beside the foot; below it (tip reaches up); far above it; far
        // aside; root and tip out of reach with the foot between them.
        let blades = [
            blade(0.3, 0.0, 0.5),
            blade(0.0, -1.0, 0.9),
            blade(0.0, 1.0, 0.5),
            blade(2.0, 0.0, 0.5),
            blade(0.0, -0.8, 3.2),
        ];
        let columns = BladeColumns::new(&blades);
        let mut flags = vec![4u8; 5];
        columns.mark_near(0..5, Vec3::new(0.0, 0.2, 0.0), 0.5, 1, &mut flags);
        assert_eq!(flags, [5, 5, 4, 4, 4]);
        let mut tail = vec![0u8; 2];
        columns.mark_near(2..4, Vec3::new(2.0, 0.1, 0.0), 0.5, 2, &mut tail);
        assert_eq!(tail, [0, 2]);
    }
}
