//! Append-only tables in fixed-size chunks, for the explicit search's per-state data: past their
//! first chunk (which grows as a vector does, so a small search holds little) they grow without
//! copying what they hold or doubling their allocation, so the memory a search holds is what it
//! stored plus at most one chunk a table, and what the budget counts is what it holds.

/// Elements a chunk holds.
const CHUNK: usize = 1 << 16;

/// A vector of `T` that only grows, a chunk at a time.
#[derive(Debug, Default)]
pub struct Chunked<T> {
    chunks: Vec<Vec<T>>,
    len: usize,
}

impl<T: Copy> Chunked<T> {
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn push(&mut self, value: T) {
        if self.len % CHUNK == 0 {
            self.chunks.push(first_or_whole(self.len, CHUNK));
        }
        if let Some(last) = self.chunks.last_mut() {
            last.push(value);
        }
        self.len += 1;
    }

    pub fn get(&self, i: usize) -> T {
        self.chunks[i / CHUNK][i % CHUNK]
    }

    /// Bytes allocated, and what they would be after `more` pushes.
    pub fn bytes_after(&self, more: usize) -> usize {
        allocated(self.len + more, 1) * std::mem::size_of::<T>()
    }
}

/// Records of `stride` bytes each, in chunks of [`CHUNK`] records.
#[derive(Debug, Default)]
pub struct Records {
    chunks: Vec<Vec<u8>>,
    stride: usize,
    len: usize,
}

impl Records {
    /// No records yet; each will take `stride` bytes.
    pub fn new(stride: usize) -> Records {
        Records {
            stride,
            ..Records::default()
        }
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn stride(&self) -> usize {
        self.stride
    }

    /// Record `i`, `stride` bytes.
    pub fn get(&self, i: usize) -> &[u8] {
        let at = (i % CHUNK) * self.stride;
        &self.chunks[i / CHUNK][at..at + self.stride]
    }

    /// Appends `record`, which is `stride` bytes long.
    pub fn push(&mut self, record: &[u8]) {
        debug_assert_eq!(record.len(), self.stride);
        if self.len % CHUNK == 0 {
            self.chunks
                .push(first_or_whole(self.len, CHUNK * self.stride));
        }
        if let Some(last) = self.chunks.last_mut() {
            last.extend_from_slice(record);
        }
        self.len += 1;
    }

    /// Bytes allocated, and what they would be after `more` records.
    pub fn bytes_after(&self, more: usize) -> usize {
        allocated(self.len + more, self.stride)
    }
}

/// A new chunk: the first grows as a vector does, the others are allocated whole.
fn first_or_whole<T>(len: usize, whole: usize) -> Vec<T> {
    if len == 0 {
        Vec::new()
    } else {
        Vec::with_capacity(whole)
    }
}

/// The elements of `width` units allocated for `n` elements: the first chunk's vector at its
/// doubled capacity, whole chunks after it.
fn allocated(n: usize, width: usize) -> usize {
    if n <= CHUNK {
        (n * width).next_power_of_two()
    } else {
        n.div_ceil(CHUNK) * CHUNK * width
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunked_keeps_every_value_across_chunks() {
        let mut v = Chunked::default();
        for i in 0..(2 * CHUNK + 3) as u32 {
            v.push(i);
        }
        assert_eq!(v.len(), 2 * CHUNK + 3);
        assert_eq!(v.get(CHUNK), CHUNK as u32);
        assert_eq!(v.get(2 * CHUNK + 2), (2 * CHUNK + 2) as u32);
        assert_eq!(v.bytes_after(0), 3 * CHUNK * 4);
        let mut small = Chunked::default();
        small.push(1u32);
        assert_eq!(small.bytes_after(20), 32 * 4, "a small table holds little");
    }

    #[test]
    fn records_keep_every_record_across_chunks() {
        let mut r = Records::new(3);
        for i in 0..CHUNK + 5 {
            r.push(&[(i % 251) as u8, 1, 2]);
        }
        assert_eq!(r.len(), CHUNK + 5);
        assert_eq!(r.get(2), [2, 1, 2]);
        assert_eq!(r.get(CHUNK + 1), [((CHUNK + 1) % 251) as u8, 1, 2]);
        assert_eq!(r.bytes_after(0), 2 * CHUNK * 3);
    }
}
