//! The dependency walk on the device, recorded whole: from the requested voxels of the finest
//! level to every level's set of needed voxels (sorted stage-tagged keys), in one submission
//! that the host waits for once.
//!
//! Every length the walk produces (a stage's expanded set, its unique set, the parents handed
//! to the level above) stays in a word of a small counter buffer on the device: the kernels
//! read their length there (`lazy_deps_expand.comp`, `lazy_deps_unique.comp`,
//! `lazy_deps_parents.comp`, the radix sort's counted form), and `lazy_walk_step.comp` does the
//! arithmetic between them. The buffers come from a pool whose capacities are learned: per
//! level, the largest set and expanded set per requested voxel walked so far, with a margin.
//! A set that outgrows its buffer is clamped (nothing is written past a buffer), the overflow
//! is flagged, and the walk runs again with the capacities the counters demanded: rare once
//! the first requests have taught the pool, and counted in [`WalkSets::attempts`]. The host
//! walk (`deps.rs`) is the reference; the tests compare the two on every request kind.

use super::keys::lazy_key;
use crate::kernels::synth_solid;
use crate::shader_constants::{
    LAZY_WALK_EXPANDED, LAZY_WALK_FIRST_FREE, LAZY_WALK_GROWN, LAZY_WALK_OVERFLOW,
    LAZY_WALK_SORTED, LAZY_WALK_TOTAL,
};
use crate::solid::schedule::LevelSchedule;
use crate::{SynthError, SynthResult};
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Kernel, Recorder};
use lazysolid_compute::prims::{RadixSort, Scan, MAX_ELEMENTS};
use std::sync::Arc;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ExpandPush<'a> {
        levels: DeviceAddress<'a>,
        tagged: DeviceAddress<'a>,
        out_keys: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        count: DeviceAddress<'a>,
        grown: DeviceAddress<'a>,
        range: u32,
        cap: u32,
        level: u32,
        stage: u32,
        cls: u32,
        version: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct TaggedUniquePush<'a> {
        tagged: DeviceAddress<'a>,
        flags: DeviceAddress<'a>,
        out_keys: DeviceAddress<'a>,
        count: DeviceAddress<'a>,
        range: u32,
        cap: u32,
        write: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ParentsPush<'a> {
        levels: DeviceAddress<'a>,
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        count: DeviceAddress<'a>,
        outside: DeviceAddress<'a>,
        fresh: DeviceAddress<'a>,
        or_bits: u64,
        range: u32,
        resolution: u32,
        level: u32,
        stage: u32,
        mode: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct WalkStepPush<'a> {
        words: DeviceAddress<'a>,
        op: u32,
        count: u32,
        demand: u32,
        cap: u32,
        args: u32,
        width: u32,
    }
}

// The scan writes its total to word 0 of the buffer it is given: the counters.
const _: () = assert!(LAZY_WALK_TOTAL == 0);

/// `lazy_walk_step.comp` after a stage's expand.
const STEP_EXPANDED: u32 = 0;
/// `lazy_walk_step.comp` after the scan of a unique pass's heads.
const STEP_KEPT: u32 = 1;
/// `lazy_walk_step.comp` after the scan of a count's flags.
const STEP_COUNT: u32 = 2;
/// `lazy_walk_step.comp`: the workgroup counts of a dispatch over a set.
const STEP_ARGS: u32 = 3;
/// `lazy_walk_step.comp`: a length the host knows (`cap`) into a counter.
const STEP_SET: u32 = 4;

/// Counter words of the workgroup counts (x, y, z) of the dispatches over the current set.
const ARGS_SET: u32 = LAZY_WALK_FIRST_FREE;
/// Counter words of the workgroup counts of the dispatches over a stage's expanded set.
const ARGS_EXPANDED: u32 = ARGS_SET + 3;
/// The first per-level counter word (`Words`).
const LAZY_WALK_COUNTS: u32 = ARGS_EXPANDED + 3;

/// One `lazy_walk_step.comp` operation: `op` on the length at counter `count`, its demand
/// raising counter `demand`, clamped to `cap`.
struct Step {
    op: u32,
    count: u32,
    demand: u32,
    cap: usize,
}

/// Entries every buffer of the pool holds beyond what the ratios ask: small requests (a few
/// voxels walk to a few hundred entries per level) never retry.
const SLACK: usize = 4096;

