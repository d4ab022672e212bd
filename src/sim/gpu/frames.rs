//! Driving the simulation headless: frames submitted with up to `FRAME_SLOTS` in flight (as
//! the app runs them, so the GPU is not left idle while the host records the next one), or one
//! at a time; each finished frame's timestamps and runtime guard are read after its fence.

use super::object::GUARD_CLEAR;
use super::{GpuSim, FRAME_SLOTS};
use crate::sim::gpu_types::{GUARD_FAST, GUARD_NON_FINITE, GUARD_RUNAWAY, GUARD_STRAIN};
use crate::sim::stability::{GuardCause, GuardTrip};
use crate::vk::{Access, GpuContext};
use anyhow::Result;

/// GPU time of one frame by stage, from timestamps [ms].
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct FrameTiming {
    pub total_ms: f64,
    pub physics_ms: f64,
    pub constraints_ms: f64,
    pub surface_ms: f64,
    /// Where fused objects' time is: `None`, there are none; `Some(true)`, every object is
    /// fused, so `physics_ms` is the whole simulation and the stages are not separable;
    /// `Some(false)`, some are, and their whole step is in `physics_ms`.
    #[serde(skip)]
    pub fused: Option<bool>,
}

impl GpuSim {
    /// Records and submits the next frame without waiting for it. First waits for the frame
    /// that last used its slot (`FRAME_SLOTS` frames back) and returns that frame's GPU timing
    /// (when the device has timestamps), or the runtime guard's report as an error.
    pub fn submit_frame(&mut self, ctx: &GpuContext) -> Result<Option<FrameTiming>> {
        let slot = (self.frames % FRAME_SLOTS as u64) as usize;
        let finished = self.complete(ctx, slot)?;
        let mut rec = self.slots[slot].begin(ctx)?;
        self.record_frame(&mut rec, Access::ComputeReadWrite, slot)?;
        self.slots[slot].submit(ctx, rec)?;
        self.unread[slot] = true;
        Ok(finished)
    }

    /// Waits for every frame in flight; returns their timings, oldest first.
    pub fn finish_frames(&mut self, ctx: &GpuContext) -> Result<Vec<FrameTiming>> {
        let mut timings = Vec::new();
        for i in 0..FRAME_SLOTS as u64 {
            let slot = ((self.frames + i) % FRAME_SLOTS as u64) as usize;
            timings.extend(self.complete(ctx, slot)?);
        }
        Ok(timings)
    }

    /// Simulates one frame and waits for it; returns its GPU timing when available.
    pub fn step_frame(&mut self, ctx: &GpuContext) -> Result<Option<FrameTiming>> {
        self.finish_frames(ctx)?;
        self.submit_frame(ctx)?;
        Ok(self.finish_frames(ctx)?.pop())
    }

    /// Waits for the frame in `slot`, then (once per frame) checks the guard and reads its
    /// timing.
    fn complete(&mut self, ctx: &GpuContext, slot: usize) -> Result<Option<FrameTiming>> {
        self.slots[slot].wait(ctx)?;
        if !std::mem::take(&mut self.unread[slot]) {
            return Ok(None);
        }
        if let Some(trip) = self.check_guard()? {
            return Err(trip.into());
        }
        if let Some(trip) = self.check_energy(ctx)? {
            return Err(trip.into());
        }
        self.read_timing(ctx, slot)
    }

    /// Waits for every frame in flight (their timings stay readable).
    pub(super) fn wait_all(&mut self, ctx: &GpuContext) -> Result<(), crate::vk::VkError> {
        self.slots.iter_mut().try_for_each(|s| s.wait(ctx))
    }

