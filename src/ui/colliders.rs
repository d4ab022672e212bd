//! The editor's colliders: the ground switch, a list entry and an add button per collider type,
//! and the panel of the selected one. A new collider type adds its entry, button and panel
//! here (its simulation side is one row of `sim::collider`).

use super::editor::Selection;
use super::widgets::{check, drag, drag3, optional};
use crate::scene::{BoxCollider, Capsule, Ground, Motion, Scene, Sphere, MAX_FRICTION};
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
    out
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
    ui.same_line();
    if scene.ground.is_none() && ui.button("+ ground") {
        scene.ground = Some(Ground::default());
        added = Some(Selection::Ground);
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
