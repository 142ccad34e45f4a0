//! `[[props]]`: static OBJ meshes (rocks, logs, a plank bridge) placed on the
//! terrain. The feet stand on them: the foot rays hit the nearest of ground
//! and props through one ray-cast scene, and the renderer draws them.

use std::path::{Path, PathBuf};

use engine::asset::{AssetError, load_obj, load_obj_from_str};
use engine::geom::TriMesh;
use glam::{Mat4, Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::{finite, in_range, positive};

/// Most accepted `[[props]]` entries.
pub const MAX_PROPS: usize = 1024;
/// Largest accepted OBJ file for a prop, bytes (a detailed rock is a few
/// hundred kilobytes; beyond this the mesh would cost more than a run can use).
pub const MAX_PROP_FILE_BYTES: u64 = 64 << 20;
/// Largest accepted prop scale factor.
pub const MAX_PROP_SCALE: f32 = 100.0;
/// Deepest a prop may be sunk into the ground, or raised above it, metres.
pub const MAX_PROP_SINK: f32 = 10.0;

/// The meshes compiled into the program, by name: `builtin = "rock"`.
const BUILTIN_PROPS: [(&str, &str); 3] = [
    ("rock", include_str!("../../props/rock.obj")),
    ("log", include_str!("../../props/log.obj")),
    ("plank-bridge", include_str!("../../props/plank-bridge.obj")),
];

/// One static mesh on the terrain. Its local origin (the centre of its base)
/// goes on the ground at `at`, `sink` metres lower; the mesh is scaled, then
/// turned by `yaw_deg` about Y (from +X towards -Z, like a path heading).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PropSpec {
    /// An OBJ file, resolved against the scene's folder (or use `builtin`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<PathBuf>,
    /// A mesh compiled into the program: `rock`, `log` or `plank-bridge`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub builtin: Option<String>,
    /// `[x, z]` on the terrain, metres.
    pub at: [f32; 2],
    /// Turn about Y, degrees.
    #[serde(default)]
    pub yaw_deg: f32,
    /// Uniform scale.
    #[serde(default = "unit_scale")]
    pub scale: f32,
    /// How far below the ground under `at` the origin goes, metres (negative: above).
    #[serde(default)]
    pub sink: f32,
}

fn unit_scale() -> f32 {
    1.0
}

impl PropSpec {
    /// Checks the fields of entry `field` (`props[2]`) on a terrain of `size` metres.
    pub(crate) fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        match (&self.mesh, &self.builtin) {
            (Some(_), Some(_)) | (None, None) => {
                return Err(SceneError::invalid(
                    field,
                    "give exactly one of `mesh` (an OBJ file) and `builtin` (a mesh name)",
                ));
            }
            (None, Some(name)) if builtin_obj(name).is_none() => {
                return Err(SceneError::invalid(
                    format!("{field}.builtin"),
                    format!("unknown prop \"{name}\" (known: {})", builtin_names()),
                ));
            }
            _ => {}
        }
        in_range(&format!("{field}.at[0]"), self.at[0], 0.0, size[0])?;
        in_range(&format!("{field}.at[1]"), self.at[1], 0.0, size[1])?;
        finite(&format!("{field}.yaw_deg"), self.yaw_deg)?;
        positive(&format!("{field}.scale"), self.scale, MAX_PROP_SCALE)?;
        in_range(
            &format!("{field}.sink"),
            self.sink,
            -MAX_PROP_SINK,
            MAX_PROP_SINK,
        )?;
        Ok(())
    }

    /// The OBJ file of a `mesh` prop, resolved against `base_dir`.
    pub fn mesh_path(&self, base_dir: &Path) -> Option<PathBuf> {
        self.mesh.as_ref().map(|p| base_dir.join(p))
    }

    /// Checks that a `mesh` file exists, is a regular file and is not larger
    /// than [`MAX_PROP_FILE_BYTES`] (before anything is read); returns its size in bytes
    /// (0 for a built-in mesh).
    pub(crate) fn check_file(&self, field: &str, base_dir: &Path) -> Result<u64, SceneError> {
        let Some(path) = self.mesh_path(base_dir) else {
            return Ok(0);
        };
        let field = format!("{field}.mesh");
        let bad = |path: PathBuf, reason: String| SceneError::BadFile {
            field: field.clone(),
            path,
            reason,
        };
        let meta = match std::fs::metadata(&path) {
            Ok(meta) => meta,
            Err(_) => return Err(SceneError::MissingFile { field, path }),
        };
        if !meta.is_file() {
            return Err(bad(path, "not a regular file".into()));
        }
        if meta.len() > MAX_PROP_FILE_BYTES {
            let reason = format!(
                "{} bytes, more than the limit {MAX_PROP_FILE_BYTES}",
                meta.len()
            );
            return Err(bad(path, reason));
        }
        Ok(meta.len())
    }

    /// The mesh in world space, its origin on the ground at height
    /// `ground_y` (the terrain under `at`). A file that cannot be loaded is
    /// an error naming the field, the file and the reason.
    pub fn world_mesh(
        &self,
        field: &str,
        base_dir: &Path,
        ground_y: f32,
    ) -> Result<TriMesh, SceneError> {
        let mut mesh = self.local_mesh(field, base_dir)?;
        let place = Mat4::from_scale_rotation_translation(
            Vec3::splat(self.scale),
            Quat::from_rotation_y(self.yaw_deg.to_radians()),
            Vec3::new(self.at[0], ground_y - self.sink, self.at[1]),
        );
        for p in &mut mesh.positions {
            *p = place.transform_point3(*p);
        }
        mesh.compute_normals();
        Ok(mesh)
    }

    /// The mesh as loaded, in its own frame.
    fn local_mesh(&self, field: &str, base_dir: &Path) -> Result<TriMesh, SceneError> {
        let loaded = match (&self.mesh, &self.builtin) {
            (Some(_), _) => {
                let path = self.mesh_path(base_dir).unwrap_or_default();
                load_obj(&path).map_err(|e| obj_error(format!("{field}.mesh"), &path, e))
            }
            (None, Some(name)) => {
                let text = builtin_obj(name).ok_or_else(|| {
                    SceneError::invalid(
                        format!("{field}.builtin"),
                        format!("unknown prop \"{name}\""),
                    )
                })?;
                load_obj_from_str(text)
                    .map_err(|e| obj_error(format!("{field}.builtin"), Path::new(name), e))
            }
            (None, None) => Err(SceneError::invalid(field, "no mesh given")),
        }?;
        Ok(loaded)
    }
}

