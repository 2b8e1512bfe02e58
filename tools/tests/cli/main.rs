//! The `lazysolid` binary as a user runs it, including the ways it must fail clearly.
//!
//! One test binary (`cargo test -p lazysolid-tools --test cli`), so the tests cost one link: a
//! module per subcommand (the bench suites under `bench`), a module per check that cuts across
//! them (help, renamed flags, revision, unwritable outputs, assets, photos of any size as
//! exemplars), and the helpers they share in `support`.

mod assets;
mod bench;
mod damaged_inputs;
mod device;
mod diff;
mod fracture;
mod help;
mod multiscale;
mod photos;
mod renamed_flags;
mod render;
mod revision;
mod solid;
mod support;
mod synth;
mod unwritable_outputs;
