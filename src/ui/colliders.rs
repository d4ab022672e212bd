//! The editor's colliders: the ground switch, a list entry and an add button per collider type,
//! and the panel of the selected one. A new collider type adds its entry, button and panel
//! here (its simulation side is one row of `sim::collider`).

use super::editor::Selection;
use super::widgets::{check, drag, drag3, optional};
use crate::scene::{BoxCollider, Capsule, Ground, MeshCollider, Motion, Scene, Sphere, MAX_FRICTION};
use imgui::Ui;

/// The list entries of the scene's colliders, with what selecting each selects.
pub fn entries(scene: &Scene) -> Vec<(String, Selection)> {
    let mut out = Vec::new();
    if let Some(g) = &scene.ground {
        out.push((format!("ground (y {:.2} m)##g", g.height), Selection::Ground));
    }
    for (i, s) in scene.spheres.iter().enumerate() {
        out.push((format!("sphere {i} (r {:.2} m)##s{i}", s.radius), Selection::Sphere(i)));
    }
    for (i, b) in scene.boxes.iter().enumerate() {
        let [x, y, z] = b.half_extents.map(|h| 2.0 * h);
        out.push((format!("box {i} ({x:.2} x {y:.2} x {z:.2} m)##b{i}"), Selection::Box(i)));
    }
    for (i, c) in scene.capsules.iter().enumerate() {
        out.push((format!("capsule {i} (r {:.2} m)##k{i}", c.radius), Selection::Capsule(i)));
    }
    for (i, m) in scene.meshes.iter().enumerate() {
        let name = std::path::Path::new(&m.file).file_name().map(|n| n.to_string_lossy().into_owned());
        let triangles = m.loaded.as_ref().map_or(0, |f| f.triangles.len());
        let name = name.unwrap_or_default();
        out.push((format!("mesh {i} ({name}, {triangles} triangles)##m{i}"), Selection::Mesh(i)));
    }
    out
}

