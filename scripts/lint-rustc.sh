#!/usr/bin/env bash
# The compiler of the workspace's own crates in scripts/test.sh (RUSTC_WORKSPACE_WRAPPER): rustc
# with Clippy's lints, every warning an error. The test build then lints the code it compiles,
# so the suite checks each crate once instead of once for `cargo clippy` and again for the
# tests (docs/testing.md, "Where the time goes"). Dependencies are compiled by rustc as always.
# Cargo calls it as `lint-rustc.sh RUSTC ARGS...`; clippy-driver drops the RUSTC argument.
exec clippy-driver "$@" -D warnings
