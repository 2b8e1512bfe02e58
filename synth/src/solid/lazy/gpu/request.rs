//! A request's way through the lazy state: positions or device keys in chunks, each chunk's
//! dependency walk and synthesis, and what the caller takes from it (triples, colours or the
//! dependency sets themselves).

use super::memory::check_fits;
use super::*;

impl GpuLazySolid {
    /// Runs `requested` (in the order given) in chunks of
    /// [`GpuLazySolid::set_chunk_voxels`]: per chunk the dependency walk and every level's
    /// synthesis, then `extract(self, first, len)` while the chunk's final versions are stored,
    /// then the policy.
    pub(super) fn run_chunks(
        &mut self,
        requested: Requested<'_>,
        extract: &mut ChunkExtract<'_>,
    ) -> SynthResult<LazyReport> {
        let total = requested.len();
        let mut report = LazyReport::default();
        let mut first = 0;
        loop {
            let len = self.chunk_voxels.min(total - first);
            let start = std::time::Instant::now();
            let before = self.gpu.submissions();
            let host_keys;
            let walk = match requested {
                Requested::Host(keys) => {
                    let mut sorted = keys[first..first + len].to_vec();
                    sorted.sort_unstable();
                    sorted.dedup();
                    host_keys = (!sorted.is_empty())
                        .then(|| GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &sorted))
                        .transpose()?;
                    WalkRequest {
                        keys: host_keys
                            .as_ref()
                            .map_or(DeviceAddress::NULL, GpuBuffer::address),
                        n: sorted.len(),
                        or_bits: 0,
                        resolution: 0,
                    }
                }
                Requested::Device(keys) => WalkRequest {
                    keys: if len == 0 {
                        DeviceAddress::NULL
                    } else {
                        keys.keys.address_at(first)?
                    },
                    n: len,
                    or_bits: texture_key_bits(),
                    resolution: self.resolution,
                },
            };
            let mut r = self.synthesize(walk, start)?;
            r.peak_state_bytes = self.bytes() + self.walk.bytes();
            if len > 0 {
                extract(self, first, len)?;
            }
            report.dropped_levels = self.apply_policy(first + len >= total)?;
            r.waits = self.gpu.submissions().since(before).waits;
            report.add(&r);
            first += len;
            if first >= total {
                break;
            }
        }
        self.walk.release();
        Ok(report)
    }

    /// The dependency sets of the finest-level voxels `requested` given what is stored,
    /// walked on the GPU and read back (what [`dependencies_cpu`](crate::solid::lazy::dependencies_cpu)
    /// computes from the same stored versions).
    ///
    /// # Errors
    /// As [`GpuLazySolid::request`].
    pub fn dependencies(&mut self, requested: &[[i32; 3]]) -> SynthResult<Dependencies> {
        self.check_requested(requested)?;
        let mut keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
        keys.sort_unstable();
        keys.dedup();
        let buffer = (!keys.is_empty())
            .then(|| GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &keys))
            .transpose()?;
        let request = WalkRequest {
            keys: buffer
                .as_ref()
                .map_or(DeviceAddress::NULL, GpuBuffer::address),
            n: keys.len(),
            or_bits: 0,
            resolution: 0,
        };
        let walked = self.walk(request)?;
        let mut levels = Vec::with_capacity(walked.sets.len());
        for set in &walked.sets {
            let tagged = if set.len == 0 {
                Vec::new()
            } else {
                set.tagged.read_range(0, set.len)?
            };
            levels.push(LevelDeps {
                keys: tagged.iter().map(|&t| untag(t).0).collect(),
                need: tagged.iter().map(|&t| untag(t).1 as u8).collect(),
            });
        }
        self.walk.give_back(walked.sets);
        self.walk.release();
        Ok(levels.into())
    }

    pub(super) fn check_requested(&self, requested: &[[i32; 3]]) -> SynthResult<()> {
        let r = self.resolution as i32;
        let limit = format!("must lie in 0..{r} (the texture's resolution)");
        for &p in requested {
            check_within(p, 0..r, &limit)?;
        }
        self.check_count(requested.len())
    }

    /// Refuses a request of more voxels than one walk may hold.
    pub(super) fn check_count(&self, n: usize) -> SynthResult<()> {
        if n > MAX_ELEMENTS / 8 {
            return Err(SynthError::Parameter {
                name: "requested voxels",
                value: n.to_string(),
                limit: format!(
                    "at most {} per request (split the request)",
                    MAX_ELEMENTS / 8
                ),
            });
        }
        Ok(())
    }

    /// Synthesizes the voxels `keys` (sorted Morton keys of positions in the `R³` grid: a
    /// mesh's surface or interpolation voxels, a cut's) and returns their RGBA8 colours on the
    /// device in key order, ready as a
    /// [`ColourSource::Buffer`](lazysolid_compute::store::ColourSource::Buffer) for any store.
    ///
    /// # Errors
    /// As [`GpuLazySolid::request`].
    pub fn colours(&mut self, keys: &VoxelKeys) -> SynthResult<(GpuBuffer<u32>, LazyReport)> {
        let start = std::time::Instant::now();
        let n = keys.len();
        self.check_count(n)?;
        let colours = GpuBuffer::<u32>::new(&self.gpu, "lazy colours", n.max(1))?;
        let errors = GpuBuffer::<u32>::new(&self.gpu, "lazy colour errors", 1)?;
        let mut report = self.run_chunks(Requested::Device(keys), &mut |me, first, len| {
            let push = ColoursPush {
                levels: me.records.address(),
                keys: keys.keys.address_at(first)?,
                rgb: me.rgb.address(),
                colours: colours.address_at(first)?,
                errors: errors.address(),
                n: len as u32,
                level: (me.levels.len() - 1) as u32,
                side: me.synth.side(),
            };
            me.gpu.submit(|rec| {
                if first == 0 {
                    rec.fill(&errors, 0);
                }
                rec.dispatch(&me.colour, me.colour.groups_for(len as u64), &[], &push)
            })?;
            Ok(())
        })?;
        check_errors(&errors, "voxels missing or not final")?;
        report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
        self.last = report.clone();
        Ok((colours, report))
    }

    /// The dependency walk and the synthesis of every level for `request`.
    pub(super) fn synthesize(
        &mut self,
        request: WalkRequest<'_>,
        start: std::time::Instant,
    ) -> SynthResult<LazyReport> {
        if request.n == 0 {
            let zeros = vec![0; self.levels.len()];
            return Ok(LazyReport {
                needed: zeros.clone(),
                computed: zeros.clone(),
                upsampled: zeros,
                ..LazyReport::default()
            });
        }
        let walked = self.walk(request)?;
        let mut report = LazyReport {
            deps_ms: start.elapsed().as_secs_f64() * 1e3,
            walks: walked.attempts,
            ..LazyReport::default()
        };
        let (computed, ms, growths) = self.synthesize_levels(&walked.sets)?;
        report.table_growths = growths;
        report.needed = walked.sets.iter().map(|s| s.len as u64).collect();
        report.upsampled = walked.sets.iter().map(|s| s.fresh as u64).collect();
        report.computed = computed;
        report.gpu_ms = ms;
        self.walk.give_back(walked.sets);
        Ok(report)
    }

    /// The dependency walk on the GPU (`walk.rs`): per level, coarsest first, the sorted
    /// stage-tagged keys.
    pub(super) fn walk(&mut self, request: WalkRequest<'_>) -> SynthResult<WalkSets> {
        let schedules: Vec<LevelSchedule> = self.levels.iter().map(|l| l.schedule).collect();
        let info = self.gpu.info();
        let (max_alloc, heap) = (
            info.max_memory_allocation_size.min(info.max_buffer_size),
            info.heap_size,
        );
        let state = self.bytes();
        let check = move |what: &str, bytes: u64, total: u64| {
            check_fits(what, bytes, state + total, max_alloc, heap)
        };
        self.walk
            .walk(self.records.address(), &schedules, request, &check)
    }

    /// Synthesizes the finest-level voxels `requested` (positions in `[0, R)³`) and returns
    /// their final triples in the same order.
    ///
    /// # Errors
    /// A position outside the texture, state that would exceed the device's limits, or a GPU
    /// failure.
    pub fn request(&mut self, requested: &[[i32; 3]]) -> SynthResult<(Vec<[u32; 3]>, LazyReport)> {
        let start = std::time::Instant::now();
        self.check_requested(requested)?;
        let keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
        let n = keys.len();
        if n == 0 {
            let mut report = self.run_chunks(Requested::Host(&keys), &mut |_, _, _| Ok(()))?;
            report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
            return Ok((Vec::new(), report));
        }
        let keys_buf = GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &keys)?;
        let out = GpuBuffer::<[u32; 3]>::new(&self.gpu, "lazy requested triples", n)?;
        let errors = GpuBuffer::<u32>::new(&self.gpu, "lazy gather errors", 1)?;
        let mut report = self.run_chunks(Requested::Host(&keys), &mut |me, first, len| {
            let push = GatherPush {
                levels: me.records.address(),
                keys: keys_buf.address_at(first)?,
                triples: out.address_at(first)?,
                errors: errors.address(),
                n: len as u32,
                level: (me.levels.len() - 1) as u32,
            };
            me.gpu.submit(|rec| {
                if first == 0 {
                    rec.fill(&errors, 0);
                }
                rec.dispatch(&me.gather, me.gather.groups_for(len as u64), &[], &push)
            })?;
            Ok(())
        })?;
        check_errors(&errors, "requested voxels missing or not final")?;
        let triples = out.read()?;
        report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok((triples, report))
    }
}
