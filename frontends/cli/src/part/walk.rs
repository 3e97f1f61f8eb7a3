//! The chunks of a PNG followed byte by byte as they go by, in whatever
//! pieces they come (the decoder, which checks their CRCs, takes them; the
//! encoder writes them): the SHA-256 of the image data as stored, the
//! image data's zlib stream inflated again to its end and its Adler-32
//! (the output dropped), and the chunk before `IEND`. Nothing is held but
//! a small buffer.

use flate2::{Decompress, FlushDecompress, Status};
use sha2::{Digest, Sha256};

/// A chunk's type and the first bytes of its data: enough for `IHDR`'s
/// width and height, and for a `tEXt` chunk's keyword of up to 15 bytes
/// and its NUL.
#[derive(Clone, Copy, Default)]
pub(super) struct Head {
    /// The chunk's type.
    pub(super) kind: [u8; 4],
    /// Its first bytes, zeros past `len`.
    bytes: [u8; 16],
    /// How many of `bytes` are the chunk's.
    len: usize,
}

impl Head {
    /// The first bytes of the chunk's data (up to 16).
    pub(super) fn bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

/// A walk over a PNG file's bytes (see the module doc).
pub(super) struct Walker {
    /// Where the walk is in the file.
    at: Walk,
    /// The chunk the walk is in.
    chunk: Head,
    /// The last chunk walked to its end, `IEND` aside: once the walk is
    /// past `IEND`, the chunk before it.
    last: Head,
    /// The image data's zlib stream, inflated again (its checksum on), if
    /// it is to be checked.
    zlib: Option<Decompress>,
    /// The SHA-256 of the stored image data so far.
    image_data: Sha256,
    /// Bytes inflated so far.
    inflated: u64,
    /// The bytes the stream must inflate to: the filtered size of an
    /// 8-bit RGBA image of the size `IHDR` gives (a filter byte and 4
    /// bytes a pixel, a row), once it is read. A stream that makes more
    /// is refused at once, not inflated on (a bomb in the image data).
    limit: u64,
    /// Whether the zlib stream has ended.
    ended: bool,
    /// What the walk found first, if anything.
    problem: Option<String>,
}

/// Where a [`Walker`] is in the file.
#[derive(Clone, Copy)]
enum Walk {
    /// In the 8-byte signature, so many bytes read.
    Signature(usize),
    /// In a chunk's length and type, so many bytes read.
    Header([u8; 8], usize),
    /// In a chunk's data, so many bytes left.
    Data(u32),
    /// In a chunk's CRC, so many bytes left.
    Crc(usize),
    /// Past `IEND`.
    End,
}

impl Walker {
    /// A walk from a file's first byte, which checks the image data's
    /// zlib stream if `inflate` (else only hashes the image data).
    pub(super) fn new(inflate: bool) -> Walker {
        Walker {
            at: Walk::Signature(0),
            chunk: Head::default(),
            last: Head::default(),
            zlib: inflate.then(|| Decompress::new(true)),
            image_data: Sha256::new(),
            inflated: 0,
            limit: u64::MAX,
            ended: false,
            problem: None,
        }
    }

    /// Notes `problem` unless one was noted before.
    pub(super) fn found(&mut self, problem: String) {
        self.problem.get_or_insert(problem);
    }

