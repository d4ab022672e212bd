//! The editor panels: simulation controls, wind, light, the object list with add and remove,
//! the selected object's panel (`objects`, `colliders`), preset load/save, and stats.

use super::colliders;
use super::objects::{cloth_panel, mesh_cloth_panel, new_cloth, new_rope, rope_panel};
use super::widgets::{check, choice, color, drag, drag3, int, tip};
use super::wind;
use crate::scene::Scene;
use crate::sim::gpu::FrameTiming;
use imgui::{Condition, TreeNodeFlags, Ui};
use std::path::PathBuf;

/// What the user asked for besides editing values.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    TogglePause,
    Step,
    Reset,
    FitCamera,
    ResetCamera,
    Load(PathBuf),
    Save(PathBuf),
    AddClothFromPreset(PathBuf),
    /// Start recording into the file (`.usda` or `.obj`), or stop and write it.
    ToggleRecording(PathBuf),
    Undo,
    Redo,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Selection {
    #[default]
    None,
    Cloth(usize),
    Rope(usize),
    MeshCloth(usize),
    Ground,
    Sphere(usize),
    Box(usize),
    Capsule(usize),
    Mesh(usize),
    /// The wind cone and the light: selected for their translate handles in the view.
    Wind,
    Light,
}

impl Selection {
    /// Object `object` of `scene`'s simulation (its cloths, then its ropes, then its mesh
    /// cloths).
    pub fn of_object(object: usize, scene: &Scene) -> Self {
        let (cloths, ropes) = (scene.cloths.len(), scene.ropes.len());
        match object {
            i if i < cloths => Selection::Cloth(i),
            i if i < cloths + ropes => Selection::Rope(i - cloths),
            i => Selection::MeshCloth(i - cloths - ropes),
        }
    }

    /// The simulation's object this selects in `scene` (None: a collider, the wind, the light
    /// or nothing).
    pub fn object(self, scene: &Scene) -> Option<usize> {
        match self {
            Selection::Cloth(i) => Some(i),
            Selection::Rope(j) => Some(scene.cloths.len() + j),
            Selection::MeshCloth(k) => Some(scene.cloths.len() + scene.ropes.len() + k),
            _ => None,
        }
    }
}

/// Editor state that is not part of the scene.
#[derive(Debug, Clone, Default)]
pub struct EditorState {
    pub selected: Selection,
    /// Scroll the Scene panel to the selected object's panel when it is next drawn (the app's
    /// `--select`).
    pub show_selected: bool,
    pub preset_path: String,
    pub cloth_preset_path: String,
    /// Every message (the last is the status line under the Scene panel): the newest over the
    /// view for a few seconds, all in the Log window.
    pub notices: super::notices::Notices,
    /// The point the camera looks at, where new objects are placed [m].
    pub look_at: [f64; 3],
    pub paused: bool,
    pub shaders_note: String,
    /// Hide the stats window (reproducible screenshots).
    pub hide_stats: bool,
    /// Hide every window (pictures of the scene alone).
    pub hide_ui: bool,
    /// Shader compile errors (the running pipelines are the last good ones).
    pub shader_errors: Vec<String>,
    /// The controls window (F1).
    pub show_help: bool,
    /// Where the Scene panel was last drawn: x, y, width, height in ImGui's (logical) pixels.
    pub panel: Option<[f32; 4]>,
    /// Where the Stats window was last drawn, the same way.
    pub stats_panel: Option<[f32; 4]>,
    /// What `integrator = "auto"` picked for the running simulation.
    pub auto_picked: Option<String>,
    /// The file the Record button writes (`.usda` or `.obj`).
    pub record_path: String,
    /// Frames recorded so far and the file, while recording.
    pub recording: Option<(u64, String)>,
    /// Simulate as many frames per drawn frame as the wall clock asks (up to 4), instead of one.
    pub real_time: bool,
    /// The existing file a Save would replace, once asked: Save again (Replace) writes it.
    pub replace: Option<String>,
    /// Edits that can be undone and redone.
    pub undo_depth: (usize, usize),
    /// The scene differs from the one last loaded or saved.
    pub unsaved: bool,
    /// A field or other widget is being edited (a drag in progress): its edits are one step.
    pub ui_active: bool,
    /// The mesh file the "+ mesh" button adds as a collider.
    pub mesh_path: String,
}

