//! Spatial hash tables on the GPU, each with a plain-Rust reference:
//!
//! - [`RobinHoodTable`]: open addressing with Robin Hood insertion and a max-age table folded
//!   into the cells, with the coherent probe sequence of García, Lefebvre, Hornus and Lasram
//!   (2011) or a randomizing one ([`Probe`]);
//! - [`CuckooTable`]: single-pass cuckoo hashing with four hash functions (Alcantara et al.),
//!   the constant-probe baseline;
//! - [`DenseTable`]: a plain array over the whole universe, the practical limit of any lookup;
//! - [`perfect`]: perfect spatial hashing (Lefebvre and Hoppe 2006), two reads per lookup.
//!
//! Keys are points of a 2D or 3D [`Universe`] laid out as integers ([`KeyLayout`]); payloads
//! are `u32` below [`crate::shader_constants::HASH_NOT_FOUND`]. The cell layouts, the offset
//! table and the limits are described in `docs/hashing.md`.

mod cell;
pub(crate) mod cuckoo;
mod cuckoo_cpu;
pub(crate) mod dense;
mod error;
mod kernels;
mod keys;
pub(crate) mod open_addressing;
pub mod perfect;
mod probe;
pub(crate) mod robin_hood;
mod robin_hood_cpu;
pub(crate) mod validate;

pub use cell::{CellFormat, CellWidth};
pub use cuckoo::{max_iterations as cuckoo_max_iterations, CuckooConfig, CuckooTable};
pub use cuckoo_cpu::{cuckoo_slot_cpu, CuckooCpu, CuckooFunctions};
pub use dense::DenseTable;
pub use error::HashError;
pub use kernels::HashKernels;
pub use keys::{morton_decode, morton_encode, KeyLayout, Universe};
pub use open_addressing::plain_open_addressing_ages;
pub use probe::{fastmod_multiplier, probe_slot, table_mod, Probe};
pub use robin_hood::{AppendScratch, BuildReport, RobinHoodConfig, RobinHoodTable};
pub use robin_hood_cpu::{plain_open_addressing_ages_cpu, RobinHoodCpu};
pub(crate) use validate::CheckCounters;
pub use validate::{validate_keys_cpu, KeyCheck};
