//! lazysolid's own caches: the container every entry is stored in (`DiskCache::load`:
//! magic, version, key, length and checksum) and the payloads inside, the exemplar analysis
//! (`decode_analysis`) and the solid candidates (`decode_candidates`), whose decoders check
//! every size against the exemplar they are asked for.

use crate::mutate;
use crate::oracle::{self, MIB};
use lazysolid_synth::cache::KeyBuilder;
use lazysolid_synth::solid::{
    analyze_solid, candidates_cpu, decode_candidates, encode_candidates, CandidateParams,
    SolidExemplars,
};
use lazysolid_synth::{
    analyze, decode_analysis, encode_analysis, AnalysisParams, DiskCache, Exemplar,
};
use lazysolid_tests::exemplar_crop;
use proptest::prelude::*;
use std::sync::OnceLock;

/// Bytes a decoder may hold per byte of its payload, plus a fixed part: a count in the payload
/// must be checked against the exemplar before it sizes anything.
fn bound(len: usize) -> usize {
    oracle::bound(len, 16, 4 * MIB)
}

/// A 16×20 crop of terra with its analysis, and a 16² crop of leather with its candidates,
/// encoded as the caches store them.
struct Payloads {
    exemplar: Exemplar,
    analysis: Vec<u8>,
    candidates: Vec<u8>,
}

fn payloads() -> &'static Payloads {
    static CELL: OnceLock<Payloads> = OnceLock::new();
    CELL.get_or_init(|| {
        let exemplar = exemplar_crop("terra.pat", 0, 0, 16, 20);
        let analysis = analyze(&exemplar, &AnalysisParams::default()).unwrap();
        let solid = SolidExemplars::new(
            exemplar_crop("leather.pat", 8, 8, 16, 16),
            [None, None, None],
        )
        .unwrap();
        let candidates =
            candidates_cpu(&analyze_solid(&solid), &CandidateParams::default()).unwrap();
        Payloads {
            analysis: encode_analysis(&analysis),
            candidates: encode_candidates(&candidates),
            exemplar,
        }
    })
}

/// A payload as a case: no file of its own to name (its container's path is added by the
/// cache when it reports the entry).
fn payload(bytes: &[u8]) -> oracle::Case<'_> {
    oracle::Case {
        format: "caches",
        name: "",
        bytes,
    }
}

#[test]
fn the_seeds_decode() {
    let p = payloads();
    decode_analysis(&p.analysis, &p.exemplar, &AnalysisParams::default()).unwrap();
    decode_candidates(&p.candidates, 16).unwrap();
}

proptest! {
    #![proptest_config(oracle::config_for(2))]

    /// A damaged entry of either kind is refused with its path (never handed on as a hit).
    #[test]
    fn mutated_entries(analysis in any::<bool>(), edits in mutate::mutations()) {
        let p = payloads();
        let payload = if analysis { &p.analysis } else { &p.candidates };
        let dir = tempfile::tempdir().unwrap();
        let cache = DiskCache::new(dir.path());
        let key = KeyBuilder::new("fuzz", 1).bytes("payload", payload).finish();
        cache.store("fuzz", &key, payload).unwrap();
        let path = cache.entry_path("fuzz", &key);
        let stored = std::fs::read(&path).unwrap();
        let damaged = mutate::apply(&stored, &edits);
        std::fs::write(&path, &damaged).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let case = oracle::Case {
            format: "caches",
            name: &name,
            bytes: &damaged,
        };
        oracle::check(&case, bound(damaged.len()), || match cache.load("fuzz", &key) {
            Ok(Some(read)) if damaged == stored && read == *payload => Ok(()),
            Ok(other) => Err(format!(
                "a damaged entry of {} bytes was read as {:?} bytes",
                damaged.len(),
                other.map(|b| b.len())
            )),
            Err(e) => Err(e.to_string()),
        })?;
    }

    /// A payload that passed its checksum but does not fit the exemplar asked for (another
    /// version's, or a collision) is decoded or refused, never trusted blindly.
    #[test]
    fn mutated_payloads(analysis in any::<bool>(), edits in mutate::mutations()) {
        let p = payloads();
        if analysis {
            let bytes = mutate::apply(&p.analysis, &edits);
            oracle::check(&payload(&bytes), bound(bytes.len()), || {
                decode_analysis(&bytes, &p.exemplar, &AnalysisParams::default())
            })?;
        } else {
            let bytes = mutate::apply(&p.candidates, &edits);
            oracle::check(&payload(&bytes), bound(bytes.len()), || decode_candidates(&bytes, 16))?;
        }
    }
}

/// Payloads that once broke a decoder, each decoded as both kinds.
#[test]
fn regression_cases() {
    let p = payloads();
    for file in crate::regressions("caches") {
        let bytes = std::fs::read(&file).unwrap();
        oracle::check(&payload(&bytes), bound(bytes.len()), || {
            decode_analysis(&bytes, &p.exemplar, &AnalysisParams::default()).map(|_| ())
        })
        .unwrap();
        oracle::check(&payload(&bytes), bound(bytes.len()), || {
            decode_candidates(&bytes, 16).map(|_| ())
        })
        .unwrap();
    }
}