/// What pressing Save on the file field's `path` does: a file that does not exist yet is
/// written at once; one that exists is written only when the press confirms the question the
/// first press asked (`state.replace` names it; editing the path asks again).
pub fn save_pressed(state: &mut EditorState, path: &str, exists: bool) -> Option<Action> {
    if !exists || state.replace.as_deref() == Some(path) {
        state.replace = None;
        return Some(Action::Save(PathBuf::from(path)));
    }
    state.replace = Some(path.to_string());
    None
}

/// Where the Scene panel first appears in a view of `size` logical pixels: x, y, width,
/// height (at most the view's height less a margin; it scrolls).
pub fn panel_start(size: [f32; 2]) -> [f32; 4] {
    [10.0, 10.0, 400.0, 620f32.min(size[1] - 20.0).max(100.0)]
}

/// The Stats window's width (its lines wrap within it) and height before it is first drawn.
const STATS_WIDTH: f32 = 330.0;
const STATS_HEIGHT: f32 = 280.0;

/// Where the Stats window first appears in a view of `size` logical pixels: at the top right,
/// x, y, width, height (its height until it is drawn: it takes its content's).
fn stats_start(size: [f32; 2]) -> [f32; 4] {
    [(size[0] - STATS_WIDTH - 10.0).max(0.0), 10.0, STATS_WIDTH, STATS_HEIGHT]
}

/// The rectangles (x, y, width, height, logical pixels) of the windows over a view of
/// `size` logical pixels: where they were last drawn, or where they will first appear.
pub fn covered(state: &EditorState, size: [f32; 2]) -> Vec<[f32; 4]> {
    if state.hide_ui {
        return Vec::new();
    }
    let mut rects = vec![state.panel.unwrap_or(panel_start(size))];
    if !state.hide_stats {
        rects.push(state.stats_panel.unwrap_or(stats_start(size)));
    }
    rects
}

/// Timings shown in the stats panel.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    pub device: String,
    pub cpu_frame_ms: f64,
    pub sim: Option<FrameTiming>,
    pub render_ms: Option<f64>,
    pub ui_ms: Option<f64>,
    pub particles: u64,
    pub simulated_time: f64,
    /// Simulated time per wall-clock time while running (1: real time), `None` when paused.
    pub speed: Option<f64>,
}