/// An OBJ that failed to load, as a scene error naming the field, the file and the reason.
fn obj_error(field: String, path: &Path, error: AssetError) -> SceneError {
    match error {
        AssetError::Missing { .. } => SceneError::MissingFile {
            field,
            path: path.to_path_buf(),
        },
        other => SceneError::BadFile {
            field,
            path: path.to_path_buf(),
            reason: other.to_string(),
        },
    }
}

/// The OBJ text of the built-in prop `name`.
fn builtin_obj(name: &str) -> Option<&'static str> {
    (BUILTIN_PROPS.iter())
        .find(|(n, _)| *n == name)
        .map(|&(_, text)| text)
}

/// The built-in prop names, comma separated.
fn builtin_names() -> String {
    let names: Vec<&str> = BUILTIN_PROPS.iter().map(|&(n, _)| n).collect();
    names.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rock() -> PropSpec {
        PropSpec {
            mesh: None,
            builtin: Some("rock".into()),
            at: [2.0, 3.0],
            yaw_deg: 90.0,
            scale: 2.0,
            sink: 0.05,
        }
    }

    #[test]
    fn a_builtin_prop_is_placed_on_the_ground() {
        let mesh = rock().world_mesh("props[0]", Path::new(""), 1.0).unwrap();
        let top = mesh.positions.iter().map(|p| p.y).fold(f32::MIN, f32::max);
        // 12 cm high, scaled by 2, from 5 cm under the ground at 1 m.
        assert!((top - (1.0 - 0.05 + 0.24)).abs() < 1e-4, "{top}");
        // Turned 90 degrees: the long axis (0.9 m along X, scaled) lies along Z.
        let (lo, hi) = mesh
            .positions
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                (lo.min(p.z), hi.max(p.z))
            });
        assert!(
            hi - lo > 1.6 && (0.5 * (hi + lo) - 3.0).abs() < 0.1,
            "{lo}..{hi}"
        );
    }

    #[test]
    fn bad_entries_name_the_field() {
        let mut p = rock();
        p.builtin = Some("boulder".into());
        let e = p.validate("props[1]", [10.0, 10.0]).unwrap_err();
        assert!(
            e.to_string().starts_with("props[1].builtin: unknown prop"),
            "{e}"
        );
        let mut p = rock();
        p.mesh = Some("rock.obj".into());
        assert!(p.validate("props[0]", [10.0, 10.0]).is_err());
        let mut p = rock();
        p.at = [12.0, 1.0];
        let e = p.validate("props[0]", [10.0, 10.0]).unwrap_err();
        assert!(e.to_string().starts_with("props[0].at[0]"), "{e}");
    }

    #[test]
    fn an_obj_that_fails_to_load_names_the_file_and_the_reason() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("broken.obj"), "v 0 0 0\nf 1 2 9\n").unwrap();
        let p = PropSpec {
            mesh: Some("broken.obj".into()),
            builtin: None,
            ..rock()
        };
        let e = p.world_mesh("props[3]", dir.path(), 0.0).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("props[3].mesh: cannot use"), "{text}");
        assert!(text.contains("broken.obj"), "{text}");
        let missing = PropSpec {
            mesh: Some("nowhere.obj".into()),
            ..p
        };
        let e = missing.check_file("props[3]", dir.path()).unwrap_err();
        assert!(matches!(e, SceneError::MissingFile { .. }), "{e}");
    }
}
