//! [`Model::scaled`]: a model converted to another length unit.

use glam::{Mat4, Vec3};

use super::{AnimError, Clip, Joint, Model, Skeleton, SkinnedMesh};

impl Model {
    /// The same model with every length multiplied by `factor` (e.g. 0.01 to
    /// turn centimetres into metres): joint offsets, inverse bind matrices'
    /// translations, vertex positions and translation keys. Rotations and
    /// scales are kept, so it poses and skins exactly as before, `factor`
    /// times larger.
    pub fn scaled(&self, factor: f32) -> Result<Model, AnimError> {
        let conjugate = |m: &Mat4| {
            Mat4::from_scale(Vec3::splat(factor)) * *m * Mat4::from_scale(Vec3::splat(1.0 / factor))
        };
        let joints = (self.skeleton.joints().iter())
            .map(|j| {
                let mut rest = j.rest;
                rest.translation *= factor;
                Joint {
                    rest,
                    inverse_bind: conjugate(&j.inverse_bind),
                    ..j.clone()
                }
            })
            .collect();
        let skeleton = Skeleton::new(joints)?;
        let mesh = &self.mesh;
        let mesh = SkinnedMesh::new(
            mesh.positions().iter().map(|p| *p * factor).collect(),
            mesh.normals().to_vec(),
            mesh.indices().to_vec(),
            mesh.joints().to_vec(),
            mesh.weights().to_vec(),
            mesh.joint_count(),
        )?;
        let clips = (self.clips.iter())
            .map(|c| {
                let channels = c
                    .channels()
                    .iter()
                    .map(|ch| ch.with_lengths_scaled(factor))
                    .collect();
                Clip::new(c.name().to_string(), channels, skeleton.len())
            })
            .collect::<Result<_, _>>()?;
        Ok(Model {
            skeleton,
            mesh,
            clips,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::{SkinnedVertices, Transform, skin_matrices, skin_serial};
    use glam::Quat;

    #[test]
    fn a_scaled_model_skins_to_the_scaled_positions() {
        let joints = vec![
            Joint {
                name: "root".into(),
                parent: None,
                rest: Transform {
                    translation: Vec3::new(0.0, 10.0, 0.0),
                    rotation: Quat::from_rotation_x(0.3),
                    scale: Vec3::ONE,
                },
                inverse_bind: Mat4::from_translation(Vec3::new(0.0, -10.0, 0.0)),
            },
            Joint {
                name: "tip".into(),
                parent: Some(0),
                rest: Transform::from_translation(Vec3::new(0.0, 100.0, 0.0)),
                inverse_bind: Mat4::from_translation(Vec3::new(0.0, -110.0, 0.0)),
            },
        ];
        let mesh = SkinnedMesh::new(
            vec![
                Vec3::new(1.0, 50.0, 0.0),
                Vec3::new(2.0, 120.0, 0.0),
                Vec3::ZERO,
            ],
            vec![Vec3::Z; 3],
            vec![0, 1, 2],
            vec![[0, 0, 0, 0], [1, 0, 0, 0], [0, 1, 0, 0]],
            vec![
                [1.0, 0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
                [0.5, 0.5, 0.0, 0.0],
            ],
            2,
        )
        .unwrap();
        let model = Model {
            skeleton: Skeleton::new(joints).unwrap(),
            mesh,
            clips: Vec::new(),
        };
        let skinned = |m: &Model| {
            let mut matrices = Vec::new();
            skin_matrices(&m.skeleton, &m.skeleton.rest_globals(), &mut matrices);
            let mut out = SkinnedVertices::default();
            skin_serial(&m.mesh, &matrices, &mut out).unwrap();
            out.positions
        };
        let small = model.scaled(0.01).unwrap();
        for (a, b) in skinned(&model).iter().zip(skinned(&small)) {
            assert!((*a * 0.01).distance(b) < 1e-5, "{a} vs {b}");
        }
    }
}
