//! What the lazy state keeps and how its buffers grow: the memory policy applied after a
//! request, a level kept in part, the moves of a level's versions into larger buffers, and
//! the device limits every allocation is checked against.

use super::*;

impl GpuLazySolid {
    /// Empties the levels the policy does not keep, cuts back the one it keeps in part, and
    /// fits the others' versions to the voxels they hold (the policy weighs what is kept,
    /// not what a request grew it to); returns how many levels that held voxels were emptied
    /// or cut back.
    pub(super) fn apply_policy(&mut self, last: bool) -> SynthResult<u32> {
        // The budget weighs each level as fitted; only the levels it keeps whole are fitted
        // (one kept in part is rebuilt, one emptied freed), after the request's last chunk
        // (between chunks the levels keep the room they grew, which the next chunk uses),
        // all in one submission.
        let fits = self.policy != MemoryPolicy::Keep;
        let mut moves = Vec::new();
        let bytes: Vec<u64> = if fits {
            self.levels.iter().map(LevelState::fitted_bytes).collect()
        } else {
            self.levels.iter().map(LevelState::bytes).collect()
        };
        let mut changed = false;
        let mut dropped = 0;
        for (l, keep) in self.policy.plan(&bytes).into_iter().enumerate() {
            if self.levels[l].len == 0 {
                continue;
            }
            match keep {
                LevelKeep::All => {
                    if fits && last {
                        if let Some(fitted) = self.levels[l].fitted_slots() {
                            moves.push(self.resize_later(l, fitted)?);
                            changed = true;
                        }
                    }
                }
                LevelKeep::Part(bytes) => {
                    self.keep_part(l, bytes)?;
                    dropped += 1;
                }
                LevelKeep::Nothing => {
                    self.levels[l].clear(&self.gpu, l)?;
                    dropped += 1;
                }
            }
        }
        if !moves.is_empty() {
            self.gpu.submit(|rec| {
                for m in &moves {
                    self.record_move(rec, m)?;
                }
                Ok(())
            })?;
        }
        if dropped > 0 || changed {
            self.write_records()?;
        }
        Ok(dropped)
    }

    /// Keeps of level `l` the voxels that fit in `bytes` (table, versions and counts), the
    /// first ones in Morton order, a region of the level; the rest are recomputed where a
    /// later request needs them.
    pub(super) fn keep_part(&mut self, l: usize, bytes: u64) -> SynthResult<()> {
        let state = &self.levels[l];
        let Some(table) = &state.table else {
            return Ok(());
        };
        let words = 3 * state.stride as usize;
        // A kept voxel's bytes: its versions and count, and its share of the table's cells at
        // the load factor a table is built at; the fitted buffers round up to INITIAL_SLOTS.
        let cell = table.bytes() as f64 / f64::from(table.table_size().max(1));
        let per_voxel = (4 * words + 4) as f64 + cell / table.config().load_factor;
        let estimate = ((bytes as f64 - 2.0 * cell) / per_voxel).max(0.0) as usize;
        let mut keep = estimate
            .saturating_sub(INITIAL_SLOTS)
            .min(state.len as usize);
        let (keys, slots) = table.entries().map_err(|e| hash_error(l, e))?;
        // The table's keys are Morton codes (`lazy_table_key`): the first ones are a region.
        let mut pairs: Vec<(u64, u32)> = keys.into_iter().zip(slots).collect();
        pairs.sort_unstable();
        let (versions, counts) = (state.versions.read()?, state.counts.read()?);
        let universe = state.universe;
        let config = RobinHoodConfig {
            validate: true,
            ..RobinHoodConfig::default()
        };
        // The estimate is checked against the bytes built; past them, fewer voxels.
        while keep > 0 {
            let slots = keep.div_ceil(INITIAL_SLOTS) * INITIAL_SLOTS;
            let mut kept_versions = vec![0u32; slots * words];
            let mut kept_counts = vec![0u32; slots];
            for (i, &(_, s)) in pairs[..keep].iter().enumerate() {
                let s = s as usize;
                kept_versions[i * words..(i + 1) * words]
                    .copy_from_slice(&versions[s * words..(s + 1) * words]);
                kept_counts[i] = counts[s];
            }
            let keys: Vec<u64> = pairs[..keep].iter().map(|p| p.0).collect();
            let payloads: Vec<u32> = (0..keep as u32).collect();
            let table =
                RobinHoodTable::build_from_slices(&self.hash, universe, &keys, &payloads, config)
                    .map_err(|e| hash_error(l, e))?;
            let built = table.bytes() + 4 * (kept_versions.len() + kept_counts.len()) as u64;
            if built > bytes {
                keep = (keep as f64 * bytes as f64 / built as f64 * 0.98) as usize;
                continue;
            }
            let gpu = &self.gpu;
            let state = &mut self.levels[l];
            state.versions =
                GpuBuffer::from_slice(gpu, format!("lazy versions level {l}"), &kept_versions)?;
            state.counts =
                GpuBuffer::from_slice(gpu, format!("lazy counts level {l}"), &kept_counts)?;
            state.table = Some(table);
            state.len = keep as u32;
            return Ok(());
        }
        self.levels[l].clear(&self.gpu, l)
    }

