//! VTK's block-compressed binary data: the encoding of one array in a VTK XML file written
//! with `compressor="vtkZLibDataCompressor"` and `header_type="UInt64"`.
//!
//! The bytes of the array are cut into blocks of [`BLOCK_SIZE`] bytes (the last one may be
//! shorter); each block is compressed on its own with zlib (RFC 1950). The encoded array is
//! a header of little-endian u64 words followed by the compressed blocks:
//!
//! ```text
//! [number of blocks, BLOCK_SIZE, size of the last block if partial (else 0),
//!  compressed size of block 1, …, compressed size of block n]  block 1 … block n
//! ```
//!
//! which is what VTK's readers (and ParaView's, and meshio) expect. The compression level is
//! fixed, so the same bytes always give the same encoding.

use crate::error::{Error, Result};
use miniz_oxide::deflate::compress_to_vec_zlib;
use miniz_oxide::inflate::decompress_to_vec_zlib_with_limit;

/// Uncompressed size of a block (bytes): VTK's default.
pub const BLOCK_SIZE: usize = 32 * 1024;

/// The zlib compression level (0–10 in miniz): 6, zlib's default balance of size and speed.
/// The compressor is miniz_oxide itself (not a back end chosen by cargo features), so the
/// bytes do not depend on how the program was built.
const LEVEL: u8 = 6;

/// Encodes `bytes` as one VTK array: header and zlib-compressed blocks (see the module
/// documentation). Empty input gives the header `[0, BLOCK_SIZE, 0]` and no block.
pub fn compress(bytes: &[u8]) -> Vec<u8> {
    let blocks: Vec<Vec<u8>> = bytes
        .chunks(BLOCK_SIZE)
        .map(|block| compress_to_vec_zlib(block, LEVEL))
        .collect();
    let mut out =
        Vec::with_capacity(8 * (3 + blocks.len()) + blocks.iter().map(Vec::len).sum::<usize>());
    for word in [blocks.len(), BLOCK_SIZE, bytes.len() % BLOCK_SIZE] {
        out.extend_from_slice(&(word as u64).to_le_bytes());
    }
    for b in &blocks {
        out.extend_from_slice(&(b.len() as u64).to_le_bytes());
    }
    for b in &blocks {
        out.extend_from_slice(b);
    }
    out
}

/// Decodes one VTK array encoded as by [`compress`] (any block size) at the start of
/// `data`: returns the uncompressed bytes and the number of bytes of `data` the encoded
/// array takes (header and blocks).
///
/// # Errors
/// [`Error::Invalid`] naming the part of the encoding that is wrong: a truncated header or
/// block, a block size of 0 with blocks, a block that is not valid zlib data or does not
/// decompress to its size.
pub fn decompress(data: &[u8]) -> Result<(Vec<u8>, usize)> {
    let bad = |field: &str, value: String, allowed: &str| Error::Invalid {
        field: format!("zlib-compressed VTK array: {field}"),
        value,
        allowed: allowed.into(),
    };
    let word = |i: usize| -> Result<usize> {
        data.get(8 * i..8 * i + 8)
            .and_then(|w| w.try_into().ok())
            .map(|w| u64::from_le_bytes(w) as usize)
            .ok_or_else(|| {
                bad(
                    "header",
                    format!("{} bytes", data.len()),
                    "a header of 3 + (number of blocks) little-endian u64 words",
                )
            })
    };
    let (n_blocks, block_size, last) = (word(0)?, word(1)?, word(2)?);
    if n_blocks > 0 && (block_size == 0 || last >= block_size) {
        return Err(bad(
            "block sizes",
            format!("block size {block_size}, last block {last}"),
            "a positive block size larger than the size of the last block",
        ));
    }
    let header = n_blocks
        .checked_add(3)
        .and_then(|words| words.checked_mul(8))
        .filter(|&bytes| bytes <= data.len())
        .ok_or_else(|| {
            bad(
                "header",
                format!("{n_blocks} blocks in {} bytes", data.len()),
                "a header of 3 + (number of blocks) little-endian u64 words within the data",
            )
        })?;
    let mut at = header;
    let mut out = Vec::new();
    for k in 0..n_blocks {
        let size = word(3 + k)?;
        let block = at
            .checked_add(size)
            .and_then(|end| data.get(at..end))
            .ok_or_else(|| {
                bad(
                    &format!("block {k}"),
                    format!("{size} bytes from byte {at}"),
                    &format!("within the {} bytes given", data.len()),
                )
            })?;
        let expect = if k + 1 == n_blocks && last > 0 {
            last
        } else {
            block_size
        };
        let plain = decompress_to_vec_zlib_with_limit(block, expect).map_err(|e| {
            bad(
                &format!("block {k}"),
                format!("{e:?}"),
                &format!("valid zlib data of at most {expect} bytes"),
            )
        })?;
        if plain.len() != expect {
            return Err(bad(
                &format!("block {k}"),
                format!("{} bytes uncompressed", plain.len()),
                &format!("{expect} bytes, as the header says"),
            ));
        }
        out.extend_from_slice(&plain);
        at += size;
    }
    Ok((out, at))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// Bytes that do not repeat with the block size (a linear congruential sequence).
    fn bytes(n: usize) -> Vec<u8> {
        let mut x: u32 = 12345;
        (0..n)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                (x >> 24) as u8
            })
            .collect()
    }

    #[test]
    fn round_trip_of_empty_short_exact_and_multi_block_data() {
        for n in [0, 1, 1000, BLOCK_SIZE, BLOCK_SIZE + 1, 3 * BLOCK_SIZE + 17] {
            let data = bytes(n);
            let encoded = compress(&data);
            let (decoded, used) = decompress(&encoded).unwrap();
            assert_eq!(decoded, data, "n = {n}");
            assert_eq!(used, encoded.len(), "n = {n}");
            // The header: number of blocks ⌈n / BLOCK_SIZE⌉, block size, n mod BLOCK_SIZE.
            let word = |i: usize| u64::from_le_bytes(encoded[8 * i..8 * i + 8].try_into().unwrap());
            assert_eq!(word(0) as usize, n.div_ceil(BLOCK_SIZE), "n = {n}");
            assert_eq!(word(1) as usize, BLOCK_SIZE);
            assert_eq!(word(2) as usize, n % BLOCK_SIZE, "n = {n}");
        }
    }

    #[test]
    fn encoding_is_deterministic_and_compresses_repetitive_data() {
        let zeros = vec![0u8; 10 * BLOCK_SIZE];
        let a = compress(&zeros);
        assert_eq!(a, compress(&zeros));
        assert!(a.len() < zeros.len() / 100, "{} bytes", a.len());
    }

    #[test]
    fn damaged_data_is_an_error_naming_the_block() {
        let data = bytes(2 * BLOCK_SIZE + 5);
        let encoded = compress(&data);
        let truncated = &encoded[..encoded.len() - 3];
        let e = decompress(truncated).unwrap_err().to_string();
        assert!(e.contains("block 2"), "{e}");
        let mut flipped = encoded.clone();
        let header = 8 * 6;
        flipped[header + 1] ^= 0xff;
        let e = decompress(&flipped).unwrap_err().to_string();
        assert!(e.contains("block 0"), "{e}");
        let e = decompress(&encoded[..10]).unwrap_err().to_string();
        assert!(e.contains("header"), "{e}");
        let mut huge = encoded.clone();
        huge[..8].copy_from_slice(&u64::MAX.to_le_bytes());
        let e = decompress(&huge).unwrap_err().to_string();
        assert!(e.contains("header"), "{e}");
    }
}
