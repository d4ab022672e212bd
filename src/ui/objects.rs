//! The editor's objects: the panel of a selected cloth or rope with every parameter, and the
//! new cloth and rope the add buttons make.

use super::widgets::{button, check, choice, color, drag, drag3, int, optional};
use crate::scene::{
    Cloth, ClothPins, Orientation, PerSpring, PinBox, PinGroup, Rope, RopePins, SelfContact, MAX_FRICTION,
};
use imgui::Ui;

fn springs(ui: &Ui, label: &str, v: &mut PerSpring, speed: f32, min: f64, max: f64) {
    ui.text(label);
    drag(ui, &format!("structural##{label}"), &mut v.structural, speed, min, max);
    drag(ui, &format!("shear##{label}"), &mut v.shear, speed, min, max);
    drag(ui, &format!("bending##{label}"), &mut v.bending, speed, min, max);
}

/// An object's `pin_box` (the particles inside it are pinned too), while it has one: its
/// corners. `id` tells one box's fields from another's.
fn pin_box(ui: &Ui, b: &mut Option<PinBox>, id: &str) {
    if let Some(b) = b {
        ui.text_disabled("and those inside the box:");
        drag3(ui, &format!("box min [m]##{id}"), &mut b.min, 0.005);
        drag3(ui, &format!("box max [m]##{id}"), &mut b.max, 0.005);
    }
}

/// An object's further pin groups (`pin_group`), each with its listed particles (Ctrl+click
/// and the preset edit the lists), its box and its own motion, and a button to remove it.
/// Returns whether "add pin group" was pressed (the object adds one, `Cloth::add_pin_group`).
fn pin_groups<P>(ui: &Ui, groups: &mut Vec<PinGroup<P>>) -> bool {
    let mut remove = None;
    for (g, group) in groups.iter_mut().enumerate() {
        let _id = ui.push_id_usize(g);
        ui.separator();
        let listed = group.pinned.len();
        ui.text(format!(
            "pin group {}: {listed} listed particle{}",
            g + 1,
            if listed == 1 { "" } else { "s" }
        ));
        pin_box(ui, &mut group.pin_box, "group");
        super::colliders::motion_with(
            ui,
            &mut group.pin_motion,
            ["pins move", "pin velocity [m/s]", "pins turn", "pin angular velocity [degrees/s]"],
            [0.0, 0.2, 0.0],
        );
        if button(ui, "remove pin group") {
            remove = Some(g);
        }
    }
    if let Some(g) = remove {
        groups.remove(g);
    }
    ui.separator();
    let full = groups.len() + 1 >= crate::sim::model::PIN_GROUPS;
    !full && button(ui, "add pin group")
}

/// How an object's pins move (`pin_motion`), while it has pins: with none it has no motion
/// (a scene with one would be refused).
fn pin_motion(ui: &Ui, m: &mut Option<crate::scene::Motion>, pins: bool) {
    if !pins {
        *m = None;
        return;
    }
    super::colliders::motion_with(
        ui,
        m,
        ["pins move", "pin velocity [m/s]", "pins turn", "pin angular velocity [degrees/s]"],
        [0.0, 0.2, 0.0],
    );
}

pub fn cloth_panel(ui: &Ui, c: &mut Cloth) {
    ui.text(format!("cloth '{}'", c.name));
    int(ui, "columns", &mut c.resolution[0], 2, 4096);
    int(ui, "rows", &mut c.resolution[1], 2, 4096);
    drag(ui, "width [m]", &mut c.size[0], 0.01, 0.01, 100.0);
    drag(ui, "height [m]", &mut c.size[1], 0.01, 0.01, 100.0);
    drag3(ui, "origin [m]", &mut c.origin, 0.01);
    choice(ui, "orientation", &mut c.orientation, &[Orientation::Vertical, Orientation::Horizontal]);
    choice(
        ui,
        "pins",
        &mut c.pin,
        &[
            ClothPins::None,
            ClothPins::TopRow,
            ClothPins::TopCorners,
            ClothPins::LeftColumn,
            ClothPins::Corners,
        ],
    );
    pin_box(ui, &mut c.pin_box, "own");
    let pins = c.has_pins();
    pin_motion(ui, &mut c.pin_motion, pins);
    if pin_groups(ui, &mut c.pin_groups) {
        c.add_pin_group();
    }
    drag(ui, "mass [kg/particle]", &mut c.mass, 0.0005, 1e-6, 100.0);
    springs(ui, "stiffness [N/m]", &mut c.stiffness, 1.0, 0.0, 1e6);
    springs(ui, "rest length scale", &mut c.rest_scale, 0.005, 0.05, 10.0);
    drag(ui, "spring damping [N s/m]", &mut c.damping, 0.0005, 0.0, 100.0);
    drag(ui, "drag [N s/m]", &mut c.drag, 0.0005, 0.0, 100.0);
    optional(ui, "stretch limit", &mut c.stretch_limit, 0.1, 0.005, 10.0);
    drag(ui, "friction", &mut c.friction, 0.01, 0.0, MAX_FRICTION);
    drag(ui, "collision margin [m]", &mut c.collision_margin, 0.001, 0.0, 10.0);
    check(ui, "self-collision", &mut c.self_collision);
    if c.self_collision {
        let default = c.default_self_collision_distance();
        optional(ui, "self-collision distance [m]", &mut c.self_collision_distance, default, 0.001, 10.0);
        choice(ui, "self-contact", &mut c.self_contact, &SelfContact::ALL);
    }
    color(ui, "front colour", &mut c.color);
    color(ui, "back colour", &mut c.back_color);
}

