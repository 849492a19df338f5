//! SDO: the server of the emulated encoder and the client frames of a
//! master (CiA 301 SDO protocol, as public summaries describe it; the note
//! only shows one request, seed 003 §8 step 5).
//!
//! ```text
//!  request byte 0 (client → server, 0x600 + node)      response byte 0 (server → client, 0x580 + node)
//!  001 0 nn e s  initiate download  (0x22: e=1, s=0)    0110 0000  0x60  download confirmed
//!  000 t nnn c   download segment                       001t 0000  0x20 | t<<4
//!  010 0 0000    initiate upload    0x40                010 0 nn e s  0x43/0x47/0x4B/0x4F expedited, 0x41 segmented (size in 4..7)
//!  011 t 0000    upload segment     0x60 | t<<4         000 t nnn c  segment, 7 − n bytes, c = last
//!  100 0 0000    abort              0x80 idx sub code   100 0 0000  0x80 idx sub code (little-endian)
//!  bytes 1..2 index (low byte first), byte 3 sub-index, bytes 4..7 data or size
//! ```
//! An expedited download without size (`e = 1, s = 0`, the note's `0x22`)
//! writes the object's own size from bytes 4 on.

/// SDO abort codes (CiA 301) the server sends.
pub mod abort {
    /// Toggle bit not alternated.
    pub const TOGGLE: u32 = 0x0503_0000;
    /// SDO protocol timed out.
    pub const TIMEOUT: u32 = 0x0504_0000;
    /// Client/server command specifier not valid or unknown.
    pub const COMMAND: u32 = 0x0504_0001;
    /// Attempt to write a read-only object.
    pub const READ_ONLY: u32 = 0x0601_0002;
    /// Object does not exist in the object dictionary.
    pub const NO_OBJECT: u32 = 0x0602_0000;
    /// Data type does not match, length of service parameter does not match.
    pub const LENGTH: u32 = 0x0607_0010;
    /// Sub-index does not exist.
    pub const NO_SUBINDEX: u32 = 0x0609_0011;
    /// Invalid value for parameter (value range exceeded, value not allowed).
    pub const RANGE: u32 = 0x0609_0030;
    /// Value of parameter written too high.
    pub const TOO_HIGH: u32 = 0x0609_0031;
    /// Value of parameter written too low.
    pub const TOO_LOW: u32 = 0x0609_0032;
    /// Data cannot be transferred because of the present device state.
    pub const STATE: u32 = 0x0800_0022;
}

/// What an abort code means (CiA 301 wording, shortened).
pub fn abort_name(code: u32) -> &'static str {
    match code {
        abort::TOGGLE => "toggle bit not alternated",
        abort::TIMEOUT => "SDO protocol timed out",
        abort::COMMAND => "command specifier not valid",
        abort::READ_ONLY => "attempt to write a read-only object",
        abort::NO_OBJECT => "object does not exist",
        abort::LENGTH => "length of service parameter does not match",
        abort::NO_SUBINDEX => "sub-index does not exist",
        abort::RANGE => "value range of parameter exceeded",
        abort::TOO_HIGH => "value of parameter written too high",
        abort::TOO_LOW => "value of parameter written too low",
        abort::STATE => "not possible in the present device state",
        _ => "unknown abort code",
    }
}

/// The dictionary side of a server.
pub trait ObjectAccess {
    /// Whether `index`/`sub` may be written (existence and access), or the abort code.
    fn writable(&self, index: u16, sub: u8) -> Result<(), u32>;
    /// The value of `index`/`sub`, little-endian, or the abort code.
    fn read(&mut self, index: u16, sub: u8) -> Result<Vec<u8>, u32>;
    /// Writes `data` (exactly as many bytes as the client sent; `sized`:
    /// the client said how many), or returns the abort code.
    fn write(&mut self, index: u16, sub: u8, data: &[u8], sized: bool) -> Result<(), u32>;
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Transfer {
    Idle,
    Download {
        index: u16,
        sub: u8,
        toggle: bool,
        buf: Vec<u8>,
        size: Option<usize>,
    },
    Upload {
        index: u16,
        sub: u8,
        toggle: bool,
        data: Vec<u8>,
        pos: usize,
    },
}

/// The SDO server: one transfer at a time.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Server {
    t: Transfer,
}

impl Default for Server {
    fn default() -> Self {
        Server { t: Transfer::Idle }
    }
}