/// Headroom over the largest ratio seen, so that a request a little larger than the last
/// relative to its voxels does not retry.
const HEADROOM: f64 = 1.25;

/// Walks a request made of at most this many attempts before giving up (each retry at least
/// doubles the capacities that overflowed).
const MAX_ATTEMPTS: u32 = 24;

/// One level's dependency set on the GPU: sorted stage-tagged keys, `len` of them, `fresh`
/// of which the level's state does not hold yet.
pub(crate) struct LevelSet {
    pub tagged: GpuBuffer<u64>,
    pub len: usize,
    pub fresh: usize,
}

/// The requested voxels of a walk: `n` plain keys at `keys` on the device, sorted and unique,
/// each with `or_bits` set to make it a lazy key (a texture position's Morton key becomes its
/// lazy key by setting the bias bits, because every position lies below the bias), and every
/// position below `resolution` (checked on the device; 0: not checked).
#[derive(Clone, Copy)]
pub(crate) struct WalkRequest<'a> {
    pub keys: DeviceAddress<'a>,
    pub n: usize,
    pub or_bits: u64,
    pub resolution: u32,
}

/// The bits that make the Morton key of a position in `[0, 2^(LAZY_AXIS_BITS − 1))³` its lazy
/// key: the bias added to every coordinate sets the bit just above the position's.
pub(crate) fn texture_key_bits() -> u64 {
    lazy_key([0; 3])
}

/// What a walk found: the sets per level (coarsest first) and the attempts it took.
pub(crate) struct WalkSets {
    pub sets: Vec<LevelSet>,
    pub attempts: u32,
}

/// Buffer capacities, in entries, per level: the level's set and its stages' expanded sets.
#[derive(Clone, Debug, PartialEq)]
struct Caps {
    set: Vec<usize>,
    out: Vec<usize>,
}

impl Caps {
    fn max_set(&self) -> usize {
        self.set.iter().copied().max().unwrap_or(1)
    }

    fn max_out(&self) -> usize {
        self.out.iter().copied().max().unwrap_or(1)
    }
}

/// The walk's buffers.
struct Pool {
    caps: Caps,
    /// Level `l`'s final set.
    sets: Vec<Option<GpuBuffer<u64>>>,
    /// The other half of every level's ping-pong between stages.
    spare: GpuBuffer<u64>,
    /// A stage's expanded set; between levels, the parents.
    out: GpuBuffer<u64>,
    /// A unique pass's heads, or the new voxels' flags, scanned in place.
    flags: GpuBuffer<u32>,
}

/// The walk's kernels, scratch and learned capacities.
pub(crate) struct DeviceWalk {
    gpu: Gpu,
    expand: Arc<Kernel>,
    unique: Arc<Kernel>,
    parents: Arc<Kernel>,
    step: Arc<Kernel>,
    scan: Scan,
    sort: RadixSort,
    /// Per level, the largest set length per requested voxel seen (coarsest first).
    set_ratio: Vec<f64>,
    /// Per level, the largest expanded length per requested voxel seen.
    out_ratio: Vec<f64>,
    /// Entries every buffer holds beyond the ratios' ask ([`SLACK`]).
    slack: usize,
    pool: Option<Pool>,
}

/// Word indices of the counters of a walk over `levels` levels.
struct Words {
    levels: u32,
}

impl Words {
    fn count(&self, l: usize) -> u32 {
        LAZY_WALK_COUNTS + l as u32
    }
    fn demand_set(&self, l: usize) -> u32 {
        LAZY_WALK_COUNTS + self.levels + l as u32
    }
    fn demand_out(&self, l: usize) -> u32 {
        LAZY_WALK_COUNTS + 2 * self.levels + l as u32
    }
    fn fresh(&self, l: usize) -> u32 {
        LAZY_WALK_COUNTS + 3 * self.levels + l as u32
    }
    fn errors(&self) -> u32 {
        LAZY_WALK_COUNTS + 4 * self.levels
    }
    fn outside(&self) -> u32 {
        LAZY_WALK_COUNTS + 4 * self.levels + 1
    }
    fn len(&self) -> usize {
        (LAZY_WALK_COUNTS + 4 * self.levels + 2) as usize
    }
}

