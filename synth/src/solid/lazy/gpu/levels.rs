//! One chunk's synthesis of every level in two submissions: the lookups and inserts of
//! the walk's sets, then the upsampling and correction of the voxels without a version.

use super::*;

impl GpuLazySolid {
    /// Synthesizes every level's dependency set in two submissions, whatever the number of
    /// levels: first every level's lookups and the inserts of its new voxels (room made
    /// beforehand from the walk's count of them), then every level's upsampling and
    /// correction, coarsest first. Returns per level the versions computed, the device time of
    /// the second submission in milliseconds, and the hash tables made, grown or refilled
    /// (each waits on the host a few times; the growth is geometric).
    pub(super) fn synthesize_levels(
        &mut self,
        sets: &[LevelSet],
    ) -> SynthResult<(Vec<u64>, f64, u32)> {
        let gpu = self.gpu.clone();
        // Room for every level's new voxels: versions and counts (copied at the start of the
        // first submission) and table cells.
        let mut moved = Vec::new();
        let mut growths = 0;
        for (l, set) in sets.iter().enumerate() {
            if set.len == 0 || set.fresh == 0 {
                continue;
            }
            moved.extend(self.reserve_later(l, self.levels[l].len as usize + set.fresh)?);
            let state = &mut self.levels[l];
            let total = u64::from(state.len) + set.fresh as u64;
            match &mut state.table {
                Some(t) => {
                    if t.reserve(total).map_err(|e| hash_error(l, e))? {
                        growths += 1;
                    }
                }
                None => {
                    let config = RobinHoodConfig {
                        validate: true,
                        ..RobinHoodConfig::default()
                    };
                    let t = RobinHoodTable::with_room(&self.hash, state.universe, total, config)
                        .map_err(|e| hash_error(l, e))?;
                    state.table = Some(t);
                    growths += 1;
                }
            }
        }
        self.write_records()?;
        let mut work: Vec<LevelWork> = Vec::new();
        for (l, set) in sets.iter().enumerate() {
            if set.len == 0 {
                continue;
            }
            let n = set.len;
            let fresh = set.fresh;
            let stages = self.levels[l].schedule.final_stage();
            work.push(LevelWork {
                l,
                n,
                fresh,
                base: self.levels[l].len,
                slots: GpuBuffer::new(&gpu, format!("lazy slots level {l}"), n)?,
                flags: GpuBuffer::new(&gpu, format!("lazy new flags level {l}"), n)?,
                totals: GpuBuffer::new(&gpu, format!("lazy new and work level {l}"), 2)?,
                order_keys: GpuBuffer::new(&gpu, format!("lazy order keys level {l}"), n)?,
                order: GpuBuffer::new(&gpu, format!("lazy order level {l}"), n)?,
                new_keys: GpuBuffer::new(&gpu, "lazy new keys", fresh.max(1))?,
                new_payloads: GpuBuffer::new(&gpu, "lazy new slots", fresh.max(1))?,
                append: match (&self.levels[l].table, fresh) {
                    (Some(t), 1..) => Some(t.append_scratch()?),
                    _ => None,
                },
                errors: GpuBuffer::new(&gpu, "lazy synthesis errors", 1)?,
                ranges: GpuBuffer::new(
                    &gpu,
                    format!("lazy stage ranges level {l}"),
                    (stages * LAZY_RANGE_WORDS) as usize,
                )?,
            });
        }
        // Every level's lookups, new slots and inserts.
        gpu.submit(|rec| {
            for m in &moved {
                self.record_move(rec, m)?;
            }
            for w in &work {
                rec.fill(&w.totals, 0);
                rec.fill(&w.errors, 0);
            }
            for w in &work {
                let l = w.l;
                let push = PreparePush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    flags: w.flags.address(),
                    work: w.totals.address_at(1)?,
                    order_keys: w.order_keys.address(),
                    order: w.order.address(),
                    n: w.n as u32,
                    level: l as u32,
                };
                let k = &self.prepare;
                rec.dispatch(k, k.groups_for(w.n as u64), &[], &push)?;
                self.scan
                    .record(rec, &w.flags, &w.flags, w.n, Some(&w.totals))?;
                let (Some(scratch), Some(table)) = (&w.append, &self.levels[l].table) else {
                    continue;
                };
                let push = AssignPush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    offsets: w.flags.address(),
                    new_keys: w.new_keys.address(),
                    new_payloads: w.new_payloads.address(),
                    n: w.n as u32,
                    level: l as u32,
                    base: w.base,
                };
                rec.dispatch(&self.assign, self.assign.groups_for(w.n as u64), &[], &push)?;
                table.record_append(rec, scratch, &w.new_keys, &w.new_payloads, w.fresh)?;
            }
            Ok(())
        })?;
        let mut computed = vec![0u64; sets.len()];
        for w in &mut work {
            let l = w.l;
            let totals = w.totals.read()?;
            if totals[0] as usize != w.fresh {
                return Err(SynthError::Parameter {
                    name: "lazy walk",
                    value: format!("{} new voxels at level {l}", w.fresh),
                    limit: format!("the lookups found {} (a device fault?)", totals[0]),
                });
            }
            computed[l] = u64::from(totals[1]);
            if let Some(scratch) = w.append.take() {
                let table = self.levels[l].table.as_mut().expect("made above");
                let inserted = table
                    .finish_append(scratch, w.fresh)
                    .map_err(|e| hash_error(l, e))?;
                if !inserted {
                    // An age overflowed: the table is as it was; the host insert grows it.
                    table
                        .insert(&w.new_keys, &w.new_payloads, w.fresh)
                        .map_err(|e| hash_error(l, e))?;
                    growths += 1;
                }
            }
            self.levels[l].len += w.fresh as u32;
        }
        self.write_records()?;
        // Every level's upsampling and correction.
        let side = self.synth.side();
        let grouped = self.visit == VisitOrder::Grouped;
        let ((), stamps) = gpu.submit_timed(|rec| {
            rec.timestamp()?;
            for w in &work {
                let l = w.l;
                if computed[l] == 0 {
                    continue;
                }
                let n = w.n;
                let spacing = self.synth.spacing(l);
                let table = self.synth.level_table(l);
                let schedule = self.levels[l].schedule;
                // The correction's visiting order (lazy_prepare.comp) and each stage's
                // stretch of it: a stage visits only the voxels it may correct, side by side
                // in whole SIMD groups. Unsorted, `order` is the identity and every stretch
                // all of it.
                if grouped {
                    self.sort
                        .record_u32_pairs(rec, &w.order_keys, &w.order, n, LAZY_ORDER_BITS)?;
                }
                self.stage_ranges.record(
                    rec,
                    &w.order_keys,
                    &w.ranges,
                    n,
                    schedule,
                    !grouped,
                    self.correct.workgroup_size(),
                )?;
                let push = LazyUpsamplePush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    errors: w.errors.address(),
                    n: n as u32,
                    level: l as u32,
                    side,
                    spacing,
                    seed: self.params.seed,
                    strength: self.params.jitter[l],
                };
                let k = &self.upsample;
                rec.dispatch(k, k.groups_for(n as u64), &[], &push)?;
                for stage in 1..=schedule.final_stage() {
                    let cls = schedule.stage_class(stage);
                    let push = LazyCorrectPush {
                        levels: self.records.address(),
                        table: table.address(),
                        keys: sets[l].tagged.address(),
                        order: w.order.address(),
                        ranges: w.ranges.address(),
                        slots: w.slots.address(),
                        errors: w.errors.address(),
                        level: l as u32,
                        stage,
                        cls,
                        version: schedule.version_at(stage, cls),
                        side,
                        spacing,
                        keep_current: self.params.keep_current as u32,
                        seed: self.params.seed,
                        strength: self.params.jitter[l],
                    };
                    rec.dispatch_indirect(
                        &self.correct,
                        &w.ranges,
                        u64::from((stage - 1) * LAZY_RANGE_WORDS),
                        &[],
                        &push,
                    )?;
                }
            }
            rec.timestamp()
        })?;
        for w in &work {
            check_errors(&w.errors, "dependencies missing during synthesis")?;
        }
        Ok((computed, (stamps[1] - stamps[0]) * 1e-6, growths))
    }
}
