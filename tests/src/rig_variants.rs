//! Characters the way other tools export them, built from the built-in human
//! by changing one thing at a time: bone names, length units, up and forward
//! axes, bind pose, extra and missing bones, proportions. Each edit keeps the
//! model a valid skinned character (the mesh re-skinned to a new bind pose
//! where the bind pose changes).

use engine::anim::{Joint, RigPreset, Skeleton, Transform};
use glam::{Affine3A, Mat4, Quat, Vec3};
use softwalk_systems::character::CharacterRig;

use crate::glb_writer::RigParts;

impl RigParts {
    /// The built-in human's parts.
    pub fn human() -> RigParts {
        let model = CharacterRig::parse_human().expect("the built-in human");
        let mesh = &model.mesh;
        RigParts {
            joints: model.skeleton.joints().to_vec(),
            positions: mesh.positions().to_vec(),
            normals: mesh.normals().to_vec(),
            indices: mesh.indices().to_vec(),
            skin: mesh.joints().to_vec(),
            weights: mesh.weights().to_vec(),
            triangle_mesh: vec![0; mesh.triangle_count()],
            outside_skin: Vec::new(),
            props: Vec::new(),
        }
    }

    /// The index of the joint named `name` (panics if there is none: a test bug).
    pub fn joint(&self, name: &str) -> usize {
        (self.joints.iter())
            .position(|j| j.name == name)
            .unwrap_or_else(|| panic!("no joint {name}"))
    }

    /// Each joint's global matrix in the rest pose.
    pub fn globals(&self) -> Vec<Mat4> {
        Skeleton::new(self.joints.clone())
            .expect("a valid skeleton")
            .rest_globals()
    }

    /// Renames every joint through `rename`.
    pub fn rename(&mut self, rename: impl Fn(&str) -> String) {
        for joint in &mut self.joints {
            joint.name = rename(&joint.name);
        }
    }

    /// Renames the game-engine names of every role to `preset`'s first name
    /// for it, and prefixes every other joint with `prefix`.
    pub fn rename_to_preset(&mut self, preset: RigPreset, prefix: &str) {
        use engine::anim::BoneRole;
        self.rename(|name| {
            BoneRole::ALL
                .into_iter()
                .find(|&r| softwalk_app::scene::role_key(r) == name)
                .map_or_else(
                    || format!("{prefix}{name}"),
                    |r| preset.names(r)[0].to_string(),
                )
        });
    }

    /// Makes the rest pose given by `locals` the new bind pose: the mesh is
    /// skinned into it and the inverse bind matrices follow.
    pub fn rebind(&mut self, locals: Vec<Transform>) {
        let old_binds: Vec<Mat4> = self.joints.iter().map(|j| j.inverse_bind).collect();
        for (joint, rest) in self.joints.iter_mut().zip(locals) {
            joint.rest = rest;
        }
        let globals = self.globals();
        let skinning: Vec<Affine3A> = (globals.iter().zip(&old_binds))
            .map(|(g, b)| Affine3A::from_mat4(*g * *b))
            .collect();
        for v in 0..self.positions.len() {
            let (mut p, mut n) = (Vec3::ZERO, Vec3::ZERO);
            for (&j, &w) in self.skin[v].iter().zip(&self.weights[v]) {
                p += w * skinning[j as usize].transform_point3(self.positions[v]);
                n += w * skinning[j as usize].transform_vector3(self.normals[v]);
            }
            self.positions[v] = p;
            self.normals[v] = n.normalize_or_zero();
        }
        for (joint, g) in self.joints.iter_mut().zip(&globals) {
            joint.inverse_bind = g.inverse();
        }
    }

    /// Turns the whole figure by `turn` about the origin (its root joints'
    /// rest transforms), as the new bind pose.
    pub fn turn(&mut self, turn: Quat) {
        let locals = (self.joints.iter())
            .map(|j| match j.parent {
                None => Transform {
                    translation: turn * j.rest.translation,
                    rotation: turn * j.rest.rotation,
                    scale: j.rest.scale,
                },
                Some(_) => j.rest,
            })
            .collect();
        self.rebind(locals);
    }

