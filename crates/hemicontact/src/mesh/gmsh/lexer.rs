//! Lexing a `.msh` file: a cursor over its bytes that reads whitespace-separated tokens
//! (ASCII numbers, quoted names, section markers) or raw little-endian numbers (the body of
//! a binary section), tracks the line (ASCII) or byte offset (binary) of what it read last
//! for error messages, and checks announced counts against the bytes left before anything
//! is allocated for them.

use crate::error::{Error, FileLocation, Result};

/// A cursor over the file's bytes that reads tokens (ASCII) or raw little-endian numbers
/// (binary sections), tracking the line number and the location of the last item read.
pub(super) struct Reader<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) pos: usize,
    /// Line of `pos` (1-based; meaningful in ASCII files only).
    pub(super) line: u64,
    /// The file is binary: locations are byte offsets.
    pub(super) binary_file: bool,
    /// Numbers are currently read in binary (the body of a binary section).
    pub(super) binary: bool,
    /// Location of the item read last (for error messages).
    pub(super) at: FileLocation,
    pub(super) file: &'a str,
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
pub(super) fn show(token: &[u8]) -> String {
    let s = String::from_utf8_lossy(token);
    let mut out: String = s.chars().take(40).collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out
}

impl<'a> Reader<'a> {
    pub(super) fn new(bytes: &'a [u8], file: &'a str) -> Self {
        Reader {
            bytes,
            pos: 0,
            line: 1,
            binary_file: false,
            binary: false,
            at: FileLocation::Line(1),
            file,
        }
    }

    pub(super) fn err(&self, message: impl Into<String>) -> Error {
        Error::MeshFile {
            file: self.file.to_string(),
            location: self.at,
            message: message.into(),
        }
    }