/// The mesh file field, its Browse button, "+ mesh", which reads the file and adds it as a
/// collider where the camera looks (`look_at`), its lowest point on the ground or at the
/// point, and "+ mesh cloth", which adds it as a cloth (`objects::add_mesh_cloth`); an
/// unreadable or bad mesh is the error's one line.
pub fn add_mesh(
    ui: &Ui,
    scene: &mut Scene,
    path: &mut String,
    look_at: [f64; 3],
) -> Result<Option<Selection>, String> {
    ui.set_next_item_width(ui.content_region_avail()[0] * 0.7);
    ui.input_text("##mesh file", path).hint("mesh file (.obj, .gltf, .glb)").build();
    ui.same_line();
    super::browse::browse_files(ui, "mesh", path, &["obj", "gltf", "glb"]);
    let collider = ui.button("+ mesh");
    ui.same_line();
    if ui.button("+ mesh cloth") {
        return super::objects::add_mesh_cloth(scene, path, look_at).map(Some);
    }
    if !collider {
        return Ok(None);
    }
    let file = std::path::absolute(path.trim()).map_err(|e| format!("{}: {e}", path.trim()))?;
    let read = crate::scene::mesh_file::read(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let scale = fitting_scale(&read.vertices);
    let (lo, hi) = crate::sim::collider_mesh::bounds(&read.vertices);
    let at = glam::DVec3::from_array(look_at);
    let floor = scene.ground.as_ref().map_or(at.y, |g| g.height.max(at.y - 1.0));
    let center = glam::DVec3::new(
        at.x - 0.5 * (lo.x + hi.x) * scale,
        floor - lo.y * scale,
        at.z - 0.5 * (lo.z + hi.z) * scale,
    );
    scene.meshes.push(MeshCollider {
        file: file.display().to_string(),
        center: center.to_array(),
        rotation: [0.0; 3],
        scale,
        thickness: 0.0,
        // (more than every object's margin, as validation asks)
        reach: 2.0 * scene.widest_margin().max(0.015),
        motion: None,
        loaded: Some(std::sync::Arc::new(read)),
    });
    Ok(Some(Selection::Mesh(scene.meshes.len() - 1)))
}

/// The scale that fits a mesh file of `vertices` to a few metres if it is far larger (a file
/// in millimetres or centimetres): a power of ten.
pub(super) fn fitting_scale(vertices: &[glam::DVec3]) -> f64 {
    let (lo, hi) = crate::sim::collider_mesh::bounds(vertices);
    let size = (hi - lo).max_element();
    if size > 10.0 {
        10f64.powf(-(size / 2.0).log10().ceil())
    } else {
        1.0
    }
}

/// The add buttons (on the current line); returns what was added. A new collider is placed
/// where the camera looks (`look_at`), above the ground and clear of the rest of the scene.
pub fn add_buttons(ui: &Ui, scene: &mut Scene, look_at: [f64; 3]) -> Option<Selection> {
    let mut added = None;
    let place = |scene: &Scene, min: [f64; 3], max: [f64; 3]| {
        let (min, max) = (glam::DVec3::from_array(min), glam::DVec3::from_array(max));
        crate::scene::place::offset(scene, (min, max), glam::DVec3::from_array(look_at))
    };
    let moved = |p: [f64; 3], d: glam::DVec3| (glam::DVec3::from_array(p) + d).to_array();
    if ui.button("+ sphere") {
        let d = place(scene, [-0.25; 3], [0.25; 3]);
        scene.spheres.push(Sphere { center: moved([0.0; 3], d), radius: 0.25, motion: None });
        added = Some(Selection::Sphere(scene.spheres.len() - 1));
    }
    ui.same_line();
    if ui.button("+ box") {
        let d = place(scene, [-0.3, -0.25, -0.3], [0.3, 0.25, 0.3]);
        scene.boxes.push(BoxCollider {
            center: moved([0.0; 3], d),
            half_extents: [0.3, 0.25, 0.3],
            rotation: [0.0; 3],
            motion: None,
        });
        added = Some(Selection::Box(scene.boxes.len() - 1));
    }
    ui.same_line();
    if ui.button("+ capsule") {
        let d = place(scene, [-0.5, -0.1, -0.1], [0.5, 0.1, 0.1]);
        scene.capsules.push(Capsule {
            start: moved([-0.4, 0.0, 0.0], d),
            end: moved([0.4, 0.0, 0.0], d),
            radius: 0.1,
            motion: None,
        });
        added = Some(Selection::Capsule(scene.capsules.len() - 1));
    }
    if scene.ground.is_none() {
        ui.same_line();
        if ui.button("+ ground") {
            scene.ground = Some(Ground::default());
            added = Some(Selection::Ground);
        }
    }
    added
}

/// Removes the selected collider; false when the selection is not a collider.
pub fn remove(scene: &mut Scene, selected: Selection) -> bool {
    match selected {
        Selection::Ground => scene.ground = None,
        Selection::Sphere(i) if i < scene.spheres.len() => drop(scene.spheres.remove(i)),
        Selection::Box(i) if i < scene.boxes.len() => drop(scene.boxes.remove(i)),
        Selection::Capsule(i) if i < scene.capsules.len() => drop(scene.capsules.remove(i)),
        Selection::Mesh(i) if i < scene.meshes.len() => drop(scene.meshes.remove(i)),
        _ => return false,
    }
    true
}

/// The panel of the selected collider; false when the selection is not a collider.
pub fn panel(ui: &Ui, scene: &mut Scene, selected: Selection) -> bool {
    match selected {
        Selection::Ground => match &mut scene.ground {
            Some(g) => {
                drag(ui, "height [m]##ground", &mut g.height, 0.01, -1e3, 1e3);
                // Unticked: each object's own friction applies.
                optional(ui, "friction (own)##ground", &mut g.friction, 0.5, 0.01, MAX_FRICTION);
            }
            None => return false,
        },
        Selection::Sphere(i) if i < scene.spheres.len() => {
            let s = &mut scene.spheres[i];
            drag3(ui, "centre [m]", &mut s.center, 0.01);
            drag(ui, "radius [m]##collider", &mut s.radius, 0.005, 0.001, 100.0);
            motion(ui, &mut s.motion);
        }
        Selection::Box(i) if i < scene.boxes.len() => {
            let b = &mut scene.boxes[i];
            drag3(ui, "centre [m]", &mut b.center, 0.01);
            drag3(ui, "half extents [m]", &mut b.half_extents, 0.005);
            b.half_extents = b.half_extents.map(|h| h.clamp(0.001, 100.0));
            drag3(ui, "rotation x, y, z [deg]", &mut b.rotation, 0.5);
            b.rotation = b.rotation.map(|a| a.clamp(-360.0, 360.0));
            motion(ui, &mut b.motion);
        }
        Selection::Capsule(i) if i < scene.capsules.len() => {
            let c = &mut scene.capsules[i];
            drag3(ui, "start [m]##capsule", &mut c.start, 0.01);
            drag3(ui, "end [m]##capsule", &mut c.end, 0.01);
            drag(ui, "radius [m]##collider", &mut c.radius, 0.005, 0.001, 100.0);
            motion(ui, &mut c.motion);
        }
        Selection::Mesh(i) if i < scene.meshes.len() => {
            let m = &mut scene.meshes[i];
            ui.text_disabled(&m.file);
            drag3(ui, "centre [m]", &mut m.center, 0.01);
            drag3(ui, "rotation x, y, z [deg]", &mut m.rotation, 0.5);
            m.rotation = m.rotation.map(|a| a.clamp(-360.0, 360.0));
            drag(ui, "scale##mesh", &mut m.scale, 0.001, 1e-6, 1e6);
            drag(ui, "thickness [m]##mesh", &mut m.thickness, 0.001, 0.0, 1.0);
            drag(ui, "reach [m]##mesh", &mut m.reach, 0.001, 0.001, 1.0);
            motion(ui, &mut m.motion);
        }
        _ => return false,
    }
    true
}

/// A collider's motion: a constant velocity behind a checkbox; keyframes are shown, and edited
/// in the preset.
fn motion(ui: &Ui, m: &mut Option<Motion>) {
    motion_with(ui, m, ["moves", "velocity [m/s]", "turns", "angular velocity [degrees/s]"], [0.2, 0.0, 0.0]);
}

/// A motion (a collider's, or an object's pins'), its widgets labelled `[checkbox, velocity,
/// checkbox, angular velocity]`, starting at velocity `start` or a turn of 90 degrees/s about
/// the vertical when ticked; the motion is dropped when neither is left.
pub(super) fn motion_with(ui: &Ui, m: &mut Option<Motion>, labels: [&str; 4], start: [f64; 3]) {
    // (keyed motion is edited in the preset: no checkbox here to drop it)
    if let Some(keyed) = m.as_ref().filter(|m| !m.keyframes.is_empty() || !m.rotation_keyframes.is_empty()) {
        if !keyed.keyframes.is_empty() {
            ui.text_disabled(format!(
                "moves along {} keyframes (edit them in the preset)",
                keyed.keyframes.len()
            ));
        }
        if !keyed.rotation_keyframes.is_empty() {
            let n = keyed.rotation_keyframes.len();
            ui.text_disabled(format!("turns along {n} rotation keyframes (edit them in the preset)"));
        }
        if let Some(w) = keyed.angular_velocity {
            ui.text_disabled(format!(
                "turns at [{}, {}, {}] degrees/s (edit it in the preset)",
                w[0], w[1], w[2]
            ));
        }
        return;
    }
    let mut moving = m.as_ref().is_some_and(|m| m.velocity.is_some());
    if check(ui, labels[0], &mut moving) {
        m.get_or_insert_with(Default::default).velocity = moving.then_some(start);
    }
    if let Some(Motion { velocity: Some(v), .. }) = m {
        drag3(ui, labels[1], v, 0.01);
    }
    let mut turning = m.as_ref().is_some_and(|m| m.angular_velocity.is_some());
    if check(ui, labels[2], &mut turning) {
        let motion = m.get_or_insert_with(Default::default);
        motion.angular_velocity = turning.then_some([0.0, 90.0, 0.0]);
        if !turning {
            motion.pivot = None; // (what it turned about)
        }
    }
    if let Some(Motion { angular_velocity: Some(w), .. }) = m {
        drag3(ui, labels[3], w, 1.0);
    }
    if m.as_ref().is_some_and(|m| m.velocity.is_none() && m.angular_velocity.is_none()) {
        *m = None;
    }
}