/// Builds the editor windows over `scene` (edited in place) and returns the actions.
pub fn build(ui: &Ui, state: &mut EditorState, scene: &mut Scene, stats: &Stats) -> Vec<Action> {
    let mut actions = Vec::new();
    state.ui_active = false;
    recording_indicator(ui, state);
    // Notices over the part of the view between the Scene panel and the Stats window (when
    // that leaves room for them).
    let size = ui.io().display_size;
    let left = state.panel.filter(|_| !state.hide_ui).map_or(0.0, |[x, _, w, _]| x + w);
    let right = (state.stats_panel.filter(|_| !state.hide_ui && !state.hide_stats))
        .map(|[x, ..]| x)
        .filter(|&x| x - left >= 240.0)
        .unwrap_or(size[0]);
    state.notices.draw(ui, [left, 0.0, right, size[1]]);
    if state.hide_ui {
        return actions;
    }
    let [x, y, w, h] = panel_start(size);
    ui.window("Scene").position([x, y], Condition::FirstUseEver).size([w, h], Condition::FirstUseEver).build(
        || {
            let ([x, y], [w, h]) = (ui.window_pos(), ui.window_size());
            state.panel = Some([x, y, w, h]);
            // Fields leave room on their right for the longest label, so that no label is
            // cut off whatever the panel's width (a scrollbar takes some).
            let label = ui.calc_text_size("self-collision distance [m]")[0] + ui.clone_style().item_inner_spacing[0];
            let _width = ui.push_item_width(-label);
            simulation_panel(ui, state, scene, &mut actions);
            if ui.collapsing_header("Wind", TreeNodeFlags::empty()) {
                wind::wind_panel(ui, &mut scene.wind);
            }
            if ui.collapsing_header("Light", TreeNodeFlags::empty()) {
                drag3(ui, "position [m]##light", &mut scene.light.position, 0.02);
                color(ui, "colour##light", &mut scene.light.color);
                drag(ui, "ambient", &mut scene.light.ambient, 0.01, 0.0, 1.0);
            }
            if ui.collapsing_header("Objects", TreeNodeFlags::DEFAULT_OPEN) {
                object_list(ui, state, scene);
                ui.separator();
                if std::mem::take(&mut state.show_selected) {
                    ui.set_scroll_here_y_with_ratio(0.0);
                }
                selected_panel(ui, state, scene);
            }
            if ui.collapsing_header("Presets", TreeNodeFlags::DEFAULT_OPEN) {
                if ui.input_text("file##preset", &mut state.preset_path).build() {
                    state.replace = None;
                }
                let from = std::env::current_dir().map(|d| format!(" ({})", d.display())).unwrap_or_default();
                tip(ui, &format!("The preset file to load or save, from the folder the app was started in{from} (Load also finds a shipped preset by its name); type a new name to save a copy"));
                if ui.button("Load") {
                    let path = super::browse::resolve_preset(&state.preset_path, "");
                    actions.push(Action::Load(path));
                }
                ui.same_line();
                let path = state.preset_path.clone();
                if state.replace.as_deref() == Some(path.as_str()) {
                    ui.text_colored([1.0, 0.8, 0.4, 1.0], "exists:");
                    ui.same_line();
                    if ui.button("Replace") {
                        actions.extend(save_pressed(state, &path, true));
                    }
                    ui.same_line();
                    if ui.button("Cancel##save") {
                        state.replace = None;
                    }
                } else if ui.button(if state.unsaved { "Save*###save" } else { "Save###save" }) {
                    let exists = std::path::Path::new(&path).exists();
                    actions.extend(save_pressed(state, &path, exists));
                }
                ui.same_line();
                if super::browse::browse_button(ui, "preset", &mut state.preset_path) {
                    state.replace = None;
                }
                tip(ui, "Pick the file from its folder's presets");
                ui.input_text("cloth preset##add", &mut state.cloth_preset_path).build();
                if ui.button("Add cloths from that preset") {
                    let path = super::browse::resolve_preset(&state.cloth_preset_path, &state.preset_path);
                    actions.push(Action::AddClothFromPreset(path));
                }
                ui.same_line();
                super::browse::browse_button(ui, "cloth", &mut state.cloth_preset_path);
            }
            if ui.small_button(format!("Log ({})###log", state.notices.len())) {
                state.notices.show_log = !state.notices.show_log;
            }
            if let Some((text, error)) = state.notices.last() {
                let colour = if error { [1.0, 0.45, 0.4, 1.0] } else { [0.6, 0.9, 0.6, 1.0] };
                ui.same_line();
                ui.text_wrapped_colored(colour, text);
            }
        },
    );
    if !state.hide_stats {
        stats_window(ui, stats, state, scene);
    }
    if !state.shader_errors.is_empty() {
        shader_errors(ui, &state.shader_errors);
    }
    if state.show_help {
        help_window(ui, &mut state.show_help);
    }
    state.ui_active = ui.is_any_item_active();
    actions
}

/// While recording, a red dot and "REC", the frames so far and the file, at the top right of
/// the view (also with the panels hidden; under the Stats window where it is shown): a
/// recording slows the app, and should not be left running unnoticed.
fn recording_indicator(ui: &Ui, state: &EditorState) {
    let Some((frames, file)) = &state.recording else { return };
    let text = format!("REC  {frames} frame{}  {file}", if *frames == 1 { "" } else { "s" });
    let size = ui.calc_text_size(&text);
    let stats = state.stats_panel.filter(|_| !state.hide_ui && !state.hide_stats);
    let [x, y] = badge_origin(ui.io().display_size, size, stats);
    let draw = ui.get_foreground_draw_list();
    draw.add_rect([x - 8.0, y - 4.0], [x + size[0] + 30.0, y + size[1] + 4.0], [0.0, 0.0, 0.0, 0.6])
        .filled(true)
        .rounding(4.0)
        .build();
    draw.add_circle([x + 6.0, y + size[1] / 2.0], 6.0, [0.95, 0.15, 0.15, 1.0]).filled(true).build();
    draw.add_text([x + 20.0, y], [1.0, 1.0, 1.0, 1.0], &text);
}

