//! Recording the spatial hash of self-collision on the per-stage path, and its contact lists
//! (glsl/include/lists.glsl). With lists on, the pass that writes a substep's positions notes
//! whether some particle has left its list's skin and if so sets the indirect dispatches of
//! the count, the scan and the scatter, which build the hash; the constraints then search it
//! and rebuild the lists, or else walk the lists. The passes of a substep that rebuilds nothing
//! dispatch no workgroups. With lists off, that pass counts the particles into the hash and
//! every substep scans, scatters and searches it. `ListPolicy` turns the lists off while they
//! do not last.

use super::object::{list_control_range, list_dispatch_offset, GpuObject, HashBuffers, SCAN_BLOCK};
use super::pipelines::{has_creases, Stage};
use super::GpuSim;
use crate::vk::{Access, BufferBarrier, Recorder};

/// Frames the per-stage contact lists (self-contact's, and between objects) stay off once they
/// did not last: a settling cloth comes to rest within a few dozen frames, and a trial that
/// fails costs one frame of rebuilds (docs/PERFORMANCE.md, "Longer lists where cloths keep
/// their edges apart, and shorter pauses").
const LISTS_OFF_FRAMES: u32 = 16;

/// Whether an object's per-stage contact lists are on. A substep that rebuilds them costs more
/// than one without lists (the hash's cells are twice as wide and the lists are written), one
/// that walks them a fraction (measured on the H100, docs/log.md), so they pay only
/// while they last: when more than a quarter of a frame's substeps rebuilt them (a cloth in
/// motion), they are turned off for `LISTS_OFF_FRAMES` frames, then tried again. Either way the
/// contacts found are the same (exact). Driven by the counters the constraints keep, read with
/// the guard after each frame.
#[derive(Debug, Default)]
pub(super) struct ListPolicy {
    off_frames: u32,
    /// The counters at the last read (substeps run with lists on, and rebuilt).
    seen: Option<[u32; 2]>,
    /// Set by `GpuSim::force_contact_lists`.
    forced: Option<bool>,
}

impl ListPolicy {
    pub fn on(&self) -> bool {
        self.forced.unwrap_or(self.off_frames == 0)
    }

    /// After a frame's fence: the counters (`list_counters` in glsl/include/lists.glsl) and
    /// the substeps a frame has.
    pub fn observe(&mut self, counters: [u32; 2], substeps: u32) {
        self.observe_share(counters, substeps, [1, 4]);
    }

    /// `observe`, the lists turned off where more than `share` (a fraction, [numerator,
    /// denominator]) of the substeps rebuilt them.
    pub fn observe_share(&mut self, counters: [u32; 2], substeps: u32, share: [u64; 2]) {
        if let Some(seen) = self.seen {
            let on = counters[0].wrapping_sub(seen[0]);
            let rebuilt = counters[1].wrapping_sub(seen[1]);
            if self.off_frames == 0
                && on >= substeps
                && rebuilt <= on
                && share[1] * rebuilt as u64 > share[0] * on as u64
            {
                self.off_frames = LISTS_OFF_FRAMES;
            }
        }
        self.seen = Some(counters);
    }

    /// The counters were cleared (a stale frame): the next read is a baseline again.
    pub fn restart(&mut self) {
        self.seen = None;
    }

    /// A frame was recorded.
    pub fn frame(&mut self) {
        self.off_frames = self.off_frames.saturating_sub(1);
    }
}

impl GpuSim {
    /// Contact lists (of self-contact on the per-stage path, and between objects) always on or
    /// off (`Some`), or as `ListPolicy`
    /// decides (`None`, the default); for tests and measurements.
    pub fn force_contact_lists(&mut self, on: Option<bool>) {
        for o in &mut self.objects {
            o.lists.forced = on;
        }
        if let Some(c) = &mut self.contact {
            c.policy.forced = on;
        }
    }

    /// Whether object `o`'s substeps use its per-stage contact lists (push constant `lists`).
    pub(super) fn lists_on(&self, o: &GpuObject) -> bool {
        o.hash.is_some() && !self.is_fused(o) && o.lists.on() && !o.pins_move
    }

    /// The objects not fused that use the spatial hash, with their hash buffers.
    pub(super) fn hashed(&self) -> Vec<(&GpuObject, &HashBuffers)> {
        let stepped = self.objects.iter().filter(|o| !self.is_fused(o));
        stepped.filter_map(|o| o.hash.as_deref().map(|h| (o, h))).collect()
    }

