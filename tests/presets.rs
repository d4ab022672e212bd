//! Every shipped preset loads, builds and runs on the GPU with validation and synchronization
//! validation (two substeps per frame, to keep lavapipe quick).

mod common;

use msdsim::scene;
use msdsim::sim::gpu::GpuSim;

#[test]
fn every_preset_loads_and_runs() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let mut names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    let ctx = common::gpu();
    for path in &names {
        let scene = scene::load(path, &["sim.substeps=2".to_string()])
            .unwrap_or_else(|e| panic!("{} does not load: {e}", path.display()));
        assert!(!scene.cloths.is_empty() || !scene.ropes.is_empty(), "{} is empty", path.display());
        let model = scene::to_model(&scene);
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        sim.step_frame(&ctx).unwrap();
        let states = sim.read_states(&ctx).unwrap();
        for (o, s) in model.objects.iter().zip(&states) {
            assert!(
                s.particles.iter().all(|p| p.pos.iter().all(|x| x.is_finite())),
                "{}: {} has non-finite positions",
                path.display(),
                o.name
            );
        }
        sim.destroy(&ctx);
    }
    for required in ["curtain", "flag", "towel", "rope", "playground"] {
        assert!(
            names.iter().any(|p| p.file_stem().unwrap() == required),
            "presets/{required}.toml is missing"
        );
    }
    common::assert_clean(&ctx);
}
