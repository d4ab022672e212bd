//! Hot reload, headless on the Vulkan device with validation and synchronization validation:
//! the simulation runs from a copy of `glsl/` in a temporary folder, watched for changes.
//! Editing a constant changes the motion; a broken shader keeps the old pipeline and reports
//! the compiler's file:line; restoring it recovers; a header change that would break the host's
//! struct layout is refused. Replaced pipelines are freed only after the frames that used them.

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::shaders::ShaderSet;
use msdsim::sim::gpu::GpuSim;
use msdsim::vk::RetireQueue;
use std::path::Path;
use std::time::{Duration, Instant};

struct Rig {
    ctx: std::sync::Arc<msdsim::vk::GpuContext>,
    shaders: ShaderSet,
    sim: GpuSim,
    retired: RetireQueue,
    frame_dt: f64,
}

impl Rig {
    /// Vertical acceleration over one frame [m/s^2] (free particles: gravity alone).
    fn acceleration(&mut self) -> f64 {
        let v0 = self.sim.read_states(&self.ctx).unwrap()[0].particles[0].vel[1] as f64;
        self.sim.step_frame(&self.ctx).unwrap();
        // step_frame waited for the frame: every frame recorded so far has completed.
        self.retired.release(&self.ctx, self.sim.frames());
        let v1 = self.sim.read_states(&self.ctx).unwrap()[0].particles[0].vel[1] as f64;
        (v1 - v0) / self.frame_dt
    }

    /// Waits (up to 10 s) for the watcher to report changed shaders, then reloads them.
    fn reload(&mut self) -> (Vec<String>, Vec<String>) {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            let changes = self.shaders.changes();
            if !changes.shaders.is_empty() {
                let (reloaded, old) = self.sim.reload(&self.ctx, &mut self.shaders, &changes.shaders);
                self.retired.push(self.sim.frames(), old);
                return (changes.shaders, reloaded);
            }
            assert!(Instant::now() < deadline, "the watcher saw no change within 10 s");
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

#[test]
fn edit_break_restore_and_a_refused_header_change() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("glsl");
    copy_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl"), &dir);
    // The physics code lives in a header that physics.comp and fused.comp (the path this
    // small scene takes) both include; the gravity knob in one they share with predict.comp
    // (the iterative integrators', which this scene does not build).
    let physics = dir.join("include/physics_body.glsl");
    let original = std::fs::read_to_string(&physics).unwrap();
    let forces = dir.join("include/forces.glsl");
    let forces_original = std::fs::read_to_string(&forces).unwrap();
    assert!(
        forces_original.contains("const float GRAVITY_SCALE = 1.0;"),
        "the physics shader's gravity knob"
    );
    let both = ["fused.comp".to_string(), "physics.comp".to_string()];

    let ctx = gpu();
    let mut shaders = ShaderSet::directory(&dir).unwrap();
    let mut model = scene(vec![cloth(2, 2, 0.1)]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    let sim = GpuSim::with_shaders(&ctx, &model, &mut shaders).unwrap();
    let mut rig = Rig { ctx, shaders, sim, retired: RetireQueue::default(), frame_dt: model.frame_dt };
    let close = |a: f64, b: f64| (a - b).abs() < 1e-3 * b.abs();

    let a = rig.acceleration();
    assert!(close(a, -9.81), "before any edit: {a}");

    // Edit a constant: gravity doubles, the state carries on. The set tracks the includes of the
    // shaders it compiled, so predict.comp (never built here) is not among the changes.
    std::fs::write(&forces, forces_original.replace("GRAVITY_SCALE = 1.0;", "GRAVITY_SCALE = 2.0;")).unwrap();
    let (changed, reloaded) = rig.reload();
    assert_eq!((changed.as_slice(), reloaded.as_slice()), (&both[..], &both[..]));
    assert!(!rig.retired.is_empty(), "the old pipelines wait for their frames");
    let a = rig.acceleration();
    assert!(close(a, -19.62), "after the edit: {a}");
    assert!(rig.retired.is_empty(), "released once their frames completed");

    // A broken shader: the old pipeline keeps running, the error names the file and line.
    std::fs::write(&physics, broken(&original)).unwrap();
    let (_, reloaded) = rig.reload();
    assert!(reloaded.is_empty(), "a broken shader must not be swapped in");
    let errors: Vec<_> = rig.shaders.errors().map(|(n, e)| (n.clone(), e.clone())).collect();
    assert_eq!(errors.len(), 2, "both shaders including the header fail: {errors:?}");
    let line = original.lines().position(|l| l.contains(BROKEN_LINE)).unwrap() + 1;
    for (_, e) in &errors {
        assert!(e.contains(&format!("physics_body.glsl:{line}:")), "file:line in {e:?}");
    }
    let a = rig.acceleration();
    assert!(close(a, -19.62), "the last good pipeline still runs: {a}");

    // Restoring the files recovers and clears the error.
    std::fs::write(&forces, &forces_original).unwrap();
    let _ = rig.reload();
    std::fs::write(&physics, &original).unwrap();
    let (_, reloaded) = rig.reload();
    assert_eq!(reloaded, both);
    assert_eq!(rig.shaders.errors().count(), 0);
    let a = rig.acceleration();
    assert!(close(a, -9.81), "after restoring: {a}");

    // A header change that moves a member of a shared struct is refused for every shader that
    // includes it; the running pipelines stay.
    let header = dir.join("include/layout.glsl");
    let header_text = std::fs::read_to_string(&header).unwrap();
    std::fs::write(&header, header_text.replace("    float mass; ", "    float extra; float mass; "))
        .unwrap();
    let (changed, reloaded) = rig.reload();
    assert!(changed.len() >= 4, "every shader including the header: {changed:?}");
    assert!(reloaded.is_empty());
    let errors: Vec<String> = rig.shaders.errors().map(|(_, e)| e.clone()).collect();
    assert!(
        errors.iter().all(|e| e.contains("break the host's struct layout") && e.contains("ObjectParams")),
        "{errors:?}"
    );
    let a = rig.acceleration();
    assert!(close(a, -9.81), "still running: {a}");
    std::fs::write(&header, &header_text).unwrap();
    let (_, reloaded) = rig.reload();
    assert!(reloaded.len() >= 4, "{reloaded:?}");
    assert_eq!(rig.shaders.errors().count(), 0);

    let Rig { ctx, sim, retired, .. } = rig;
    sim.destroy(&ctx);
    retired.destroy(&ctx);
    assert_clean(&ctx);
}
