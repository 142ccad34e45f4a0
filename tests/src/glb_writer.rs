//! A minimal `.glb` writer for test models: one skinned mesh, its skin over
//! every joint, and the joints as a node tree. Enough for the loader to read
//! back what a game programmer's exporter would write.

use engine::anim::Joint;
use glam::{Mat4, Vec3};
use serde_json::{Value, json};

/// A skinned character as plain data: joints (parents first) and a mesh whose
/// vertices name joints by index.
#[derive(Debug, Clone)]
pub struct RigParts {
    /// The joints, parents first; every joint is in the skin.
    pub joints: Vec<Joint>,
    /// Bind-pose positions.
    pub positions: Vec<Vec3>,
    /// Bind-pose normals.
    pub normals: Vec<Vec3>,
    /// Triangle corners.
    pub indices: Vec<u32>,
    /// 4 joint indices per vertex.
    pub skin: Vec<[u16; 4]>,
    /// 4 weights per vertex.
    pub weights: Vec<[f32; 4]>,
    /// Which glTF mesh each triangle is written to (all 0: one mesh). Every
    /// mesh is drawn with the character's skin by a node of its own.
    pub triangle_mesh: Vec<u8>,
    /// Joints written as plain nodes, outside the skin's joint list (an
    /// armature node above the bones); no vertex may use them.
    pub outside_skin: Vec<String>,
    /// Props written before the character, each a mesh drawn with a skin of
    /// its own, bound to one joint (as exporters write a skinned weapon).
    pub props: Vec<Prop>,
}

/// A one-triangle mesh with a skin of its own: one joint, named.
#[derive(Debug, Clone)]
pub struct Prop {
    /// The joint it follows.
    pub joint: String,
    /// Its triangle, bind pose.
    pub triangle: [Vec3; 3],
}

/// One mesh's vertices as accessor data.
struct MeshData {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    skin: Vec<[u16; 4]>,
    weights: Vec<[f32; 4]>,
    indices: Vec<u32>,
}

/// The glTF buffer the writer fills.
#[path = "../../engine/tests/anim_support/glb_buffer.rs"]
mod glb_buffer;

use glb_buffer::{GlbBuffer as Chunks, float_bytes, glb};

impl Chunks {
    /// Adds `values` as an accessor of `kind` floats.
    fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str) -> usize {
        let bytes = float_bytes(values.iter().flatten().copied());
        self.add(bytes, 5126, values.len(), kind, None)
    }
}

impl Chunks {
    /// A mesh's accessors as a glTF mesh.
    fn mesh(&mut self, data: &MeshData) -> Value {
        let (lo, hi) = (data.positions.iter())
            .map(|p| Vec3::from(*p))
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let position = self.add(
            float_bytes(data.positions.iter().flatten().copied()),
            5126,
            data.positions.len(),
            "VEC3",
            Some((lo.to_array(), hi.to_array())),
        );
        let normal = self.floats(&data.normals, "VEC3");
        let joints = self.add(
            data.skin
                .iter()
                .flatten()
                .flat_map(|j| j.to_le_bytes())
                .collect(),
            5123,
            data.skin.len(),
            "VEC4",
            None,
        );
        let weights = self.floats(&data.weights, "VEC4");
        let indices = self.add(
            data.indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
            5125,
            data.indices.len(),
            "SCALAR",
            None,
        );
        json!({"primitives": [{
            "attributes": {"POSITION": position, "NORMAL": normal, "JOINTS_0": joints, "WEIGHTS_0": weights},
            "indices": indices
        }]})
    }

    /// A skin over `joints` with their inverse bind matrices.
    fn skin(&mut self, joints: Vec<usize>, binds: &[Mat4]) -> Value {
        let binds: Vec<[f32; 16]> = binds.iter().map(Mat4::to_cols_array).collect();
        let binds = self.floats(&binds, "MAT4");
        json!({"joints": joints, "inverseBindMatrices": binds})
    }
}