    /// Grows level `l`'s versions and counts to hold `slots` voxels, returning the copy of
    /// what they held for the caller to record before any work reads the level.
    pub(super) fn reserve_later(
        &mut self,
        l: usize,
        slots: usize,
    ) -> SynthResult<Option<MovedLevel>> {
        let state = &self.levels[l];
        let have = state.counts.len();
        if slots <= have {
            return Ok(None);
        }
        let stride = state.stride as usize;
        // Half as much again, so that a level growing over many chunks copies its versions
        // a logarithmic number of times.
        let grown = slots.max(have + have / 2).div_ceil(INITIAL_SLOTS) * INITIAL_SLOTS;
        let words = grown as u64 * 3 * stride as u64;
        if words > u32::MAX as u64 {
            return Err(SynthError::Parameter {
                name: "lazy state",
                value: format!("{grown} voxels at level {l}"),
                limit: format!(
                    "at most {} voxels per level (32-bit word indices)",
                    u32::MAX as u64 / (3 * stride as u64)
                ),
            });
        }
        self.resize_later(l, grown).map(Some)
    }

    /// Moves level `l`'s versions and counts into buffers of `grown` voxels (at least the
    /// voxels it holds), refusing what the device cannot hold, and returns the copy of what
    /// they held for the caller to record before any work reads the level.
    pub(super) fn resize_later(&mut self, l: usize, grown: usize) -> SynthResult<MovedLevel> {
        let stride = self.levels[l].stride as usize;
        let words = grown as u64 * 3 * stride as u64;
        let info = self.gpu.info();
        let kept = self.levels.iter().map(LevelState::bytes).sum::<u64>();
        let old = self.levels[l].versions.bytes() + self.levels[l].counts.bytes();
        check_fits(
            &format!("the versions of level {l}"),
            words * 4,
            kept - old + words * 4 + grown as u64 * 4,
            info.max_memory_allocation_size.min(info.max_buffer_size),
            info.heap_size,
        )?;
        let state = &mut self.levels[l];
        let versions = GpuBuffer::<u32>::new(
            &self.gpu,
            format!("lazy versions level {l}"),
            words as usize,
        )?;
        let counts = GpuBuffer::<u32>::new(&self.gpu, format!("lazy counts level {l}"), grown)?;
        let used = state.len as usize;
        Ok(MovedLevel {
            l,
            versions: std::mem::replace(&mut state.versions, versions),
            counts: std::mem::replace(&mut state.counts, counts),
            used,
        })
    }

    /// Records the copy of a moved level's versions and counts into its new buffers (the
    /// counts past its voxels zeroed).
    pub(super) fn record_move(
        &self,
        rec: &mut lazysolid_compute::gpu::Recorder<'_>,
        m: &MovedLevel,
    ) -> lazysolid_compute::gpu::GpuResult<()> {
        let state = &self.levels[m.l];
        let words = m.used * 3 * state.stride as usize;
        rec.fill(&state.counts, 0);
        rec.copy(&m.versions, 0, &state.versions, 0, words)?;
        rec.copy(&m.counts, 0, &state.counts, 0, m.used)
    }
}

/// Share of the device heap the kept state and one step's buffers may take: the rest is left
/// to the radix sort's scratch, the stores and the renderer.
const HEAP_SHARE: f64 = 0.75;

/// Refuses a buffer of `bytes` (`what`) over the device's largest allocation `max_alloc`, or a
/// request whose kept state and buffers (`total` bytes) would pass [`HEAP_SHARE`] of `heap`,
/// naming the limit.
pub(super) fn check_fits(
    what: &str,
    bytes: u64,
    total: u64,
    max_alloc: u64,
    heap: u64,
) -> SynthResult<()> {
    let mib = |b: u64| format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64);
    if bytes > max_alloc {
        return Err(SynthError::Parameter {
            name: "lazy synthesis request",
            value: format!("{} for {what}", mib(bytes)),
            limit: format!(
                "the device's largest buffer is {} (request fewer voxels at once, or a lower \
                 resolution)",
                mib(max_alloc)
            ),
        });
    }
    let budget = (heap as f64 * HEAP_SHARE) as u64;
    if total > budget {
        return Err(SynthError::Parameter {
            name: "lazy synthesis request",
            value: format!("{} of kept state and buffers at {what}", mib(total)),
            limit: format!(
                "{:.0} % of the device heap, {} (request fewer voxels, or a lower resolution)",
                HEAP_SHARE * 100.0,
                mib(budget)
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::check_fits;

    #[test]
    fn requests_past_the_device_limits_are_refused_with_the_limit() {
        let mib = 1u64 << 20;
        assert!(check_fits("x", 10 * mib, 100 * mib, 128 * mib, 2048 * mib).is_ok());
        let e = check_fits(
            "the versions of level 6",
            200 * mib,
            300 * mib,
            128 * mib,
            2048 * mib,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("200.0 MiB for the versions of level 6") && e.contains("128.0 MiB"),
            "{e}"
        );
        let e = check_fits(
            "the dependency set of level 5",
            10 * mib,
            1600 * mib,
            128 * mib,
            2048 * mib,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("1600.0 MiB") && e.contains("75 % of the device heap, 1536.0 MiB"),
            "{e}"
        );
    }
}
