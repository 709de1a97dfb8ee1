//! ZIP archives of stored files (no compression), to carry an animation's frames (an SVG
//! or PNG per frame) as one download; and CRC-32, which ZIP and PNG chunks share.
//!
//! The layout is PKWARE's APPNOTE (version 6.3): per file a local header, its name and its
//! bytes; then the central directory (a header per file, pointing back at its local
//! header) and the end-of-central-directory record. Every entry is "stored" (method 0),
//! version 2.0, with the UTF-8 flag (bit 11) set, so names are read as UTF-8 everywhere,
//! a DOS date of 1980-01-01 00:00 (the earliest; no clock is read, so the same files give
//! the same bytes), and no extra fields or ZIP64: at most 65,535 files and 4 GiB less one
//! byte in all (checked, an [`AnimationError::TooLarge`] otherwise).

use std::collections::HashSet;

use super::AnimationError;

/// The table of CRC-32 (IEEE 802.3, the reflected polynomial 0xEDB88320) for each byte.
const CRC_TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut n = 0;
    while n < 256 {
        let mut c = n as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 == 1 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            k += 1;
        }
        table[n] = c;
        n += 1;
    }
    table
};

/// CRC-32 of `bytes` as ZIP, PNG and gzip define it (IEEE 802.3).
///
/// ```
/// assert_eq!(akap::animation::crc32(b"123456789"), 0xCBF4_3926);
/// ```
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32_update(0, bytes)
}

/// Continues CRC-32 `crc` (of the bytes so far) over `bytes`.
pub(crate) fn crc32_update(crc: u32, bytes: &[u8]) -> u32 {
    let mut c = !crc;
    for &b in bytes {
        c = CRC_TABLE[((c ^ u32::from(b)) & 0xFF) as usize] ^ (c >> 8);
    }
    !c
}

/// Most files in one archive (without ZIP64).
pub const MAX_FILES: usize = 0xFFFF;

/// Largest archive, in bytes (without ZIP64, every offset and size fits 32 bits).
pub const MAX_ZIP_BYTES: u64 = 0xFFFF_FFFF;

/// Longest file name, in bytes of UTF-8.
pub const MAX_NAME_BYTES: usize = 1024;

/// Why `name` cannot be a file's name in the archive, if it cannot: empty, too long,
/// absolute (`/a`, `\a`, `C:`), a part that is empty, `.` or `..`, a backslash (a separator
/// on Windows), or a control character.
fn name_problem(name: &str) -> Option<&'static str> {
    let problem = if name.is_empty() {
        "is empty"
    } else if name.len() > MAX_NAME_BYTES {
        "is longer than 1024 bytes"
    } else if name.starts_with('/') {
        "is absolute; names are relative paths like \"frames/0001.svg\""
    } else if name.contains('\\') {
        "has a backslash; separate folders with \"/\""
    } else if name.as_bytes().get(1) == Some(&b':') {
        "starts with a drive letter"
    } else if name.chars().any(char::is_control) {
        "has a control character"
    } else if name.split('/').any(|part| part == "..") {
        "has a \"..\" part, which would leave the folder it is unpacked into"
    } else if name.split('/').any(|part| part.is_empty() || part == ".") {
        "has an empty or \".\" part"
    } else {
        return None;
    };
    Some(problem)
}

fn put16(out: &mut Vec<u8>, v: u16) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

/// Version needed to extract (2.0) and the flags: bit 11, names in UTF-8.
const VERSION: u16 = 20;
const FLAGS: u16 = 1 << 11;
/// MS-DOS time 00:00:00 and date 1980-01-01 ((1980 - 1980) << 9 | 1 << 5 | 1).
const DOS_TIME: u16 = 0;
const DOS_DATE: u16 = (1 << 5) | 1;

/// The fields local and central headers share, from "version needed" to the name's length.
fn common_fields(out: &mut Vec<u8>, crc: u32, size: u32, name_len: u16) {
    put16(out, VERSION);
    put16(out, FLAGS);
    put16(out, 0); // stored
    put16(out, DOS_TIME);
    put16(out, DOS_DATE);
    put32(out, crc);
    put32(out, size); // compressed size
    put32(out, size); // uncompressed size
    put16(out, name_len);
    put16(out, 0); // extra field length
}

