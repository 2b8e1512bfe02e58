//! An on-disk cache of derived data, keyed by content: the exemplar analysis of the 2D
//! synthesizer (and the 3D candidates of the solid synthesizer) costs hundreds of milliseconds
//! to seconds on the CPU but is a pure function of the exemplar's pixels and a few parameters,
//! so a second run of the same exemplar should pay only the synthesis.
//!
//! Two generic parts, so every kind of derived data shares them:
//! - [`KeyBuilder`] hashes (BLAKE3) a kind name, a format version and labelled fields into a
//!   [`CacheKey`]. Each field is framed by its label and length, so two different field
//!   sequences never feed the hash the same bytes. A consumer puts in *everything* its result
//!   depends on, and bumps its format version whenever its algorithm or encoding changes.
//! - [`DiskCache`] stores and loads byte payloads by kind and key, one file per entry:
//!   `DIR/KIND/KEYHEX.bin` with a header (magic, container version, the key again, payload
//!   length, BLAKE3 checksum of the payload). Writes go to a temporary file in the same
//!   folder, then a rename, so a reader sees a whole entry or none; a truncated or altered
//!   file fails the length or checksum test and reads as [`CacheError::Corrupt`], which
//!   callers treat as a miss (recompute, overwrite, warn) — never a panic.
//!
//! [`ByteWriter`] and [`ByteReader`] encode a consumer's payload as little-endian fields and
//! `Pod` slices, with every read bounds-checked.
//!
//! The folder is `LAZYSOLID_CACHE_DIR` when set, else the user's cache folder
//! (`~/.cache/lazysolid` on Linux, from the `dirs` crate).

use bytemuck::Pod;
use lazysolid_compute::atomic_file::{write_atomically, AtomicWriteError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Environment variable that overrides the cache folder.
pub const CACHE_DIR_ENV: &str = "LAZYSOLID_CACHE_DIR";

/// Version of the entry container (header layout); a consumer's payload has its own version
/// inside its key.
const CONTAINER_VERSION: u32 = 1;

/// First bytes of every entry file.
const MAGIC: [u8; 8] = *b"LZSCACHE";

/// Header: magic, container version, key, payload length, payload checksum.
const HEADER_LEN: usize = MAGIC.len() + 4 + 32 + 8 + 32;

/// Why the cache could not be used. None of these stops a computation: callers recompute
/// (and warn) instead.
#[derive(Debug, thiserror::Error)]
pub enum CacheError {
    /// No folder to cache in.
    #[error("no cache folder: {0}")]
    NoFolder(String),
    /// A file system operation failed.
    #[error("{path}: {action}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The system error.
        source: std::io::Error,
    },
    /// Writing an entry failed (the step and the system's reason).
    #[error(transparent)]
    Write(#[from] AtomicWriteError),
    /// An entry exists but is not a whole, unaltered entry for its key.
    #[error("{path}: corrupt cache entry: {reason}")]
    Corrupt {
        /// The entry file.
        path: PathBuf,
        /// Which test it failed.
        reason: String,
    },
    /// A payload does not decode as the consumer's format.
    #[error("cache payload does not decode: {0}")]
    Decode(String),
}

/// The 256-bit content key of one cache entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CacheKey([u8; 32]);

impl CacheKey {
    /// The key as 64 lowercase hexadecimal digits (the entry's file name).
    pub fn hex(&self) -> String {
        self.0.iter().map(|b| format!("{b:02x}")).collect()
    }
}

/// Hashes everything a cached value depends on into a [`CacheKey`].
pub struct KeyBuilder {
    hasher: blake3::Hasher,
}

impl KeyBuilder {
    /// Starts the key of an entry of `kind` (e.g. `"synth-analysis"`) in payload format
    /// `format_version`. The target's byte order is part of every key, since payloads are
    /// written in the machine's layout where they hold `Pod` slices.
    pub fn new(kind: &str, format_version: u32) -> KeyBuilder {
        let builder = KeyBuilder {
            hasher: blake3::Hasher::new(),
        };
        builder
            .bytes("kind", kind.as_bytes())
            .u32("format version", format_version)
            .bytes(
                "byte order",
                if cfg!(target_endian = "little") {
                    b"le"
                } else {
                    b"be"
                },
            )
    }

    /// Adds a field: its label, its length and its bytes.
    pub fn bytes(mut self, label: &str, bytes: &[u8]) -> KeyBuilder {
        for part in [label.as_bytes(), bytes] {
            self.hasher.update(&(part.len() as u64).to_le_bytes());
            self.hasher.update(part);
        }
        self
    }

    /// Adds an integer field.
    pub fn u32(self, label: &str, value: u32) -> KeyBuilder {
        self.bytes(label, &value.to_le_bytes())
    }

    /// Adds a floating-point field by its bits (so `0.1` and the nearest other float differ).
    pub fn f64(self, label: &str, value: f64) -> KeyBuilder {
        self.bytes(label, &value.to_bits().to_le_bytes())
    }

    /// Adds a flag.
    pub fn bool(self, label: &str, value: bool) -> KeyBuilder {
        self.bytes(label, &[value as u8])
    }

    /// The key.
    pub fn finish(self) -> CacheKey {
        CacheKey(*self.hasher.finalize().as_bytes())
    }
}

/// A folder of cache entries.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DiskCache {
    dir: PathBuf,
}

