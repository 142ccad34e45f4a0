use glam::Mat4;

use super::{AnimError, Pose, Transform};

/// One joint (bone) of a [`Skeleton`].
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Its name, e.g. `thigh_l` (the key for bone maps and retargeting).
    pub name: String,
    /// Its parent's index, always smaller than its own; `None` for a root.
    pub parent: Option<usize>,
    /// Its local transform in the rest (bind) pose.
    pub rest: Transform,
    /// The inverse of its global matrix in the bind pose: mesh space to joint space.
    pub inverse_bind: Mat4,
}

/// Joints in an order where every parent comes before its children.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skeleton {
    joints: Vec<Joint>,
}

impl Skeleton {
    /// A skeleton of these joints; refused if a parent does not come before its
    /// child or a rest transform or inverse bind matrix is not finite.
    pub fn new(joints: Vec<Joint>) -> Result<Skeleton, AnimError> {
        for (k, joint) in joints.iter().enumerate() {
            if let Some(parent) = joint.parent
                && parent >= k
            {
                return Err(AnimError::ParentOrder {
                    joint: k,
                    name: joint.name.clone(),
                    parent,
                });
            }
            if !joint.rest.is_finite() || !joint.inverse_bind.is_finite() {
                return Err(AnimError::NonFinite {
                    what: format!("joint {k} ({:?})'s rest transform", joint.name),
                });
            }
        }
        Ok(Skeleton { joints })
    }

    /// The joints, parents first.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// How many joints there are.
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// Whether there is no joint.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// The index of the first joint with this exact name.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// The indices of a joint's children.
    pub fn children(&self, joint: usize) -> impl Iterator<Item = usize> + '_ {
        self.joints
            .iter()
            .enumerate()
            .filter(move |(_, j)| j.parent == Some(joint))
            .map(|(k, _)| k)
    }

    /// Whether `ancestor` is `joint` or one of its ancestors.
    pub fn is_ancestor(&self, ancestor: usize, joint: usize) -> bool {
        let mut current = Some(joint);
        while let Some(k) = current {
            if k == ancestor {
                return true;
            }
            current = self.joints.get(k).and_then(|j| j.parent);
        }
        false
    }

    /// The rest pose: every joint at its rest local transform.
    pub fn rest_pose(&self) -> Pose {
        Pose {
            locals: self.joints.iter().map(|j| j.rest).collect(),
        }
    }

    /// The global matrices of the rest pose.
    pub fn rest_globals(&self) -> Vec<Mat4> {
        let mut globals = Vec::new();
        self.rest_pose().globals(self, &mut globals);
        globals
    }
}
