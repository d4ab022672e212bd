//! Frames in flight (headless `simulate` and `bench --end-to-end` submit the next frame before
//! the last one has finished, as the app does): the state must be exactly what one frame at a
//! time computes, every frame's timing must arrive once, in order, and the offscreen frame must
//! draw the scene with no validation or synchronization-validation message.
//! Run on lavapipe with validation and synchronization validation.

use crate::common;

use common::{assert_clean, gpu, GOOD};
use msdsim::app::offscreen;
use msdsim::render::view::SKY;
use msdsim::scene::{self, Scene};
use msdsim::sim::gpu::GpuSim;

/// The tests' small preset with wind and cloth self-collision: every stage and barrier kind.
fn busy_scene() -> Scene {
    let text = GOOD.replace("pin = \"top_row\"", "pin = \"top_row\"\nself_collision = true")
        + "[wind]\nenabled = true\nmodel = \"paper\"\nforce = 0.05\n";
    scene::parse(&text, "test", &[]).expect("the test preset parses")
}

#[test]
fn frames_in_flight_compute_exactly_what_one_frame_at_a_time_does() {
    let ctx = gpu();
    let model = scene::to_model(&busy_scene());
    const FRAMES: usize = 12;
    for fused in [true, false] {
        let mut one = GpuSim::new(&ctx, &model).unwrap();
        let mut many = GpuSim::new(&ctx, &model).unwrap();
        one.set_fused(&ctx, fused).unwrap();
        many.set_fused(&ctx, fused).unwrap();
        let mut timed_one = 0;
        for _ in 0..FRAMES {
            timed_one += one.step_frame(&ctx).unwrap().is_some() as usize;
        }
        let mut timed_many = 0;
        for _ in 0..FRAMES {
            timed_many += many.submit_frame(&ctx).unwrap().is_some() as usize;
        }
        timed_many += many.finish_frames(&ctx).unwrap().len();
        // A second finish has nothing left to report: each frame's timing arrives once.
        assert!(many.finish_frames(&ctx).unwrap().is_empty());
        assert_eq!(timed_one, timed_many, "fused {fused}: timings of one at a time vs in flight");
        assert!(
            timed_many == 0 || timed_many == FRAMES,
            "fused {fused}: {timed_many} timings for {FRAMES} frames"
        );
        let (a, b) = (one.read_states(&ctx).unwrap(), many.read_states(&ctx).unwrap());
        assert_eq!(many.frames(), FRAMES as u64);
        for (o, (a, b)) in a.iter().zip(&b).enumerate() {
            // Exactly equal: the same commands in the same order, only submitted earlier.
            assert_eq!(a.particles, b.particles, "fused {fused}: object {o}'s state differs");
            assert_eq!(a.surface, b.surface, "fused {fused}: object {o}'s surface differs");
        }
        one.destroy(&ctx);
        many.destroy(&ctx);
    }
    assert_clean(&ctx);
}

#[test]
fn the_end_to_end_frame_draws_the_scene_offscreen() {
    let ctx = gpu();
    let extent = [96, 64];
    let options = offscreen::Options { extent, warmup: 3, frames: 9, fused_slots: None, capture: true };
    let run = offscreen::measure(&ctx, &busy_scene(), options, &mut msdsim::shaders::ShaderSet::embedded())
        .unwrap();
    assert_eq!(run.frames, 9);
    assert!(run.wall_ms > 0.0 && run.frames_per_second().is_finite());
    let pixels = run.pixels.expect("captured");
    assert_eq!(pixels.len(), (extent[0] * extent[1] * 4) as usize);
    let sky = SKY.map(|c| (c * 255.0).round() as i32);
    let drawn = pixels.chunks_exact(4).filter(|p| (0..3).any(|i| (p[i] as i32 - sky[i]).abs() > 2)).count();
    let all = (extent[0] * extent[1]) as usize;
    // The camera is fitted to the objects: they (and the grid) cover part of the frame, the
    // sky the rest.
    assert!(drawn > all / 50 && drawn < all, "{drawn} of {all} pixels differ from the sky");
    if ctx.info().timestamp_period_ns.is_some() {
        assert!(run.sim_gpu.is_some() && run.render_gpu.is_some());
    }
    assert_clean(&ctx);
}

/// A reset while paused (the app's Ctrl+R): the initial state is uploaded, the time starts
/// again from zero, and the surface stage alone (no simulation) makes the surface show the
/// initial state at once: exactly what a new simulation shows before its first step.
#[test]
fn a_reset_surface_shows_the_initial_state_without_simulating() {
    use msdsim::vk::Access;
    let ctx = gpu();
    let model = scene::to_model(&busy_scene());
    let surface_now = |sim: &mut GpuSim| {
        assert!(sim.take_surface_stale(), "the upload left the surface stale");
        ctx.one_shot("surface", |rec| {
            sim.record_surface(rec, Access::ComputeReadWrite);
            Ok(())
        })
        .unwrap();
        sim.read_states(&ctx).unwrap()
    };
    let mut fresh = GpuSim::new(&ctx, &model).unwrap();
    let initial = surface_now(&mut fresh);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    for _ in 0..10 {
        sim.step_frame(&ctx).unwrap();
    }
    assert!(!sim.take_surface_stale());
    let particles: Vec<_> =
        model.objects.iter().map(|o| msdsim::sim::gpu::particles(o, model.frame_dt)).collect();
    sim.upload_states(&ctx, &particles).unwrap();
    sim.reset_time();
    assert_eq!(sim.time(), 0.0);
    let reset = surface_now(&mut sim);
    for (a, b) in initial.iter().zip(&reset) {
        assert_eq!(a.particles, b.particles);
        assert_eq!(a.surface, b.surface, "the surface after a reset is the initial one");
    }
    fresh.destroy(&ctx);
    sim.destroy(&ctx);
    assert_clean(&ctx);
}