/// A ZIP archive holding `files` (name, bytes) stored, in the order given. Names are
/// relative paths with `/` between folders; each is refused (before anything is written)
/// when empty, absolute, with a `..`, `.` or empty part, a backslash or a control
/// character, longer than [`MAX_NAME_BYTES`], or the same as an earlier one.
///
/// ```
/// let zip = akap::animation::write_zip(&[("a.txt", b"hi".as_slice())])?;
/// assert_eq!(&zip[..4], b"PK\x03\x04");
/// assert_eq!(zip.len(), 30 + 5 + 2 + 46 + 5 + 22);
/// # Ok::<(), akap::animation::AnimationError>(())
/// ```
pub fn write_zip<N: AsRef<str>, B: AsRef<[u8]>>(files: &[(N, B)]) -> Result<Vec<u8>, AnimationError> {
    if files.len() > MAX_FILES {
        return Err(AnimationError::TooLarge {
            what: "the ZIP archive",
            size: files.len() as u64,
            limit: MAX_FILES as u64,
            unit: "files",
        });
    }
    let mut seen = HashSet::with_capacity(files.len());
    let mut total: u64 = 22;
    for (name, bytes) in files {
        let name = name.as_ref();
        if let Some(reason) = name_problem(name) {
            return Err(AnimationError::FileName { name: name.to_string(), reason });
        }
        if !seen.insert(name) {
            return Err(AnimationError::FileName { name: name.to_string(), reason: "is given twice" });
        }
        total += 30 + 46 + 2 * name.len() as u64 + bytes.as_ref().len() as u64;
    }
    if total > MAX_ZIP_BYTES {
        return Err(AnimationError::TooLarge {
            what: "the ZIP archive",
            size: total,
            limit: MAX_ZIP_BYTES,
            unit: "bytes",
        });
    }
    // Every size and offset below fits its field: the total does.
    let mut out = Vec::with_capacity(total as usize);
    let mut central = Vec::new();
    for (name, bytes) in files {
        let (name, bytes) = (name.as_ref().as_bytes(), bytes.as_ref());
        let crc = crc32(bytes);
        let offset = out.len() as u32;
        put32(&mut out, 0x0403_4B50);
        common_fields(&mut out, crc, bytes.len() as u32, name.len() as u16);
        out.extend_from_slice(name);
        out.extend_from_slice(bytes);

        put32(&mut central, 0x0201_4B50);
        put16(&mut central, VERSION); // version made by: 2.0, MS-DOS attributes
        common_fields(&mut central, crc, bytes.len() as u32, name.len() as u16);
        put16(&mut central, 0); // comment length
        put16(&mut central, 0); // disk number
        put16(&mut central, 0); // internal attributes
        put32(&mut central, 0); // external attributes
        put32(&mut central, offset);
        central.extend_from_slice(name);
    }
    let directory_offset = out.len() as u32;
    out.extend_from_slice(&central);
    put32(&mut out, 0x0605_4B50);
    put16(&mut out, 0); // this disk
    put16(&mut out, 0); // the directory's disk
    put16(&mut out, files.len() as u16);
    put16(&mut out, files.len() as u16);
    put32(&mut out, central.len() as u32);
    put32(&mut out, directory_offset);
    put16(&mut out, 0); // comment length
    debug_assert_eq!(out.len() as u64, total);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_of_known_strings() {
        // The check value of CRC-32/ISO-HDLC, and two more from its definition.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b""), 0);
        assert_eq!(crc32(b"a"), 0xE8B7_BE43);
        assert_eq!(crc32_update(crc32(b"1234"), b"56789"), 0xCBF4_3926);
    }

    #[test]
    fn names_are_checked() {
        for bad in ["", "/a", "a\\b", "C:x", "a/../b", "..", "a//b", "./a", "a/", "a\u{7}"] {
            assert!(name_problem(bad).is_some(), "{bad:?}");
        }
        for good in ["a", "frames/0001.svg", "é/ü.png", "a..b", ".hidden"] {
            assert_eq!(name_problem(good), None, "{good:?}");
        }
    }
}
