//! [`ModelUnits`]: the length unit a character model was authored in, told
//! from how tall it stands.
//!
//! glTF says metres, but exports from FBX and other tools often hold
//! centimetres (with or without a 0.01 scale on the armature). A standing
//! human is 0.5 to 3 m tall, so its standing height in file units says which
//! unit the file uses; a height that fits no unit is refused rather than
//! guessed.

use std::fmt;

use super::model_error::ModelError;

/// Shortest and tallest standing figure accepted, metres.
pub const STANDING_HEIGHT_M: (f32, f32) = (0.5, 3.0);

/// A model's length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelUnits {
    /// Metres (glTF's own unit).
    Metres,
    /// Centimetres (typical of FBX exports without a 0.01 armature scale).
    Centimetres,
    /// Millimetres.
    Millimetres,
}

impl ModelUnits {
    /// Every unit, the most likely first.
    pub const ALL: [ModelUnits; 3] = [
        ModelUnits::Metres,
        ModelUnits::Centimetres,
        ModelUnits::Millimetres,
    ];

    /// Metres per unit.
    pub fn metres(self) -> f32 {
        match self {
            ModelUnits::Metres => 1.0,
            ModelUnits::Centimetres => 0.01,
            ModelUnits::Millimetres => 0.001,
        }
    }

    /// The unit in which a figure standing `height` file units tall is
    /// between 0.5 and 3 m; refused when there is none.
    pub fn of_standing_height(height: f32) -> Result<ModelUnits, ModelError> {
        let (low, high) = STANDING_HEIGHT_M;
        ModelUnits::ALL
            .into_iter()
            .find(|u| (low..=high).contains(&(height * u.metres())))
            .ok_or(ModelError::Units { height })
    }
}

impl fmt::Display for ModelUnits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ModelUnits::Metres => "metres",
            ModelUnits::Centimetres => "centimetres",
            ModelUnits::Millimetres => "millimetres",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standing_heights_tell_the_unit_and_odd_ones_are_refused() {
        let unit = |h| ModelUnits::of_standing_height(h).ok();
        assert_eq!(unit(1.75), Some(ModelUnits::Metres));
        assert_eq!(unit(175.0), Some(ModelUnits::Centimetres));
        assert_eq!(unit(1750.0), Some(ModelUnits::Millimetres));
        for odd in [0.1, 10.0, 400.0, 17500.0, f32::NAN] {
            let e = ModelUnits::of_standing_height(odd).unwrap_err();
            assert!(e.to_string().contains("units tall"), "{e}");
        }
    }
}