/// The top left of the recording badge's text of `text` size in a view of `display` size: at the
/// top right, or under the Stats window (`stats`: x, y, width, height) where the badge would
/// cover it (it covered the window's title). The badge reaches 8 pixels left of the text, 30
/// right of it and 4 above and below.
fn badge_origin(display: [f32; 2], text: [f32; 2], stats: Option<[f32; 4]>) -> [f32; 2] {
    let x = (display[0] - text[0] - 40.0).max(8.0);
    let (left, right) = (x - 8.0, x + text[0] + 30.0);
    let y = 10.0;
    match stats {
        Some([sx, sy, sw, sh])
            if left < sx + sw && right > sx && y - 4.0 < sy + sh && y + text[1] + 4.0 > sy =>
        {
            [x, sy + sh + 10.0]
        }
        _ => [x, y],
    }
}

/// The app's controls (the table in docs/guide/app.md), shown with F1.
const CONTROLS: [(&str, &str); 19] = [
    ("left-drag on cloth or rope", "grab the particle (within 12 pixels) and drag it"),
    ("Ctrl + left click", "pin the particle where it is, or free it"),
    ("left click on a sphere, box or capsule", "select it (its arrows in the view, its panel)"),
    ("left-drag on empty space, right-drag", "orbit (above the ground; Alt: also below)"),
    ("middle-drag, Shift + drag", "pan"),
    ("wheel", "zoom towards the cursor"),
    ("W A S D, Q E", "fly forward/left/back/right, down/up"),
    ("F", "fit the scene in view"),
    ("Home", "reset the camera"),
    ("Space", "pause or resume"),
    ("N", "step one frame"),
    ("Ctrl + R", "reset the simulation"),
    ("Ctrl + Z", "undo the last edit of the scene (not the simulation)"),
    ("Ctrl + Shift + Z, Ctrl + Y", "redo it"),
    ("F12", "save a screenshot (msdsim-<time>.png)"),
    ("F9", "start or stop recording (the file in the Simulation panel)"),
    ("F1", "show or hide these controls"),
    ("Esc", "let go of a drag; close these controls, the log or Replace"),
    ("Esc, Esc", "quit (twice within 3 s; the close button too, with unsaved edits)"),
];

fn help_window(ui: &Ui, open: &mut bool) {
    ui.window("Controls (F1)").opened(open).always_auto_resize(true).build(|| {
        // The descriptions start past the widest key, so the columns never run together.
        let column = CONTROLS.iter().map(|(key, _)| ui.calc_text_size(key)[0]).fold(0.0, f32::max) + 16.0;
        for (key, what) in CONTROLS {
            ui.text(key);
            ui.same_line_with_pos(column);
            ui.text_disabled(what);
        }
    });
}

trait TextWrappedColored {
    fn text_wrapped_colored(&self, colour: [f32; 4], text: &str);
}

impl TextWrappedColored for Ui {
    fn text_wrapped_colored(&self, colour: [f32; 4], text: &str) {
        let _c = self.push_style_color(imgui::StyleColor::Text, colour);
        self.text_wrapped(text);
    }
}