    /// Barriers of the spatial hash buffers around the physics stage, which counts into them
    /// (lists off) or notes whether the lists hold: `before` (after the previous constraints)
    /// or after it.
    pub(super) fn hash_barriers_at_physics(&self, before: bool) -> Vec<BufferBarrier<'_>> {
        // With lists on, physics set the dispatches of the hash passes that come next.
        let dispatches = (self.hashed().into_iter())
            .filter(|(o, _)| !before && self.lists_on(o))
            .filter_map(|(o, _)| o.self_list.as_ref())
            .map(|l| BufferBarrier::new(l, Access::ComputeWrite, Access::ComputeOrIndirect));
        self.hashed()
            .into_iter()
            .flat_map(|(_, h)| {
                if before {
                    // The scan zeroed the counts; the scatter read the ranks.
                    vec![
                        BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                        BufferBarrier::new(&h.cell_rank, Access::ComputeRead, Access::ComputeWrite),
                    ]
                } else {
                    // With lists off physics counted; the scan rewrites the starts the last
                    // query read.
                    vec![
                        BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                        BufferBarrier::new(&h.cell_rank, Access::ComputeWrite, Access::ComputeRead),
                        BufferBarrier::new(&h.starts, Access::ComputeRead, Access::ComputeWrite),
                        BufferBarrier::new(&h.block_sums, Access::ComputeRead, Access::ComputeReadWrite),
                    ]
                }
            })
            .chain(dispatches)
            .collect()
    }

    /// Zeroes the control blocks of the per-stage contact lists when a frame starts (each
    /// substep's constraints zero the next one's; this also starts a frame after one of an
    /// odd number of substeps at the right parity).
    pub(super) fn record_list_control_cleared(&self, rec: &mut Recorder<'_>) {
        let lists: Vec<_> = (self.hashed().into_iter())
            .filter(|(o, _)| self.lists_on(o))
            .filter_map(|(o, _)| o.self_list.as_ref().map(|l| (o, l)))
            .collect();
        if lists.is_empty() {
            return;
        }
        let around =
            |src, dst| lists.iter().map(|(_, l)| BufferBarrier::new(l, src, dst)).collect::<Vec<_>>();
        rec.barrier(&around(Access::ComputeOrIndirect, Access::TransferWrite));
        for (o, l) in &lists {
            let (offset, bytes) = list_control_range(o.particles as u64);
            rec.fill_range(l, offset, bytes, 0);
        }
        rec.barrier(&around(Access::TransferWrite, Access::ComputeReadWrite));
    }

    /// The spatial hash of substep `substep` after the physics stage: with lists on, the
    /// count, then (for all) the scan (one dispatch) and the scatter, each ordered after the
    /// one before by a barrier on exactly the buffers it reads; with lists on each is
    /// dispatched indirectly (no workgroups when the lists hold).
    pub(super) fn record_hash_build(&self, rec: &mut Recorder<'_>, substep: u32) {
        let hashed = self.hashed();
        if hashed.is_empty() {
            return;
        }
        let each = |f: &dyn Fn(&HashBuffers) -> Vec<BufferBarrier<'_>>| -> Vec<BufferBarrier<'_>> {
            hashed.iter().flat_map(|(_, h)| f(h)).collect()
        };
        // With lists on, dispatched as the substep's physics set; else every substep.
        let dispatch =
            |rec: &mut Recorder<'_>, o: &GpuObject, stage: Stage, pass: u64, groups: [u32; 3]| match o
                .self_list
                .as_ref()
                .filter(|_| self.lists_on(o))
            {
                Some(l) => {
                    let offset = list_dispatch_offset(o.particles, substep, pass);
                    rec.dispatch_indirect(self.pipelines.get(stage), o.sets[1], l, offset, &[]);
                }
                None => rec.dispatch(self.pipelines.get(stage), o.sets[1], groups),
            };
        let per_particle = |o: &GpuObject| [o.particles.div_ceil(256), 1, 1];
        for (o, _) in hashed.iter().filter(|(o, _)| self.lists_on(o)) {
            dispatch(rec, o, Stage::HashCount, 0, per_particle(o));
        }
        rec.barrier(&each(&|h| {
            vec![
                BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                BufferBarrier::new(&h.cell_rank, Access::ComputeWrite, Access::ComputeRead),
            ]
        }));
        for (o, h) in &hashed {
            dispatch(rec, o, Stage::HashScan, 1, [h.buckets.div_ceil(SCAN_BLOCK as u32), 1, 1]);
        }
        rec.barrier(&each(&|h| {
            vec![
                BufferBarrier::new(&h.starts, Access::ComputeWrite, Access::ComputeRead),
                BufferBarrier::new(&h.block_sums, Access::ComputeWrite, Access::ComputeRead),
                BufferBarrier::new(&h.sorted, Access::ComputeRead, Access::ComputeWrite),
            ]
        }));
        for (o, _) in &hashed {
            dispatch(rec, o, Stage::HashScatter(has_creases(o.plan.features)), 0, per_particle(o));
        }
        // The constraints read the sorted positions, and write the lists and the next
        // substep's control block, which the passes above read as their dispatches.
        let lists = hashed.iter().filter(|(o, _)| self.lists_on(o)).filter_map(|(o, _)| o.self_list.as_ref());
        let mut last =
            each(&|h| vec![BufferBarrier::new(&h.sorted, Access::ComputeWrite, Access::ComputeRead)]);
        last.extend(
            lists.map(|l| BufferBarrier::new(l, Access::ComputeOrIndirect, Access::ComputeReadWrite)),
        );
        // With edge-edge contact the scatter wrote the ring creases the search reads (its
        // shader has that store whatever its specialization, so validation counts it written
        // wherever it is bound: a placeholder without self-contact pairs).
        last.extend(hashed.iter().map(|(o, _)| {
            let pairs = o.self_pairs.as_ref().unwrap_or(&o.placeholder);
            BufferBarrier::new(pairs, Access::ComputeWrite, Access::ComputeReadWrite)
        }));
        rec.barrier(&last);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_go_off_while_most_substeps_rebuild_and_come_back() {
        let mut p = ListPolicy::default();
        p.observe([1000, 7], 16); // the first read is only a baseline
        assert!(p.on());
        p.observe([1016, 10], 16); // 3 of 16 rebuilt: on
        p.frame();
        assert!(p.on());
        p.observe([1032, 15], 16); // 5 of 16: off
        for _ in 0..LISTS_OFF_FRAMES - 1 {
            p.frame();
            assert!(!p.on());
            p.observe([1032, 15], 16); // counters still while off
        }
        p.frame();
        assert!(p.on());
        p.observe([u32::MAX, u32::MAX - 1], 16); // counters that wrap: 4 of 16 since
        p.observe([15, 2], 16);
        assert!(p.on());
        p.observe([31, 7], 16); // 5 of 16
        assert!(!p.on());
        p.forced = Some(false);
        assert!(!p.on());
    }
}
