//! Mouse and keyboard: camera controls and grabbing particles.
//!
//! Left-drag on a particle grabs it (it follows the cursor at its depth, pinned, until the
//! button is released or Esc lets go of it; on an object whose pins move, its pins carry it
//! within each frame too, from where the cursor put it); a click on a sphere, box or capsule in front of
//! any particle selects it (`handles::pick_collider`); left-drag elsewhere or right-drag orbits; middle-drag or Shift+drag pans;
//! the wheel zooms; W/A/S/D/Q/E fly; F fits the scene; Home resets the camera; Space pauses;
//! N steps one frame; Ctrl+R resets the simulation; Ctrl+Z undoes an edit, Ctrl+Shift+Z or
//! Ctrl+Y redoes it; Esc closes what is open, else twice within 3 s quits.

use crate::render::camera::OrbitCamera;
use crate::sim::gpu::ObjectState;
use crate::sim::model::{ObjectKind, ObjectModel, SimModel};
use glam::Vec3;
use std::collections::HashSet;
use winit::event::{ElementState, KeyEvent, MouseButton, MouseScrollDelta, WindowEvent};
use winit::keyboard::{Key, KeyCode, ModifiersState, NamedKey, PhysicalKey};

/// A grabbed particle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grab {
    pub object: usize,
    pub index: u32,
    /// Distance along the pick ray at which it is held [m].
    pub depth: f32,
    /// Whether it was pinned before the grab (restored on release).
    pub was_pinned: bool,
    /// Where it is held now [m].
    pub target: Vec3,
}

/// A key action for the app.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyAction {
    TogglePause,
    Step,
    Reset,
    Fit,
    ResetCamera,
    Screenshot,
    Help,
    Record,
    Undo,
    Redo,
    /// Esc with nothing held: the app closes what is open, else asks to quit (`escape`).
    Escape,
    /// Esc once: the app asks for a second press (`QUIT_CONFIRM`) before quitting.
    QuitAsk,
    Quit,
}

/// How long a first Esc waits for the second that quits [s].
pub const QUIT_CONFIRM: f64 = 3.0;

#[derive(Default)]
pub struct Input {
    pub cursor: [f32; 2],
    last_cursor: Option<[f32; 2]>,
    buttons: HashSet<MouseButton>,
    keys: HashSet<KeyCode>,
    modifiers: ModifiersState,
    /// Keys whose press went to an editor field as its characters alone (`typed`): their
    /// release goes nowhere either.
    typing: HashSet<PhysicalKey>,
    /// The left button went down this frame outside the UI: the app tries a pick.
    pub pick_requested: bool,
    /// Ctrl + left click: pin or unpin the particle under the cursor.
    pub pin_requested: bool,
    pub grab: Option<Grab>,
    /// The grab ended this frame: the app releases the particle.
    pub released: Option<Grab>,
    /// Left-drag that started on empty space orbits.
    left_orbits: bool,
    /// When Esc was pressed to quit, waiting for the second press.
    quit_asked: Option<std::time::Instant>,
    pub actions: Vec<KeyAction>,
}

impl Input {
    /// Esc pressed: lets go of a held particle (where it is now; an earlier question to quit is
    /// forgotten), else the app decides (`KeyAction::Escape`).
    fn on_escape(&mut self) -> Option<KeyAction> {
        if let Some(grab) = self.grab.take() {
            self.released = Some(grab);
            self.quit_asked = None;
            return None;
        }
        Some(KeyAction::Escape)
    }

    /// Esc (or the close button) at `now` with nothing to close: quit when it follows a first
    /// press within QUIT_CONFIRM seconds, else ask (a stray Esc, meant for a text field, loses
    /// nothing).
    pub(super) fn escape(&mut self, now: std::time::Instant) -> KeyAction {
        match self.quit_asked.take() {
            Some(at) if now.duration_since(at).as_secs_f64() <= QUIT_CONFIRM => KeyAction::Quit,
            _ => {
                self.quit_asked = Some(now);
                KeyAction::QuitAsk
            }
        }
    }

    /// The Esc that asked to quit closed something instead: the next press asks again.
    pub(super) fn forget_quit(&mut self) {
        self.quit_asked = None;
    }

