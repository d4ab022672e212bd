//! Saving a preset with the editor's save function (`scene::save`, what the Save button runs)
//! and loading it back gives the identical scene, for every shipped preset and for a scene
//! edited the way the editor edits (objects added with generated names, optional values set).

use msdsim::scene::{self, Scene};

fn round_trip(scene: &Scene, name: &str) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    scene::save(scene, &path).unwrap();
    let back = scene::load(&path, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        &back,
        scene,
        "{name} changed in the round trip:\n{}",
        std::fs::read_to_string(&path).unwrap()
    );
}

#[test]
fn every_preset_survives_save_and_load() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue; // (the meshes some presets read)
        }
        let scene = scene::load(&path, &[]).unwrap();
        round_trip(&scene, path.file_name().unwrap().to_str().unwrap());
    }
}

#[test]
fn an_edited_scene_survives_save_and_load() {
    let mut s = msdsim::app::load_scene(None, &[]).unwrap();
    let mut extra = s.cloths[0].clone();
    extra.name = msdsim::ui::unique_name(&s, "cloth");
    extra.stretch_limit = None;
    extra.self_collision_distance = Some(0.0123);
    extra.pinned = vec![[1, 2], [3, 0]];
    extra.pin_motion = Some(scene::Motion {
        keyframes: vec![[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 1.0 / 3.0, 0.0]],
        angular_velocity: Some([0.0, 45.0, 0.1]),
        pivot: Some([0.2, 1.0 / 7.0, 0.0]),
        ..Default::default()
    });
    extra.color = [0.1, 0.2, 0.3];
    s.cloths.push(extra);
    s.ropes[0].ring_weights = Some(vec![[0.5, 0.25]; 8]);
    s.spheres.push(scene::Sphere {
        center: [0.1, -0.2, 1.0 / 3.0],
        radius: 0.1,
        motion: Some(scene::Motion {
            keyframes: vec![[0.0, 0.1, -0.2, 0.3], [1.5, 0.4, 0.0, 0.3]],
            ..Default::default()
        }),
    });
    s.light.ambient = 0.3;
    s.wind.enabled = false;
    s.sim.frame_dt = 1.0 / 120.0;
    round_trip(&s, "edited.toml");
}
