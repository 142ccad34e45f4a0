use std::path::Path;

use glam::{Mat4, Quat, Vec3};
use gltf::{Document, Skin};

use super::GltfError;
use super::accessor::AccessorReader;
use crate::anim::{Joint, Skeleton, Transform};

/// A skin's joints as a [`Skeleton`], with the maps from glTF indices to joints.
pub(super) struct SkinSkeleton {
    /// The skin's joints and every ancestor node of theirs, parents first.
    pub skeleton: Skeleton,
    /// For each node, its joint index if it is in the skeleton.
    pub node_to_joint: Vec<Option<usize>>,
    /// For each entry of the skin's joint list, its joint index.
    pub skin_to_joint: Vec<usize>,
}

/// Builds the skeleton of `skin`: its joints plus their ancestor nodes (so a
/// parent node's transform, e.g. an armature's, is part of the pose), ordered by
/// depth so parents come first, with the skin's inverse bind matrices (identity
/// for ancestors that are not in the skin).
pub(super) fn skin_skeleton(
    document: &Document,
    skin: &Skin,
    reader: &AccessorReader,
) -> Result<SkinSkeleton, GltfError> {
    let path = reader.path;
    let parents = node_parents(document, path)?;
    let joint_nodes: Vec<usize> = skin.joints().map(|n| n.index()).collect();
    let inverse_binds = inverse_binds(skin, joint_nodes.len(), reader)?;
    let mut selected = vec![false; parents.len()];
    for &node in &joint_nodes {
        for ancestor in ancestors(node, &parents) {
            selected[ancestor] = true;
        }
    }
    let mut order: Vec<usize> = (0..parents.len()).filter(|&n| selected[n]).collect();
    order.sort_by_key(|&n| (ancestors(n, &parents).count(), n));
    let mut node_to_joint = vec![None; parents.len()];
    for (joint, &node) in order.iter().enumerate() {
        node_to_joint[node] = Some(joint);
    }
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    let mut joints = Vec::with_capacity(order.len());
    for &node in &order {
        let inverse_bind = joint_nodes
            .iter()
            .position(|&n| n == node)
            .map_or(Mat4::IDENTITY, |k| inverse_binds[k]);
        joints.push(Joint {
            name: nodes[node]
                .name()
                .map_or_else(|| format!("node{node}"), str::to_string),
            parent: parents[node].and_then(|p| node_to_joint[p]),
            rest: node_transform(&nodes[node], path)?,
            inverse_bind,
        });
    }
    let skeleton =
        Skeleton::new(joints).map_err(|e| GltfError::from_anim(path, "skin 0 joints", e))?;
    let skin_to_joint = joint_nodes
        .iter()
        .map(|&n| node_to_joint[n].unwrap_or(0))
        .collect();
    Ok(SkinSkeleton {
        skeleton,
        node_to_joint,
        skin_to_joint,
    })
}

/// Each node's parent; refused if a node has two parents or the parents loop.
fn node_parents(document: &Document, path: &Path) -> Result<Vec<Option<usize>>, GltfError> {
    let count = document.nodes().count();
    let mut parents = vec![None; count];
    for node in document.nodes() {
        for child in node.children() {
            if parents[child.index()].is_some() || child.index() == node.index() {
                return Err(invalid(path, child.index(), "has more than one parent"));
            }
            parents[child.index()] = Some(node.index());
        }
    }
    for node in 0..count {
        if ancestors(node, &parents).nth(count).is_some() {
            return Err(invalid(path, node, "is its own ancestor"));
        }
    }
    Ok(parents)
}

/// `node`, its parent, its parent's parent, ... (endless on a cycle: callers bound it).
fn ancestors(node: usize, parents: &[Option<usize>]) -> impl Iterator<Item = usize> + '_ {
    std::iter::successors(Some(node), move |&n| parents[n])
}

fn inverse_binds(
    skin: &Skin,
    joints: usize,
    reader: &AccessorReader,
) -> Result<Vec<Mat4>, GltfError> {
    let Some(accessor) = skin.inverse_bind_matrices() else {
        return Ok(vec![Mat4::IDENTITY; joints]);
    };
    let part = format!("skin {} inverseBindMatrices", skin.index());
    let matrices = reader.floats::<16>(&accessor, &part)?;
    if matrices.len() < joints {
        return Err(GltfError::Invalid {
            path: reader.path.to_path_buf(),
            part,
            reason: format!("{} matrices for {joints} joints", matrices.len()),
        });
    }
    Ok(matrices.iter().map(Mat4::from_cols_array).collect())
}

fn node_transform(node: &gltf::Node, path: &Path) -> Result<Transform, GltfError> {
    let (t, r, s) = node.transform().decomposed();
    let transform = Transform {
        translation: Vec3::from(t),
        rotation: Quat::from_array(r).normalize(),
        scale: Vec3::from(s),
    };
    if !transform.is_finite() {
        return Err(GltfError::NonFinite {
            path: path.to_path_buf(),
            part: format!("node {} transform", node.index()),
            index: 0,
        });
    }
    Ok(transform)
}

fn invalid(path: &Path, node: usize, reason: &str) -> GltfError {
    GltfError::Invalid {
        path: path.to_path_buf(),
        part: format!("node {node}"),
        reason: reason.to_string(),
    }
}
