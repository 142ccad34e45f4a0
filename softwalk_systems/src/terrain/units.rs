//! The reference grid and rate the paper's cell- and step-based terrain
//! parameters were tuned at, and their conversion to metres and seconds.
//!
//! The paper's terrain is 10 m over 512 samples and runs at 60 Hz. Every
//! terrain parameter that the paper states in cells or per step is stated
//! here once in metres or per second (at [`REFERENCE_CELL_M`] and
//! [`REFERENCE_RATE_HZ`]) and converted to cells with the grid's own cell
//! size, and to steps with the step's `dt`, so the same scene gives the same
//! prints at any resolution and step rate.

/// The reference cell size, metres: the paper's 10 m over 512 samples
/// (`10 / 512` m, about 1.95 cm).
pub const REFERENCE_CELL_M: f32 = 10.0 / 512.0;

/// The reference step rate, steps per second (the paper's 60 Hz).
pub const REFERENCE_RATE_HZ: f32 = 60.0;

/// A length in metres as a whole number of cells of size `cell` (rounded
/// up, with a 1e-3 cell slack so a length of exactly `n` cells is `n`).
pub fn cells_covering(length_m: f32, cell: f32) -> usize {
    (length_m / cell - 1e-3).ceil().max(0.0) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_convert_to_whole_cells() {
        assert_eq!(cells_covering(8.0 * REFERENCE_CELL_M, REFERENCE_CELL_M), 8);
        assert_eq!(cells_covering(8.0 * REFERENCE_CELL_M, 10.0 / 511.0), 8);
        assert_eq!(cells_covering(8.0 * REFERENCE_CELL_M, 10.0 / 1023.0), 16);
        assert_eq!(cells_covering(8.0 * REFERENCE_CELL_M, 10.0 / 255.0), 4);
        assert_eq!(cells_covering(0.0, 0.1), 0);
    }
}
