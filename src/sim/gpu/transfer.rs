//! Copies between the host and the simulation's state buffers: uploads of whole states and
//! readbacks of the state and surface, each a one-shot command buffer after the frames in
//! flight have finished.

use super::{GpuSim, ObjectState};
use crate::sim::gpu_types::{Particle, SurfaceVertex};
use crate::vk::{Access, Buffer, BufferBarrier, BufferUsage, GpuContext, MemoryKind, Recorder, VkError};
use anyhow::{Context as _, Result};

/// The word that fills a contact list buffer to make every list invalid: the fused kernel's
/// `LIST_VALID` word is then not 1, and per stage every particle's list was built at infinity.
pub(super) const LISTS_INVALID: u32 = 0x7F80_0000;

/// Fills the first `bytes` of `buffers` (each with its word), state the kernels carry from
/// frame to frame, between the frames that use them: the contact lists with `LISTS_INVALID`
/// (not their counters), the BDF2 histories with zero ("none"). Recorded before a frame
/// whenever something outside the kernels changed the state or the parameters.
pub(super) fn record_cleared(rec: &mut Recorder<'_>, buffers: &[(&Buffer, u64, u32)]) {
    if buffers.is_empty() {
        return;
    }
    let around = |src, dst| buffers.iter().map(|(b, ..)| BufferBarrier::new(b, src, dst)).collect::<Vec<_>>();
    rec.barrier(&around(Access::ComputeOrIndirect, Access::TransferWrite));
    for (b, bytes, word) in buffers {
        rec.fill_range(b, 0, *bytes, *word);
    }
    rec.barrier(&around(Access::TransferWrite, Access::ComputeOrIndirect));
}

impl GpuSim {
    /// Replaces every object's state (positions, velocities, pins) with `states[i]`.
    pub fn upload_states(&mut self, ctx: &GpuContext, states: &[Vec<Particle>]) -> Result<()> {
        self.lists_stale = true;
        self.history_stale = true;
        anyhow::ensure!(states.len() == self.objects.len(), "one state per object");
        for (s, o) in states.iter().zip(&self.objects) {
            anyhow::ensure!(s.len() == o.particles as usize, "state size does not match the object");
        }
        let bytes: u64 = states.iter().map(|s| std::mem::size_of_val(s.as_slice()) as u64).sum();
        let mut staging =
            Buffer::new(ctx, "upload staging", bytes, BufferUsage::TRANSFER_SRC, MemoryKind::Upload)?;
        self.wait_all(ctx)?;
        let result = (|| -> Result<(), VkError> {
            let mut offset = 0;
            for s in states {
                staging.write(offset, s)?;
                offset += std::mem::size_of_val(s.as_slice()) as u64;
            }
            ctx.one_shot("upload", |rec| {
                let mut offset = 0;
                for (s, o) in states.iter().zip(&self.objects) {
                    let size = std::mem::size_of_val(s.as_slice()) as u64;
                    rec.copy_buffer_region(&staging, offset, &o.state[0], 0, size);
                    offset += size;
                }
                // The spatial hash counts start at zero (the scan re-zeroes them every substep),
                // also for objects fused now, which may run per stage later.
                let counts: Vec<_> =
                    self.objects.iter().filter_map(|o| o.hash.as_ref().map(|h| &h.counts)).collect();
                rec.barrier(
                    &counts
                        .iter()
                        .map(|c| BufferBarrier::new(c, Access::ComputeReadWrite, Access::TransferWrite))
                        .collect::<Vec<_>>(),
                );
                for c in &counts {
                    rec.fill_buffer(c, 0);
                }
                // The inter-object contact sums and the scene hash's counts start at zero (the
                // contact pass rewrites the sums and the scan re-zeroes the counts every substep).
                let scene_counts = self.contact.as_ref().map(|c| &c.counts);
                if let Some(counts) = scene_counts {
                    rec.barrier(&[BufferBarrier::new(
                        counts,
                        Access::ComputeReadWrite,
                        Access::TransferWrite,
                    )]);
                }
                for c in self.objects.iter().filter_map(|o| o.contact.as_ref()).chain(scene_counts) {
                    rec.fill_buffer(c, 0);
                }
                let to_compute: Vec<_> = self
                    .objects
                    .iter()
                    .map(|o| BufferBarrier::new(&o.state[0], Access::TransferWrite, Access::ComputeReadWrite))
                    .chain(
                        self.objects
                            .iter()
                            .filter_map(|o| o.contact.as_ref())
                            .chain(scene_counts)
                            .map(|c| BufferBarrier::new(c, Access::TransferWrite, Access::ComputeReadWrite)),
                    )
                    .chain(
                        counts
                            .iter()
                            .map(|c| BufferBarrier::new(c, Access::TransferWrite, Access::ComputeReadWrite)),
                    )
                    .collect();
                rec.barrier(&to_compute);
                Ok(())
            })
        })();
        staging.destroy(ctx);
        self.surface_stale = true;
        if result.is_ok() {
            // The energy check starts again from what was written.
            self.start_energy(&super::energy::states_of(states));
        }
        result.context("uploading the simulation state")
    }