/// An abort frame's data.
pub fn abort_frame(index: u16, sub: u8, code: u32) -> [u8; 8] {
    let c = code.to_le_bytes();
    [
        0x80,
        index as u8,
        (index >> 8) as u8,
        sub,
        c[0],
        c[1],
        c[2],
        c[3],
    ]
}

fn head(cmd: u8, index: u16, sub: u8) -> [u8; 8] {
    [cmd, index as u8, (index >> 8) as u8, sub, 0, 0, 0, 0]
}

impl Server {
    /// Whether a segmented transfer is under way.
    pub fn busy(&self) -> bool {
        self.t != Transfer::Idle
    }

    /// Answers one request (the 8 data bytes of a frame on 0x600 + node);
    /// `None` for an abort from the client (no answer).
    pub fn request(&mut self, d: &[u8], od: &mut impl ObjectAccess) -> Option<[u8; 8]> {
        let mut r = [0u8; 8];
        r[..d.len().min(8)].copy_from_slice(&d[..d.len().min(8)]);
        let index = r[1] as u16 | (r[2] as u16) << 8;
        let sub = r[3];
        let ccs = r[0] >> 5;
        let (ti, ts) = match &self.t {
            Transfer::Download { index, sub, .. } | Transfer::Upload { index, sub, .. } => {
                (*index, *sub)
            }
            Transfer::Idle => (index, sub),
        };
        let answer = match ccs {
            1 => {
                self.t = Transfer::Idle;
                let (e, s, n) = (r[0] & 2 != 0, r[0] & 1 != 0, ((r[0] >> 2) & 3) as usize);
                if e {
                    let len = if s { 4 - n } else { 4 };
                    od.write(index, sub, &r[4..4 + len], s)
                        .map(|_| head(0x60, index, sub))
                        .unwrap_or_else(|c| abort_frame(index, sub, c))
                } else {
                    match od.writable(index, sub) {
                        Ok(()) => {
                            let size =
                                s.then(|| u32::from_le_bytes([r[4], r[5], r[6], r[7]]) as usize);
                            self.t = Transfer::Download {
                                index,
                                sub,
                                toggle: false,
                                buf: Vec::new(),
                                size,
                            };
                            head(0x60, index, sub)
                        }
                        Err(c) => abort_frame(index, sub, c),
                    }
                }
            }
            0 => match &mut self.t {
                Transfer::Download {
                    index,
                    sub,
                    toggle,
                    buf,
                    size,
                } => {
                    let (t, n, c) = (r[0] & 0x10 != 0, ((r[0] >> 1) & 7) as usize, r[0] & 1 != 0);
                    if t != *toggle {
                        let a = abort_frame(*index, *sub, abort::TOGGLE);
                        self.t = Transfer::Idle;
                        a
                    } else {
                        buf.extend_from_slice(&r[1..8 - n]);
                        *toggle = !*toggle;
                        let ok = [0x20 | (t as u8) << 4, 0, 0, 0, 0, 0, 0, 0];
                        if c {
                            let (index, sub, buf, size) =
                                (*index, *sub, std::mem::take(buf), *size);
                            self.t = Transfer::Idle;
                            if size.is_some_and(|s| s != buf.len()) {
                                abort_frame(index, sub, abort::LENGTH)
                            } else {
                                od.write(index, sub, &buf, true)
                                    .map(|_| ok)
                                    .unwrap_or_else(|c| abort_frame(index, sub, c))
                            }
                        } else {
                            ok
                        }
                    }
                }
                _ => abort_frame(ti, ts, abort::COMMAND),
            },
            2 => {
                self.t = Transfer::Idle;
                match od.read(index, sub) {
                    Ok(v) if v.len() <= 4 && !v.is_empty() => {
                        let mut a = head(0x43 | ((4 - v.len()) as u8) << 2, index, sub);
                        a[4..4 + v.len()].copy_from_slice(&v);
                        a
                    }
                    Ok(v) => {
                        let mut a = head(0x41, index, sub);
                        a[4..8].copy_from_slice(&(v.len() as u32).to_le_bytes());
                        self.t = Transfer::Upload {
                            index,
                            sub,
                            toggle: false,
                            data: v,
                            pos: 0,
                        };
                        a
                    }
                    Err(c) => abort_frame(index, sub, c),
                }
            }
            3 => match &mut self.t {
                Transfer::Upload {
                    index,
                    sub,
                    toggle,
                    data,
                    pos,
                } => {
                    let t = r[0] & 0x10 != 0;
                    if t != *toggle {
                        let a = abort_frame(*index, *sub, abort::TOGGLE);
                        self.t = Transfer::Idle;
                        a
                    } else {
                        let chunk = &data[*pos..(*pos + 7).min(data.len())];
                        let last = *pos + chunk.len() == data.len();
                        let mut a = [
                            (t as u8) << 4 | ((7 - chunk.len()) as u8) << 1 | last as u8,
                            0,
                            0,
                            0,
                            0,
                            0,
                            0,
                            0,
                        ];
                        a[1..1 + chunk.len()].copy_from_slice(chunk);
                        *pos += chunk.len();
                        *toggle = !*toggle;
                        if last {
                            self.t = Transfer::Idle;
                        }
                        a
                    }
                }
                _ => abort_frame(ti, ts, abort::COMMAND),
            },
            4 => {
                self.t = Transfer::Idle;
                return None;
            }
            _ => {
                self.t = Transfer::Idle;
                abort_frame(ti, ts, abort::COMMAND)
            }
        };
        if answer[0] == 0x80 {
            self.t = Transfer::Idle;
        }
        Some(answer)
    }
}