impl DeviceWalk {
    /// The walk for `levels` levels, with first capacities for a fresh state: a set a few
    /// times the requested voxels at the finest level, a quarter of that a level up (a surface's
    /// voxels), expanded sets several times their set.
    pub fn new(gpu: &Gpu, levels: usize) -> SynthResult<DeviceWalk> {
        let set_ratio: Vec<f64> = (0..levels)
            .map(|l| 4.0 / 4f64.powi((levels - 1 - l) as i32))
            .collect();
        let out_ratio = set_ratio.iter().map(|r| r * 8.0).collect();
        Ok(DeviceWalk {
            gpu: gpu.clone(),
            expand: gpu.kernel(&synth_solid::LAZY_DEPS_EXPAND)?,
            unique: gpu.kernel(&synth_solid::LAZY_DEPS_UNIQUE)?,
            parents: gpu.kernel(&synth_solid::LAZY_DEPS_PARENTS)?,
            step: gpu.kernel(&synth_solid::LAZY_WALK_STEP)?,
            scan: Scan::new(gpu)?,
            sort: RadixSort::new(gpu)?,
            set_ratio,
            out_ratio,
            slack: SLACK,
            pool: None,
        })
    }

    /// Forgets the learned capacities and the slack: the next walks start from buffers of one
    /// entry per level and grow by retries (how the tests reach the retry path).
    pub fn start_small(&mut self) {
        self.set_ratio.fill(0.0);
        self.out_ratio.fill(0.0);
        self.slack = 1;
        self.pool = None;
    }

    /// Hands a walk's sets back to the pool once their level has been synthesized.
    pub fn give_back(&mut self, sets: Vec<LevelSet>) {
        if let Some(pool) = &mut self.pool {
            for ((slot, set), &cap) in pool.sets.iter_mut().zip(sets).zip(&pool.caps.set) {
                if slot.is_none() && set.tagged.len() >= cap {
                    *slot = Some(set.tagged);
                }
            }
        }
    }

    /// Frees the pool (its capacities stay learned): between requests the walk holds nothing.
    pub fn release(&mut self) {
        self.pool = None;
    }

    /// Bytes the pool holds now.
    pub fn bytes(&self) -> u64 {
        self.pool.as_ref().map_or(0, |p| {
            let sets: u64 = p.sets.iter().flatten().map(GpuBuffer::bytes).sum();
            sets + p.spare.bytes() + p.out.bytes() + p.flags.bytes()
        })
    }