    /// Copies every object's state and surface back to the host.
    pub fn read_states(&mut self, ctx: &GpuContext) -> Result<Vec<ObjectState>> {
        self.wait_all(ctx)?;
        let p = std::mem::size_of::<Particle>() as u64;
        let s = std::mem::size_of::<SurfaceVertex>() as u64;
        let bytes: u64 = self.objects.iter().map(|o| o.particles as u64 * p + o.surface_len as u64 * s).sum();
        let readback = Buffer::new(ctx, "readback", bytes, BufferUsage::TRANSFER_DST, MemoryKind::Readback)?;
        let result = (|| -> Result<Vec<ObjectState>> {
            ctx.one_shot("readback", |rec| {
                let to_copy: Vec<_> = self
                    .objects
                    .iter()
                    .flat_map(|o| {
                        [
                            BufferBarrier::new(&o.state[0], Access::ComputeWrite, Access::TransferRead),
                            BufferBarrier::new(&o.surface, Access::ComputeWrite, Access::TransferRead),
                        ]
                    })
                    .collect();
                rec.barrier(&to_copy);
                let mut offset = 0;
                for o in &self.objects {
                    rec.copy_buffer_region(&o.state[0], 0, &readback, offset, o.particles as u64 * p);
                    offset += o.particles as u64 * p;
                    rec.copy_buffer_region(&o.surface, 0, &readback, offset, o.surface_len as u64 * s);
                    offset += o.surface_len as u64 * s;
                }
                let back: Vec<_> = self
                    .objects
                    .iter()
                    .flat_map(|o| {
                        [
                            BufferBarrier::new(&o.state[0], Access::TransferRead, Access::ComputeReadWrite),
                            BufferBarrier::new(&o.surface, Access::TransferRead, Access::ComputeWrite),
                        ]
                    })
                    .chain([BufferBarrier::new(&readback, Access::TransferWrite, Access::HostRead)])
                    .collect();
                rec.barrier(&back);
                Ok(())
            })?;
            let words: Vec<u8> = readback.read::<u8>(bytes as usize)?;
            let mut at = 0usize;
            let mut take = |len: usize| {
                let slice = &words[at..at + len];
                at += len;
                slice
            };
            Ok(self
                .objects
                .iter()
                .map(|o| ObjectState {
                    particles: bytemuck::pod_collect_to_vec(take(o.particles as usize * p as usize)),
                    surface: bytemuck::pod_collect_to_vec(take(o.surface_len as usize * s as usize)),
                })
                .collect())
        })();
        readback.destroy(ctx);
        result.context("reading the simulation state back")
    }
}
