//! Recording the spatial hash of self-collision: the objects that use it, its barriers around
//! the physics stage (which counts the particles into it), and the scan and scatter that build
//! it before the constraints query it.

use super::object::{GpuObject, HashBuffers, SCAN_BLOCK};
use super::pipelines::Stage;
use super::GpuSim;
use crate::vk::{Access, BufferBarrier, Recorder};

impl GpuSim {
    /// The objects that use the spatial hash, with their hash buffers.
    pub(super) fn hashed(&self) -> Vec<(&GpuObject, &HashBuffers)> {
        self.objects.iter().filter_map(|o| o.hash.as_deref().map(|h| (o, h))).collect()
    }

    /// Barriers of the spatial hash buffers around the physics stage, which counts into them:
    /// `before` (after the previous constraints) or after it.
    pub(super) fn hash_barriers_at_physics(&self, before: bool) -> Vec<BufferBarrier<'_>> {
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
                    // The scan reads the counts and rewrites the starts the last query read.
                    vec![
                        BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                        BufferBarrier::new(&h.cell_rank, Access::ComputeWrite, Access::ComputeRead),
                        BufferBarrier::new(&h.starts, Access::ComputeRead, Access::ComputeWrite),
                        BufferBarrier::new(&h.block_sums, Access::ComputeRead, Access::ComputeWrite),
                    ]
                }
            })
            .collect()
    }

    /// The rest of the spatial hash after the physics stage counted the particles: the scan
    /// (one dispatch for tables of one block, else three) and the scatter, each ordered after
    /// the one before by a barrier on exactly the buffers it reads.
    pub(super) fn record_hash_build(&self, rec: &mut Recorder<'_>) {
        let hashed = self.hashed();
        if hashed.is_empty() {
            return;
        }
        let each = |f: &dyn Fn(&HashBuffers) -> Vec<BufferBarrier<'_>>| -> Vec<BufferBarrier<'_>> {
            hashed.iter().flat_map(|(_, h)| f(h)).collect()
        };
        for (o, h) in &hashed {
            rec.dispatch(
                self.pipelines.get(Stage::HashScan(0)),
                o.sets[1],
                [h.buckets.div_ceil(SCAN_BLOCK as u32), 1, 1],
            );
        }
        let multi: Vec<_> = hashed.iter().filter(|(_, h)| h.buckets as u64 > SCAN_BLOCK).collect();
        if !multi.is_empty() {
            rec.barrier(&each(&|h| {
                vec![
                    BufferBarrier::new(&h.starts, Access::ComputeWrite, Access::ComputeReadWrite),
                    BufferBarrier::new(&h.block_sums, Access::ComputeWrite, Access::ComputeReadWrite),
                ]
            }));
            for (o, _) in &multi {
                rec.dispatch(self.pipelines.get(Stage::HashScan(1)), o.sets[1], [1, 1, 1]);
            }
            rec.barrier(&each(&|h| {
                vec![BufferBarrier::new(&h.block_sums, Access::ComputeWrite, Access::ComputeRead)]
            }));
            for (o, h) in &multi {
                rec.dispatch(
                    self.pipelines.get(Stage::HashScan(2)),
                    o.sets[1],
                    [(h.buckets + 1).div_ceil(512), 1, 1],
                );
            }
        }
        rec.barrier(&each(&|h| {
            vec![
                BufferBarrier::new(&h.starts, Access::ComputeWrite, Access::ComputeRead),
                BufferBarrier::new(&h.sorted, Access::ComputeRead, Access::ComputeWrite),
            ]
        }));
        for (o, _) in &hashed {
            rec.dispatch(
                self.pipelines.get(Stage::HashScatter),
                o.sets[1],
                [o.particles.div_ceil(256), 1, 1],
            );
        }
        rec.barrier(&each(&|h| {
            vec![BufferBarrier::new(&h.sorted, Access::ComputeWrite, Access::ComputeRead)]
        }));
    }
}
