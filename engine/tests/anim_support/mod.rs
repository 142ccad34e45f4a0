//! A hand-built two-bone glTF for the animation tests: joint 0 `root` at the
//! origin, joint 1 `tip` one metre up, a 3-vertex triangle skinned to them, and
//! a clip `bend` turning `tip` 90 degrees about +z over one second.
#![allow(dead_code)]

mod glb_buffer;

use glb_buffer::{GlbBuffer, float_bytes as floats, glb};

/// What the glTF holds; tests change fields to make bad files.
pub struct TwoBones {
    pub positions: Vec<[f32; 3]>,
    pub joints: Vec<[u8; 4]>,
    pub weights: Vec<[f32; 4]>,
    /// Whether the mesh node has its skin.
    pub skinned: bool,
    /// The node the clip's channel animates (1 = `tip`, 2 = the mesh node).
    pub channel_target: usize,
    /// The POSITION accessor's declared count (3 unless testing short buffers).
    pub position_count: usize,
    /// The clip's interpolation.
    pub interpolation: &'static str,
    /// Key times and rotation values (3 per key for CUBICSPLINE).
    pub times: Vec<f32>,
    pub rotations: Vec<[f32; 4]>,
}

impl Default for TwoBones {
    fn default() -> Self {
        let h = std::f32::consts::FRAC_1_SQRT_2;
        TwoBones {
            positions: vec![[0.1, 0.0, 0.0], [0.1, 1.0, 0.0], [0.1, 2.0, 0.0]],
            joints: vec![[0, 0, 0, 0], [0, 1, 0, 0], [1, 0, 0, 0]],
            weights: vec![
                [1.0, 0.0, 0.0, 0.0],
                [0.5, 0.5, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
            ],
            skinned: true,
            channel_target: 1,
            position_count: 3,
            interpolation: "LINEAR",
            times: vec![0.0, 1.0],
            rotations: vec![[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, h, h]],
        }
    }
}

impl TwoBones {
    /// The glTF JSON (buffer as `uri`, or the GLB chunk when `uri` is `None`) and the buffer bytes.
    pub fn build(&self, uri: Option<&str>) -> (String, Vec<u8>) {
        let mut b = GlbBuffer::default();
        // glTF requires bounds on POSITION; these need not be tight.
        let position = b.add(
            floats(self.positions.iter().flatten().copied()),
            5126,
            self.position_count,
            "VEC3",
            Some(([-9.0; 3], [9.0; 3])),
        );
        let normal = b.add(
            floats(self.positions.iter().flat_map(|_| [0.0, 0.0, 1.0])),
            5126,
            self.positions.len(),
            "VEC3",
            None,
        );
        let joints = b.add(
            self.joints.iter().flatten().copied().collect(),
            5121,
            self.joints.len(),
            "VEC4",
            None,
        );
        let weights = b.add(
            floats(self.weights.iter().flatten().copied()),
            5126,
            self.weights.len(),
            "VEC4",
            None,
        );
        let indices = b.add(
            [0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()).collect(),
            5123,
            3,
            "SCALAR",
            None,
        );
        let mut ibm = Vec::new();
        for y in [0.0f32, -1.0] {
            ibm.extend([
                1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, y, 0.0, 1.0,
            ]);
        }
        let ibm = b.add(floats(ibm), 5126, 2, "MAT4", None);
        let times = b.add(
            floats(self.times.iter().copied()),
            5126,
            self.times.len(),
            "SCALAR",
            None,
        );
        let rotations = b.add(
            floats(self.rotations.iter().flatten().copied()),
            5126,
            self.rotations.len(),
            "VEC4",
            None,
        );
        let buffer = match uri {
            Some(u) => format!(r#"{{"byteLength":{},"uri":"{u}"}}"#, b.bin.len()),
            None => format!(r#"{{"byteLength":{}}}"#, b.bin.len()),
        };
        let skin = if self.skinned { r#","skin":0"# } else { "" };
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,2]}}],
"nodes":[{{"name":"root","children":[1]}},{{"name":"tip","translation":[0,1,0]}},{{"name":"mesh","mesh":0{skin}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{position},"NORMAL":{normal},"JOINTS_0":{joints},"WEIGHTS_0":{weights}}},"indices":{indices}}}]}}],
"skins":[{{"joints":[0,1],"inverseBindMatrices":{ibm}}}],
"animations":[{{"name":"bend","channels":[{{"sampler":0,"target":{{"node":{},"path":"rotation"}}}}],"samplers":[{{"input":{times},"output":{rotations},"interpolation":"{}"}}]}}],
"bufferViews":[{}],"accessors":[{}],"buffers":[{buffer}]}}"#,
            self.channel_target,
            self.interpolation,
            b.views.join(","),
            b.accessors.join(","),
        );
        (json, b.bin)
    }

    /// A `.gltf` whose buffer is a base64 `data:` URI.
    pub fn gltf_text(&self) -> String {
        let (_, bin) = self.build(Some("x"));
        let (json, _) = self.build(Some(&format!(
            "data:application/octet-stream;base64,{}",
            base64(&bin)
        )));
        json
    }

    /// A `.glb`.
    pub fn glb(&self) -> Vec<u8> {
        let (json, bin) = self.build(None);
        glb(json.into_bytes(), bin)
    }
}

/// Standard padded base64.
pub fn base64(bytes: &[u8]) -> String {
    const TABLE: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(TABLE[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The default human shipped with the repository.
pub fn human_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/characters/human.glb")
}
