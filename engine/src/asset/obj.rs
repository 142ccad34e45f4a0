use std::fmt::Write as _;
use std::io::BufRead;
use std::path::Path;

use glam::Vec3;

use super::AssetError;
use crate::geom::{HeightGrid, MeshPart, TriMesh};
use crate::io::write_atomic;

/// Loads an OBJ file as one [`TriMesh`]: each object (`o`) or group (`g`) becomes
/// a named [`MeshPart`] (a character can name its parts after bones), polygons
/// are fan-triangulated, materials are ignored, and normals are computed when
/// the file has none.
pub fn load_obj(path: &Path) -> Result<TriMesh, AssetError> {
    let text = std::fs::read_to_string(path).map_err(|source| AssetError::reading(path, source))?;
    parse_obj(text.as_bytes(), path)
}

/// Like [`load_obj`] on OBJ text held in memory; errors name the file `<string>`.
///
/// ```
/// let mesh = engine::asset::load_obj_from_str(
///     "o foot\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n",
/// ).unwrap();
/// assert_eq!(mesh.part("foot").unwrap().triangles, 0..1);
/// ```
pub fn load_obj_from_str(text: &str) -> Result<TriMesh, AssetError> {
    parse_obj(text.as_bytes(), Path::new("<string>"))
}

fn parse_obj(mut reader: impl BufRead, path: &Path) -> Result<TriMesh, AssetError> {
    let path_buf = || path.to_path_buf();
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| load_error(e, path))?;
    let mut mesh = TriMesh::default();
    let mut all_have_normals = true;
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        let first_triangle = mesh.triangles.len();
        for (k, p) in m.positions.chunks_exact(3).enumerate() {
            let v = Vec3::new(p[0], p[1], p[2]);
            if !v.is_finite() {
                return Err(AssetError::NonFinite {
                    path: path_buf(),
                    what: format!("vertex {k} of object {:?}", model.name),
                });
            }
            mesh.positions.push(v);
        }
        let count = m.positions.len() / 3;
        if m.normals.len() == m.positions.len() {
            mesh.normals.extend(
                m.normals
                    .chunks_exact(3)
                    .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or_zero()),
            );
        } else {
            all_have_normals = false;
        }
        for t in m.indices.chunks_exact(3) {
            if t.iter().any(|&v| v as usize >= count) {
                return Err(AssetError::IndexOutOfRange {
                    path: path_buf(),
                    reason: format!(
                        "a face of object {:?} indexes past its {count} vertices",
                        model.name
                    ),
                });
            }
            mesh.triangles.push([base + t[0], base + t[1], base + t[2]]);
        }
        add_part(
            &mut mesh.parts,
            &model.name,
            first_triangle..mesh.triangles.len(),
        );
    }
    if mesh.triangles.is_empty() {
        return Err(AssetError::EmptyMesh { path: path_buf() });
    }
    let normals_usable = all_have_normals && mesh.normals.iter().all(|n| n.is_normalized());
    if !normals_usable {
        mesh.compute_normals();
    }
    mesh.validate().map_err(|e| AssetError::MalformedObj {
        path: path_buf(),
        reason: e.to_string(),
    })?;
    Ok(mesh)
}

/// Adds a part, merging it into the previous one when tobj split an object
/// only because its material changed.
fn add_part(parts: &mut Vec<MeshPart>, name: &str, triangles: std::ops::Range<usize>) {
    if triangles.is_empty() {
        return;
    }
    match parts.last_mut() {
        Some(last) if last.name == name && last.triangles.end == triangles.start => {
            last.triangles.end = triangles.end;
        }
        _ => parts.push(MeshPart {
            name: name.to_string(),
            triangles,
        }),
    }
}

fn load_error(e: tobj::LoadError, path: &Path) -> AssetError {
    use tobj::LoadError as E;
    let path = path.to_path_buf();
    match e {
        E::FaceVertexOutOfBounds
        | E::FaceNormalOutOfBounds
        | E::FaceTexCoordOutOfBounds
        | E::FaceColorOutOfBounds => AssetError::IndexOutOfRange {
            path,
            reason: e.to_string(),
        },
        _ => AssetError::MalformedObj {
            path,
            reason: e.to_string(),
        },
    }
}

/// Writes `mesh` as an OBJ file (positions, normals, one `o` per part),
/// atomically. Coordinates are printed exactly, so loading gives the same mesh.
pub fn save_obj(mesh: &TriMesh, path: &Path) -> Result<(), AssetError> {
    let text = obj_text(mesh);
    write_atomic(path, |w| w.write_all(text.as_bytes()))?;
    Ok(())
}

/// Writes the triangulated surface of `grid` as an OBJ file (opens in Blender),
/// with the same diagonals as [`HeightGrid::height_at`].
pub fn save_grid_obj(grid: &HeightGrid, path: &Path) -> Result<(), AssetError> {
    save_obj(&grid.to_tri_mesh(), path)
}

fn obj_text(mesh: &TriMesh) -> String {
    let mut s = String::with_capacity(mesh.positions.len() * 60 + mesh.triangles.len() * 30);
    s.push_str("# written by softwalk\n");
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    let has_normals = mesh.normals.len() == mesh.positions.len();
    if has_normals {
        for n in &mesh.normals {
            let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
        }
    }
    let face = |s: &mut String, t: [u32; 3]| {
        let [a, b, c] = t.map(|v| v + 1);
        let _ = if has_normals {
            writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}")
        } else {
            writeln!(s, "f {a} {b} {c}")
        };
    };
    let n = mesh.triangles.len();
    let mut covered = vec![false; n];
    for part in &mesh.parts {
        let _ = writeln!(s, "o {}", part.name);
        let range = part.triangles.start.min(n)..part.triangles.end.min(n);
        for (seen, &t) in covered[range.clone()]
            .iter_mut()
            .zip(&mesh.triangles[range])
        {
            *seen = true;
            face(&mut s, t);
        }
    }
    if covered.iter().any(|c| !c) {
        s.push_str("o mesh\n");
        for (k, _) in covered.iter().enumerate().filter(|(_, c)| !**c) {
            face(&mut s, mesh.triangles[k]);
        }
    }
    s
}
