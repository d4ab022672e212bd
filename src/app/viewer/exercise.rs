//! The app's scripted exercises for the tests (`--exercise-window`, `--exercise-editor`):
//! they drive the window and the editor's code paths frame by frame, with frames in flight,
//! and fail on anything refused.

use super::super::handles;
use super::super::input::KeyAction;
use super::{Outcome, Viewer};
use crate::app::SimHost;
use crate::scene;
use crate::ui::{Action, Selection};
use anyhow::{Context as _, Result};
use glam::Vec3;
use winit::dpi::PhysicalSize;

impl Viewer {
    /// The scripted window exercise of `--exercise-window`: resizes, a minimise and restore
    /// cycle, then exit.
    pub(super) fn exercise(&mut self) -> Outcome {
        let sizes = [(4, [700, 500]), (8, [420, 300]), (12, [900, 650]), (28, [640, 480])];
        for (at, [w, h]) in sizes {
            if self.tick == at {
                let _ = self.window.request_inner_size(PhysicalSize::new(w, h));
            }
        }
        match self.tick {
            16 => {
                self.window.set_minimized(true);
                // Without a window manager the request may do nothing: report the zero size a
                // minimised window gets, as the platform would.
                self.resized(PhysicalSize::new(0, 0));
            }
            22 => {
                self.window.set_minimized(false);
                self.resized(self.window.inner_size());
            }
            40 => return Outcome::Exit,
            _ => {}
        }
        Outcome::Continue
    }

