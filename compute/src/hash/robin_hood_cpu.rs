//! Sequential Robin Hood hashing: the reference the GPU tables are compared with word for word.
//! Entries are totally ordered (age, then payload, then key), and the older-wins rule makes the
//! result the key-optimal stable matching of keys to slots, whatever the insertion order, so a
//! sequential build and a parallel one end in the same table.

use super::cell::CellFormat;
use super::probe::{probe_slot, Probe};
use crate::shader_constants::{HASH_MAX_AGE, HASH_NOT_FOUND};

/// A Robin Hood table in host memory, cells widened to 64 bits.
#[derive(Clone, Debug)]
pub struct RobinHoodCpu {
    /// The cells, with MAT in the age bits once [`RobinHoodCpu::finish`] has run.
    pub cells: Vec<u64>,
    /// The layout.
    pub format: CellFormat,
    /// The probe sequence.
    pub probe: Probe,
    finished: bool,
}

/// Outcome of inserting keys into the CPU reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CpuInsertion {
    /// Keys that would need an age above `HASH_MAX_AGE`.
    pub failed: u32,
    /// Duplicate keys met.
    pub duplicates: u32,
}

impl RobinHoodCpu {
    /// An empty table of `table_size` cells.
    pub fn new(table_size: u32, format: CellFormat, probe: Probe) -> RobinHoodCpu {
        RobinHoodCpu {
            cells: vec![0; table_size as usize],
            format,
            probe,
            finished: false,
        }
    }

    fn table_size(&self) -> u32 {
        self.cells.len() as u32
    }

    /// Inserts `(key, payload)` pairs. A finished table first gets its keys' ages back.
    pub fn insert(&mut self, keys: &[u64], payloads: &[u32]) -> CpuInsertion {
        if self.finished {
            self.restore_ages();
        }
        let f = self.format;
        let mut out = CpuInsertion::default();
        'keys: for (&key, &payload) in keys.iter().zip(payloads) {
            let mut entry = f.pack(1, key, payload);
            loop {
                let slot = probe_slot(
                    self.probe,
                    f.key1(entry) - 1,
                    f.age(entry),
                    self.table_size(),
                ) as usize;
                let prev = self.cells[slot];
                if prev < entry {
                    self.cells[slot] = entry;
                    if prev == 0 {
                        continue 'keys;
                    }
                    entry = prev;
                } else if f.key1(prev) == f.key1(entry) {
                    out.duplicates += 1;
                    continue 'keys;
                }
                if f.age(entry) >= HASH_MAX_AGE {
                    out.failed += 1;
                    continue 'keys;
                }
                entry += 1 << f.age_shift();
            }
        }
        out
    }

    /// Folds the max-age table into the cells (what queries read).
    pub fn finish(&mut self) {
        let f = self.format;
        let n = self.table_size();
        let mut mat = vec![0u32; n as usize];
        for &c in &self.cells {
            if c != 0 {
                let home = probe_slot(self.probe, f.key1(c) - 1, 1, n) as usize;
                mat[home] = mat[home].max(f.age(c));
            }
        }
        for (c, m) in self.cells.iter_mut().zip(mat) {
            if *c != 0 {
                *c = f.with_age(*c, m);
            }
        }
        self.finished = true;
    }

    fn restore_ages(&mut self) {
        let f = self.format;
        let n = self.table_size();
        for s in 0..n {
            let c = self.cells[s as usize];
            if c != 0 {
                let key = f.key1(c) - 1;
                let age = (1..=HASH_MAX_AGE)
                    .find(|&a| probe_slot(self.probe, key, a, n) == s)
                    .unwrap_or(0);
                self.cells[s as usize] = f.with_age(c, age);
            }
        }
        self.finished = false;
    }

    /// The payload of `key`, or `HASH_NOT_FOUND`; the table must be finished.
    pub fn lookup(&self, key: u64) -> u32 {
        assert!(self.finished, "finish() the table before querying it");
        let f = self.format;
        let n = self.table_size();
        let home = self.cells[probe_slot(self.probe, key, 1, n) as usize];
        if home == 0 {
            return HASH_NOT_FOUND;
        }
        for age in 1..=f.age(home) {
            let c = self.cells[probe_slot(self.probe, key, age, n) as usize];
            if f.key1(c) == key + 1 {
                return f.payload(c);
            }
        }
        HASH_NOT_FOUND
    }
}

/// Plain open addressing (first come, first served): the probe step at which each key found an
/// empty slot, 0 past `max_age`. Unlike Robin Hood the result depends on the insertion order;
/// this inserts in the order given.
pub fn plain_open_addressing_ages_cpu(
    keys: &[u64],
    table_size: u32,
    probe: Probe,
    max_age: u32,
) -> Vec<u32> {
    let mut used = vec![false; table_size as usize];
    keys.iter()
        .map(|&k| {
            for age in 1..=max_age {
                let s = probe_slot(probe, k, age, table_size) as usize;
                if !used[s] {
                    used[s] = true;
                    return age;
                }
            }
            0
        })
        .collect()
}