/// Client: expedited download with the size indicated (`0x23`, `0x27`, `0x2B`, `0x2F` for 4, 3, 2, 1 bytes).
pub fn download(index: u16, sub: u8, data: &[u8]) -> [u8; 8] {
    let n = data.len().clamp(1, 4);
    let mut a = head(0x23 | ((4 - n) as u8) << 2, index, sub);
    a[4..4 + n].copy_from_slice(&data[..n]);
    a
}

/// Client: expedited download without size (`0x22`, the form of the note's example), `v` little-endian in bytes 4..7.
pub fn download_unsized(index: u16, sub: u8, v: u32) -> [u8; 8] {
    let mut a = head(0x22, index, sub);
    a[4..8].copy_from_slice(&v.to_le_bytes());
    a
}

/// Client: initiate upload (`0x40`).
pub fn upload(index: u16, sub: u8) -> [u8; 8] {
    head(0x40, index, sub)
}

/// A server response as a client sees it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Response {
    /// Initiate download confirmed (`0x60`).
    Downloaded {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
    },
    /// Expedited upload: the value.
    Uploaded {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
        /// Value bytes.
        data: Vec<u8>,
    },
    /// Segmented upload begins: the size.
    UploadSegmented {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
        /// Size in bytes.
        size: u32,
    },
    /// A download segment confirmed (toggle).
    SegmentDownloaded(bool),
    /// An upload segment: toggle, bytes, last.
    Segment(bool, Vec<u8>, bool),
    /// Abort.
    Abort {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
        /// Abort code.
        code: u32,
    },
    /// Not a valid response.
    Invalid,
}

/// Reads a response frame's 8 data bytes. `segment`: the client expects a
/// segment (the command specifier alone cannot tell an upload segment from
/// other responses).
pub fn parse_response(d: &[u8], segment: bool) -> Response {
    if d.len() < 8 {
        return Response::Invalid;
    }
    let index = d[1] as u16 | (d[2] as u16) << 8;
    let sub = d[3];
    match d[0] >> 5 {
        4 => Response::Abort {
            index,
            sub,
            code: u32::from_le_bytes([d[4], d[5], d[6], d[7]]),
        },
        0 if segment => {
            let n = ((d[0] >> 1) & 7) as usize;
            Response::Segment(d[0] & 0x10 != 0, d[1..8 - n].to_vec(), d[0] & 1 != 0)
        }
        1 if segment => Response::SegmentDownloaded(d[0] & 0x10 != 0),
        3 if d[0] == 0x60 => Response::Downloaded { index, sub },
        2 if d[0] & 2 != 0 => {
            let n = if d[0] & 1 != 0 {
                4 - ((d[0] >> 2) & 3) as usize
            } else {
                4
            };
            Response::Uploaded {
                index,
                sub,
                data: d[4..4 + n].to_vec(),
            }
        }
        2 => Response::UploadSegmented {
            index,
            sub,
            size: u32::from_le_bytes([d[4], d[5], d[6], d[7]]),
        },
        _ => Response::Invalid,
    }
}
