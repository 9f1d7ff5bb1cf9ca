//! The line ends of a file in order, found 64 bytes at a time: a bit mask of the block's
//! `\n`s (SSE2 on x86_64, eight bytes per step elsewhere), then one bit per line. DXF lines
//! are short (`  0`, `LINE`, `1.5`), so a search per line would pay its set-up every few
//! bytes.
//!
//! The file's line ends in order from a bit mask per 64-byte block (SSE2 on x86_64, a portable
//! eight-bytes-per-step fallback, both tested against a byte loop): the next two at once for a pair
//! (`quick_two`: the usual cases, inlined, nothing taken otherwise).

#[derive(Clone, Copy)]
pub(crate) struct LineEnds<'a> {
    bytes: &'a [u8],
    /// Start of the block `mask` describes.
    base: usize,
    /// The `\n`s of the block not taken yet: bit `i` is byte `base + i`.
    mask: u64,
}

impl<'a> LineEnds<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        LineEnds {
            bytes,
            base: 0,
            mask: block_mask(bytes, 0),
        }
    }

    /// The next two line ends (the second may be the length: a last line without one);
    /// `None` when there is no `\n` left.
    #[inline(always)]
    pub(crate) fn next_two(&mut self) -> Option<(usize, usize)> {
        let first = self.mask;
        let rest = first & first.wrapping_sub(1);
        if rest == 0 {
            // about one pair in five, where a block ends
            return self.next_two_across();
        }
        self.mask = rest & (rest - 1);
        Some((
            self.base + first.trailing_zeros() as usize,
            self.base + rest.trailing_zeros() as usize,
        ))
    }

    /// [`LineEnds::next_two`] for the usual cases only (two line ends in this block, or in
    /// this block and the next, or both in the next), inlined whole so that a caller's copy
    /// stays in registers; `None`, nothing taken, for the others.
    #[inline(always)]
    pub(crate) fn quick_two(&mut self) -> Option<(usize, usize)> {
        let first = self.mask;
        let rest = first & first.wrapping_sub(1);
        if rest != 0 {
            self.mask = rest & (rest - 1);
            return Some((
                self.base + first.trailing_zeros() as usize,
                self.base + rest.trailing_zeros() as usize,
            ));
        }
        let next_base = self.base + 64;
        if next_base >= self.bytes.len() {
            return None;
        }
        let next = block_mask(self.bytes, next_base);
        let next_rest = next & next.wrapping_sub(1);
        let two = if first != 0 && next != 0 {
            self.mask = next_rest;
            (
                self.base + first.trailing_zeros() as usize,
                next_base + next.trailing_zeros() as usize,
            )
        } else if first == 0 && next_rest != 0 {
            self.mask = next_rest & (next_rest - 1);
            (
                next_base + next.trailing_zeros() as usize,
                next_base + next_rest.trailing_zeros() as usize,
            )
        } else {
            return None;
        };
        self.base = next_base;
        Some(two)
    }

    #[inline(never)]
    fn next_two_across(&mut self) -> Option<(usize, usize)> {
        // the usual case: one line end left here, the next one in the next block
        if self.mask != 0 && self.base + 64 < self.bytes.len() {
            let first = self.base + self.mask.trailing_zeros() as usize;
            self.base += 64;
            self.mask = block_mask(self.bytes, self.base);
            if self.mask != 0 {
                let second = self.base + self.mask.trailing_zeros() as usize;
                self.mask &= self.mask - 1;
                return Some((first, second));
            }
            return Some((first, self.next_end()));
        }
        let first = self.next_end();
        (first < self.bytes.len()).then(|| (first, self.next_end()))
    }

    /// The file.
    #[inline(always)]
    pub(crate) fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// No line end is left to take (the rest of the file is read otherwise).
    pub(crate) fn exhaust(&mut self) {
        self.mask = 0;
        self.base = self.bytes.len();
    }

    /// The index of the next `\n`, or the length once there is none left.
    #[inline]
    pub(crate) fn next_end(&mut self) -> usize {
        while self.mask == 0 {
            // each block is read once: the loop is bounded by the file
            if self.base + 64 >= self.bytes.len() {
                return self.bytes.len();
            }
            self.base += 64;
            self.mask = block_mask(self.bytes, self.base);
        }
        let i = self.base + self.mask.trailing_zeros() as usize;
        self.mask &= self.mask - 1;
        i
    }
}

/// The `\n`s of the 64 bytes from `base` (fewer at the end of the file).
#[inline(always)]
fn block_mask(b: &[u8], base: usize) -> u64 {
    let rest = b.get(base..).unwrap_or_default();
    match rest.first_chunk::<64>() {
        Some(block) => newlines(block),
        None => rest
            .iter()
            .enumerate()
            .filter(|(_, &c)| c == b'\n')
            .fold(0, |m, (i, _)| m | 1 << i),
    }
}