impl DiskCache {
    /// A cache in `dir` (created on the first store).
    pub fn new(dir: impl Into<PathBuf>) -> DiskCache {
        DiskCache { dir: dir.into() }
    }

    /// The user's cache: `LAZYSOLID_CACHE_DIR` when set, else `lazysolid` in the platform's
    /// cache folder.
    ///
    /// # Errors
    /// [`CacheError::NoFolder`] when `LAZYSOLID_CACHE_DIR` is set but empty, or when it is
    /// unset and the platform has no cache folder (no home directory).
    pub fn user() -> Result<DiskCache, CacheError> {
        match std::env::var_os(CACHE_DIR_ENV) {
            Some(dir) if dir.is_empty() => Err(CacheError::NoFolder(format!(
                "{CACHE_DIR_ENV} is set but empty; name a folder or unset it"
            ))),
            Some(dir) => Ok(DiskCache::new(dir)),
            None => dirs::cache_dir()
                .map(|d| DiskCache::new(d.join("lazysolid")))
                .ok_or_else(|| {
                    CacheError::NoFolder(format!(
                        "the platform has no user cache folder; set {CACHE_DIR_ENV}"
                    ))
                }),
        }
    }

    /// The cache folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The file of the entry `key` of `kind`.
    pub fn entry_path(&self, kind: &str, key: &CacheKey) -> PathBuf {
        self.dir.join(kind).join(format!("{}.bin", key.hex()))
    }

