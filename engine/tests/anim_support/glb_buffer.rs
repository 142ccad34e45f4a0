//! The binary side of a hand-written glTF for tests: buffer views and
//! accessors over one growing buffer, and the GLB container around a JSON
//! document and that buffer. Shared by the engine's animation tests and the
//! integration tests' `glb_writer` (which includes this file by path: the
//! engine cannot depend on the test crate).

/// Buffer views and accessors, as JSON objects, over one growing buffer.
#[derive(Default)]
pub struct GlbBuffer {
    /// The buffer's bytes.
    pub bin: Vec<u8>,
    /// One JSON buffer view per accessor.
    pub views: Vec<String>,
    /// The JSON accessors.
    pub accessors: Vec<String>,
}

impl GlbBuffer {
    /// Adds `bytes` (4-byte aligned) as a view and an accessor of `count`
    /// `kind`s of `component`, with `bounds` (min, max) when given; returns
    /// the accessor's index.
    pub fn add(
        &mut self,
        bytes: Vec<u8>,
        component: u32,
        count: usize,
        kind: &str,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            self.bin.len(),
            bytes.len()
        ));
        self.bin.extend(bytes);
        let bounds = match bounds {
            Some((lo, hi)) => format!(r#","min":{lo:?},"max":{hi:?}"#),
            None => String::new(),
        };
        self.accessors.push(format!(
            r#"{{"bufferView":{},"componentType":{component},"count":{count},"type":"{kind}"{bounds}}}"#,
            self.views.len() - 1
        ));
        self.accessors.len() - 1
    }
}

/// Little-endian bytes of `values`.
pub fn float_bytes(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
    values.into_iter().flat_map(f32::to_le_bytes).collect()
}

/// The GLB container: header, JSON chunk (space padded), BIN chunk (zero padded).
pub fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
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