#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
fn newlines(block: &[u8; 64]) -> u64 {
    newlines_sse2(block)
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
fn newlines(block: &[u8; 64]) -> u64 {
    newlines_swar(block)
}

/// Sixteen bytes compared per instruction.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
fn newlines_sse2(block: &[u8; 64]) -> u64 {
    use std::arch::x86_64::{
        __m128i, _mm_cmpeq_epi8, _mm_loadu_si128, _mm_movemask_epi8, _mm_set1_epi8,
    };
    let mut mask = 0;
    for (k, sixteen) in block.chunks_exact(16).enumerate() {
        // SAFETY: SSE2 is enabled for this build (the cfg above; every x86_64 CPU has it),
        // and the unaligned load reads the sixteen bytes of `sixteen`, no more.
        let bits = unsafe {
            let v = _mm_loadu_si128(sixteen.as_ptr().cast::<__m128i>());
            _mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_set1_epi8(b'\n' as i8)))
        };
        mask |= u64::from(bits as u32 & 0xffff) << (16 * k);
    }
    mask
}

/// Eight bytes per step in a plain `u64`: an exact zero-byte test of `word ^ "\n\n…"` (no
/// borrow between bytes), its high bits gathered into eight bits by one multiplication.
#[cfg_attr(all(target_arch = "x86_64", target_feature = "sse2"), allow(dead_code))]
fn newlines_swar(block: &[u8; 64]) -> u64 {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    let mut mask = 0;
    for (k, eight) in block.chunks_exact(8).enumerate() {
        let mut w = [0u8; 8];
        w.copy_from_slice(eight);
        let x = u64::from_le_bytes(w) ^ 0x0a0a_0a0a_0a0a_0a0a;
        // high bit of each byte: set when the byte of `x` is not zero
        let nonzero = ((x & LOW7) + LOW7) | x;
        let zero = !nonzero & !LOW7;
        // bit 8i+7 → bit 56+i (the products never overlap, so nothing carries)
        let bits = ((zero >> 7).wrapping_mul(0x0102_0408_1020_4080)) >> 56;
        mask |= bits << (8 * k);
    }
    mask
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naive(block: &[u8; 64]) -> u64 {
        (0..64)
            .filter(|&i| block[i] == b'\n')
            .fold(0, |m, i| m | 1 << i)
    }

    #[test]
    fn masks_match_a_byte_loop() {
        let mut seed = 0x1234_5678_9abc_def1u64;
        let alphabet = b"\n\n\x0a\x0b\x09\r\x8a\xff\x00 0a";
        for round in 0..20_000 {
            let mut block = [0u8; 64];
            for b in block.iter_mut() {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                *b = if round % 3 == 0 {
                    seed as u8
                } else {
                    alphabet[(seed >> 40) as usize % alphabet.len()]
                };
            }
            assert_eq!(newlines_swar(&block), naive(&block), "{block:?}");
            #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
            assert_eq!(newlines_sse2(&block), naive(&block), "{block:?}");
        }
        for fill in [[b'\n'; 64], [0; 64], [0xff; 64]] {
            assert_eq!(newlines_swar(&fill), naive(&fill));
            #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
            assert_eq!(newlines_sse2(&fill), naive(&fill));
        }
    }

    #[test]
    fn every_line_end_in_order_then_the_length() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for len in 0..700 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            // sparse or dense line ends, long lines now and then
            let density = [1, 3, 5, 40][len % 4];
            let bytes: Vec<u8> = (0..len)
                .map(|i| {
                    let r = seed.rotate_left(i as u32 % 64) ^ (i as u64).wrapping_mul(0x9e37);
                    if r.is_multiple_of(density) {
                        b'\n'
                    } else {
                        b'x'
                    }
                })
                .collect();
            let want: Vec<usize> = (0..len).filter(|&i| bytes[i] == b'\n').collect();
            let mut ends = LineEnds::new(&bytes);
            let mut got = Vec::new();
            let mut k = 0u32;
            while got.len() < want.len() {
                k += 1;
                // the three ways of taking them, mixed
                if (seed >> (k % 64)) & 3 == 1 {
                    let before = ends;
                    match ends.quick_two() {
                        Some((a, b)) => {
                            got.extend([a, b]);
                            continue;
                        }
                        // nothing taken
                        None => assert_eq!((ends.base, ends.mask), (before.base, before.mask)),
                    }
                }
                if (seed >> (k % 64)) & 1 == 0 {
                    if let Some((a, b)) = ends.next_two() {
                        got.push(a);
                        // the length when `a` was the last line end
                        got.extend((b < len).then_some(b));
                        continue;
                    }
                }
                got.push(ends.next_end());
            }
            assert_eq!(got, want, "{len}");
            assert_eq!(ends.next_two(), None);
            // a last line without a line end: its end is the length
            if let Some(&last) = want.last() {
                let mut ends = LineEnds::new(&bytes);
                for _ in 1..want.len() {
                    ends.next_end();
                }
                let two = ends.next_two();
                assert_eq!(two, Some((last, len)), "{len}");
            }
            assert_eq!(ends.next_end(), len);
            assert_eq!(ends.next_end(), len);
        }
    }
}