    /// Reads the runtime guard of every object (after the fence of the last recorded frame):
    /// the first object whose state went non-finite or ran away, as a report with advice. The
    /// guard is cleared, so a resumed simulation reports again only if it trips again.
    pub fn check_guard(&mut self) -> Result<Option<GuardTrip>> {
        if let Some(c) = &mut self.contact {
            c.observe(self.model.substeps * self.model.contact_rounds())?;
        }
        let listed: Vec<bool> = self.objects.iter().map(|o| self.lists_on(o)).collect();
        let time = self.time();
        for (i, o) in self.objects.iter_mut().enumerate() {
            let [flags, first, lists_on, lists_rebuilt] = o.guard.read::<u32>(4)?[..] else {
                unreachable!("four words read")
            };
            if listed[i] {
                o.lists.observe([lists_on, lists_rebuilt], self.model.substeps);
            }
            if flags != 0 {
                // Flags and first particle only: words 2 and 3 are the contact lists' counters.
                o.guard.write(0, &GUARD_CLEAR[..2])?;
            }
            let cause = if flags & GUARD_NON_FINITE != 0 {
                Some(GuardCause::NonFinite)
            } else if flags & GUARD_RUNAWAY != 0 {
                Some(GuardCause::Runaway)
            } else if flags & GUARD_STRAIN != 0 {
                Some(GuardCause::Overstretched)
            } else {
                None
            };
            if let Some(cause) = cause {
                return Ok(Some(GuardTrip::new(&self.model, i, first, cause, time)));
            }
            if flags & GUARD_FAST != 0 && !self.warned {
                // Said once per simulation: in the log now, to the app by `take_warning`.
                self.warned = true;
                let o = &self.model.objects[i];
                let limit = crate::sim::collider::contact_speed(&self.model);
                let text = format!(
                    "{} '{}' moved faster than contacts are exact at t = {time:.3} s (particle {first}): {}; \
                     past it a particle can pass through a collider or another object. More substeps raise the limit.",
                    o.kind.label(),
                    o.name,
                    limit.map(|l| l.to_string()).unwrap_or_default()
                );
                log::warn!("{text}");
                self.warning = Some(text);
            }
        }
        Ok(None)
    }

    /// Leaves the contact-speed warning unsaid: for runs that measure a setting (the chart,
    /// `auto`'s calibration), whose error already shows what the warning would, and whose user
    /// did not choose the setting.
    pub fn silence_contact_warning(&mut self) {
        self.warned = true;
    }

    /// The warning that a particle outran the contact speed (`sim::collider::contact_speed`),
    /// once per simulation, the first time it is asked for after it happened.
    pub fn take_warning(&mut self) -> Option<String> {
        self.warning.take()
    }

    /// Per-stage GPU time of the last frame recorded with timestamp `slot`, after its fence.
    pub fn read_timing(&self, ctx: &GpuContext, slot: usize) -> Result<Option<FrameTiming>> {
        let Some(pool) = self.timestamps.get(slot) else { return Ok(None) };
        let ms = |a: f64, b: f64| (b - a).max(0.0) * 1e-6;
        let last = 1 + 2 * self.model.substeps;
        let fused = self.objects.iter().filter(|o| self.is_fused(o)).count();
        let mut timing =
            FrameTiming { fused: (fused > 0).then_some(fused == self.objects.len()), ..Default::default() };
        if self.stage_timing && timing.fused == Some(true) {
            // Every object fused: the pass, then the surface stage (record_frame writes these).
            let [start, pass] = pool.read_range_ns(ctx, 0, 2)?[..] else { return Ok(None) };
            let [surface_start, end] = pool.read_range_ns(ctx, last - 1, 2)?[..] else { return Ok(None) };
            timing.physics_ms = ms(start, pass);
            timing.surface_ms = ms(surface_start, end);
            timing.total_ms = ms(start, end);
        } else if self.stage_timing {
            let t = pool.read_ns(ctx, last + 1)?;
            for s in 0..self.model.substeps as usize {
                timing.physics_ms += ms(t[2 * s], t[2 * s + 1]);
                timing.constraints_ms += ms(t[2 * s + 1], t[2 * s + 2]);
            }
            timing.surface_ms = ms(t[last as usize - 1], t[last as usize]);
            timing.total_ms = ms(t[0], t[last as usize]);
        } else {
            // Only the first and the last timestamps were written.
            let start = pool.read_range_ns(ctx, 0, 1)?;
            let end = pool.read_range_ns(ctx, last, 1)?;
            timing.total_ms = ms(start[0], end[0]);
        }
        Ok(Some(timing))
    }
}