    /// Handles a window event the UI did not capture (`ui_mouse` / `ui_keys`: ImGui wants them).
    /// `floor`: the ground's height, which an orbit keeps the eye above unless Alt is held;
    /// `size`: the window's, in pixels.
    pub fn handle(
        &mut self,
        event: &WindowEvent,
        camera: &mut OrbitCamera,
        view: (Option<f32>, [f32; 2]),
        ui_mouse: bool,
        ui_keys: bool,
    ) {
        let (floor, size) = view;
        match event {
            WindowEvent::CursorMoved { position, .. } => {
                let now = [position.x as f32, position.y as f32];
                if let Some(last) = self.last_cursor {
                    let (dx, dy) = (now[0] - last[0], now[1] - last[1]);
                    let left =
                        self.buttons.contains(&MouseButton::Left) && self.grab.is_none() && self.left_orbits;
                    let right = self.buttons.contains(&MouseButton::Right);
                    let middle = self.buttons.contains(&MouseButton::Middle);
                    if middle || ((left || right) && self.modifiers.shift_key()) {
                        camera.pan(dx, dy);
                    } else if left || right {
                        camera.orbit(dx, dy, floor.filter(|_| !self.modifiers.alt_key()));
                    }
                }
                self.cursor = now;
                self.last_cursor = Some(now);
            }
            WindowEvent::MouseInput { state, button, .. } => match state {
                ElementState::Pressed if !ui_mouse => {
                    self.buttons.insert(*button);
                    if *button == MouseButton::Left && self.modifiers.control_key() {
                        self.pin_requested = true;
                    } else if *button == MouseButton::Left && !self.modifiers.shift_key() {
                        self.pick_requested = true;
                        self.left_orbits = false;
                    }
                }
                ElementState::Pressed => {}
                ElementState::Released => {
                    self.buttons.remove(button);
                    if *button == MouseButton::Left {
                        self.released = self.grab.take().or(self.released.take());
                        self.left_orbits = false;
                    }
                }
            },
            WindowEvent::MouseWheel { delta, .. } if !ui_mouse => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                camera.zoom_at(steps, self.cursor, size, floor.filter(|_| !self.modifiers.alt_key()));
            }
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else { return };
                if event.state == ElementState::Released {
                    self.keys.remove(&code);
                    return;
                }
                if ui_keys {
                    return;
                }
                self.keys.insert(code);
                if event.repeat {
                    return;
                }
                let action = match code {
                    KeyCode::Space => Some(KeyAction::TogglePause),
                    KeyCode::KeyN => Some(KeyAction::Step),
                    KeyCode::KeyR if self.modifiers.control_key() => Some(KeyAction::Reset),
                    KeyCode::KeyZ if self.modifiers.control_key() && self.modifiers.shift_key() => {
                        Some(KeyAction::Redo)
                    }
                    KeyCode::KeyZ if self.modifiers.control_key() => Some(KeyAction::Undo),
                    KeyCode::KeyY if self.modifiers.control_key() => Some(KeyAction::Redo),
                    KeyCode::KeyF => Some(KeyAction::Fit),
                    KeyCode::Home => Some(KeyAction::ResetCamera),
                    KeyCode::F12 => Some(KeyAction::Screenshot),
                    KeyCode::F1 => Some(KeyAction::Help),
                    KeyCode::F9 => Some(KeyAction::Record),
                    KeyCode::Escape => self.on_escape(),
                    _ => None,
                };
                self.actions.extend(action);
            }
            WindowEvent::Focused(false) => {
                self.keys.clear();
                self.buttons.clear();
                self.typing.clear();
            }
            _ => {}
        }
    }

    /// A scripted left button (the app's exercise): pressed (a pick is tried) or held at
    /// `at`, or released.
    pub fn script_left(&mut self, down: bool, at: [f32; 2]) {
        self.cursor = at;
        self.last_cursor = Some(at);
        if down && !self.buttons.contains(&MouseButton::Left) {
            self.pick_requested = true;
            self.left_orbits = false;
        }
        if down {
            self.buttons.insert(MouseButton::Left);
        } else {
            self.buttons.remove(&MouseButton::Left);
            self.released = self.grab.take().or(self.released.take());
        }
    }

    /// Whether the left button is held.
    pub fn left_down(&self) -> bool {
        self.buttons.contains(&MouseButton::Left)
    }

    /// The pick found nothing: the left drag orbits instead.
    pub fn pick_missed(&mut self) {
        self.left_orbits = true;
    }

    /// Flies the camera with the held keys for `dt` seconds (not while Ctrl is held).
    pub fn fly(&self, camera: &mut OrbitCamera, dt: f32) {
        if self.modifiers.control_key() {
            return;
        }
        let axis = |plus: KeyCode, minus: KeyCode| {
            self.keys.contains(&plus) as i32 as f32 - self.keys.contains(&minus) as i32 as f32
        };
        let (f, r, u) = (
            axis(KeyCode::KeyW, KeyCode::KeyS),
            axis(KeyCode::KeyD, KeyCode::KeyA),
            axis(KeyCode::KeyE, KeyCode::KeyQ),
        );
        if f != 0.0 || r != 0.0 || u != 0.0 {
            camera.fly(f, r, u, dt);
        }
    }
}