    /// Walks `request` through the levels of `schedules` (coarsest first), whose state the
    /// kernels read through `records`; `check` refuses buffers the device cannot hold (the
    /// bytes of one buffer and of the whole pool).
    ///
    /// # Errors
    /// Dependencies outside the state's extent, requested positions outside the texture, sets
    /// past the device's limits, or a GPU failure.
    pub fn walk(
        &mut self,
        records: DeviceAddress<'_>,
        schedules: &[LevelSchedule],
        request: WalkRequest<'_>,
        check: &dyn Fn(&str, u64, u64) -> SynthResult<()>,
    ) -> SynthResult<WalkSets> {
        let levels = schedules.len();
        let words = Words {
            levels: levels as u32,
        };
        for attempt in 1..=MAX_ATTEMPTS {
            let caps = self.caps_for(request.n);
            self.reserve(&caps, check)?;
            let counters = GpuBuffer::new(&self.gpu, "lazy walk counters", words.len())?;
            let pool = self.pool.take().expect("reserved above");
            let gpu = self.gpu.clone();
            let recorded = gpu.submit(|rec| {
                self.record(rec, &pool, &caps, &counters, records, schedules, request)
            });
            self.pool = Some(pool);
            recorded?;
            let w = counters.read()?;
            if w[words.outside() as usize] != 0 {
                return Err(SynthError::Parameter {
                    name: "requested voxels",
                    value: format!(
                        "{} positions outside the texture",
                        w[words.outside() as usize]
                    ),
                    limit: format!(
                        "must lie in 0..{} (the texture's resolution)",
                        request.resolution
                    ),
                });
            }
            let n = request.n.max(1) as f64;
            if w[LAZY_WALK_OVERFLOW as usize] != 0 {
                for l in 0..levels {
                    let (set, out) = (
                        w[words.demand_set(l) as usize] as usize,
                        w[words.demand_out(l) as usize] as usize,
                    );
                    // At least double what overflowed: the demands past the first overflow
                    // were counted on clamped sets and may be short.
                    let grown = |ratio: f64, want: usize, cap: usize| {
                        (ratio * 2.0).max(want.max(2 * cap) as f64 / n)
                    };
                    if set > caps.set[l] {
                        self.set_ratio[l] = grown(self.set_ratio[l], set, caps.set[l]);
                    }
                    if out > caps.out[l] {
                        self.out_ratio[l] = grown(self.out_ratio[l], out, caps.out[l]);
                    }
                }
                continue;
            }
            let errors = w[words.errors() as usize];
            if errors != 0 {
                return Err(SynthError::Parameter {
                    name: "lazy margin",
                    value: format!("{errors} dependencies outside the state's extent"),
                    limit: format!(
                        "dependencies must stay within {} voxels of the texture",
                        super::gpu::LAZY_MARGIN
                    ),
                });
            }
            let pool = self.pool.as_mut().expect("reserved above");
            let mut sets = Vec::with_capacity(levels);
            for l in 0..levels {
                let len = w[words.count(l) as usize] as usize;
                self.set_ratio[l] = self.set_ratio[l].max(len as f64 / n);
                let out = w[words.demand_out(l) as usize] as usize;
                self.out_ratio[l] = self.out_ratio[l].max(out as f64 / n);
                let tagged = pool.sets[l].take().expect("reserved above");
                let fresh = w[words.fresh(l) as usize] as usize;
                sets.push(LevelSet { tagged, len, fresh });
            }
            return Ok(WalkSets {
                sets,
                attempts: attempt,
            });
        }
        Err(SynthError::Parameter {
            name: "lazy dependency walk",
            value: format!("{MAX_ATTEMPTS} attempts"),
            limit: "the sets kept outgrowing their buffers (a GPU fault?)".into(),
        })
    }

    /// The capacities for a request of `n` voxels.
    fn caps_for(&self, n: usize) -> Caps {
        let of = |ratio: f64| (ratio * HEADROOM * n as f64).ceil() as usize + self.slack;
        let set: Vec<usize> = self.set_ratio.iter().map(|&r| of(r)).collect();
        let mut set = set;
        if let Some(finest) = set.last_mut() {
            *finest = (*finest).max(n);
        }
        let out = self
            .out_ratio
            .iter()
            .zip(&set)
            .map(|(&r, &s)| of(r).max(s))
            .collect();
        Caps { set, out }
    }

    /// Makes the pool hold at least `caps`.
    fn reserve(
        &mut self,
        caps: &Caps,
        check: &dyn Fn(&str, u64, u64) -> SynthResult<()>,
    ) -> SynthResult<()> {
        let fits = |have: &Caps| {
            have.set.iter().zip(&caps.set).all(|(h, c)| h >= c)
                && have.out.iter().zip(&caps.out).all(|(h, c)| h >= c)
        };
        if let Some(pool) = &self.pool {
            if fits(&pool.caps) && pool.sets.iter().all(Option::is_some) {
                return Ok(());
            }
        }
        let held = self.pool.take().map(|p| p.caps);
        let caps = match held {
            Some(h) => Caps {
                set: h
                    .set
                    .iter()
                    .zip(&caps.set)
                    .map(|(a, b)| *a.max(b))
                    .collect(),
                out: h
                    .out
                    .iter()
                    .zip(&caps.out)
                    .map(|(a, b)| *a.max(b))
                    .collect(),
            },
            None => caps.clone(),
        };
        let largest = caps.max_out().max(caps.max_set());
        if largest > MAX_ELEMENTS {
            return Err(SynthError::Parameter {
                name: "lazy dependency set",
                value: format!("{largest} entries"),
                limit: format!("at most {MAX_ELEMENTS} (split the request)"),
            });
        }
        let total = 8 * (caps.set.iter().sum::<usize>() + caps.max_set() + caps.max_out())
            + 4 * caps.max_out();
        check("the dependency sets", 8 * largest as u64, total as u64)?;
        let gpu = &self.gpu;
        let sets = caps
            .set
            .iter()
            .enumerate()
            .map(|(l, &c)| GpuBuffer::new(gpu, format!("lazy set level {l}"), c).map(Some))
            .collect::<Result<Vec<_>, _>>()?;
        self.pool = Some(Pool {
            spare: GpuBuffer::new(gpu, "lazy walk spare set", caps.max_set())?,
            out: GpuBuffer::new(gpu, "lazy walk expanded set", caps.max_out())?,
            flags: GpuBuffer::new(gpu, "lazy walk flags", caps.max_out())?,
            sets,
            caps,
        });
        Ok(())
    }

