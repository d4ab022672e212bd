//! The editor's objects: the panel of a selected cloth or rope with every parameter, and the
//! new cloth and rope the add buttons make.

use super::widgets::{button, check, choice, color, drag, drag3, int, optional};
use crate::scene::{
    Cloth, ClothPins, MeshCloth, Orientation, PerSpring, PinBox, PinGroup, Rope, RopePins, SelfContact,
    MAX_FRICTION,
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

/// An object's own pin box and how its pins (`pins`: it has some) move, then its pin groups;
/// whether "add pin group" was pressed.
fn own_pins<P>(
    ui: &Ui,
    (own_box, motion, pins): (&mut Option<PinBox>, &mut Option<crate::scene::Motion>, bool),
    groups: &mut Vec<PinGroup<P>>,
) -> bool {
    pin_box(ui, own_box, "own");
    pin_motion(ui, motion, pins);
    pin_groups(ui, groups)
}

/// A cloth's springs: stiffness and rest length scale per spring type, damping and drag.
fn cloth_springs(
    ui: &Ui,
    (stiffness, rest_scale): (&mut PerSpring, &mut PerSpring),
    damping: &mut f64,
    drag_: &mut f64,
) {
    springs(ui, "stiffness [N/m]", stiffness, 1.0, 0.0, 1e6);
    springs(ui, "rest length scale", rest_scale, 0.005, 0.05, 10.0);
    drag(ui, "spring damping [N s/m]", damping, 0.0005, 0.0, 100.0);
    drag(ui, "drag [N s/m]", drag_, 0.0005, 0.0, 100.0);
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
    let pins = c.has_pins();
    if own_pins(ui, (&mut c.pin_box, &mut c.pin_motion, pins), &mut c.pin_groups) {
        c.add_pin_group();
    }
    drag(ui, "mass [kg/particle]", &mut c.mass, 0.0005, 1e-6, 100.0);
    cloth_springs(ui, (&mut c.stiffness, &mut c.rest_scale), &mut c.damping, &mut c.drag);
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
    let pins = r.has_pins();
    if own_pins(ui, (&mut r.pin_box, &mut r.pin_motion, pins), &mut r.pin_groups) {
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

/// A mesh cloth's panel: its file (read once; a new file is added anew), where it is placed,
/// its pins and material. Its particles are Ctrl+clicked as a grid's are.
pub fn mesh_cloth_panel(ui: &Ui, c: &mut MeshCloth) {
    ui.text(format!("mesh cloth '{}'", c.name));
    ui.text_disabled(&c.file);
    let build = c.loaded.as_ref().map(|f| f.built(c));
    let built = build.as_ref().and_then(|b| b.as_ref().ok()).cloned();
    if let Some((positions, mesh)) = built.as_deref() {
        ui.text_disabled(format!("{} particles, {} triangles", positions.len(), mesh.triangles.len()));
    }
    drag3(ui, "centre [m]##mesh cloth", &mut c.center, 0.01);
    drag3(ui, "rotation x, y, z [deg]", &mut c.rotation, 0.5);
    c.rotation = c.rotation.map(|a| a.clamp(-360.0, 360.0));
    drag(ui, "scale##mesh cloth", &mut c.scale, 0.001, 1e-6, 1e6);
    drag(ui, "weld [m]", &mut c.weld, 0.0001, 0.0, 1.0);
    let pins = c.has_pins();
    if own_pins(ui, (&mut c.pin_box, &mut c.pin_motion, pins), &mut c.pin_groups) {
        c.add_pin_group();
    }
    drag(ui, "density [kg/m^2]", &mut c.density, 0.005, 1e-6, 1e3);
    cloth_springs(ui, (&mut c.stiffness, &mut c.rest_scale), &mut c.damping, &mut c.drag);
    optional(ui, "stretch limit", &mut c.stretch_limit, 0.1, 0.005, 10.0);
    drag(ui, "friction", &mut c.friction, 0.01, 0.0, MAX_FRICTION);
    drag(ui, "collision margin [m]", &mut c.collision_margin, 0.001, 0.0, 10.0);
    check(ui, "self-collision", &mut c.self_collision);
    if c.self_collision {
        let default = built.as_deref().map_or(0.01, |(_, mesh)| 0.5 * mesh.mean_edge);
        optional(ui, "self-collision distance [m]", &mut c.self_collision_distance, default, 0.001, 10.0);
    }
    if !c.seams.is_empty() {
        let pairs = c.seam_pairs().iter().map(Vec::len).sum::<usize>();
        ui.text_disabled(format!("{} seams, {pairs} vertex pairs (edit them in the preset)", c.seams.len()));
    }
    drag(ui, "sew [m]", &mut c.sew, 0.0005, 0.0, 1.0);
    if c.sew > 0.0 && c.seam_stiffness == 0.0 {
        // (found seams need a stiffness to close: the skirt preset's, until the user sets one)
        c.seam_stiffness = 100.0;
    }
    if c.sew > 0.0 {
        // (what the sewing found, or why it found nothing, as the editor last built it)
        match (&build, built.as_deref()) {
            (_, Some((_, mesh))) => {
                let sewn = mesh.springs.iter().filter(|s| s.kind == crate::sim::cloth_mesh::SEAM).count() / 2;
                ui.text_disabled(format!("{sewn} vertex pairs sewn in all"));
            }
            (Some(Err(e)), None) => ui.text_wrapped(e),
            _ => {}
        }
    }
    if !c.seams.is_empty() || c.sew > 0.0 {
        drag(ui, "seam stiffness [N/m]", &mut c.seam_stiffness, 1.0, 0.0, 1e6);
    }
    color(ui, "front colour", &mut c.color);
    color(ui, "back colour", &mut c.back_color);
}

/// Adds a mesh cloth from the file at `path` (scaled to fit a few metres if far larger),
/// placed where the camera looks (`look_at`), clear of the scene; the error says what is wrong
/// with the file or the mesh.
pub fn add_mesh_cloth(
    scene: &mut crate::scene::Scene,
    path: &str,
    look_at: [f64; 3],
) -> Result<super::Selection, String> {
    let file = std::path::absolute(path.trim()).map_err(|e| format!("{}: {e}", path.trim()))?;
    let read = crate::scene::mesh_file::read_faces(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let scale = super::colliders::fitting_scale(&read.vertices);
    let name = super::editor::unique_name(scene, "garment");
    let mut cloth = new_mesh_cloth(name, std::sync::Arc::new(read), scale);
    if let Err(e) = cloth.build() {
        return Err(format!("{}: {e}", file.display()));
    }
    crate::scene::place::place_mesh_cloth(scene, &mut cloth, glam::DVec3::from_array(look_at));
    scene.mesh_cloths.push(cloth);
    Ok(super::Selection::MeshCloth(scene.mesh_cloths.len() - 1))
}

/// A new mesh cloth named `name` from `file` (read into `loaded`) at `scale`: a light cotton
/// (0.15 kg/m^2) that holds its shape, unpinned.
pub fn new_mesh_cloth(
    name: String,
    loaded: std::sync::Arc<crate::scene::mesh_file::FaceFile>,
    scale: f64,
) -> MeshCloth {
    MeshCloth {
        name,
        file: loaded.path.display().to_string(),
        center: [0.0; 3],
        rotation: [0.0; 3],
        scale,
        weld: 0.0,
        density: 0.15,
        stiffness: PerSpring { structural: 200.0, shear: 40.0, bending: 1.0 },
        rest_scale: PerSpring { structural: 1.0, shear: 1.0, bending: 1.0 },
        damping: 0.002,
        drag: 0.0,
        stretch_limit: None,
        friction: 0.3,
        collision_margin: 0.01,
        self_collision: false,
        self_collision_distance: None,
        pinned: Vec::new(),
        pin_box: None,
        pin_motion: None,
        pin_groups: Vec::new(),
        seams: Vec::new(),
        sew: 0.0,
        seam_stiffness: 0.0,
        color: [0.2, 0.45, 0.75],
        back_color: [0.8, 0.8, 0.75],
        loaded: Some(loaded),
    }
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

#[cfg(test)]
mod tests {
    /// A mesh cloth added from a file lands where the camera looks, clear of the ground, in a
    /// scene that validates and builds with it; a file that is not a mesh is refused with its
    /// name and nothing added.
    #[test]
    fn a_mesh_cloth_added_from_a_file_is_placed_and_valid() {
        let mut scene = crate::scene::parse("", "new", &[]).unwrap();
        let file = concat!(env!("CARGO_MANIFEST_DIR"), "/presets/meshes/holed_flag.obj");
        let selected = super::add_mesh_cloth(&mut scene, file, [0.0, 1.0, 0.0]).unwrap();
        assert_eq!(selected, super::super::Selection::MeshCloth(0));
        crate::scene::validate(&scene).unwrap();
        let o = scene.mesh_cloths[0].build().unwrap();
        let lowest = o.positions.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let ground = scene.ground.as_ref().map_or(f64::NEG_INFINITY, |g| g.height);
        assert!(lowest > ground, "its lowest particle at {lowest}, the ground at {ground}");
        let e = super::add_mesh_cloth(&mut scene, "Cargo.toml", [0.0; 3]).unwrap_err();
        assert!(e.contains("Cargo.toml"), "{e}");
        assert_eq!(scene.mesh_cloths.len(), 1);
    }
}
