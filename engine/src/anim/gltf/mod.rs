//! glTF 2.0 import (`.gltf` with `data:` or local buffer files, and `.glb`) of a
//! rigged, skinned character and its animation clips.
//!
//! The JSON or GLB is parsed and validated by the `gltf` crate; buffers are
//! resolved here (never from the network) and every accessor is bounds-checked
//! before it is read. Bad files get a [`GltfError`] naming the file and the part.

mod accessor;
mod animation;
mod base64;
mod buffers;
mod error;
mod mesh;
mod skeleton;

use std::io::Read;
use std::path::Path;

pub use error::GltfError;

use crate::anim::Model;
use accessor::AccessorReader;

/// The largest glTF file, or buffer file, the loader reads (512 MiB).
pub const MAX_FILE_BYTES: u64 = 512 << 20;

/// Loads the character of a `.gltf` or `.glb` file: the skin with the most
/// joints (the first of those on a tie) and every mesh a node draws with it,
/// merged into one (a body, its clothes, hair and eyes), its skeleton and
/// every animation clip. Meshes drawn with other skins (props) are left out.
pub fn load_gltf(path: &Path) -> Result<Model, GltfError> {
    let bytes = read_limited(path)?;
    load_gltf_from_slice(&bytes, path)
}

/// Like [`load_gltf`] on bytes held in memory; `path` names them in errors and
/// locates relative buffer files.
pub fn load_gltf_from_slice(bytes: &[u8], path: &Path) -> Result<Model, GltfError> {
    let malformed = |reason: String| GltfError::Malformed {
        path: path.to_path_buf(),
        reason,
    };
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| malformed(e.to_string()))?;
    let json = document.into_json();
    check_before_validation(&json).map_err(malformed)?;
    let document = gltf::Document::from_json(json).map_err(|e| malformed(e.to_string()))?;
    let buffers = buffers::load_buffers(&document, blob, path)?;
    let reader = AccessorReader {
        path,
        buffers: &buffers,
    };
    let (meshes, skin) = character_meshes(&document).ok_or_else(|| GltfError::MissingSkin {
        path: path.to_path_buf(),
        reason: "no node has both a mesh and a skin".to_string(),
    })?;
    let rig = skeleton::skin_skeleton(&document, &skin, &reader)?;
    let joint_count = rig.skeleton.len();
    let mesh = mesh::skinned_mesh(&meshes, &rig.skin_to_joint, joint_count, &reader)?;
    let clips = document
        .animations()
        .map(|a| {
            animation::clip(
                document.as_json(),
                &a,
                &rig.node_to_joint,
                joint_count,
                &reader,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Model {
        skeleton: rig.skeleton,
        mesh,
        clips,
    })
}

/// The character's skin (the one with the most joints, the first on a tie)
/// and each distinct mesh drawn with it, in node order; `None` without any
/// skinned node.
fn character_meshes(document: &gltf::Document) -> Option<(Vec<gltf::Mesh<'_>>, gltf::Skin<'_>)> {
    let skinned: Vec<(gltf::Mesh, gltf::Skin)> = document
        .nodes()
        .filter_map(|n| Some((n.mesh()?, n.skin()?)))
        .collect();
    let skin = skinned
        .iter()
        .map(|(_, s)| s)
        .rev()
        .max_by_key(|s| s.joints().count())?
        .clone();
    let mut meshes: Vec<gltf::Mesh> = Vec::new();
    for (mesh, s) in &skinned {
        if s.index() == skin.index() && meshes.iter().all(|m| m.index() != mesh.index()) {
            meshes.push(mesh.clone());
        }
    }
    Some((meshes, skin))
}

/// Checks what the `gltf` crate's own validation indexes without checking
/// (it panics on a primitive attribute naming an accessor that does not exist).
fn check_before_validation(json: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(a) = primitive
                .attributes
                .values()
                .find(|a| a.value() >= json.accessors.len())
            {
                return Err(format!(
                    "mesh {m} primitive {p} names accessor {}, but there are {}",
                    a.value(),
                    json.accessors.len()
                ));
            }
        }
    }
    Ok(())
}

/// The bytes of a file no larger than [`MAX_FILE_BYTES`], checked before reading.
pub(crate) fn read_limited(path: &Path) -> Result<Vec<u8>, GltfError> {
    let read_error = |source| GltfError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(read_error)?;
    let bytes = file.metadata().map_err(read_error)?.len();
    if bytes > MAX_FILE_BYTES {
        return Err(GltfError::TooLarge {
            path: path.to_path_buf(),
            part: "the file".to_string(),
            bytes,
            limit: MAX_FILE_BYTES,
        });
    }
    let mut data = Vec::with_capacity(bytes as usize);
    file.take(MAX_FILE_BYTES)
        .read_to_end(&mut data)
        .map_err(read_error)?;
    Ok(data)
}