fn simulation_panel(ui: &Ui, state: &mut EditorState, scene: &mut Scene, actions: &mut Vec<Action>) {
    if !ui.collapsing_header("Simulation", TreeNodeFlags::DEFAULT_OPEN) {
        return;
    }
    if ui.button(if state.paused { "Resume (space)" } else { "Pause (space)" }) {
        actions.push(Action::TogglePause);
    }
    ui.same_line();
    if ui.button("Step (N)") {
        actions.push(Action::Step);
    }
    ui.same_line();
    if ui.button("Reset (Ctrl+R)") {
        actions.push(Action::Reset);
    }
    let (undo, redo) = state.undo_depth;
    ui.disabled(undo == 0, || {
        if ui.button(format!("Undo (Ctrl+Z): {undo}###undo")) {
            actions.push(Action::Undo);
        }
    });
    tip(ui, "Take back the last edit of the scene: a value, a drag of a handle, a pin, an object added or removed, a load. The simulation is not rewound: the scene is applied as an edit is.");
    ui.same_line();
    ui.disabled(redo == 0, || {
        if ui.button(format!("Redo (Ctrl+Shift+Z): {redo}###redo")) {
            actions.push(Action::Redo);
        }
    });
    if ui.button("Fit camera (F)") {
        actions.push(Action::FitCamera);
    }
    ui.same_line();
    if ui.button("Reset camera (Home)") {
        actions.push(Action::ResetCamera);
    }
    let label = match &state.recording {
        Some((n, _)) => format!("Stop recording (F9): {n} frame{}###record", if *n == 1 { "" } else { "s" }),
        None => "Record (F9)###record".to_string(),
    };
    if ui.button(label) {
        actions.push(Action::ToggleRecording(PathBuf::from(&state.record_path)));
    }
    tip(ui, "Record the animated surfaces of every simulated frame: .usda is one USD file (Blender, Houdini, usdview, Omniverse), .obj a numbered OBJ file a frame. The app slows down while it records (each frame is read back).");
    ui.same_line();
    ui.set_next_item_width(-1.0);
    ui.input_text("##record file", &mut state.record_path).build();
    tip(ui, "the recording's file: NAME.usda, NAME.obj for NAME_00001.obj, NAME_00002.obj, ..., NAME.glb (glTF), or NAME.pc2 for a point cache a mesh with the meshes in NAME.obj");
    check(ui, "real time", &mut state.real_time);
    int(ui, "substeps", &mut scene.sim.substeps, 1, 4096);
    let past = past_explicit_limit(scene);
    if let Some((_, why)) = past.first() {
        let more = if past.len() > 1 { format!(" ({} objects are)", past.len()) } else { String::new() };
        ui.text_wrapped_colored(WARNING, &format!("{why}{more}"));
    }
    let mut ms = scene.sim.frame_dt * 1e3;
    if drag(ui, "frame dt [ms]", &mut ms, 0.05, 0.1, 1000.0) {
        scene.sim.frame_dt = ms * 1e-3;
    }
    ui.text(format!("substep dt: {:.4} ms", scene.sim.frame_dt * 1e3 / scene.sim.substeps as f64));
    drag3(ui, "gravity [m/s^2]", &mut scene.sim.gravity, 0.05);
    if scene.cloths.len() + scene.ropes.len() > 1 {
        check(ui, "objects touch each other", &mut scene.sim.inter_object);
    }
    if scene.sim.inter_object && scene.cloths.len() > 1 {
        check(ui, "cloths keep their edges apart", &mut scene.sim.inter_object_edges);
    }
    let triangles = scene.cloths.iter().any(|c| c.self_collision && c.self_contact.triangles());
    if triangles || scene.mesh_cloths.iter().any(|c| c.self_collision) {
        int(ui, "contact iterations", &mut scene.sim.contact_iterations, 1, 64);
    }
    use crate::scene::IntegratorChoice as I;
    choice(ui, "integrator", &mut scene.sim.integrator, &I::all());
    match scene.sim.integrator {
        I::Method(m) if m.iterative() => {
            int(ui, "iterations", &mut scene.sim.iterations, 1, 1000);
            if m.method().relaxed {
                drag(ui, "relaxation", &mut scene.sim.relaxation, 0.01, 0.05, 1.95);
            }
        }
        I::Method(_) => {}
        I::Auto => {
            drag(ui, "tolerance (of size)", &mut scene.sim.tolerance, 0.0005, 1e-4, 0.5);
            if let Some(picked) = &state.auto_picked {
                ui.text_wrapped(picked);
            }
        }
    }
}

