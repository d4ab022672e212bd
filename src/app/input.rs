//! Mouse and keyboard: camera controls and grabbing particles.
//!
//! Left-drag on a particle grabs it (it follows the cursor at its depth, pinned, until the
//! button is released); left-drag elsewhere or right-drag orbits; middle-drag or Shift+drag pans;
//! the wheel zooms; W/A/S/D/Q/E fly; F fits the scene; Home resets the camera; Space pauses;
//! N steps one frame; Ctrl+R resets the simulation; Esc quits.

use crate::render::camera::OrbitCamera;
use crate::sim::gpu::ObjectState;
use glam::Vec3;
use std::collections::HashSet;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::keyboard::{KeyCode, ModifiersState, PhysicalKey};

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
    Quit,
}

#[derive(Default)]
pub struct Input {
    pub cursor: [f32; 2],
    last_cursor: Option<[f32; 2]>,
    buttons: HashSet<MouseButton>,
    keys: HashSet<KeyCode>,
    modifiers: ModifiersState,
    /// The left button went down this frame outside the UI: the app tries a pick.
    pub pick_requested: bool,
    /// Ctrl + left click: pin or unpin the particle under the cursor.
    pub pin_requested: bool,
    pub grab: Option<Grab>,
    /// The grab ended this frame: the app releases the particle.
    pub released: Option<Grab>,
    /// Left-drag that started on empty space orbits.
    left_orbits: bool,
    pub actions: Vec<KeyAction>,
}

impl Input {
    /// Handles a window event the UI did not capture (`ui_mouse` / `ui_keys`: ImGui wants them).
    pub fn handle(&mut self, event: &WindowEvent, camera: &mut OrbitCamera, ui_mouse: bool, ui_keys: bool) {
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
                        camera.orbit(dx, dy);
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
                        self.released = self.grab.take();
                        self.left_orbits = false;
                    }
                }
            },
            WindowEvent::MouseWheel { delta, .. } if !ui_mouse => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                camera.zoom(steps);
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
                    KeyCode::KeyF => Some(KeyAction::Fit),
                    KeyCode::Home => Some(KeyAction::ResetCamera),
                    KeyCode::F12 => Some(KeyAction::Screenshot),
                    KeyCode::F1 => Some(KeyAction::Help),
                    KeyCode::Escape => Some(KeyAction::Quit),
                    _ => None,
                };
                self.actions.extend(action);
            }
            WindowEvent::Focused(false) => {
                self.keys.clear();
                self.buttons.clear();
            }
            _ => {}
        }
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

/// The particle nearest to the ray (origin, unit direction) within a pick radius that grows
/// with distance; (object, index, depth along the ray, pinned).
pub fn pick(states: &[ObjectState], origin: Vec3, dir: Vec3) -> Option<(usize, u32, f32, bool)> {
    let mut best: Option<(f32, (usize, u32, f32, bool))> = None;
    for (o, state) in states.iter().enumerate() {
        for (i, p) in state.particles.iter().enumerate() {
            let x = Vec3::new(p.pos[0], p.pos[1], p.pos[2]);
            let t = (x - origin).dot(dir);
            if t <= 0.0 {
                continue;
            }
            let miss = (x - (origin + dir * t)).length();
            let radius = 0.02 + 0.015 * t;
            if miss < radius && best.is_none_or(|(b, _)| miss / radius < b) {
                best = Some((miss / radius, (o, i as u32, t, p.pos[3] > 0.5)));
            }
        }
    }
    best.map(|(_, hit)| hit)
}
