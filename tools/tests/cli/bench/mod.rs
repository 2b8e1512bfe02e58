//! `lazysolid bench …`: one module per suite, each run at small sizes with the validation layer
//! on, its table, CSV, JSON and figures checked, and its bad arguments refused.

mod ctree;
mod cuts;
mod glints;
mod hash;
mod lazy;
mod normalmaps;
mod prims;
mod psh;
mod solid;
mod synth;
mod textures;