fn object_list(ui: &Ui, state: &mut EditorState, scene: &mut Scene) {
    let mut pick = |label: String, sel: Selection| {
        if ui.selectable_config(&label).selected(state.selected == sel).build() {
            state.selected = sel;
        }
    };
    for (i, c) in scene.cloths.iter().enumerate() {
        pick(format!("cloth  {}##c{i}", c.name), Selection::Cloth(i));
    }
    for (i, r) in scene.ropes.iter().enumerate() {
        pick(format!("rope   {}##r{i}", r.name), Selection::Rope(i));
    }
    for (i, m) in scene.mesh_cloths.iter().enumerate() {
        pick(format!("mesh cloth  {}##mc{i}", m.name), Selection::MeshCloth(i));
    }
    for (label, sel) in colliders::entries(scene) {
        pick(label, sel);
    }
    if scene.wind.enabled {
        pick("wind".into(), Selection::Wind);
    }
    pick("light".into(), Selection::Light);
    // New objects go where the camera looks, clear of the rest of the scene.
    let look_at = glam::DVec3::from_array(state.look_at);
    if ui.button("+ cloth") {
        let mut cloth = new_cloth(unique_name(scene, "cloth"));
        crate::scene::place::place_cloth(scene, &mut cloth, look_at);
        scene.cloths.push(cloth);
        state.selected = Selection::Cloth(scene.cloths.len() - 1);
    }
    ui.same_line();
    if ui.button("+ rope") {
        let mut rope = new_rope(unique_name(scene, "rope"));
        crate::scene::place::place_rope(scene, &mut rope, look_at);
        scene.ropes.push(rope);
        state.selected = Selection::Rope(scene.ropes.len() - 1);
    }
    ui.same_line();
    if ui.button("remove") {
        match state.selected {
            Selection::Cloth(i) if i < scene.cloths.len() => drop(scene.cloths.remove(i)),
            Selection::Rope(i) if i < scene.ropes.len() => drop(scene.ropes.remove(i)),
            Selection::MeshCloth(i) if i < scene.mesh_cloths.len() => drop(scene.mesh_cloths.remove(i)),
            other => drop(colliders::remove(scene, other)),
        }
        state.selected = Selection::None;
    }
    if let Some(added) = colliders::add_buttons(ui, scene, state.look_at) {
        state.selected = added;
    }
    match colliders::add_mesh(ui, scene, &mut state.mesh_path, state.look_at) {
        Ok(Some(added)) => state.selected = added,
        Ok(None) => {}
        Err(e) => state.notices.push(&e, true),
    }
}

/// A name not used by any object, from `base`.
pub fn unique_name(scene: &Scene, base: &str) -> String {
    let taken = |n: &str| {
        scene.cloths.iter().any(|c| c.name == n)
            || scene.ropes.iter().any(|r| r.name == n)
            || scene.mesh_cloths.iter().any(|m| m.name == n)
    };
    (1..).map(|i| format!("{base}{i}")).find(|n| !taken(n)).unwrap_or_else(|| base.to_string())
}

/// The cloths and ropes past the predicted explicit limit (ACCURACY.md, "The predicted explicit
/// limit") at the scene's substeps, with what to change; none for an iterative method or
/// `auto`, which stay stable. The editor says so beside the substeps and in the object's panel,
/// as `simulate` warns before a run.
pub fn past_explicit_limit(scene: &Scene) -> Vec<(Selection, String)> {
    use crate::scene::IntegratorChoice;
    use crate::sim::model::ObjectKind;
    use crate::sim::stability::predict_object;
    if !matches!(scene.sim.integrator, IntegratorChoice::Method(m) if !m.iterative()) {
        return Vec::new();
    }
    let (frame_dt, substeps) = (scene.sim.frame_dt, scene.sim.substeps);
    let cloths = scene.cloths.iter().enumerate().map(|(i, c)| {
        let p = predict_object(&c.name, ObjectKind::Cloth, c.resolution, c.stiffness.to_array(), c.mass);
        (Selection::Cloth(i), p)
    });
    let ropes = scene.ropes.iter().enumerate().map(|(i, r)| {
        let p = predict_object(&r.name, ObjectKind::Rope, [r.nodes, 1], r.stiffness_array(), r.mass);
        (Selection::Rope(i), p)
    });
    cloths
        .chain(ropes)
        .filter(|(_, p)| p.min_substeps(frame_dt) > substeps)
        .map(|(sel, p)| {
            let why = format!(
                "{} '{}' is past the stable substep predicted for this method: {}",
                p.kind.label(),
                p.name,
                p.substep_advice(frame_dt)
            );
            (sel, why)
        })
        .collect()
}

/// Colour of a warning beside a field.
const WARNING: [f32; 4] = [1.0, 0.75, 0.3, 1.0];

