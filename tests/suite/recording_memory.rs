//! A long USD recording takes the memory of a few frames, not of all of them (issue 29: 20,000
//! frames of the curtain peaked at 5.1 GB when every frame was kept until the end). No GPU: the
//! frames are made up, the recording and its file are the app's.
//!
//! The heap is measured by a counting allocator, per thread (other tests of this binary run on
//! threads of their own), from before the first frame to after the file is written.

use msdsim::export::Recording;
use msdsim::sim::gpu::ObjectState;
use msdsim::sim::gpu_types::{Particle, SurfaceVertex, ROPE_RING};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn count(delta: isize) {
    // try_with: a thread being torn down has no counters left; its allocations go uncounted.
    let _ = LIVE.try_with(|live| {
        let now = live.get() + delta;
        live.set(now);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now)));
    });
}

// SAFETY: every call is passed to the system allocator unchanged; the counting touches only
// const-initialised thread-locals, which never allocate.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size() as isize);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        count(-(layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count(layout.size() as isize);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size as isize - layout.size() as isize);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// Recordings of 150 and 1,500 frames of a 30 x 30 cloth and a 40-node rope (1,236 recorded
/// vertices with the rope's caps: 44 KB a frame of points, normals and velocities; every
/// frame kept would be 67 MB at 1,500, and the text built whole about 200 MB more). Between the
/// two lengths the heap's peak may grow only by the list of frame times (8 bytes a frame,
/// doubled as it grows) and one frame; in all, by the file's write buffer (1 MiB) and 16 frames'
/// worth: a frame being spooled or written, and the text of the meshes' topology (two and a
/// half frames here, whatever the length). The file holds every frame, the last one as added.
#[test]
fn a_long_usd_recording_takes_the_memory_of_a_few_frames() {
    let (short, frame_bytes) = record(150);
    let (long, _) = record(1500);
    println!("the heap grew by {short} bytes over 150 frames, {long} over 1,500 (a frame: {frame_bytes})");
    assert!(
        long - short <= 16 * 1500 + frame_bytes,
        "1,500 frames took {} bytes more than 150 (a frame is {frame_bytes} bytes)",
        long - short
    );
    let allowed = (1 << 20) + 16 * frame_bytes;
    assert!(long <= allowed, "the heap grew by {long} bytes over 1,500 frames (allowed {allowed})");
}

/// Records `frames` made-up frames as USD and checks the file; returns how far the heap grew
/// while recording and writing, and a frame's bytes.
fn record(frames: u64) -> (isize, isize) {
    let text = "[[cloth]]\nname = \"sheet\"\nresolution = [30, 30]\nsize = [1.0, 1.0]\norigin = [0.0, 1.0, 0.0]\nmass = 0.01\nstiffness = { structural = 10.0, shear = 1.0, bending = 1.0 }\n\n[[rope]]\nname = \"cord\"\nnodes = 40\nstart = [0.0, 2.0, 0.0]\nend = [1.0, 2.0, 0.0]\nmass = 0.01\nstiffness = 10.0\nbending_stiffness = 1.0\nradius = 0.02\n";
    let scene = msdsim::scene::parse(text, "memory.toml", &[]).expect("the test scene");
    let model = msdsim::scene::to_model(&scene);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("long.usda");
    let vertices: usize = model.objects.iter().map(|o| o.surface_count()).sum::<usize>() + 2 * ROPE_RING;
    let frame_bytes = 36 * vertices as isize;

    let mut states: Vec<ObjectState> = model
        .objects
        .iter()
        .map(|o| ObjectState {
            particles: vec![Particle::default(); o.particle_count()],
            surface: vec![
                SurfaceVertex { pos: [0.0, 1.0, 0.0, 1.0], normal: [0.0, 1.0, 0.0, 0.0] };
                o.surface_count()
            ],
        })
        .collect();
    let mut recording = Recording::new(&model, &msdsim::export::colors(&scene), &path, Some(frames)).unwrap();
    let start = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(start));
    for f in 0..frames {
        for s in &mut states {
            for (k, v) in s.surface.iter_mut().enumerate() {
                v.pos = [k as f32 * 1e-3, 1.0 + f as f32 * 1e-3, 0.5, 1.0];
            }
            for p in &mut s.particles {
                p.vel = [0.0, f as f32 * 1e-2, 0.0, 0.0];
            }
        }
        recording.add(&states, f as f64 / 60.0).unwrap();
    }
    msdsim::atomic_file::replace_with(&path, false, |w| recording.write_to(w)).unwrap();
    let grown = PEAK.with(Cell::get) - start;

    let usda = std::fs::read_to_string(&path).unwrap();
    // The first frame is the state at time 0: time codes 0 to frames - 1.
    let last = frames - 1;
    assert!(
        usda.contains(&format!("startTimeCode = 0\n    endTimeCode = {last}\n")),
        "time codes 0..={last}"
    );
    let points: Vec<&str> =
        usda.lines().filter(|l| l.trim_start().starts_with(&format!("{last}: ["))).collect();
    // The last frame of each mesh's points, normals, velocities and extent.
    assert_eq!(points.len(), 8, "{:?}", points.iter().map(|l| &l[..60.min(l.len())]).collect::<Vec<_>>());
    let last_y = 1.0 + (frames - 1) as f32 * 1e-3;
    assert!(
        points[0].contains(&format!("(0, {last_y}, 0.5), (0.001, {last_y}, 0.5)")),
        "{}",
        &points[0][..100]
    );
    (grown, frame_bytes)
}