    /// The scripted editor exercise of `--exercise-editor`: the editor's code paths (a parameter
    /// edit, a substep change, a layout change, an F12 screenshot, reset, pinning by click, save
    /// and load, the Record button, loading a shipped preset by its bare name, dragging a
    /// sphere by its translate handle with the rope on it,
    /// closing the window with that edit unsaved (it asks), undoing the drag with Ctrl+Z and
    /// redoing it, closing twice: it quits and keeps the edit in a rescue file) with frames in
    /// flight, then exit. Any refusal is an error.
    pub(super) fn exercise_editor(&mut self) -> Result<Outcome> {
        let mut scene = self.host().scene().clone();
        let saved = std::env::temp_dir().join(format!("msdsim-exercise-{}.toml", std::process::id()));
        let expect = |host: &SimHost, what: &str, ok: bool| {
            if ok {
                Ok(())
            } else {
                Err(anyhow::anyhow!("exercise: {what} did not apply ({:?})", host.scene().sim))
            }
        };
        match self.tick {
            3 => {
                for c in &mut scene.cloths {
                    c.stiffness.structural *= 1.5;
                }
                scene.sim.gravity[0] = 1.0;
                self.pending_scene = Some(scene);
            }
            6 => {
                scene.sim.substeps += 1;
                self.pending_scene = Some(scene);
            }
            9 => {
                scene.spheres.push(scene::Sphere { center: [0.0, 0.2, 0.4], radius: 0.1, motion: None });
                self.pending_scene = Some(scene);
            }
            10 => self.shot = Some((saved.with_extension("png"), true)),
            12 => self.pending_actions.push(Action::Reset),
            11 => self.editor.show_help = true, // the controls window draws clean too
            13 => {
                // Ctrl + click's path: pin rope node 5 (saved with the preset at 14).
                let host = self.host.as_mut().expect("host");
                let p = host.sim_mut().read_states(&self.ctx)?[0].particles[5].pos;
                host.set_pinned(&self.ctx, 0, 5, true, [p[0], p[1], p[2]])
                    .map_err(|e| anyhow::anyhow!("exercise: pinning failed: {e}"))?;
            }
            14 => self.pending_actions.push(Action::Save(saved.clone())),
            16 => {
                self.pending_actions.push(Action::Load(saved.clone()));
            }
            // The Record button's path: frames 17 and 18 into a USD file, written at 19.
            17 | 19 => self.pending_actions.push(Action::ToggleRecording(saved.with_extension("usda"))),
            // While it records, the view shows so (checked at 20).
            18 => self.shot = Some((saved.with_extension("rec.png"), false)),
            20 => {
                let host = self.host();
                expect(host, "the stiffness edit", host.scene().sim.gravity[0] == 1.0)?;
                expect(host, "the new sphere", host.scene().spheres.iter().any(|s| s.radius == 0.1))?;
                let pinned = host.scene().ropes.first().is_some_and(|r| r.pinned.contains(&5));
                expect(host, "the pin saved with the preset and loaded back", pinned)?;
                let shot = saved.with_extension("png");
                let written = std::fs::metadata(&shot).map(|m| m.len()).unwrap_or(0);
                expect(host, "the F12 screenshot", written > 1000)?;
                let usda = std::fs::read_to_string(saved.with_extension("usda")).unwrap_or_default();
                let recorded = usda.starts_with("#usda 1.0") && usda.contains("endTimeCode = 2\n");
                expect(host, "the recording of two frames", recorded && usda.contains("def Mesh"))?;
                let notice = self.editor.notices.current(std::time::Instant::now()).is_some();
                expect(host, "the recording's notice over the view", notice)?;
                let indicator = recording_indicator_shown(&saved.with_extension("rec.png"));
                expect(
                    host,
                    "the recording indicator (a red dot at the top right or under Stats)",
                    indicator,
                )?;
                let _ = std::fs::remove_file(saved.with_extension("rec.png"));
                let _ = std::fs::remove_file(&saved);
                let _ = std::fs::remove_file(&shot);
                let _ = std::fs::remove_file(saved.with_extension("usda"));
                if let Some((text, true)) = self.editor.notices.last() {
                    anyhow::bail!("exercise: the editor reported an error: {text}");
                }
            }
            // Load by a shipped preset's bare name: the field then shows the file loaded, so
            // that Save writes there (not a new ./rope.toml).
            21 => {
                self.editor.preset_path = "rope.toml".into();
                let path = crate::ui::resolve_preset(&self.editor.preset_path, "");
                self.pending_actions.push(Action::Load(path));
            }
            // (applied over the next frames: on a CPU device a rebuild is announced first)
            30 => {
                let shown = std::path::PathBuf::from(&self.editor.preset_path);
                let shipped = shown.ends_with("presets/rope.toml") && shown.is_file();
                expect(
                    self.host(),
                    &format!("the loaded file in the preset field ({})", shown.display()),
                    shipped,
                )?;
            }
            // A translate handle, once the rope (reloaded at 21) lies on sphere 0: select the
            // sphere, press on its x arrow, drag 40 pixels right over two frames and let go.
            60 => self.editor.selected = Selection::Sphere(0),
            61..=63 => {
                let size = self.window.inner_size();
                let size = [size.width as f32, size.height as f32];
                let at =
                    handles::position(self.host().scene(), Selection::Sphere(0)).context("no sphere 0")?;
                let tip = handles::screen_tip(&self.camera, size, at, 0).context("sphere 0 off screen")?;
                let cursor = [tip[0] - 4.0 + 20.0 * (self.tick - 61) as f32, tip[1]];
                if self.tick == 61 {
                    self.exercise_start = Some(at);
                    self.exercise_rope_x = self.rope_mean_x()?;
                }
                self.input.script_left(self.tick < 63, cursor);
            }
            // The drag left an unsaved edit: the window's close button asks first (and the
            // second press would quit; the exercise goes on instead).
            74 => {
                let quit = self.handle_event(&winit::event::WindowEvent::CloseRequested);
                let asked = self.editor.notices.last().is_some_and(|(m, _)| m.contains("unsaved edits"));
                expect(self.host(), "closing with unsaved edits asking first", !quit && asked)?;
            }
            // It moved along x only, and the rope lying on it came along (friction).
            75 => {
                let rope_x = self.rope_mean_x()? - self.exercise_rope_x;
                let host = self.host();
                let moved = handles::position(host.scene(), Selection::Sphere(0)).unwrap_or_default()
                    - self.exercise_start.unwrap_or_default();
                let along_x = moved.x > 0.01 && moved.y.abs() < 1e-4 && moved.z.abs() < 1e-4;
                expect(host, &format!("the sphere dragged along x by its handle (moved {moved})"), along_x)?;
                let dragged = rope_x > 0.002;
                expect(
                    host,
                    &format!("the rope on the dragged sphere moving with it ({rope_x} m)"),
                    dragged,
                )?;
                if let Some((text, true)) = self.editor.notices.last() {
                    anyhow::bail!("exercise: the editor reported an error: {text}");
                }
                self.input.actions.push(KeyAction::Undo);
            }
            // The drag was one step: undone, the sphere is back where it started; redone, it is
            // where the drag left it.
            77 | 79 => {
                let at = handles::position(self.host().scene(), Selection::Sphere(0)).unwrap_or_default();
                let start = self.exercise_start.unwrap_or_default();
                if self.tick == 77 {
                    let back = at.distance(start) < 1e-6;
                    expect(
                        self.host(),
                        &format!("Ctrl+Z undoing the drag (sphere at {at}, began at {start})"),
                        back,
                    )?;
                    self.input.actions.push(KeyAction::Redo);
                } else {
                    let redone = at.x - start.x > 0.01;
                    expect(self.host(), &format!("Ctrl+Shift+Z redoing the drag (sphere at {at})"), redone)?;
                    // Closing twice, and Esc (as the keys queue it) until it quits, each quit
                    // with the edit kept in a rescue file.
                    let close = winit::event::WindowEvent::CloseRequested;
                    let by_close = self.handle_event(&close) || self.handle_event(&close);
                    self.expect_rescued(by_close, start, "closing twice")?;
                    let escape = |v: &mut Self| {
                        v.input.actions.push(KeyAction::Escape);
                        v.handle_event(&winit::event::WindowEvent::Focused(true))
                    };
                    let by_escape = (0..4).any(|_| escape(self));
                    self.expect_rescued(by_escape, start, "Esc until it quits")?;
                    return Ok(Outcome::Exit);
                }
            }
            _ => {}
        }
        Ok(Outcome::Continue)
    }