    /// Turns joint `name` so the bone from it to `child` points along
    /// `direction` (world axes), as the new bind pose.
    pub fn aim_bone(&mut self, name: &str, child: &str, direction: Vec3) {
        let (j, c) = (self.joint(name), self.joint(child));
        let globals = self.globals();
        let bone = globals[c].w_axis.truncate() - globals[j].w_axis.truncate();
        let world_turn = Quat::from_rotation_arc(bone.normalize(), direction.normalize());
        let parent_turn = self.joints[j]
            .parent
            .map_or(Quat::IDENTITY, |p| Quat::from_mat4(&globals[p]).normalize());
        let mut locals: Vec<Transform> = self.joints.iter().map(|j| j.rest).collect();
        locals[j].rotation =
            (parent_turn.inverse() * world_turn * parent_turn * locals[j].rotation).normalize();
        self.rebind(locals);
    }

    /// Gives every joint the global rotation `frame(joint, rest positions)`
    /// without moving any joint or vertex (as Blender orients each bone's Y
    /// axis along it): local transforms and inverse binds change, the bind
    /// pose does not. Joint scales must be 1.
    pub fn reorient(&mut self, frame: impl Fn(usize, &[Vec3]) -> Quat) {
        let at: Vec<Vec3> = self.globals().iter().map(|g| g.w_axis.truncate()).collect();
        let globals: Vec<Mat4> = (0..at.len())
            .map(|j| Mat4::from_rotation_translation(frame(j, &at), at[j]))
            .collect();
        for (j, global) in globals.iter().enumerate() {
            let local = match self.joints[j].parent {
                Some(p) => globals[p].inverse() * *global,
                None => *global,
            };
            let (_, rotation, translation) = local.to_scale_rotation_translation();
            self.joints[j].rest = Transform {
                translation,
                rotation,
                scale: Vec3::ONE,
            };
            self.joints[j].inverse_bind = global.inverse();
        }
    }

    /// The rotation turning +Y along the bone from joint `j` to its first
    /// child (a leaf keeps its parent's), rolled by `roll` radians about it.
    pub fn along_bone(&self, j: usize, at: &[Vec3], roll: f32) -> Quat {
        let child = (self.joints.iter()).position(|c| c.parent == Some(j));
        match (child, self.joints[j].parent) {
            (Some(c), _) => {
                let along = (at[c] - at[j]).normalize_or(Vec3::Y);
                Quat::from_rotation_arc(Vec3::Y, along) * Quat::from_rotation_y(roll)
            }
            (None, Some(p)) => self.along_bone(p, at, roll),
            (None, None) => Quat::IDENTITY,
        }
    }

    /// Puts a new root node `name` with rest transform `rest` above every
    /// current root, outside the skin (as exporters write an armature); the
    /// bind pose does not change, so the figure moves by `rest`.
    pub fn insert_root(&mut self, name: &str, rest: Transform) {
        for joint in &mut self.joints {
            joint.parent = Some(joint.parent.map_or(0, |p| p + 1));
        }
        self.joints.insert(
            0,
            Joint {
                name: name.to_string(),
                parent: None,
                rest,
                inverse_bind: rest.to_mat4().inverse(),
            },
        );
        self.outside_skin.push(name.to_string());
        for joints in &mut self.skin {
            for j in joints.iter_mut() {
                *j += 1;
            }
        }
    }

    /// Every length in `per_metre` units (100 for centimetres): offsets,
    /// inverse bind translations and vertices; the figure becomes that much larger.
    pub fn in_units(&mut self, per_metre: f32) {
        let s = Mat4::from_scale(Vec3::splat(per_metre));
        for joint in &mut self.joints {
            joint.rest.translation *= per_metre;
            joint.inverse_bind = s * joint.inverse_bind * s.inverse();
        }
        for p in &mut self.positions {
            *p *= per_metre;
        }
    }