impl RigParts {
    /// The parts as `.glb` bytes: the props' nodes first, then the joints'
    /// tree, then one node per character mesh.
    pub fn to_glb(&self) -> Vec<u8> {
        let mut c = Chunks::default();
        let mut nodes: Vec<Value> = Vec::new();
        let (mut meshes, mut skins) = (Vec::new(), Vec::new());
        let prop_count = self.props.len();
        let first_joint = prop_count;
        for (k, prop) in self.props.iter().enumerate() {
            let joint = self.joint(&prop.joint);
            meshes.push(c.mesh(&MeshData {
                positions: prop.triangle.map(|p| p.to_array()).to_vec(),
                normals: vec![[0.0, 0.0, 1.0]; 3],
                skin: vec![[0; 4]; 3],
                weights: vec![[1.0, 0.0, 0.0, 0.0]; 3],
                indices: vec![0, 1, 2],
            }));
            skins.push(c.skin(
                vec![first_joint + joint],
                &[self.joints[joint].inverse_bind],
            ));
            nodes.push(json!({"name": format!("prop{k}"), "mesh": k, "skin": k}));
        }
        nodes.extend(self.joints.iter().map(joint_node));
        for (k, joint) in self.joints.iter().enumerate() {
            if let Some(p) = joint.parent {
                let children = nodes[first_joint + p]["children"]
                    .as_array_mut()
                    .expect("children");
                children.push(json!(first_joint + k));
            }
        }
        let in_skin = self.skin_joints();
        let binds: Vec<Mat4> = in_skin
            .iter()
            .map(|&j| self.joints[j].inverse_bind)
            .collect();
        let joint_nodes = in_skin.iter().map(|&j| first_joint + j).collect();
        let character_skin = skins.len();
        skins.push(c.skin(joint_nodes, &binds));
        let mut roots: Vec<usize> = (0..prop_count).collect();
        roots.extend(
            (0..self.joints.len())
                .filter(|&k| self.joints[k].parent.is_none())
                .map(|k| first_joint + k),
        );
        let mesh_count = self
            .triangle_mesh
            .iter()
            .copied()
            .max()
            .map_or(1, |m| m + 1);
        for m in 0..mesh_count {
            let data = self.mesh_data(m);
            roots.push(nodes.len());
            nodes.push(
                json!({"name": format!("body{m}"), "mesh": meshes.len(), "skin": character_skin}),
            );
            meshes.push(c.mesh(&data));
        }
        let document = json!({
            "asset": {"version": "2.0", "generator": "softwalk tests"},
            "scene": 0,
            "scenes": [{"nodes": roots}],
            "nodes": nodes,
            "meshes": meshes,
            "skins": skins,
            "bufferViews": json_values(&c.views),
            "accessors": json_values(&c.accessors),
            "buffers": [{"byteLength": c.bin.len()}],
        });
        glb(serde_json::to_vec(&document).expect("JSON"), c.bin)
    }

    /// The joints in the skin's joint list, in order.
    fn skin_joints(&self) -> Vec<usize> {
        (0..self.joints.len())
            .filter(|&j| !self.outside_skin.contains(&self.joints[j].name))
            .collect()
    }

    /// The vertices and triangles of character mesh `m`, renumbered, their
    /// joints numbered in the skin's joint list.
    fn mesh_data(&self, m: u8) -> MeshData {
        let in_skin = self.skin_joints();
        let mut new_index = vec![u32::MAX; self.positions.len()];
        let mut used = Vec::new();
        let mut indices = Vec::new();
        for (t, corners) in self.indices.chunks_exact(3).enumerate() {
            if self.triangle_mesh.get(t).copied().unwrap_or(0) != m {
                continue;
            }
            for &v in corners {
                if new_index[v as usize] == u32::MAX {
                    new_index[v as usize] = used.len() as u32;
                    used.push(v as usize);
                }
                indices.push(new_index[v as usize]);
            }
        }
        MeshData {
            positions: used.iter().map(|&v| self.positions[v].to_array()).collect(),
            normals: used.iter().map(|&v| self.normals[v].to_array()).collect(),
            skin: used
                .iter()
                .map(|&v| {
                    self.skin[v].map(|j| {
                        let k = in_skin.iter().position(|&s| s == j as usize);
                        k.expect("a vertex uses a joint outside the skin") as u16
                    })
                })
                .collect(),
            weights: used.iter().map(|&v| self.weights[v]).collect(),
            indices,
        }
    }
}

/// A joint as a glTF node with its rest transform and an empty child list.
fn joint_node(joint: &Joint) -> Value {
    json!({
        "name": joint.name,
        "translation": joint.rest.translation.to_array(),
        "rotation": joint.rest.rotation.normalize().to_array(),
        "scale": joint.rest.scale.to_array(),
        "children": [],
    })
}

/// JSON objects written as text, as values.
fn json_values(objects: &[String]) -> Vec<Value> {
    (objects.iter())
        .map(|o| serde_json::from_str(o).expect("JSON"))
        .collect()
}
