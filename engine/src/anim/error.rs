use thiserror::Error;

/// Why a skeleton, mesh, channel or pose was refused.
#[derive(Debug, Error, PartialEq)]
pub enum AnimError {
    /// A joint's parent comes after it (parents must come first) or does not exist.
    #[error("joint {joint} ({name:?}) has parent {parent}, which does not come before it")]
    ParentOrder {
        /// The joint.
        joint: usize,
        /// Its name.
        name: String,
        /// Its parent's index.
        parent: usize,
    },
    /// A vertex uses a joint the skeleton does not have.
    #[error("vertex {vertex} uses joint {joint}, but there are {joints} joints")]
    JointOutOfRange {
        /// The vertex.
        vertex: usize,
        /// The joint index it uses.
        joint: usize,
        /// How many joints there are.
        joints: usize,
    },
    /// A vertex's skin weights do not sum to about 1.
    #[error("vertex {vertex}'s weights sum to {sum}, not 1")]
    WeightSum {
        /// The vertex.
        vertex: usize,
        /// The sum found.
        sum: f32,
    },
    /// A coarse mesh was asked for with a cube size that is not a positive
    /// finite number of metres.
    #[error("cluster size {cell} m must be a positive finite number")]
    ClusterSize {
        /// The size asked for.
        cell: f32,
    },
    /// A value is NaN or infinite.
    #[error("{what} is not finite")]
    NonFinite {
        /// Which value.
        what: String,
    },
    /// Two arrays that must have one entry per item differ in length.
    #[error("{what}: expected {expected} entries, found {found}")]
    Length {
        /// Which array.
        what: String,
        /// The length needed.
        expected: usize,
        /// The length found.
        found: usize,
    },
    /// A triangle uses a vertex that does not exist.
    #[error("triangle corner {corner} uses vertex {vertex}, but there are {vertices} vertices")]
    VertexOutOfRange {
        /// The index into the index array.
        corner: usize,
        /// The vertex it names.
        vertex: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A channel's key times are not increasing.
    #[error("channel of joint {joint}: key times must increase (key {key})")]
    KeyOrder {
        /// The joint the channel animates.
        joint: usize,
        /// The first key out of order.
        key: usize,
    },
    /// A channel animates a joint the skeleton does not have.
    #[error("a channel animates joint {joint}, but there are {joints} joints")]
    ChannelJoint {
        /// The joint index.
        joint: usize,
        /// How many joints there are.
        joints: usize,
    },
}