fn selected_panel(ui: &Ui, state: &EditorState, scene: &mut Scene) {
    for (_, why) in past_explicit_limit(scene).into_iter().filter(|(sel, _)| *sel == state.selected) {
        ui.text_wrapped_colored(WARNING, &why);
    }
    match state.selected {
        Selection::Cloth(i) if i < scene.cloths.len() => cloth_panel(ui, &mut scene.cloths[i]),
        Selection::Rope(i) if i < scene.ropes.len() => rope_panel(ui, &mut scene.ropes[i]),
        Selection::MeshCloth(i) if i < scene.mesh_cloths.len() => {
            mesh_cloth_panel(ui, &mut scene.mesh_cloths[i])
        }
        Selection::Wind | Selection::Light => ui.text_wrapped(
            "drag the arrows in the view to move it (its other settings are under Wind and Light above)",
        ),
        other => {
            if !colliders::panel(ui, scene, other) {
                ui.text_disabled("select an object to edit it");
            }
        }
    }
}

/// The compile errors overlay: shown while any shader fails; fixing the file clears it.
fn shader_errors(ui: &Ui, errors: &[String]) {
    let size = ui.io().display_size;
    ui.window("Shader errors (the last good pipelines keep running)")
        .position([size[0] * 0.5, size[1] - 12.0], Condition::Always)
        .position_pivot([0.5, 1.0])
        .size([size[0] * 0.8, 0.0], Condition::Always)
        .collapsible(false)
        .build(|| {
            for e in errors {
                ui.text_wrapped_colored([1.0, 0.45, 0.4, 1.0], e);
            }
        });
}

