//! A minimal `.glb` writer for test models: one skinned mesh, its skin over
//! every joint, and the joints as a node tree. Enough for the loader to read
//! back what a game programmer's exporter would write.

use engine::anim::Joint;
use glam::Vec3;
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
}

/// Buffer views and accessors over one growing binary chunk.
#[derive(Default)]
struct Chunks {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Chunks {
    /// Adds `bytes` as a view and an accessor of `count` `kind`s of `component`.
    fn add(&mut self, bytes: Vec<u8>, component: u32, count: usize, kind: &str) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.views.push(json!({
            "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()
        }));
        self.bin.extend(bytes);
        self.accessors.push(json!({
            "bufferView": self.views.len() - 1, "componentType": component,
            "count": count, "type": kind
        }));
        self.accessors.len() - 1
    }

    fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str) -> usize {
        let bytes = values
            .iter()
            .flatten()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        self.add(bytes, 5126, values.len(), kind)
    }
}

impl RigParts {
    /// The parts as `.glb` bytes.
    pub fn to_glb(&self) -> Vec<u8> {
        let mut c = Chunks::default();
        let position = c.floats(
            &self
                .positions
                .iter()
                .map(|p| p.to_array())
                .collect::<Vec<_>>(),
            "VEC3",
        );
        let (lo, hi) = (self.positions.iter())
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        c.accessors[position]["min"] = json!(lo.to_array());
        c.accessors[position]["max"] = json!(hi.to_array());
        let normal = c.floats(
            &self
                .normals
                .iter()
                .map(|n| n.to_array())
                .collect::<Vec<_>>(),
            "VEC3",
        );
        let joints = c.add(
            self.skin
                .iter()
                .flatten()
                .flat_map(|j| j.to_le_bytes())
                .collect(),
            5123,
            self.skin.len(),
            "VEC4",
        );
        let weights = c.floats(&self.weights, "VEC4");
        let indices = c.add(
            self.indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
            5125,
            self.indices.len(),
            "SCALAR",
        );
        let binds: Vec<[f32; 16]> = self
            .joints
            .iter()
            .map(|j| j.inverse_bind.to_cols_array())
            .collect();
        let binds = c.floats(&binds, "MAT4");
        let mut nodes: Vec<Value> = self.joints.iter().map(joint_node).collect();
        for (k, joint) in self.joints.iter().enumerate() {
            if let Some(p) = joint.parent {
                let children = nodes[p]["children"].as_array_mut().expect("children");
                children.push(json!(k));
            }
        }
        let mesh_node = nodes.len();
        nodes.push(json!({"name": "body", "mesh": 0, "skin": 0}));
        let mut roots: Vec<usize> = (0..self.joints.len())
            .filter(|&k| self.joints[k].parent.is_none())
            .collect();
        roots.push(mesh_node);
        let document = json!({
            "asset": {"version": "2.0", "generator": "softwalk tests"},
            "scene": 0,
            "scenes": [{"nodes": roots}],
            "nodes": nodes,
            "meshes": [{"primitives": [{
                "attributes": {"POSITION": position, "NORMAL": normal, "JOINTS_0": joints, "WEIGHTS_0": weights},
                "indices": indices
            }]}],
            "skins": [{"joints": (0..self.joints.len()).collect::<Vec<_>>(), "inverseBindMatrices": binds}],
            "bufferViews": c.views,
            "accessors": c.accessors,
            "buffers": [{"byteLength": c.bin.len()}],
        });
        glb(serde_json::to_vec(&document).expect("JSON"), c.bin)
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

/// The GLB container: header, JSON chunk (space padded), BIN chunk (zero padded).
fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(bin);
    out
}
