use std::path::Path;

use gltf::Document;
use gltf::buffer::Source;

use super::{GltfError, MAX_FILE_BYTES, read_limited};

/// The bytes of every buffer of `document`, in order: the GLB binary chunk, a
/// base64 `data:` URI, or a file next to the glTF file (never a remote URI).
/// Each holds at least the buffer's declared `byteLength`.
pub(super) fn load_buffers(
    document: &Document,
    blob: Option<Vec<u8>>,
    path: &Path,
) -> Result<Vec<Vec<u8>>, GltfError> {
    let mut blob = blob;
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let part = format!("buffer {}", buffer.index());
        let data = match buffer.source() {
            Source::Bin => blob.take().ok_or_else(|| GltfError::Malformed {
                path: path.to_path_buf(),
                reason: format!("{part} refers to a GLB binary chunk that is absent"),
            })?,
            Source::Uri(uri) => load_uri(uri, path, &part)?,
        };
        if (data.len() as u64) < buffer.length() as u64 {
            return Err(GltfError::BufferTooShort {
                path: path.to_path_buf(),
                part,
                needed: buffer.length() as u64,
                available: data.len() as u64,
            });
        }
        buffers.push(data);
    }
    Ok(buffers)
}

fn load_uri(uri: &str, path: &Path, part: &str) -> Result<Vec<u8>, GltfError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, encoded)) = rest.split_once(";base64,") else {
            return Err(unsupported(path, part, "a data: URI that is not base64"));
        };
        if encoded.len() as u64 > MAX_FILE_BYTES * 4 / 3 + 4 {
            return Err(GltfError::TooLarge {
                path: path.to_path_buf(),
                part: part.to_string(),
                bytes: encoded.len() as u64 * 3 / 4,
                limit: MAX_FILE_BYTES,
            });
        }
        return super::base64::decode(encoded).ok_or_else(|| GltfError::Malformed {
            path: path.to_path_buf(),
            reason: format!("{part}: the data: URI is not valid base64"),
        });
    }
    if uri.contains("://") || uri.starts_with('/') || uri.contains('\\') {
        return Err(unsupported(
            path,
            part,
            &format!("URI {uri:?} (only data: URIs and relative file names are read)"),
        ));
    }
    let file = path.parent().unwrap_or(Path::new(".")).join(uri);
    read_limited(&file)
}

fn unsupported(path: &Path, part: &str, reason: &str) -> GltfError {
    GltfError::Unsupported {
        path: path.to_path_buf(),
        part: part.to_string(),
        reason: reason.to_string(),
    }
}