    /// Checks that `quit` is true and that the rescue file it wrote holds sphere 0 dragged along
    /// x from `start` (then removes the file).
    fn expect_rescued(&mut self, quit: bool, start: Vec3, how: &str) -> Result<()> {
        let rescued = self.rescued.take();
        let kept = rescued.as_ref().and_then(|p| scene::load(p, &[]).ok());
        if let Some(path) = &rescued {
            let _ = std::fs::remove_file(path);
        }
        let moved =
            kept.is_some_and(|s| s.spheres.first().is_some_and(|s| s.center[0] - start.x as f64 > 0.01));
        if quit && moved {
            Ok(())
        } else {
            Err(anyhow::anyhow!("exercise: {how} did not quit keeping the unsaved edits in a rescue file"))
        }
    }

    /// The mean x of object 0's particles now (the rope of the exercise's preset) [m].
    fn rope_mean_x(&mut self) -> Result<f32> {
        let host = self.host.as_mut().expect("host");
        let states = host.sim_mut().read_states(&self.ctx)?;
        let rope = &states[0].particles;
        Ok(rope.iter().map(|p| p.pos[0]).sum::<f32>() / rope.len() as f32)
    }
}

/// Whether the screenshot at `path` shows the recording indicator: at least 50 pixels of its
/// dot's red (0.95, 0.15, 0.15: green and blue under a fifth of red, which no shaded cloth of
/// the default red, 0.75, 0.18, 0.16, reaches) in the right half (the dot, 6 pixels in radius,
/// has about 110; the badge sits at the top right or under the Stats window).
fn recording_indicator_shown(path: &std::path::Path) -> bool {
    let Ok(file) = std::fs::File::open(path) else { return false };
    let Ok(mut reader) = png::Decoder::new(std::io::BufReader::new(file)).read_info() else { return false };
    let mut pixels = vec![0; reader.output_buffer_size()];
    let Ok(info) = reader.next_frame(&mut pixels) else { return false };
    let channels = info.color_type.samples();
    let (width, rows) = (info.width as usize, info.height as usize);
    let red = (0..rows)
        .flat_map(|y| (width / 2..width).map(move |x| (y * width + x) * channels))
        .filter(|&i| {
            let [r, g, b] = [pixels[i], pixels[i + 1], pixels[i + 2]].map(u32::from);
            r > 200 && 5 * g < r && 5 * b < r
        })
        .count();
    red >= 50
}
