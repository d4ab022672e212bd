# Newton's side of issue 31's rows: NVIDIA Newton's example_cloth_hanging (64 x 32 cells,
# 10 substeps x 10 iterations; semi_implicit 32 substeps), GPU ms a frame between CUDA events
# around each frame's CUDA-graph launch, after 30 warm-up frames. Newton 1.8.0's example runs
# VBD with self-contact (margin 0.02, gap 0.01); vbd_noself is the same with it off.
# Usage: python3 newton_rows.py SOLVER [FRAMES [WIDTH HEIGHT]] (SOLVER: xpbd, vbd, vbd_noself,
# semi_implicit; the cloth's cells, 64 x 32 unless given; warm-up frames: 30, or FRAMES if fewer).
import statistics
import sys
import types

import warp as wp

import newton
import newton.viewer
from newton.examples.cloth.example_cloth_hanging import Example

wp.config.quiet = True
name = sys.argv[1]
frames = int(sys.argv[2]) if len(sys.argv) > 2 else 300
solver = "vbd" if name == "vbd_noself" else name
width = int(sys.argv[3]) if len(sys.argv) > 4 else 64
height = int(sys.argv[4]) if len(sys.argv) > 4 else 32
args = types.SimpleNamespace(solver=solver, height=height, width=width)
ex = Example(newton.viewer.ViewerNull(num_frames=frames + 100), args)
if name == "vbd_noself":
    ex.solver = newton.solvers.SolverVBD(model=ex.model, iterations=ex.iterations, particle_enable_self_contact=False)
    ex.capture()
for _ in range(min(30, frames)):
    ex.step()
wp.synchronize()
start = wp.Event(enable_timing=True)
end = wp.Event(enable_timing=True)
times = []
for _ in range(frames):
    wp.record_event(start)
    ex.step()
    wp.record_event(end)
    wp.synchronize_event(end)
    times.append(wp.get_event_elapsed_time(start, end))
all_start = wp.Event(enable_timing=True)
all_end = wp.Event(enable_timing=True)
wp.record_event(all_start)
for _ in range(frames):
    ex.step()
wp.record_event(all_end)
wp.synchronize_event(all_end)
back_to_back = wp.get_event_elapsed_time(all_start, all_end) / frames
print(
    f"newton {name} {width}x{height}: per frame mean {statistics.mean(times):.3f} ms, median {statistics.median(times):.3f}, "
    f"min {min(times):.3f}, max {max(times):.3f}; {frames} frames back to back {back_to_back:.3f} ms a frame"
)