/// Each object's own pick radius for `pick`: a rope's tube radius, 0 for a cloth [m].
pub fn pick_radii(model: &SimModel) -> Vec<f32> {
    let radius = |o: &ObjectModel| if o.kind == ObjectKind::Rope { o.rope_radius as f32 } else { 0.0 };
    model.objects.iter().map(radius).collect()
}

/// How far from a particle, on screen, a click still takes it [pixels].
pub const PICK_PIXELS: f32 = 12.0;

/// A pick ray: origin, unit direction, and the size of one pixel at one metre of depth [m]
/// (`OrbitCamera::pixel_size`).
#[derive(Debug, Clone, Copy)]
pub struct PickRay {
    pub origin: Vec3,
    pub dir: Vec3,
    pub pixel: f32,
}

/// The particle nearest to the ray within `PICK_PIXELS` on screen of it, or of its object's
/// own radius `radii[object]` (a rope's tube) around it, and nearer along the ray than
/// `nearer` (a collider the ray meets: what is behind it is hidden); (object, index, depth
/// along the ray, pinned).
pub fn pick(
    states: &[ObjectState],
    ray: PickRay,
    radii: &[f32],
    nearer: f32,
) -> Option<(usize, u32, f32, bool)> {
    let PickRay { origin, dir, pixel } = ray;
    let mut best: Option<(f32, (usize, u32, f32, bool))> = None;
    for (o, state) in states.iter().enumerate() {
        let own = radii.get(o).copied().unwrap_or(0.0);
        for (i, p) in state.particles.iter().enumerate() {
            let x = Vec3::new(p.pos[0], p.pos[1], p.pos[2]);
            let t = (x - origin).dot(dir);
            if t <= 0.0 || t >= nearer {
                continue;
            }
            let miss = (x - (origin + dir * t)).length();
            let radius = own + PICK_PIXELS * pixel * t;
            if miss < radius && best.is_none_or(|(b, _)| miss / radius < b) {
                best = Some((miss / radius, (o, i as u32, t, p.pos[3] > 0.5)));
            }
        }
    }
    best.map(|(_, hit)| hit)
}

impl Input {
    /// A key event while an editor field takes text (`taking_text`, ImGui's
    /// `want_text_input`): for a press that only types, its characters, which go to ImGui
    /// without the key's own press and release (an empty string for that release); `None` for
    /// what goes as it is. ImGui's input queue trickles: a key's press or release and text in
    /// one frame end that frame's input, so a field took about a character every two frames,
    /// and typing at a few frames a second fell seconds behind and looked lost (issue 69, item
    /// 11). The characters alone are all taken in one frame. Keys with Ctrl, Alt or Super,
    /// named keys but Space (Enter, Backspace, Tab, the arrows) and control characters go as
    /// they are.
    pub fn typed(&mut self, event: &KeyEvent, taking_text: bool) -> Option<String> {
        if event.state == ElementState::Released {
            return self.typing.remove(&event.physical_key).then(String::new);
        }
        let text = event.text.as_deref()?;
        if !characters_only(taking_text, &event.logical_key, text, self.modifiers) {
            return None;
        }
        self.typing.insert(event.physical_key);
        Some(text.to_owned())
    }
}

/// Whether a press of `key` that produced `text` only types it into a field taking text.
fn characters_only(taking_text: bool, key: &Key, text: &str, modifiers: ModifiersState) -> bool {
    let chord = modifiers.control_key() || modifiers.alt_key() || modifiers.super_key();
    taking_text
        && !chord
        && matches!(key, Key::Character(_) | Key::Named(NamedKey::Space))
        && !text.is_empty()
        && !text.chars().any(char::is_control)
}

