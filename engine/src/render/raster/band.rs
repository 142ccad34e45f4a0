//! Bands: the fixed horizontal strips of rows a frame is filled by, one job
//! each, and the per-band lists of what touches them.

/// `log2` of [`BAND_ROWS`]: a non-negative row's band is `row >> BAND_SHIFT`.
const BAND_SHIFT: u32 = 5;
/// Rows per band: the unit of parallel filling. Fixed, so that the image does
/// not depend on the number of threads.
pub(crate) const BAND_ROWS: i32 = 1 << BAND_SHIFT;

/// A band of the frame: colour (RGBA8) and depth of rows `y0..y1`.
pub(crate) struct Band<'a> {
    /// RGBA8 pixels of the band's rows.
    pub color: &'a mut [u8],
    /// `1/w` per pixel; 0 is empty (infinitely far).
    pub depth: &'a mut [f32],
    /// Frame width in pixels.
    pub width: i32,
    /// First row of the band.
    pub y0: i32,
    /// One past the last row of the band.
    pub y1: i32,
}

/// Item indices binned by the bands of rows they touch, each band's in the
/// order they were pushed (so depth ties resolve the same way whatever the
/// thread count).
#[derive(Debug, Default)]
pub(crate) struct BandBins(Vec<Vec<u32>>);

impl BandBins {
    /// Empty bins for the bands of a screen `height` pixels tall.
    pub fn new(height: i32) -> BandBins {
        let bands = (height.max(0) + BAND_ROWS - 1) >> BAND_SHIFT;
        BandBins(vec![Vec::new(); bands as usize])
    }

    /// Appends `item` to the bands of pixel rows `y0..=y1` (`0 <= y0 <= y1 <
    /// height`).
    pub fn push(&mut self, item: u32, (y0, y1): (i32, i32)) {
        let (first, last) = ((y0 >> BAND_SHIFT) as usize, (y1 >> BAND_SHIFT) as usize);
        for band in &mut self.0[first..=last] {
            band.push(item);
        }
    }

    /// The items of band `band`, in submission order.
    pub fn band(&self, band: i32) -> &[u32] {
        usize::try_from(band)
            .ok()
            .and_then(|k| self.0.get(k))
            .map_or(&[], Vec::as_slice)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_keep_order_and_repeat_items_spanning_bands() {
        let b = BAND_ROWS;
        let items = [
            (7, (b + 3, b + 3)),
            (1, (2 * b - 1, 3 * b + 2)),
            (4, (b, 2 * b - 1)),
            (9, (3 * b, 3 * b)),
        ];
        let mut bins = BandBins::new(5 * b);
        for (id, rows) in items {
            bins.push(id, rows);
        }
        assert!(bins.band(0).is_empty());
        assert_eq!(bins.band(1), &[7, 1, 4]);
        assert_eq!(bins.band(2), &[1]);
        assert_eq!(bins.band(3), &[1, 9]);
        assert!(bins.band(4).is_empty());
        assert!(bins.band(-1).is_empty());
        assert!(BandBins::new(0).band(0).is_empty());
    }
}
