//! Which debug overlays a frame draws: each can be shown on its own.

/// The overlay layers drawn when overlays are on (see
/// [`super::WorldView::set_overlay_layers`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OverlayLayers {
    /// The rigid proxy: the balance torque arrow at the centre of mass.
    pub proxy: bool,
    /// The centre of mass and its drop line to the ground.
    pub com: bool,
    /// The support segment between the feet keys and its midpoint.
    pub support: bool,
    /// The foot rays, their ground keys and the IK sole targets.
    pub ik_keys: bool,
    /// The virtual platforms under the feet.
    pub platforms: bool,
}

impl OverlayLayers {
    /// Every layer.
    pub const ALL: OverlayLayers = OverlayLayers {
        proxy: true,
        com: true,
        support: true,
        ik_keys: true,
        platforms: true,
    };

    /// Number of layers, the range of [`OverlayLayers::toggle`].
    pub const COUNT: usize = 5;

    /// Switches layer `index` (0 proxy, 1 centre of mass, 2 support,
    /// 3 IK keys, 4 platforms); other indices change nothing.
    pub fn toggle(&mut self, index: usize) {
        let layer = match index {
            0 => &mut self.proxy,
            1 => &mut self.com,
            2 => &mut self.support,
            3 => &mut self.ik_keys,
            4 => &mut self.platforms,
            _ => return,
        };
        *layer = !*layer;
    }
}

impl Default for OverlayLayers {
    fn default() -> Self {
        Self::ALL
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_index_toggles_one_layer() {
        let mut layers = OverlayLayers::ALL;
        layers.toggle(3);
        assert!(!layers.ik_keys && layers.proxy && layers.platforms);
        layers.toggle(OverlayLayers::COUNT);
        layers.toggle(3);
        assert_eq!(layers, OverlayLayers::ALL);
        for k in 0..OverlayLayers::COUNT {
            layers.toggle(k);
        }
        assert_eq!(
            layers,
            OverlayLayers {
                proxy: false,
                com: false,
                support: false,
                ik_keys: false,
                platforms: false,
            }
        );
    }
}