#[cfg(test)]
mod tests {
    /// Only plain characters (and spaces) typed into a field skip their key events: not
    /// outside a field, not with Ctrl (select all, copy, paste), not other named keys (Enter
    /// applies, Tab moves on), not control characters.
    #[test]
    fn only_plain_characters_typed_into_a_field_go_alone() {
        use super::characters_only;
        use winit::keyboard::{Key, ModifiersState, NamedKey};
        let a = Key::Character("a".into());
        let none = ModifiersState::empty();
        assert!(characters_only(true, &a, "a", none));
        assert!(characters_only(true, &Key::Character("8".into()), "8", ModifiersState::SHIFT));
        assert!(!characters_only(false, &a, "a", none), "no field takes text");
        assert!(!characters_only(true, &a, "a", ModifiersState::CONTROL), "Ctrl+A selects all");
        assert!(!characters_only(true, &a, "\u{1}", none), "a control character");
        assert!(!characters_only(true, &Key::Named(NamedKey::Enter), "\r", none), "Enter applies");
        assert!(characters_only(true, &Key::Named(NamedKey::Space), " ", none), "a space types");
        assert!(!characters_only(true, &Key::Named(NamedKey::Tab), "\t", none), "Tab moves on");
    }

    #[test]
    fn esc_quits_only_when_pressed_twice_in_time() {
        use std::time::{Duration, Instant};
        let mut input = Input::default();
        let t0 = Instant::now();
        assert_eq!(input.escape(t0), KeyAction::QuitAsk);
        assert_eq!(input.escape(t0 + Duration::from_secs(1)), KeyAction::Quit);
        assert_eq!(
            input.escape(t0 + Duration::from_secs(2)),
            KeyAction::QuitAsk,
            "asks again after quitting"
        );
        assert_eq!(input.escape(t0 + Duration::from_secs(6)), KeyAction::QuitAsk, "too late: asks again");
        assert_eq!(input.escape(t0 + Duration::from_secs(7)), KeyAction::Quit);
    }

    /// Esc in the middle of a grab lets go of the particle and does not ask to quit; the next
    /// Esc asks.
    #[test]
    fn esc_lets_go_of_a_grab_first() {
        let mut input = Input::default();
        let grab = Grab { object: 0, index: 3, depth: 1.0, was_pinned: false, target: Vec3::ZERO };
        input.grab = Some(grab);
        let t0 = std::time::Instant::now();
        assert_eq!(input.escape(t0), KeyAction::QuitAsk, "asked before the grab");
        assert_eq!(input.on_escape(), None);
        assert!(input.grab.is_none() && input.released.is_some_and(|r| r.index == 3));
        assert_eq!(input.on_escape(), Some(KeyAction::Escape));
        assert_eq!(input.escape(t0), KeyAction::QuitAsk, "the question before the grab is forgotten");
    }

    use super::*;
    use crate::sim::gpu_types::Particle;

    fn rope(nodes: &[Vec3]) -> ObjectState {
        ObjectState {
            particles: nodes.iter().map(|x| Particle { pos: [x.x, x.y, x.z, 0.0], vel: [0.0; 4] }).collect(),
            surface: Vec::new(),
        }
    }

    /// A click lands on a rope node when it is within PICK_PIXELS on screen of the node or
    /// within the tube's radius of it, at any distance; farther out it misses (and orbits).
    #[test]
    fn a_rope_is_picked_within_a_few_pixels_of_its_tube() {
        let pixel = 2.0 * (45f32.to_radians() * 0.5).tan() / 800.0; // 45 degrees over 800 pixels
        let states = [rope(&[Vec3::new(0.0, 0.0, -3.0), Vec3::new(0.05, 0.0, -3.0)])];
        let radii = [0.01];
        let at_pixels = |px: f32| {
            let dir = Vec3::new(0.0, px * pixel, -1.0).normalize();
            pick(&states, PickRay { origin: Vec3::ZERO, dir, pixel }, &radii, f32::INFINITY)
        };
        let tube = 0.01 / (3.0 * pixel); // the tube's radius on screen [pixels]
        assert!(at_pixels(0.0).is_some());
        assert!(at_pixels(tube + PICK_PIXELS - 1.0).is_some(), "within {PICK_PIXELS} pixels of the tube");
        assert!(at_pixels(tube + PICK_PIXELS + 2.0).is_none(), "farther out the click misses");
        let far = [rope(&[Vec3::new(0.0, 0.0, -30.0)])];
        let dir = Vec3::new(0.0, 8.0 * pixel, -1.0).normalize();
        assert!(
            pick(&far, PickRay { origin: Vec3::ZERO, dir, pixel }, &[0.0], f32::INFINITY).is_some(),
            "8 pixels at 30 m"
        );
        // Behind a collider the ray meets at 2.9 m, the rope at 3 m is hidden; in front of one
        // at 3.1 m it is taken.
        let ray = PickRay { origin: Vec3::ZERO, dir: Vec3::NEG_Z, pixel };
        assert!(pick(&states, ray, &radii, 2.9).is_none(), "hidden behind the collider");
        assert!(pick(&states, ray, &radii, 3.1).is_some(), "in front of the collider");
    }
}