    /// Walks `bytes`, the next ones of the file.
    pub(super) fn walk(&mut self, mut bytes: &[u8]) {
        /// The first `n` of `bytes` (or all), taken off them.
        fn take<'a>(n: usize, bytes: &mut &'a [u8]) -> &'a [u8] {
            let (taken, rest) = bytes.split_at(n.min(bytes.len()));
            *bytes = rest;
            taken
        }
        while !bytes.is_empty() && self.problem.is_none() {
            self.at = match self.at {
                Walk::Signature(seen) => match seen + take(8 - seen, &mut bytes).len() {
                    8 => Walk::Header([0; 8], 0),
                    seen => Walk::Signature(seen),
                },
                Walk::Header(mut header, seen) => {
                    let taken = take(8 - seen, &mut bytes);
                    header[seen..seen + taken.len()].copy_from_slice(taken);
                    match seen + taken.len() {
                        8 => {
                            let [l0, l1, l2, l3, t0, t1, t2, t3] = header;
                            self.chunk = Head {
                                kind: [t0, t1, t2, t3],
                                ..Head::default()
                            };
                            Walk::Data(u32::from_be_bytes([l0, l1, l2, l3]))
                        }
                        seen => Walk::Header(header, seen),
                    }
                }
                Walk::Data(left) => {
                    let taken = take(left as usize, &mut bytes);
                    let head = &mut self.chunk;
                    let kept = taken.len().min(head.bytes.len() - head.len);
                    head.bytes[head.len..head.len + kept].copy_from_slice(&taken[..kept]);
                    head.len += kept;
                    if &head.kind == b"IDAT" {
                        self.image_data.update(taken);
                        self.inflate(taken);
                    }
                    match left - taken.len() as u32 {
                        0 => Walk::Crc(4),
                        left => Walk::Data(left),
                    }
                }
                Walk::Crc(left) => match left - take(left, &mut bytes).len() {
                    0 => self.chunk_done(),
                    left => Walk::Crc(left),
                },
                Walk::End => {
                    // The decoder stops at IEND; `Walked::finish` looks
                    // past it.
                    self.found("data after IEND, the end of the image".into());
                    Walk::End
                }
            };
        }
    }

    /// At the end of a chunk's CRC: where the walk goes next.
    fn chunk_done(&mut self) -> Walk {
        match &self.chunk.kind {
            b"IEND" => return Walk::End,
            b"IHDR" => {
                let [w0, w1, w2, w3, h0, h1, h2, h3, ..] = self.chunk.bytes;
                let width = u32::from_be_bytes([w0, w1, w2, w3]);
                let height = u32::from_be_bytes([h0, h1, h2, h3]);
                self.limit = u64::from(height) * (1 + 4 * u64::from(width));
            }
            _ => {}
        }
        self.last = self.chunk;
        Walk::Header([0; 8], 0)
    }

    /// Inflates `data`, the next bytes of the image data, and drops the
    /// output: what counts is that the stream inflates, how much it
    /// makes, and where it ends.
    fn inflate(&mut self, mut data: &[u8]) {
        let Some(mut zlib) = self.zlib.take() else {
            return;
        };
        let mut out = [0u8; 8192];
        while self.problem.is_none() {
            if self.ended {
                if !data.is_empty() {
                    self.found("corrupt image data: more data after its zlib stream's end".into());
                }
                break;
            }
            let (before_in, before_out) = (zlib.total_in(), zlib.total_out());
            let status = zlib.decompress(data, &mut out, FlushDecompress::None);
            let used = (zlib.total_in() - before_in) as usize;
            let made = zlib.total_out() - before_out;
            data = &data[used..];
            self.inflated += made;
            if self.inflated > self.limit {
                self.found(format!(
                    "corrupt image data: it inflates to more than the {} bytes its size makes",
                    self.limit
                ));
            }
            match status {
                Err(e) => self.found(format!(
                    "corrupt image data: its zlib stream does not inflate or fails its Adler-32 check ({e})"
                )),
                Ok(Status::StreamEnd) => self.ended = true,
                // All taken in, and out: the buffer did not fill up. (A
                // call may only empty what an earlier one could not fit.)
                Ok(_) if data.is_empty() && made < out.len() as u64 => break,
                // No progress: the stream wants input it was not given.
                Ok(_) if used == 0 && made == 0 => {
                    self.found("corrupt image data: its zlib stream stopped taking data".into());
                }
                Ok(_) => {}
            }
        }
        self.zlib = Some(zlib);
    }

    /// The SHA-256 of the image data walked so far.
    pub(super) fn image_data(&mut self) -> [u8; 32] {
        self.image_data.finalize_reset().into()
    }

    /// At the end of the file of a walk that inflates: checks that the
    /// walk reached the end of `IEND` and that the image data's zlib
    /// stream ended (its Adler-32 passed) after exactly the bytes the
    /// image's size makes, and returns the SHA-256 of the stored image
    /// data and the head of the chunk before `IEND`.
    ///
    /// # Errors
    /// The first problem found.
    pub(super) fn finish(&mut self) -> Result<([u8; 32], Head), String> {
        if let Some(problem) = self.problem.take() {
            return Err(problem);
        }
        if !self.ended {
            return Err("corrupt image data: its zlib stream is cut short, with no end or Adler-32 (an IDAT chunk missing?)".into());
        }
        if self.inflated != self.limit {
            return Err(format!(
                "corrupt image data: it inflates to {} bytes where its size makes {}",
                self.inflated, self.limit
            ));
        }
        if !matches!(self.at, Walk::End) {
            return Err("corrupt: the file ends before IEND does".into());
        }
        Ok((self.image_data(), self.last))
    }
}
