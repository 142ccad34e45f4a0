use super::{AnimError, Channel, Pose, Skeleton};

/// What happens past the end of a clip.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Playback {
    /// Holds the last key.
    Once,
    /// Starts again from time 0.
    Loop,
}

/// A named animation: channels over joints of one skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    name: String,
    duration: f32,
    channels: Vec<Channel>,
}

impl Clip {
    /// A clip of these channels for a skeleton of `joints` joints; its duration is
    /// its last key time. Refused if a channel animates a joint past `joints`.
    pub fn new(name: String, channels: Vec<Channel>, joints: usize) -> Result<Clip, AnimError> {
        if let Some(c) = channels.iter().find(|c| c.joint() >= joints) {
            return Err(AnimError::ChannelJoint {
                joint: c.joint(),
                joints,
            });
        }
        let duration = channels.iter().map(Channel::end).fold(0.0, f32::max);
        Ok(Clip {
            name,
            duration,
            channels,
        })
    }

    /// Its name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its length in seconds (the last key time).
    pub fn duration(&self) -> f32 {
        self.duration
    }

    /// Its channels.
    pub fn channels(&self) -> &[Channel] {
        &self.channels
    }

    /// The clip time that `time` seconds of playback reach.
    pub fn local_time(&self, time: f32, playback: Playback) -> f32 {
        match playback {
            Playback::Loop if self.duration > 0.0 => time.rem_euclid(self.duration),
            Playback::Loop => 0.0,
            Playback::Once => time.clamp(0.0, self.duration),
        }
    }

    /// Writes the clip at `time` into `pose`: joints the clip animates get their
    /// sampled properties; the pose is first reset to `skeleton`'s rest pose if
    /// its length does not match.
    pub fn sample(&self, time: f32, playback: Playback, skeleton: &Skeleton, pose: &mut Pose) {
        if pose.locals.len() != skeleton.len() {
            *pose = skeleton.rest_pose();
        }
        let t = self.local_time(time, playback);
        for channel in &self.channels {
            if let Some(local) = pose.locals.get_mut(channel.joint()) {
                channel.apply(t, local);
            }
        }
    }

    /// The pose at `time`: the rest pose with the clip's channels applied.
    pub fn pose_at(&self, time: f32, playback: Playback, skeleton: &Skeleton) -> Pose {
        let mut pose = skeleton.rest_pose();
        self.sample(time, playback, skeleton, &mut pose);
        pose
    }
}