    /// Records the whole walk. Every dispatch over a set is indirect, sized on the device by
    /// `lazy_walk_step.comp` from the set's length, and every scan and sort follows a length
    /// on the device: the work follows the sets, not the buffers' capacities.
    #[allow(clippy::too_many_arguments)]
    fn record(
        &mut self,
        rec: &mut Recorder<'_>,
        pool: &Pool,
        caps: &Caps,
        counters: &GpuBuffer<u32>,
        records: DeviceAddress<'_>,
        schedules: &[LevelSchedule],
        request: WalkRequest<'_>,
    ) -> GpuResult<()> {
        let levels = schedules.len();
        let words = Words {
            levels: levels as u32,
        };
        let word = |i: u32| counters.address_at(i as usize);
        let set = |l: usize| pool.sets[l].as_ref().expect("reserved");
        // Level l's stages ping-pong between its set and the spare; it starts where an even
        // number of unique passes ends in its set.
        let start = |l: usize| {
            if schedules[l].final_stage() % 2 == 0 {
                set(l)
            } else {
                &pool.spare
            }
        };
        let finest = levels - 1;
        rec.fill(counters, 0);
        let set_n = Step {
            op: STEP_SET,
            count: words.count(finest),
            demand: 0,
            cap: request.n,
        };
        self.step(rec, counters, set_n)?;
        if request.n > 0 {
            let push = ParentsPush {
                levels: records,
                src: request.keys,
                dst: start(finest).address(),
                count: word(words.count(finest))?,
                outside: word(words.outside())?,
                fresh: DeviceAddress::NULL,
                or_bits: request.or_bits,
                range: request.n as u32,
                resolution: request.resolution,
                level: finest as u32,
                stage: schedules[finest].final_stage(),
                mode: 1,
            };
            rec.dispatch(
                &self.parents,
                self.parents.groups_for(request.n as u64),
                &[],
                &push,
            )?;
        }
        self.args(rec, counters, words.count(finest), ARGS_SET)?;
        for l in (0..levels).rev() {
            let schedule = schedules[l];
            let (mut cur, mut other) = if schedule.final_stage() % 2 == 0 {
                (set(l), &pool.spare)
            } else {
                (&pool.spare, set(l))
            };
            let (cap_set, cap_out) = (caps.set[l], caps.out[l]);
            for stage in (1..=schedule.final_stage()).rev() {
                let cls = schedule.stage_class(stage);
                let expand = ExpandPush {
                    levels: records,
                    tagged: cur.address(),
                    out_keys: pool.out.address(),
                    errors: word(words.errors())?,
                    count: word(words.count(l))?,
                    grown: word(LAZY_WALK_GROWN)?,
                    range: cap_set as u32,
                    cap: cap_out as u32,
                    level: l as u32,
                    stage,
                    cls,
                    version: schedule.version_at(stage, cls),
                };
                rec.dispatch_indirect(&self.expand, counters, ARGS_SET.into(), &[], &expand)?;
                let step = Step {
                    op: STEP_EXPANDED,
                    count: words.count(l),
                    demand: words.demand_out(l),
                    cap: cap_out,
                };
                self.step(rec, counters, step)?;
                self.sort.record_u64_counted(
                    rec,
                    &pool.out,
                    cap_out,
                    word(LAZY_WALK_SORTED)?,
                    64,
                )?;
                self.unique_into(
                    rec,
                    pool,
                    counters,
                    (LAZY_WALK_EXPANDED, ARGS_EXPANDED, cap_out),
                    (other, cap_set, words.count(l), words.demand_set(l)),
                )?;
                std::mem::swap(&mut cur, &mut other);
            }
            debug_assert!(std::ptr::eq(cur, set(l)));
            // The parents of the voxels the state does not hold (the others' are
            // LAZY_NO_KEY), the level above's request, and the flags of the new voxels the
            // level will store, counted for the host.
            let push = ParentsPush {
                levels: records,
                src: set(l).address(),
                dst: pool.out.address(),
                count: word(words.count(l))?,
                outside: DeviceAddress::NULL,
                fresh: pool.flags.address(),
                or_bits: 0,
                range: cap_set as u32,
                resolution: 0,
                level: l as u32,
                stage: if l > 0 {
                    schedules[l - 1].final_stage()
                } else {
                    0
                },
                mode: 0,
            };
            rec.dispatch_indirect(&self.parents, counters, ARGS_SET.into(), &[], &push)?;
            self.scan.record_counted(
                rec,
                &pool.flags,
                &pool.flags,
                cap_set,
                word(words.count(l))?,
                Some(counters),
            )?;
            let step = Step {
                op: STEP_COUNT,
                count: words.fresh(l),
                demand: 0,
                cap: 0,
            };
            self.step(rec, counters, step)?;
            if l == 0 {
                continue;
            }
            self.sort
                .record_u64_counted(rec, &pool.out, cap_set, word(words.count(l))?, 64)?;
            self.unique_into(
                rec,
                pool,
                counters,
                (words.count(l), ARGS_SET, cap_set),
                (
                    start(l - 1),
                    caps.set[l - 1],
                    words.count(l - 1),
                    words.demand_set(l - 1),
                ),
            )?;
        }
        Ok(())
    }

