use std::path::Path;

use gltf::Accessor;
use gltf::accessor::DataType;

use super::GltfError;

/// Most elements an accessor without a buffer view (all zeros) may declare.
const MAX_ZERO_ELEMENTS: usize = 1 << 24;

/// Reads accessors from loaded buffers, checking every byte range first.
pub(super) struct AccessorReader<'a> {
    /// The glTF file, for errors.
    pub path: &'a Path,
    /// Every buffer's bytes, by buffer index.
    pub buffers: &'a [Vec<u8>],
}

/// Where an accessor's elements are: the bytes from its first element to the
/// end of its buffer view, the distance between elements, and the layout.
struct Layout<'a> {
    bytes: &'a [u8],
    stride: usize,
    data_type: DataType,
    components: usize,
}

impl AccessorReader<'_> {
    /// The accessor's elements as `N` floats each (normalised integers become
    /// fractions, other integers are converted); every value must be finite.
    pub fn floats<const N: usize>(
        &self,
        accessor: &Accessor,
        part: &str,
    ) -> Result<Vec<[f32; N]>, GltfError> {
        let Some(layout) = self.layout(accessor, N, part)? else {
            return Ok(vec![[0.0; N]; accessor.count()]);
        };
        let normalized = accessor.normalized();
        let mut out = Vec::with_capacity(accessor.count());
        for index in 0..accessor.count() {
            let mut element = [0.0; N];
            for (c, value) in element.iter_mut().enumerate() {
                *value = layout.float(index, c, normalized);
            }
            if element.iter().any(|v| !v.is_finite()) {
                return Err(GltfError::NonFinite {
                    path: self.path.to_path_buf(),
                    part: part.to_string(),
                    index,
                });
            }
            out.push(element);
        }
        Ok(out)
    }

    /// The accessor's elements as `N` unsigned integers each; the accessor must
    /// hold unsigned bytes, shorts or ints, not normalised.
    pub fn uints<const N: usize>(
        &self,
        accessor: &Accessor,
        part: &str,
    ) -> Result<Vec<[u32; N]>, GltfError> {
        let Some(layout) = self.layout(accessor, N, part)? else {
            return Ok(vec![[0; N]; accessor.count()]);
        };
        if !matches!(
            layout.data_type,
            DataType::U8 | DataType::U16 | DataType::U32
        ) || accessor.normalized()
        {
            return Err(self.invalid(
                part,
                format!(
                    "needs unsigned integers, found {:?}{}",
                    layout.data_type,
                    if accessor.normalized() {
                        " (normalized)"
                    } else {
                        ""
                    }
                ),
            ));
        }
        let out = (0..accessor.count())
            .map(|index| std::array::from_fn(|c| layout.uint(index, c)))
            .collect();
        Ok(out)
    }

    /// The accessor's byte layout after checking its type and that every
    /// element lies inside its view and the view inside its buffer; `None` for
    /// an accessor without a view (its elements are zeros).
    fn layout(
        &self,
        accessor: &Accessor,
        components: usize,
        part: &str,
    ) -> Result<Option<Layout<'_>>, GltfError> {
        if accessor.sparse().is_some() {
            return Err(GltfError::Unsupported {
                path: self.path.to_path_buf(),
                part: part.to_string(),
                reason: "sparse accessors".to_string(),
            });
        }
        let found = accessor.dimensions().multiplicity();
        if found != components {
            return Err(self.invalid(
                part,
                format!("needs {components} components per element, found {found}"),
            ));
        }
        let Some(view) = accessor.view() else {
            if accessor.count() > MAX_ZERO_ELEMENTS {
                return Err(self.invalid(part, "too many elements".to_string()));
            }
            return Ok(None);
        };
        let buffer = self.buffers.get(view.buffer().index()).ok_or_else(|| {
            self.invalid(part, format!("buffer {} is absent", view.buffer().index()))
        })?;
        let view_part = format!("buffer view {}", view.index());
        let view_end = (view.offset() as u64).saturating_add(view.length() as u64);
        if view_end > buffer.len() as u64 {
            return Err(self.too_short(&view_part, view_end, buffer.len() as u64));
        }
        let view_bytes = &buffer[view.offset()..view.offset() + view.length()];
        let data_type = accessor.data_type();
        let element = data_type.size() * components;
        let stride = view.stride().unwrap_or(element);
        if stride < element {
            return Err(self.invalid(
                part,
                format!("stride {stride} is shorter than an element ({element} bytes)"),
            ));
        }
        let count = accessor.count() as u64;
        let needed = if count == 0 {
            accessor.offset() as u64
        } else {
            (count - 1)
                .saturating_mul(stride as u64)
                .saturating_add(element as u64)
                .saturating_add(accessor.offset() as u64)
        };
        if needed > view_bytes.len() as u64 {
            return Err(self.too_short(part, needed, view_bytes.len() as u64));
        }
        Ok(Some(Layout {
            bytes: &view_bytes[accessor.offset()..],
            stride,
            data_type,
            components,
        }))
    }

    pub(super) fn invalid(&self, part: &str, reason: String) -> GltfError {
        GltfError::Invalid {
            path: self.path.to_path_buf(),
            part: part.to_string(),
            reason,
        }
    }

    fn too_short(&self, part: &str, needed: u64, available: u64) -> GltfError {
        GltfError::BufferTooShort {
            path: self.path.to_path_buf(),
            part: part.to_string(),
            needed,
            available,
        }
    }
}

impl Layout<'_> {
    /// The bytes of component `c` of element `index` (in range: checked by `layout`).
    fn component(&self, index: usize, c: usize) -> &[u8] {
        let size = self.data_type.size();
        let start = index * self.stride + c * size;
        debug_assert!(c < self.components);
        &self.bytes[start..start + size]
    }

    fn float(&self, index: usize, c: usize, normalized: bool) -> f32 {
        let b = self.component(index, c);
        match self.data_type {
            DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            DataType::U8 if normalized => f32::from(b[0]) / 255.0,
            DataType::I8 if normalized => (f32::from(b[0] as i8) / 127.0).max(-1.0),
            DataType::U16 if normalized => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
            DataType::I16 if normalized => {
                (f32::from(i16::from_le_bytes([b[0], b[1]])) / 32767.0).max(-1.0)
            }
            DataType::U8 => f32::from(b[0]),
            DataType::I8 => f32::from(b[0] as i8),
            DataType::U16 => f32::from(u16::from_le_bytes([b[0], b[1]])),
            DataType::I16 => f32::from(i16::from_le_bytes([b[0], b[1]])),
            DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
        }
    }

    fn uint(&self, index: usize, c: usize) -> u32 {
        let b = self.component(index, c);
        match self.data_type {
            DataType::U8 | DataType::I8 => u32::from(b[0]),
            DataType::U16 | DataType::I16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            DataType::U32 | DataType::F32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        }
    }
}