fn stats_window(ui: &Ui, stats: &Stats, state: &mut EditorState, scene: &Scene) {
    // At the top right, out of the middle of the view; as tall as its content, its lines
    // wrapped at its width, so none is cut off.
    let [x, y, ..] = stats_start(ui.io().display_size);
    ui.window("Stats").position([x, y], Condition::FirstUseEver).always_auto_resize(true).build(|| {
        let ([x, y], [w, h]) = (ui.window_pos(), ui.window_size());
        state.stats_panel = Some([x, y, w, h]);
        let _wrap = ui.push_text_wrap_pos_with_pos(STATS_WIDTH - 2.0 * ui.clone_style().window_padding[0]);
        ui.text_disabled("F1: the controls");
        ui.text_wrapped(&stats.device);
        ui.text(format!(
            "frame {:.2} ms ({:.0} fps, wall clock)",
            stats.cpu_frame_ms,
            1e3 / stats.cpu_frame_ms.max(1e-6)
        ));
        ui.text(format!("t = {:.2} s, {} particles", stats.simulated_time, stats.particles));
        match stats.speed {
            Some(s) if s < 0.95 => ui.text_colored(
                [1.0, 0.75, 0.3, 1.0],
                format!("running at {s:.2}x real time\n(one frame's dt per drawn frame)"),
            ),
            Some(s) => ui.text(format!("running at {s:.2}x real time")),
            None => ui.text("paused"),
        }
        let ms = |v: Option<f64>| v.map(|v| format!("{v:.3} ms")).unwrap_or_else(|| "-".into());
        // The same two figures as `bench --end-to-end`: the wall clock above, the GPU's
        // own time here (simulation + scene + UI).
        let gpu = stats.sim.map(|s| s.total_ms).unwrap_or(0.0)
            + stats.render_ms.unwrap_or(0.0)
            + stats.ui_ms.unwrap_or(0.0);
        match gpu > 0.0 {
            true => ui.text(format!("GPU {} per frame ({:.0} fps GPU-only)", ms(Some(gpu)), 1e3 / gpu)),
            // (no frame timed yet)
            false => ui.text("GPU - per frame"),
        }
        ui.separator();
        ui.text("GPU time per frame (timestamps):");
        let row = |label: &str, v: Option<f64>| ui.text(format!("  {label:<26} {}", ms(v)));
        let physics = stats.sim.map(|s| s.physics_ms);
        match stats.sim.and_then(|s| s.fused) {
            // A fused object runs all its stages in one pass: not separable.
            Some(true) => row("simulation (fused)", physics),
            Some(false) => row("physics + fused objects", physics),
            None => row("physics", physics),
        }
        if stats.sim.and_then(|s| s.fused) != Some(true) {
            row("constraints", stats.sim.map(|s| s.constraints_ms));
        }
        let surface = match (scene.cloths.is_empty(), scene.ropes.is_empty()) {
            (false, false) => "cloth normals + rope tubes",
            (false, true) => "cloth normals",
            (true, false) => "rope tubes",
            (true, true) => "surface",
        };
        row(surface, stats.sim.map(|s| s.surface_ms));
        row("render", stats.render_ms);
        row("UI", stats.ui_ms);
        if !state.shaders_note.is_empty() {
            ui.separator();
            ui.text_wrapped(&state.shaders_note);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recording badge sits at the top right, under the Stats window where that is at its
    /// place (it covered the window's title), and nowhere over it.
    #[test]
    fn the_recording_badge_does_not_cover_the_stats_window() {
        let display = [1280.0, 800.0];
        let text = [260.0, 13.0];
        assert_eq!(badge_origin(display, text, None), [980.0, 10.0]);
        let [sx, sy, sw, sh] = stats_start(display);
        let [x, y] = badge_origin(display, text, Some([sx, sy, sw, sh]));
        let (left, right, top, bottom) = (x - 8.0, x + text[0] + 30.0, y - 4.0, y + text[1] + 4.0);
        let apart = right <= sx || left >= sx + sw || bottom <= sy || top >= sy + sh;
        assert!(apart, "badge [{left}, {right}] x [{top}, {bottom}] over Stats {:?}", [sx, sy, sw, sh]);
        assert!(x > display[0] / 2.0, "still at the right: {x}");
    }

    /// With an explicit method the editor names an object past the predicted stable substep,
    /// with the substeps it needs, and nothing for a method stable at any step.
    #[test]
    fn the_editor_says_when_an_object_is_past_the_explicit_limit() {
        use crate::scene::{IntegratorChoice, Rope};
        use crate::sim::model::Integrator;
        // A chain's highest mode is sqrt(4 k / m) (the bound is exact there): k = 1000 N/m,
        // m = 10 g, 632.5 rad/s, a stable substep of 3.16 ms, 6 substeps of a 1/60 s frame.
        let mut scene = Scene::default();
        scene.ropes.push(Rope {
            nodes: 40,
            stiffness: 1000.0,
            bending_stiffness: 0.0,
            mass: 0.01,
            ..new_rope("r".into())
        });
        scene.sim.frame_dt = 1.0 / 60.0;
        scene.sim.integrator = IntegratorChoice::Method(Integrator::SymplecticEuler);
        scene.sim.substeps = 5;
        let past = past_explicit_limit(&scene);
        assert_eq!(past.len(), 1, "{past:?}");
        assert_eq!(past[0].0, Selection::Rope(0));
        assert!(past[0].1.contains("use at least 6 substeps"), "{}", past[0].1);
        // The same advice as the built scene's prediction, which `simulate` prints.
        let model = crate::scene::to_model(&scene);
        let p = &crate::sim::stability::predict(&model)[0];
        assert_eq!(p.min_substeps(scene.sim.frame_dt), 6);
        scene.sim.substeps = 6;
        assert!(past_explicit_limit(&scene).is_empty());
        scene.sim.substeps = 1;
        scene.sim.integrator = IntegratorChoice::Method(Integrator::Vbd);
        assert!(past_explicit_limit(&scene).is_empty(), "an iterative method is stable at any step");
        scene.sim.integrator = IntegratorChoice::Auto;
        assert!(past_explicit_limit(&scene).is_empty(), "auto picks a stable setting");
    }

    /// Save writes a new file at once; an existing one only on the second press (Replace), and
    /// a changed path asks again.
    #[test]
    fn save_asks_before_replacing_a_file() {
        let mut state = EditorState::default();
        assert_eq!(save_pressed(&mut state, "new.toml", false), Some(Action::Save("new.toml".into())));
        assert_eq!(save_pressed(&mut state, "presets/curtain.toml", true), None, "asks first");
        assert_eq!(state.replace.as_deref(), Some("presets/curtain.toml"));
        assert_eq!(
            save_pressed(&mut state, "presets/curtain.toml", true),
            Some(Action::Save("presets/curtain.toml".into())),
            "the second press replaces it"
        );
        assert_eq!(state.replace, None);
        assert_eq!(save_pressed(&mut state, "presets/towel.toml", true), None);
        assert_eq!(save_pressed(&mut state, "presets/flag.toml", true), None, "another file asks again");
    }
}