    /// The payload stored for `key`, or `None` when there is no entry.
    ///
    /// # Errors
    /// [`CacheError::Corrupt`] for an entry that is truncated, altered or written for another
    /// key; [`CacheError::Io`] when an existing entry cannot be read.
    pub fn load(&self, kind: &str, key: &CacheKey) -> Result<Option<Vec<u8>>, CacheError> {
        let path = self.entry_path(kind, key);
        let mut bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(source) => {
                return Err(CacheError::Io {
                    path,
                    action: "reading the cache entry",
                    source,
                })
            }
        };
        let corrupt = |reason: String| CacheError::Corrupt {
            path: path.clone(),
            reason,
        };
        if bytes.len() < HEADER_LEN {
            return Err(corrupt(format!(
                "{} bytes, shorter than the {HEADER_LEN}-byte header",
                bytes.len()
            )));
        }
        let (header, payload) = bytes.split_at(HEADER_LEN);
        let mut r = ByteReader::new(header);
        let field = |e: CacheError| corrupt(e.to_string());
        if r.take(MAGIC.len()).map_err(field)? != MAGIC {
            return Err(corrupt("not a lazysolid cache entry (magic)".into()));
        }
        let version = r.u32().map_err(field)?;
        if version != CONTAINER_VERSION {
            return Err(corrupt(format!(
                "container version {version}, expected {CONTAINER_VERSION}"
            )));
        }
        if r.take(32).map_err(field)? != key.0 {
            return Err(corrupt("written for another key".into()));
        }
        let len = r.u64().map_err(field)?;
        if len != payload.len() as u64 {
            return Err(corrupt(format!(
                "payload of {} bytes, the header says {len} (truncated?)",
                payload.len()
            )));
        }
        if r.take(32).map_err(field)? != blake3::hash(payload).as_bytes() {
            return Err(corrupt("payload checksum mismatch".into()));
        }
        bytes.drain(..HEADER_LEN);
        Ok(Some(bytes))
    }

    /// Stores `payload` for `key`, replacing any entry: written to a temporary file in the
    /// entry's folder, synced, then renamed over the entry, so no reader ever sees half of it.
    ///
    /// # Errors
    /// [`CacheError::Io`] when the folder cannot be created or the file not written.
    pub fn store(&self, kind: &str, key: &CacheKey, payload: &[u8]) -> Result<(), CacheError> {
        let path = self.entry_path(kind, key);
        let folder = path.parent().expect("an entry lies in a folder").to_owned();
        let io = |path: &Path, action| {
            let path = path.to_owned();
            move |source| CacheError::Io {
                path,
                action,
                source,
            }
        };
        std::fs::create_dir_all(&folder).map_err(io(&folder, "creating the cache folder"))?;
        let mut header = ByteWriter::default();
        header.raw(&MAGIC);
        header.u32(CONTAINER_VERSION);
        header.raw(&key.0);
        header.u64(payload.len() as u64);
        header.raw(blake3::hash(payload).as_bytes());
        let header = header.into_bytes();
        write_atomically(&path, |w| {
            w.write_all(&header)
                .and_then(|()| w.write_all(payload))
                .and_then(|()| w.flush())
                .and_then(|()| w.get_ref().sync_all())
                .map_err(io(&path, "writing the cache entry"))
        })
    }

    /// Removes the entry `key` of `kind`, if there is one.
    ///
    /// # Errors
    /// [`CacheError::Io`] when an existing entry cannot be removed.
    pub fn remove(&self, kind: &str, key: &CacheKey) -> Result<(), CacheError> {
        let path = self.entry_path(kind, key);
        match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(CacheError::Io {
                path,
                action: "removing the cache entry",
                source: e,
            }),
            _ => Ok(()),
        }
    }

    /// The cached value of `key`, or `compute()`'s, stored for the next time. A corrupt entry
    /// is recomputed and overwritten, and an unreadable or unwritable cache only costs the
    /// computation; the returned [`CacheOutcome`] says which happened, so the caller can warn.
    ///
    /// # Errors
    /// Only `compute`'s.
    pub fn get_or_compute<T, E>(
        &self,
        kind: &str,
        key: &CacheKey,
        compute: impl FnOnce() -> Result<T, E>,
        encode: impl FnOnce(&T) -> Vec<u8>,
        decode: impl FnOnce(&[u8]) -> Result<T, CacheError>,
    ) -> Result<(T, CacheOutcome), E> {
        let problem = match self.load(kind, key) {
            Ok(Some(bytes)) => match decode(&bytes) {
                Ok(value) => return Ok((value, CacheOutcome::Hit)),
                Err(e) => Some(
                    CacheError::Corrupt {
                        path: self.entry_path(kind, key),
                        reason: e.to_string(),
                    }
                    .to_string(),
                ),
            },
            Ok(None) => None,
            Err(e) => Some(e.to_string()),
        };
        let value = compute()?;
        let stored = self.store(kind, key, &encode(&value));
        let outcome = match (problem, stored) {
            (None, Ok(())) => CacheOutcome::Miss,
            (Some(reason), Ok(())) => CacheOutcome::Recomputed(reason),
            (problem, Err(e)) => CacheOutcome::NotStored(match problem {
                Some(p) => format!("{p}; {e}"),
                None => e.to_string(),
            }),
        };
        Ok((value, outcome))
    }
}

/// What a cached computation did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CacheOutcome {
    /// Read from the cache.
    Hit,
    /// Computed (no entry yet) and stored.
    Miss,
    /// The entry was corrupt (the reason); recomputed and stored again.
    Recomputed(String),
    /// Computed, but the cache could not be read or written (the reason).
    NotStored(String),
    /// No cache was used.
    Disabled,
}

impl CacheOutcome {
    /// A warning for the user, for the outcomes that deserve one.
    pub fn warning(&self) -> Option<String> {
        match self {
            CacheOutcome::Recomputed(reason) => Some(format!("{reason}; recomputed")),
            CacheOutcome::NotStored(reason) => Some(format!("not cached: {reason}")),
            _ => None,
        }
    }

    /// One word for reports: `hit`, `miss`, `recomputed`, `not stored` or `off`.
    pub fn label(&self) -> &'static str {
        match self {
            CacheOutcome::Hit => "hit",
            CacheOutcome::Miss => "miss",
            CacheOutcome::Recomputed(_) => "recomputed",
            CacheOutcome::NotStored(_) => "not stored",
            CacheOutcome::Disabled => "off",
        }
    }
}

/// Encodes a payload: little-endian scalars and length-prefixed `Pod` slices.
#[derive(Default)]
pub struct ByteWriter {
    bytes: Vec<u8>,
}

impl ByteWriter {
    /// Appends bytes as they are.
    pub fn raw(&mut self, bytes: &[u8]) {
        self.bytes.extend_from_slice(bytes);
    }