    /// Adds a joint `name` under `parent` at `offset` from it (parent's axes),
    /// unrotated; vertices for which `takes` is true move their weight on
    /// `parent` onto it (a twist bone), none when it is always false (a
    /// weapon or IK bone).
    pub fn add_bone(
        &mut self,
        parent: &str,
        name: &str,
        offset: Vec3,
        takes: impl Fn(Vec3) -> bool,
    ) {
        let p = self.joint(parent);
        let global = self.globals()[p] * Mat4::from_translation(offset);
        let j = self.joints.len();
        self.joints.push(Joint {
            name: name.to_string(),
            parent: Some(p),
            rest: Transform::from_translation(offset),
            inverse_bind: global.inverse(),
        });
        for v in 0..self.positions.len() {
            if takes(self.positions[v]) {
                for slot in self.skin[v].iter_mut() {
                    if *slot as usize == p {
                        *slot = j as u16;
                    }
                }
            }
        }
    }

    /// Adds a tetrahedron on `corners`, skinned wholly to joint `name` (a
    /// tail, a scabbard, the hem of a cloak); its faces point outwards.
    pub fn add_tetrahedron(&mut self, name: &str, corners: [Vec3; 4]) {
        let j = self.joint(name) as u16;
        let centre = corners.iter().sum::<Vec3>() / 4.0;
        for face in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
            let [a, b, c] = face.map(|k| corners[k]);
            let normal = (b - a).cross(c - a).normalize();
            let (b, c, normal) = if normal.dot(a - centre) < 0.0 {
                (c, b, -normal)
            } else {
                (b, c, normal)
            };
            let first = self.positions.len() as u32;
            self.positions.extend([a, b, c]);
            self.normals.extend([normal; 3]);
            self.skin.extend([[j, 0, 0, 0]; 3]);
            self.weights.extend([[1.0, 0.0, 0.0, 0.0]; 3]);
            self.indices.extend([first, first + 1, first + 2]);
            self.triangle_mesh.push(0);
        }
    }

    /// Removes joint `name`: its children hang from its parent (their rest
    /// transforms composed with its own) and its vertex weights go to its parent.
    pub fn remove_bone(&mut self, name: &str) {
        let j = self.joint(name);
        let parent = self.joints[j].parent.expect("not a root");
        let own = self.joints[j].rest.to_mat4();
        for child in &mut self.joints {
            if child.parent == Some(j) {
                let (scale, rotation, translation) =
                    (own * child.rest.to_mat4()).to_scale_rotation_translation();
                child.rest = Transform {
                    translation,
                    rotation,
                    scale,
                };
                child.parent = Some(parent);
            }
        }
        self.joints.remove(j);
        let shift = |k: usize| if k > j { k - 1 } else { k };
        for joint in &mut self.joints {
            joint.parent = joint.parent.map(shift);
        }
        for joints in &mut self.skin {
            for slot in joints.iter_mut() {
                let k = if *slot as usize == j {
                    parent
                } else {
                    *slot as usize
                };
                *slot = shift(k) as u16;
            }
        }
    }

    /// Stretches the figure vertically: heights below `at` by `below`, the
    /// rest above it by `above` (long legs and a short torso when `below` >
    /// 1 > `above`). Joint rotations are kept; offsets and binds follow.
    pub fn stretch_vertically(&mut self, at: f32, below: f32, above: f32) {
        let warp = |p: Vec3| {
            let y = if p.y <= at {
                p.y * below
            } else {
                at * below + (p.y - at) * above
            };
            Vec3::new(p.x, y, p.z)
        };
        let old = self.globals();
        let placed: Vec<Vec3> = old.iter().map(|g| warp(g.w_axis.truncate())).collect();
        let mut globals: Vec<Mat4> = Vec::with_capacity(old.len());
        for (k, g) in old.iter().enumerate() {
            let mut moved = *g;
            moved.w_axis = placed[k].extend(1.0);
            if let Some(p) = self.joints[k].parent {
                let local = globals[p].inverse() * moved;
                self.joints[k].rest.translation = local.w_axis.truncate();
            } else {
                self.joints[k].rest.translation = placed[k];
            }
            globals.push(moved);
            self.joints[k].inverse_bind = moved.inverse();
        }
        for p in &mut self.positions {
            *p = warp(*p);
        }
    }
}
