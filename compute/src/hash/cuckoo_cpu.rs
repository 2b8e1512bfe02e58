//! Cuckoo hashing in one table with four hash functions, sequentially: the reference for
//! [`CuckooTable`](super::CuckooTable). Must match `glsl/include/hash/cuckoo.glsl`. Unlike
//! Robin Hood, the final table depends on the insertion order, so the GPU table is compared by
//! what it answers, not cell by cell.

use crate::shader_constants::{CUCKOO_FUNCTIONS, CUCKOO_PRIME, HASH_NOT_FOUND};

/// The constants of the hash functions h_j(k) = ((a_j k + b_j) mod p) mod |H|.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CuckooFunctions {
    /// Multipliers, in 1..p.
    pub a: [u32; 4],
    /// Addends, in 0..p.
    pub b: [u32; 4],
}

impl CuckooFunctions {
    /// Constants drawn from `seed` (attempt `attempt` of a build).
    pub fn from_seed(seed: u64, attempt: u32) -> CuckooFunctions {
        let mut state = seed ^ (attempt as u64).wrapping_mul(0x9e3779b97f4a7c15);
        let mut next = || {
            state = state.wrapping_add(0x9e3779b97f4a7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
            z ^ (z >> 31)
        };
        let mut a = [0u32; 4];
        let mut b = [0u32; 4];
        for j in 0..4 {
            a[j] = 1 + (next() % (CUCKOO_PRIME as u64 - 1)) as u32;
            b[j] = (next() % CUCKOO_PRIME as u64) as u32;
        }
        CuckooFunctions { a, b }
    }
}

/// h_j(key).
pub fn cuckoo_slot_cpu(f: &CuckooFunctions, key: u32, j: u32, table_size: u32) -> u32 {
    (((f.a[j as usize] as u64 * key as u64 + f.b[j as usize] as u64) % CUCKOO_PRIME as u64)
        % table_size as u64) as u32
}

/// A cuckoo table in host memory: cells `[payload : 32 | key + 1 : 32]`, 0 empty.
#[derive(Clone, Debug)]
pub struct CuckooCpu {
    /// The cells.
    pub cells: Vec<u64>,
    /// The hash functions.
    pub functions: CuckooFunctions,
}

impl CuckooCpu {
    /// Inserts `(key, payload)` pairs in order with at most `max_iterations` swaps per key;
    /// returns the number of keys left unplaced (then the table has lost keys).
    pub fn build(
        keys: &[u32],
        payloads: &[u32],
        table_size: u32,
        functions: CuckooFunctions,
        max_iterations: u32,
    ) -> (CuckooCpu, u32) {
        let mut cells = vec![0u64; table_size as usize];
        let mut failed = 0;
        'keys: for (&key, &payload) in keys.iter().zip(payloads) {
            let mut entry = ((payload as u64) << 32) | (key as u64 + 1);
            let mut slot = cuckoo_slot_cpu(&functions, key, 0, table_size);
            for _ in 0..max_iterations {
                let prev = std::mem::replace(&mut cells[slot as usize], entry);
                if prev == 0 {
                    continue 'keys;
                }
                entry = prev;
                let k = (entry as u32).wrapping_sub(1);
                let j = (0..CUCKOO_FUNCTIONS)
                    .find(|&j| cuckoo_slot_cpu(&functions, k, j, table_size) == slot)
                    .unwrap_or(CUCKOO_FUNCTIONS - 1);
                slot = cuckoo_slot_cpu(&functions, k, (j + 1) % CUCKOO_FUNCTIONS, table_size);
            }
            failed += 1;
        }
        (CuckooCpu { cells, functions }, failed)
    }

    /// Builds like the GPU table does: with the constants of attempt 0, 1, … of `seed` until
    /// every key is placed. Returns the table and the failed attempts, or `None` when all
    /// `attempts` failed.
    pub fn build_with_retries(
        keys: &[u32],
        payloads: &[u32],
        table_size: u32,
        seed: u64,
        attempts: u32,
        max_iterations: u32,
    ) -> Option<(CuckooCpu, u32)> {
        (0..attempts).find_map(|attempt| {
            let (table, failed) = Self::build(
                keys,
                payloads,
                table_size,
                CuckooFunctions::from_seed(seed, attempt),
                max_iterations,
            );
            (failed == 0).then_some((table, attempt))
        })
    }

    /// The payload of `key`, or `HASH_NOT_FOUND`.
    pub fn lookup(&self, key: u32) -> u32 {
        let n = self.cells.len() as u32;
        for j in 0..CUCKOO_FUNCTIONS {
            let c = self.cells[cuckoo_slot_cpu(&self.functions, key, j, n) as usize];
            if c as u32 == key.wrapping_add(1) {
                return (c >> 32) as u32;
            }
        }
        HASH_NOT_FOUND
    }
}
