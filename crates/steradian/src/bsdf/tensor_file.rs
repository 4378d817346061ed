//! Mitsuba's tensor file (`TensorFile`, written by `mitsuba.tensor_io.write`): named arrays
//! of any rank, the container of RGL's measured materials (`.bsdf`).
//!
//! Layout (little-endian): the 12 bytes `tensor_file\0`, the version (u8 1, u8 0), the
//! field count (u32), then per field its name (u16 length, UTF-8 bytes), rank (u16), type
//! (u8: Mitsuba's `Struct::Type`, 1 = u8 … 10 = f32, 11 = f64), data offset from the file's
//! start (u64) and shape (rank × u64); the data of each field lies at its offset, C order.

use std::collections::HashMap;

/// Mitsuba's `Struct::Type` codes of the element types steradian reads.
const TYPE_U8: u8 = 1;
const TYPE_F32: u8 = 10;

/// One field: its element type code, shape and bytes.
#[derive(Clone, Debug)]
pub struct Field<'a> {
    pub dtype: u8,
    pub shape: Vec<usize>,
    bytes: &'a [u8],
}

impl Field<'_> {
    /// The values of a float32 field; `None` for another type.
    pub fn f32s(&self) -> Option<Vec<f32>> {
        (self.dtype == TYPE_F32).then(|| {
            self.bytes
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
                .collect()
        })
    }

    /// The bytes of a uint8 field; `None` for another type.
    pub fn u8s(&self) -> Option<&[u8]> {
        (self.dtype == TYPE_U8).then_some(self.bytes)
    }
}

/// Bytes per element of a type code.
fn element_size(dtype: u8) -> Option<usize> {
    match dtype {
        1 | 2 => Some(1),
        3 | 4 | 9 => Some(2),
        5 | 6 | 10 => Some(4),
        7 | 8 | 11 => Some(8),
        _ => None,
    }
}

/// The fields of a tensor file's bytes.
pub fn parse(bytes: &[u8]) -> Result<HashMap<String, Field<'_>>, String> {
    let mut at = 0usize;
    let mut take = |n: usize| -> Result<&[u8], String> {
        let s = bytes.get(at..at + n).ok_or_else(|| {
            format!("truncated header at byte {at} ({} bytes in all)", bytes.len())
        })?;
        at += n;
        Ok(s)
    };
    if take(12)? != b"tensor_file\0" {
        return Err("not a tensor file (it does not start with \"tensor_file\")".into());
    }
    let version = take(2)?;
    if version != [1, 0] {
        return Err(format!("tensor file version {}.{}; only 1.0 exists", version[0], version[1]));
    }
    let u16_of = |b: &[u8]| u16::from_le_bytes([b[0], b[1]]) as usize;
    let u64_of = |b: &[u8]| u64::from_le_bytes(b.try_into().expect("8 bytes"));
    let count = u32::from_le_bytes(take(4)?.try_into().expect("4 bytes")) as usize;
    let mut fields = HashMap::new();
    for _ in 0..count {
        let len = u16_of(take(2)?);
        let name = String::from_utf8(take(len)?.to_vec())
            .map_err(|_| "a field name is not UTF-8".to_string())?;
        let rank = u16_of(take(2)?);
        let dtype = take(1)?[0];
        let offset = u64_of(take(8)?);
        let mut shape = Vec::with_capacity(rank);
        for _ in 0..rank {
            shape.push(u64_of(take(8)?));
        }
        let size = element_size(dtype)
            .ok_or_else(|| format!("field \"{name}\" has the unknown element type {dtype}"))?;
        let length = shape
            .iter()
            .try_fold(size as u64, |acc, &d| acc.checked_mul(d))
            .filter(|&l| offset.checked_add(l).is_some_and(|end| end <= bytes.len() as u64))
            .ok_or_else(|| {
                format!(
                    "field \"{name}\" (shape {shape:?} at offset {offset}) runs past the end of \
                     the file ({} bytes)",
                    bytes.len()
                )
            })?;
        let data = &bytes[offset as usize..(offset + length) as usize];
        let shape = shape.into_iter().map(|d| d as usize).collect();
        fields.insert(name, Field { dtype, shape, bytes: data });
    }
    Ok(fields)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file of one f32 field of shape (2, 3) and one u8 field, as `tensor_io.write` lays
    /// it out.
    fn file() -> Vec<u8> {
        let mut b = b"tensor_file\0".to_vec();
        b.extend([1, 0]);
        b.extend(2u32.to_le_bytes());
        let header_end = 12 + 2 + 4 + (2 + 1 + 2 + 1 + 8 + 16) + (2 + 1 + 2 + 1 + 8 + 8);
        let data_a = header_end as u64;
        let data_b = data_a + 24;
        for (name, dtype, offset, shape) in
            [("a", TYPE_F32, data_a, vec![2u64, 3]), ("b", TYPE_U8, data_b, vec![3u64])]
        {
            b.extend(1u16.to_le_bytes());
            b.extend(name.as_bytes());
            b.extend((shape.len() as u16).to_le_bytes());
            b.push(dtype);
            b.extend(offset.to_le_bytes());
            shape.iter().for_each(|d| b.extend(d.to_le_bytes()));
        }
        assert_eq!(b.len(), header_end);
        (0..6).for_each(|i| b.extend((i as f32 * 0.5).to_le_bytes()));
        b.extend([7, 8, 9]);
        b
    }

    #[test]
    fn fields_are_read_with_their_shapes() {
        let bytes = file();
        let f = parse(&bytes).unwrap();
        assert_eq!(f["a"].shape, vec![2, 3]);
        assert_eq!(f["a"].f32s().unwrap(), vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5]);
        assert_eq!(f["b"].u8s().unwrap(), &[7, 8, 9]);
        assert!(f["b"].f32s().is_none());
    }

    #[test]
    fn damaged_files_are_errors() {
        let bytes = file();
        assert!(parse(&bytes[..bytes.len() - 1]).unwrap_err().contains("past the end"));
        assert!(parse(&bytes[..20]).unwrap_err().contains("truncated"));
        assert!(parse(b"tensor_fil").is_err());
        let mut v2 = bytes.clone();
        v2[12] = 2;
        assert!(parse(&v2).unwrap_err().contains("version"));
    }
}