    pub(super) fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }

    /// Records the current position as the location of the next item.
    pub(super) fn mark(&mut self) {
        self.at = if self.binary_file {
            FileLocation::Byte(self.pos as u64)
        } else {
            FileLocation::Line(self.line)
        };
    }

    pub(super) fn skip_ws(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited token.
    pub(super) fn token(&mut self, what: &str) -> Result<&'a [u8]> {
        self.skip_ws();
        self.mark();
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        match self.bytes.get(start..self.pos) {
            Some(t) if !t.is_empty() => Ok(t),
            _ => Err(self.err(format!(
                "unexpected end of file while reading {what} (truncated file?)"
            ))),
        }
    }

    pub(super) fn text_u64(&mut self, what: &str) -> Result<u64> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .filter(|s| !s.starts_with('+'))
            .and_then(|s| s.parse::<u64>().ok())
            .ok_or_else(|| {
                self.err(format!(
                    "expected {what} (a non-negative integer), found `{}`",
                    show(t)
                ))
            })
    }

    pub(super) fn text_i32(&mut self, what: &str) -> Result<i32> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<i32>().ok())
            .ok_or_else(|| {
                self.err(format!(
                    "expected {what} (a 32-bit integer), found `{}`",
                    show(t)
                ))
            })
    }

    pub(super) fn text_f64(&mut self, what: &str) -> Result<f64> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| self.err(format!("expected {what} (a number), found `{}`", show(t))))
    }

    /// `N` raw bytes of a binary section.
    pub(super) fn raw<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        self.mark();
        let mut out = [0u8; N];
        match self.bytes.get(self.pos..self.pos.saturating_add(N)) {
            Some(s) if s.len() == N => {
                out.copy_from_slice(s);
                self.pos += N;
                Ok(out)
            }
            _ => Err(self.err(format!(
                "unexpected end of file while reading {what} (truncated file?)"
            ))),
        }
    }

    /// A `size_t` field.
    pub(super) fn size(&mut self, what: &str) -> Result<u64> {
        if self.binary {
            Ok(u64::from_le_bytes(self.raw::<8>(what)?))
        } else {
            self.text_u64(what)
        }
    }

    /// An `int` field.
    pub(super) fn int(&mut self, what: &str) -> Result<i32> {
        if self.binary {
            Ok(i32::from_le_bytes(self.raw::<4>(what)?))
        } else {
            self.text_i32(what)
        }
    }

    /// A `double` field.
    pub(super) fn float(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            Ok(f64::from_le_bytes(self.raw::<8>(what)?))
        } else {
            self.text_f64(what)
        }
    }

    /// Minimum bytes of an item of `numbers` fields (at least a digit and a separator each
    /// in ASCII) or `bytes` bytes (binary).
    pub(super) fn item(&self, numbers: u64, bytes: u64) -> u64 {
        if self.binary {
            bytes
        } else {
            2 * numbers
        }
    }

    /// Checks that the rest of the file can hold `count` items of at least `item_bytes`
    /// bytes each, before anything is allocated for them; returns the count as `usize`.
    pub(super) fn guard(&self, count: u64, item_bytes: u64, what: &str) -> Result<usize> {
        let remaining = self.remaining() as u64;
        match count.checked_mul(item_bytes) {
            Some(need) if need <= remaining => Ok(count as usize),
            _ => Err(self.err(format!(
                "the file claims {count} {what}, but the {remaining} bytes left cannot hold them \
                 (truncated or corrupt file)"
            ))),
        }
    }

    /// Consumes the rest of the current line (blanks only) and its line break: binary data
    /// start on the next byte.
    pub(super) fn end_of_line(&mut self, after: &str) -> Result<()> {
        loop {
            match self.bytes.get(self.pos) {
                Some(b' ' | b'\t' | b'\r') => self.pos += 1,
                Some(b'\n') => {
                    self.pos += 1;
                    self.line += 1;
                    return Ok(());
                }
                _ => {
                    self.mark();
                    return Err(self.err(format!("expected the end of the line after {after}")));
                }
            }
        }
    }

    /// Starts the body of section `name`: in a binary file, numbers are read in binary from
    /// the line after the header.
    pub(super) fn begin(&mut self, name: &str) -> Result<()> {
        if self.binary_file {
            self.end_of_line(&format!("`${name}`"))?;
            self.binary = true;
        }
        Ok(())
    }

    /// Reads `$End<name>`.
    pub(super) fn end(&mut self, name: &str) -> Result<()> {
        self.binary = false;
        let expected = format!("$End{name}");
        let t = self.token(&format!("`{expected}`"))?;
        if t != expected.as_bytes() {
            return Err(self.err(format!(
                "expected `{expected}`, found `{}`: the data of ${name} do not match its counts",
                show(t)
            )));
        }
        Ok(())
    }

    /// A name in double quotes, on one line.
    pub(super) fn quoted(&mut self, what: &str) -> Result<String> {
        self.skip_ws();
        self.mark();
        if self.bytes.get(self.pos) != Some(&b'"') {
            return Err(self.err(format!("expected {what} in double quotes")));
        }
        let start = self.pos + 1;
        let rest = self.bytes.get(start..).unwrap_or_default();
        match rest.iter().position(|&b| b == b'"' || b == b'\n') {
            Some(i) if rest[i] == b'"' => {
                let name = String::from_utf8_lossy(&rest[..i]).into_owned();
                self.pos = start + i + 1;
                Ok(name)
            }
            _ => Err(self.err(format!("{what} has no closing double quote on its line"))),
        }
    }

    /// Steps over a section the reader does not use, up to its `$End<name>` line.
    pub(super) fn skip_section(&mut self, name: &str) -> Result<()> {
        let end = format!("$End{name}");
        let end = end.as_bytes();
        let rest = self.bytes.get(self.pos..).unwrap_or_default();
        let mut found = None;
        for (i, _) in rest.iter().enumerate().filter(|(_, &b)| b == b'$') {
            let starts_line = i == 0 || rest[i - 1].is_ascii_whitespace();
            let after = rest.get(i + end.len());
            if starts_line
                && rest.get(i..i + end.len()) == Some(end)
                && after.is_none_or(|b| b.is_ascii_whitespace())
            {
                found = Some(i);
                break;
            }
        }
        let Some(i) = found else {
            return Err(self.err(format!(
                "section `${name}` has no `$End{name}` (truncated file?)"
            )));
        };
        if !self.binary_file {
            self.line += rest[..i].iter().filter(|&&b| b == b'\n').count() as u64;
        }
        self.pos += i + end.len();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locations_display_as_line_or_byte() {
        let e = Error::MeshFile {
            file: "a.msh".into(),
            location: FileLocation::Line(12),
            message: "bad".into(),
        };
        assert_eq!(e.to_string(), "a.msh:12: bad");
        let e = Error::MeshFile {
            file: "a.msh".into(),
            location: FileLocation::Byte(7),
            message: "bad".into(),
        };
        assert_eq!(e.to_string(), "a.msh (byte 7): bad");
    }

    #[test]
    fn tokens_track_lines_and_reject_bad_numbers() {
        let mut r = Reader::new(b"1\n\n  -2 x", "t");
        assert_eq!(r.text_u64("a").unwrap(), 1);
        assert_eq!(r.text_i32("b").unwrap(), -2);
        assert_eq!(r.at, FileLocation::Line(3));
        let e = r.text_u64("c").unwrap_err().to_string();
        assert!(
            e.starts_with("t:3: expected c (a non-negative integer), found `x`"),
            "{e}"
        );
        let e = r.text_u64("d").unwrap_err().to_string();
        assert!(e.contains("unexpected end of file"), "{e}");
    }

    #[test]
    fn guard_refuses_counts_the_file_cannot_hold() {
        let r = Reader::new(b"0123456789", "t");
        assert_eq!(r.guard(5, 2, "x").unwrap(), 5);
        assert!(r.guard(6, 2, "x").is_err());
        assert!(r.guard(u64::MAX, 2, "x").is_err());
    }
}
