//! A position in the bytes of an MSH file, reading its scalars as text or as binary.

use std::fmt::Display;
use std::path::Path;

use crate::io::error::{IoError, Location};

/// How the file's data sections are encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Encoding {
    /// Text: whitespace-separated numbers.
    Ascii,
    /// Binary, with the byte order of the file's endianness marker.
    Binary {
        /// Big-endian numbers.
        big_endian: bool,
    },
}

/// At most this many characters of a bad token are quoted in a message.
const QUOTE_MAX: usize = 40;

/// A reading position in a whole file held in memory.
pub(super) struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
    path: &'a Path,
    encoding: Encoding,
}

impl<'a> Cursor<'a> {
    pub(super) fn new(data: &'a [u8], path: &'a Path) -> Self {
        Self {
            data,
            pos: 0,
            path,
            encoding: Encoding::Ascii,
        }
    }

    pub(super) fn set_encoding(&mut self, encoding: Encoding) {
        self.encoding = encoding;
    }

    pub(super) fn encoding(&self) -> Encoding {
        self.encoding
    }

    pub(super) fn pos(&self) -> usize {
        self.pos
    }

    pub(super) fn path(&self) -> &'a Path {
        self.path
    }

    /// The location of byte `pos`: its line in a text file, the offset in a binary one.
    pub(super) fn location(&self, pos: usize) -> Location {
        location_of(self.data, pos, self.encoding)
    }

    pub(super) fn malformed(&self, pos: usize, message: impl Into<String>) -> IoError {
        IoError::Malformed {
            path: self.path.to_path_buf(),
            at: self.location(pos),
            message: message.into(),
        }
    }

    pub(super) fn truncated(&self, what: impl Display) -> IoError {
        IoError::Truncated {
            path: self.path.to_path_buf(),
            at: self.location(self.data.len()),
            what: what.to_string(),
        }
    }

    /// A capacity to reserve for `n` records of at least `min_bytes` each: never more than the
    /// rest of the file can hold, whatever a corrupt count says.
    pub(super) fn capacity(&self, n: usize, min_bytes: usize) -> usize {
        n.min(self.data.len().saturating_sub(self.pos) / min_bytes.max(1))
    }

    pub(super) fn at_end(&self) -> bool {
        self.pos >= self.data.len()
    }

    /// Skips spaces, tabs and line breaks.
    pub(super) fn skip_whitespace(&mut self) {
        while self.pos < self.data.len() && self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited token and its position, or `None` at the end.
    pub(super) fn token(&mut self) -> Option<(usize, &'a [u8])> {
        self.skip_whitespace();
        let start = self.pos;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        (self.pos > start).then(|| (start, &self.data[start..self.pos]))
    }

    /// The rest of the current line (without its line break, trailing `\r` dropped) and its
    /// position; the cursor moves past the line break.
    pub(super) fn line(&mut self) -> (usize, &'a [u8]) {
        let start = self.pos;
        let end = self.data[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(self.data.len(), |i| start + i);
        self.pos = (end + 1).min(self.data.len());
        let mut line = &self.data[start..end];
        if let [rest @ .., b'\r'] = line {
            line = rest;
        }
        (start, line)
    }

    /// Whether the file ends inside the line just read by [`line`](Self::line) (no line break).
    pub(super) fn line_cut_short(&self) -> bool {
        self.pos >= self.data.len() && self.data.last() != Some(&b'\n')
    }

    /// Reads a section's end marker, such as `$EndNodes`.
    pub(super) fn expect_end(&mut self, marker: &str) -> Result<(), IoError> {
        let expected = format!("$End{marker}");
        match self.token() {
            Some((_, t)) if t == expected.as_bytes() => Ok(()),
            Some((pos, t)) => Err(self.malformed(
                pos,
                format!(
                    "expected {expected}, found {} (the section holds more or fewer entries than its header says)",
                    quote(t)
                ),
            )),
            None => Err(self.truncated(format!("the ${marker} section (no {expected})"))),
        }
    }

    /// Moves past the line `$End<marker>` of a section this reader skips.
    pub(super) fn skip_section(&mut self, marker: &str) -> Result<(), IoError> {
        let end = format!("$End{marker}");
        let found = self.data[self.pos..]
            .windows(end.len())
            .position(|w| w == end.as_bytes());
        match found {
            Some(i) => {
                self.pos += i + end.len();
                Ok(())
            }
            None => Err(self.truncated(format!("the ${marker} section (no {end})"))),
        }
    }

    /// A text token parsed as `T`.
    fn ascii_parse<T: std::str::FromStr>(
        &mut self,
        what: impl Display,
        kind: &str,
    ) -> Result<T, IoError> {
        let Some((pos, tok)) = self.token() else {
            return Err(self.truncated(what));
        };
        parse_token(tok).ok_or_else(|| {
            self.malformed(
                pos,
                format!("expected {what} ({kind}), found {}", quote(tok)),
            )
        })
    }

    /// A non-negative integer written as text (whatever the file's encoding).
    pub(super) fn ascii_size(&mut self, what: impl Display) -> Result<u64, IoError> {
        self.ascii_parse(what, "a non-negative integer")
    }

    /// An integer written as text (whatever the file's encoding).
    pub(super) fn ascii_int(&mut self, what: impl Display) -> Result<i32, IoError> {
        self.ascii_parse(what, "an integer")
    }

    fn bytes<const N: usize>(&mut self, what: impl Display) -> Result<[u8; N], IoError> {
        let end = self.pos.checked_add(N).filter(|&e| e <= self.data.len());
        let Some(end) = end else {
            return Err(self.truncated(what));
        };
        let mut out = [0u8; N];
        out.copy_from_slice(&self.data[self.pos..end]);
        self.pos = end;
        Ok(out)
    }

    /// A `size_t`: 8 bytes in binary files.
    pub(super) fn size(&mut self, what: impl Display) -> Result<u64, IoError> {
        match self.encoding {
            Encoding::Ascii => self.ascii_size(what),
            Encoding::Binary { big_endian } => {
                let b = self.bytes::<8>(what)?;
                Ok(if big_endian {
                    u64::from_be_bytes(b)
                } else {
                    u64::from_le_bytes(b)
                })
            }
        }
    }

    /// A `size_t` count, also checked to fit memory: a count that exceeds the bytes left in
    /// the file is an error, not an allocation.
    pub(super) fn count(&mut self, what: impl Display) -> Result<usize, IoError> {
        if self.encoding == Encoding::Ascii {
            self.skip_whitespace();
        }
        let pos = self.pos;
        let n = self.size(&what)?;
        let left = self.data.len().saturating_sub(self.pos) as u64;
        if n > left {
            return Err(self.malformed(
                pos,
                format!("{what} is {n}, but the file ends {left} bytes later (truncated or corrupt file?)"),
            ));
        }
        usize::try_from(n).map_err(|_| self.malformed(pos, format!("{what} {n} is too large")))
    }

    /// An `int`: 4 bytes in binary files.
    pub(super) fn int(&mut self, what: impl Display) -> Result<i32, IoError> {
        match self.encoding {
            Encoding::Ascii => self.ascii_int(what),
            Encoding::Binary { big_endian } => {
                let b = self.bytes::<4>(what)?;
                Ok(if big_endian {
                    i32::from_be_bytes(b)
                } else {
                    i32::from_le_bytes(b)
                })
            }
        }
    }

    /// A `double`: 8 bytes in binary files. NaN and infinities are returned as they are.
    pub(super) fn float(&mut self, what: impl Display) -> Result<f64, IoError> {
        match self.encoding {
            Encoding::Ascii => self.ascii_parse(what, "a real number"),
            Encoding::Binary { big_endian } => {
                let b = self.bytes::<8>(what)?;
                Ok(if big_endian {
                    f64::from_be_bytes(b)
                } else {
                    f64::from_le_bytes(b)
                })
            }
        }
    }

    /// Four raw bytes (the binary endianness marker).
    pub(super) fn raw4(&mut self, what: impl Display) -> Result<[u8; 4], IoError> {
        self.bytes::<4>(what)
    }
}

/// Parses a text token.
pub(super) fn parse_token<T: std::str::FromStr>(tok: &[u8]) -> Option<T> {
    std::str::from_utf8(tok).ok()?.parse().ok()
}

/// A token for a message: quoted, escaped, and cut short if long.
pub(super) fn quote(tok: &[u8]) -> String {
    let text = String::from_utf8_lossy(tok);
    let mut short: String = text.chars().take(QUOTE_MAX).collect();
    if text.chars().count() > QUOTE_MAX {
        short.push_str("...");
    }
    format!("{short:?}")
}

/// The location of byte `pos` of `data`.
pub(super) fn location_of(data: &[u8], pos: usize, encoding: Encoding) -> Location {
    match encoding {
        Encoding::Ascii => {
            let pos = pos.min(data.len());
            Location::Line(1 + data[..pos].iter().filter(|&&b| b == b'\n').count())
        }
        Encoding::Binary { .. } => Location::Offset(pos),
    }
}

/// The locations of many positions, given in ascending order, in one pass over the file.
pub(super) fn locations_of(data: &[u8], sorted: &[usize], encoding: Encoding) -> Vec<Location> {
    match encoding {
        Encoding::Binary { .. } => sorted.iter().map(|&p| Location::Offset(p)).collect(),
        Encoding::Ascii => {
            let mut line = 1;
            let mut at = 0;
            sorted
                .iter()
                .map(|&p| {
                    let p = p.min(data.len()).max(at);
                    line += data[at..p].iter().filter(|&&b| b == b'\n').count();
                    at = p;
                    Location::Line(line)
                })
                .collect()
        }
    }
}