    /// Records the unique pass over the sorted `pool.out` (length at counter `src.0`, its
    /// dispatch's workgroup counts at counter `src.1`, at most `src.2` entries) into `dst.0`
    /// (capacity `dst.1`), its length into counter `dst.2` and its demand into counter
    /// `dst.3`; then the workgroup counts of the new set.
    fn unique_into(
        &mut self,
        rec: &mut Recorder<'_>,
        pool: &Pool,
        counters: &GpuBuffer<u32>,
        src: (u32, u32, usize),
        dst: (&GpuBuffer<u64>, usize, u32, u32),
    ) -> GpuResult<()> {
        let (count, args, range) = src;
        let (out, cap, count_word, demand_word) = dst;
        let flags = TaggedUniquePush {
            tagged: pool.out.address(),
            flags: pool.flags.address(),
            out_keys: DeviceAddress::NULL,
            count: counters.address_at(count as usize)?,
            range: range as u32,
            cap: cap as u32,
            write: 0,
        };
        rec.dispatch_indirect(&self.unique, counters, args.into(), &[], &flags)?;
        self.scan.record_counted(
            rec,
            &pool.flags,
            &pool.flags,
            range,
            counters.address_at(count as usize)?,
            Some(counters),
        )?;
        let step = Step {
            op: STEP_KEPT,
            count: count_word,
            demand: demand_word,
            cap,
        };
        self.step(rec, counters, step)?;
        let write = TaggedUniquePush {
            out_keys: out.address(),
            write: 1,
            ..flags
        };
        rec.dispatch_indirect(&self.unique, counters, args.into(), &[], &write)?;
        self.args(rec, counters, count_word, ARGS_SET)
    }

    /// Records one `lazy_walk_step.comp` operation; `STEP_EXPANDED` also writes the
    /// expanded set's workgroup counts.
    fn step(&self, rec: &mut Recorder<'_>, counters: &GpuBuffer<u32>, s: Step) -> GpuResult<()> {
        let push = WalkStepPush {
            words: counters.address(),
            op: s.op,
            count: s.count,
            demand: s.demand,
            cap: s.cap as u32,
            args: ARGS_EXPANDED,
            width: self.expand.workgroup_size(),
        };
        rec.dispatch(&self.step, [1, 1, 1], &[], &push)
    }

    /// Records the workgroup counts, at counter `args`, of a dispatch over the set whose
    /// length is counter `count`.
    fn args(
        &self,
        rec: &mut Recorder<'_>,
        counters: &GpuBuffer<u32>,
        count: u32,
        args: u32,
    ) -> GpuResult<()> {
        let push = WalkStepPush {
            words: counters.address(),
            op: STEP_ARGS,
            count,
            demand: 0,
            cap: 0,
            args,
            width: self.expand.workgroup_size(),
        };
        rec.dispatch(&self.step, [1, 1, 1], &[], &push)
    }
}
