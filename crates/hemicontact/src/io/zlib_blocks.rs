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
//! fixed, so the same bytes always give the same encoding. The blocks are independent, so
//! they are compressed in parallel (rayon); the result does not depend on the number of
//! threads.
//!
//! One compressor is kept per thread and reset before each block: setting one up allocates
//! and zeroes about 160 KiB of tables, which cost more than compressing the few hundred
//! bytes of an array of a small mesh (a load path writes thousands of them). Reset, it is
//! in the state of a new one, so the bytes are those of `compress_to_vec_zlib`.

use crate::error::{Error, Result};
use miniz_oxide::deflate::core::{
    compress as deflate, create_comp_flags_from_zip_params, CompressorOxide, TDEFLFlush,
    TDEFLStatus,
};
use miniz_oxide::inflate::decompress_to_vec_zlib_with_limit;
use std::cell::RefCell;

/// Uncompressed size of a block (bytes): VTK's default.
pub const BLOCK_SIZE: usize = 32 * 1024;

/// The zlib compression level (0–10 in miniz): 1, the fastest that still compresses.
/// The arrays written are mostly floating-point numbers, whose mantissas do not compress:
/// on the paper square at n = 512 (151 MB of arrays) level 1 gives 42.9 MB in 1.3 s and
/// zlib's default level 6 gives 41.8 MB in 2.9 s (zlib's own compressor, one thread).
/// The compressor is miniz_oxide itself (not a back end chosen by cargo features), so the
/// bytes do not depend on how the program was built.
const LEVEL: u8 = 1;

/// Encodes `bytes` as one VTK array: header and zlib-compressed blocks (see the module
/// documentation). Empty input gives the header `[0, BLOCK_SIZE, 0]` and no block.
pub fn compress(bytes: &[u8]) -> Vec<u8> {
    use rayon::prelude::*;
    let blocks: Vec<Vec<u8>> = if bytes.len() > 4 * BLOCK_SIZE {
        bytes.par_chunks(BLOCK_SIZE).map(zlib).collect()
    } else {
        bytes.chunks(BLOCK_SIZE).map(zlib).collect()
    };
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

thread_local! {
    /// This thread's compressor at [`LEVEL`] with a zlib header, made on first use.
    static COMPRESSOR: RefCell<Option<Box<CompressorOxide>>> = const { RefCell::new(None) };
}

/// `input` compressed as a zlib stream at [`LEVEL`]: the bytes of miniz_oxide's
/// `compress_to_vec_zlib(input, LEVEL)`, whose loop this is, with this thread's compressor
/// reset instead of a new one.
fn zlib(input: &[u8]) -> Vec<u8> {
    COMPRESSOR.with(|cell| {
        let mut slot = cell.borrow_mut();
        let compressor = slot.get_or_insert_with(|| {
            Box::new(CompressorOxide::new(create_comp_flags_from_zip_params(
                LEVEL.into(),
                1,
                0,
            )))
        });
        compressor.reset();
        let whole = input;
        let mut input = input;
        let mut output = vec![0; (input.len() / 2).max(2)];
        let mut out_pos = 0;
        loop {
            let (status, bytes_in, bytes_out) = deflate(
                compressor,
                input,
                &mut output[out_pos..],
                TDEFLFlush::Finish,
            );
            out_pos += bytes_out;
            match status {
                TDEFLStatus::Done => {
                    output.truncate(out_pos);
                    return output;
                }
                TDEFLStatus::Okay if bytes_in <= input.len() => {
                    input = &input[bytes_in..];
                    if output.len().saturating_sub(out_pos) < 30 {
                        output.resize(output.len() * 2, 0);
                    }
                }
                // Not reached (miniz_oxide panics here too): compressing into a buffer
                // that grows never fails.
                _ => {
                    return miniz_oxide::deflate::compress_to_vec_zlib(whole, LEVEL);
                }
            }
        }
    })
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
    fn the_reused_compressor_gives_the_bytes_of_a_new_one() {
        // Blocks of every kind one after the other: each must not see the ones before.
        let mut sizes = vec![0, 1, 2, 3, 17, 100, 1000, BLOCK_SIZE - 1, BLOCK_SIZE];
        sizes.extend([5, BLOCK_SIZE, 64, 3]);
        for (k, &n) in sizes.iter().enumerate() {
            let mut data = bytes(n + k);
            data.truncate(n);
            if k % 3 == 1 {
                data.iter_mut().for_each(|b| *b %= 4);
            }
            let fresh = miniz_oxide::deflate::compress_to_vec_zlib(&data, LEVEL);
            assert_eq!(zlib(&data), fresh, "block {k} of {n} bytes");
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