pub fn rope_panel(ui: &Ui, r: &mut Rope) {
    ui.text(format!("rope '{}'", r.name));
    int(ui, "nodes", &mut r.nodes, 2, 1 << 20);
    drag3(ui, "start [m]", &mut r.start, 0.01);
    drag3(ui, "end [m]", &mut r.end, 0.01);
    choice(ui, "pins", &mut r.pin, &[RopePins::None, RopePins::First, RopePins::Last, RopePins::Both]);
    pin_box(ui, &mut r.pin_box, "own");
    let pins = r.has_pins();
    pin_motion(ui, &mut r.pin_motion, pins);
    if pin_groups(ui, &mut r.pin_groups) {
        r.add_pin_group();
    }
    drag(ui, "mass [kg/node]", &mut r.mass, 0.0005, 1e-6, 100.0);
    drag(ui, "stiffness [N/m]", &mut r.stiffness, 1.0, 0.0, 1e6);
    drag(ui, "bending stiffness [N/m]", &mut r.bending_stiffness, 0.1, 0.0, 1e6);
    drag(ui, "rest length scale", &mut r.rest_scale, 0.005, 0.05, 10.0);
    drag(ui, "spring damping [N s/m]", &mut r.damping, 0.0005, 0.0, 100.0);
    drag(ui, "drag [N s/m]", &mut r.drag, 0.0005, 0.0, 100.0);
    optional(ui, "stretch limit", &mut r.stretch_limit, 0.05, 0.005, 10.0);
    drag(ui, "friction", &mut r.friction, 0.01, 0.0, MAX_FRICTION);
    drag(ui, "radius [m]", &mut r.radius, 0.001, 0.001, 10.0);
    check(ui, "self-collision", &mut r.self_collision);
    if r.self_collision {
        optional(
            ui,
            "self-collision distance [m]",
            &mut r.self_collision_distance,
            2.0 * r.radius,
            0.001,
            10.0,
        );
    }
    color(ui, "colour", &mut r.color);
}

pub fn new_cloth(name: String) -> Cloth {
    Cloth {
        name,
        resolution: [32, 32],
        size: [1.0, 1.0],
        origin: [-0.5, 1.8, 0.5],
        orientation: Orientation::Vertical,
        mass: 0.01,
        stiffness: PerSpring { structural: 300.0, shear: 80.0, bending: 20.0 },
        rest_scale: PerSpring { structural: 1.0, shear: 1.0, bending: 1.0 },
        damping: 0.005,
        drag: 0.002,
        stretch_limit: Some(0.1),
        friction: 0.3,
        collision_margin: 0.01,
        self_collision: false,
        self_collision_distance: None,
        self_contact: SelfContact::Triangles,
        pin: ClothPins::TopCorners,
        pinned: Vec::new(),
        pin_box: None,
        pin_motion: None,
        pin_groups: Vec::new(),
        color: [0.2, 0.45, 0.75],
        back_color: [0.8, 0.8, 0.75],
    }
}

pub fn new_rope(name: String) -> Rope {
    Rope {
        name,
        nodes: 48,
        start: [-0.6, 1.8, -0.5],
        end: [0.6, 1.8, -0.5],
        mass: 0.01,
        stiffness: 600.0,
        bending_stiffness: 2.0,
        rest_scale: 1.0,
        damping: 0.01,
        drag: 0.005,
        stretch_limit: Some(0.05),
        friction: 0.5,
        radius: 0.02,
        ring_weights: None,
        self_collision: false,
        self_collision_distance: None,
        pin: RopePins::First,
        pinned: Vec::new(),
        pin_box: None,
        pin_motion: None,
        pin_groups: Vec::new(),
        color: [0.72, 0.58, 0.36],
    }
}