    /// Appends an integer.
    pub fn u32(&mut self, v: u32) {
        self.raw(&v.to_le_bytes());
    }

    /// Appends an integer.
    pub fn u64(&mut self, v: u64) {
        self.raw(&v.to_le_bytes());
    }

    /// Appends a float by its bits.
    pub fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }

    /// Appends a slice's element count, then its bytes in the machine's layout (the key
    /// records the byte order).
    pub fn slice<T: Pod>(&mut self, values: &[T]) {
        self.u64(values.len() as u64);
        self.raw(bytemuck::cast_slice(values));
    }

    /// The payload.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }
}

/// Decodes a payload written by [`ByteWriter`]; every read checks the remaining length.
pub struct ByteReader<'a> {
    bytes: &'a [u8],
}

impl<'a> ByteReader<'a> {
    /// Reads from the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> ByteReader<'a> {
        ByteReader { bytes }
    }

    /// The next `n` bytes.
    ///
    /// # Errors
    /// [`CacheError::Decode`] when fewer remain.
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], CacheError> {
        if n > self.bytes.len() {
            return Err(CacheError::Decode(format!(
                "needs {n} more bytes, {} left",
                self.bytes.len()
            )));
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Ok(head)
    }

    /// The next integer.
    ///
    /// # Errors
    /// [`CacheError::Decode`] at the end of the payload.
    pub fn u32(&mut self) -> Result<u32, CacheError> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().expect("4 bytes"),
        ))
    }

    /// The next integer.
    ///
    /// # Errors
    /// [`CacheError::Decode`] at the end of the payload.
    pub fn u64(&mut self) -> Result<u64, CacheError> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }

    /// The next float.
    ///
    /// # Errors
    /// [`CacheError::Decode`] at the end of the payload.
    pub fn f64(&mut self) -> Result<f64, CacheError> {
        self.u64().map(f64::from_bits)
    }

    /// The next slice, which must hold `expected` elements.
    ///
    /// # Errors
    /// [`CacheError::Decode`] for another element count or too few bytes.
    pub fn slice<T: Pod>(&mut self, expected: usize) -> Result<Vec<T>, CacheError> {
        let n = self.u64()?;
        if n != expected as u64 {
            return Err(CacheError::Decode(format!(
                "a slice of {n} elements where {expected} were expected"
            )));
        }
        let bytes = self.take(expected * std::mem::size_of::<T>())?;
        // The payload's bytes need not be aligned for T: copy element by element.
        Ok(bytes
            .chunks_exact(std::mem::size_of::<T>().max(1))
            .map(bytemuck::pod_read_unaligned)
            .collect())
    }

    /// Whether the whole payload was read.
    ///
    /// # Errors
    /// [`CacheError::Decode`] when bytes are left over.
    pub fn finish(self) -> Result<(), CacheError> {
        if self.bytes.is_empty() {
            Ok(())
        } else {
            Err(CacheError::Decode(format!(
                "{} bytes left over",
                self.bytes.len()
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_are_framed() {
        let a = KeyBuilder::new("t", 1).bytes("a", b"bc").finish();
        let b = KeyBuilder::new("t", 1).bytes("ab", b"c").finish();
        let c = KeyBuilder::new("t", 2).bytes("a", b"bc").finish();
        assert_ne!(a, b);
        assert_ne!(a, c);
        assert_eq!(a, KeyBuilder::new("t", 1).bytes("a", b"bc").finish());
        assert_eq!(a.hex().len(), 64);
    }

    #[test]
    fn payload_round_trip_and_bounds() {
        let mut w = ByteWriter::default();
        w.u32(7);
        w.f64(-0.25);
        w.slice(&[1u32, 2, 3]);
        w.slice(&[[1i8, -2], [3, -4]]);
        let bytes = w.into_bytes();
        let mut r = ByteReader::new(&bytes);
        assert_eq!(r.u32().unwrap(), 7);
        assert_eq!(r.f64().unwrap(), -0.25);
        assert_eq!(r.slice::<u32>(3).unwrap(), vec![1, 2, 3]);
        assert_eq!(r.slice::<[i8; 2]>(2).unwrap(), vec![[1, -2], [3, -4]]);
        r.finish().unwrap();
        let mut short = ByteReader::new(&bytes[..10]);
        short.u32().unwrap();
        assert!(matches!(short.f64(), Err(CacheError::Decode(_))));
        let mut wrong = ByteReader::new(&bytes[12..]);
        assert!(matches!(wrong.slice::<u32>(4), Err(CacheError::Decode(_))));
    }
}
