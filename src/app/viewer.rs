//! The windowed app: one command buffer per frame records the simulation substeps (compute),
//! the simulation's compute -> vertex-input barrier on the surface buffers, the scene draws and
//! ImGui, with two frames in flight.
//!
//! Frame slot `s` owns a command buffer + fence, an "image available" semaphore, timestamps and
//! the camera uniform buffer of the renderer; the host writes a slot's resources only after
//! waiting for its fence. Edits that touch GPU parameters or rebuild the simulation wait for
//! the device to be idle first. Teardown (Drop) waits idle, then frees the UI renderer, scene
//! renderer, simulation, frame slots and swapchain, before the context and last the window.

use super::handles;
use super::input::{Input, KeyAction};
use super::recorder::AppRecorder;
use super::sim_host::SimHost;
use super::AppArgs;
use crate::render::camera::OrbitCamera;
use crate::render::view::{self, SKY};
use crate::render::SceneRenderer;
use crate::scene::{self, Scene};
use crate::shaders::ShaderSet;
use crate::sim::gpu::FRAME_SLOTS;
use crate::ui::{self, Action, EditorState, Stats};
use crate::vk::{
    Access, Acquired, Buffer, BufferBarrier, BufferUsage, CommandSlot, ContextOptions, Format, GpuContext,
    ImageBarrier, MemoryKind, RetireQueue, Semaphore, Swapchain, TimestampPool, UiRenderer, WindowHandles,
};
use anyhow::{Context as _, Result};
use glam::Vec3;
use imgui_winit_support::{HiDpiMode, WinitPlatform};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::window::Window;

struct FrameSlot {
    cmd: CommandSlot,
    available: Semaphore,
    /// Render-stage timestamps: before the scene, after the scene, after the UI.
    timestamps: Option<TimestampPool>,
    /// What the last submission of this slot recorded, for reading its timings.
    used: bool,
    simulated: bool,
}

/// What the event loop should do after a frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    Continue,
    Exit,
}

pub struct Viewer {
    // Declared before `window`: fields drop in order, so the context (and its surface) goes
    // before the window it presents to.
    ctx: GpuContext,
    swapchain: Option<Swapchain>,
    frames: Vec<FrameSlot>,
    ui_renderer: Option<UiRenderer>,
    renderer: Option<SceneRenderer>,
    host: Option<SimHost>,
    /// Pipelines replaced by hot reload, freed once their frames have completed.
    retired: RetireQueue,
    shaders: ShaderSet,
    /// A reload waiting for its first frame to be submitted: (shaders, first change seen).
    reload_pending: Option<(Vec<String>, Instant)>,
    imgui: imgui::Context,
    platform: WinitPlatform,
    window: Arc<Window>,

    args: AppArgs,
    camera: OrbitCamera,
    input: Input,
    editor: EditorState,
    stats: Stats,
    recreate: bool,
    minimized: bool,
    frame: u64,
    /// Redraw ticks, counted even while minimised (drives `--exercise-window`).
    tick: u64,
    last: Instant,
    step_once: bool,
    screenshot: Option<Buffer>,
    /// Where the screenshot of this frame goes (F12, or `--record-frames`), and whether to say so.
    shot: Option<(PathBuf, bool)>,
    /// The Record button's recording, while one runs.
    recorder: AppRecorder,
    /// The translate handle being dragged.
    handle: Option<handles::Drag>,
    /// Real-time mode: simulated time owed to the wall clock [s].
    owed: f64,
    /// `--exercise-editor`: where the dragged sphere started, and the rope's mean x then.
    exercise_start: Option<Vec3>,
    exercise_rope_x: f32,
    /// Where the unsaved scene was saved when the app quit or failed with it (`rescue_unsaved`).
    rescued: Option<PathBuf>,
    /// The UI's edited scene and actions, applied at the start of the next frame.
    pending_scene: Option<Scene>,
    /// The pending edits calibrate `integrator = "auto"` or rebuild slowly, and the notice saying
    /// so is drawn: they are applied this frame (`edits::edits_wait`).
    wait_announced: bool,
    /// How long the last build of the simulation took (at start-up, or by an edit).
    last_rebuild: std::time::Duration,
    /// Undo and redo of scene edits (created with the scene).
    history: Option<super::history::History>,
    pending_actions: Vec<Action>,
}

impl Viewer {
    pub fn new(
        window: Arc<Window>,
        options: &ContextOptions,
        args: AppArgs,
        scene: Scene,
        shaders: ShaderSet,
    ) -> Result<Self> {
        let handles = WindowHandles {
            display: window.display_handle().context("the window's display handle")?.as_raw(),
            window: window.window_handle().context("the window handle")?.as_raw(),
        };
        let ctx = GpuContext::with_window(options, handles)?;
        let size = window.inner_size();
        let swapchain = Swapchain::new(&ctx, [size.width, size.height], args.vsync, None)?;
        let mut imgui = imgui::Context::create();
        imgui.set_ini_filename(layout::panels_file(&args));
        let mut platform = WinitPlatform::new(&mut imgui);
        platform.attach_window(imgui.io_mut(), &window, HiDpiMode::Default);
        let stats = Stats { device: ctx.info().to_string(), ..Default::default() };
        let mut viewer = Self {
            ctx,
            swapchain: Some(swapchain),
            frames: Vec::new(),
            ui_renderer: None,
            renderer: None,
            host: None,
            retired: RetireQueue::default(),
            shaders,
            reload_pending: None,
            imgui,
            platform,
            window,
            editor: EditorState {
                preset_path: args.preset_label.clone(),
                cloth_preset_path: "presets/towel.toml".into(),
                paused: args.paused,
                hide_stats: args.hide_stats,
                hide_ui: args.hide_ui,
                shaders_note: String::new(),
                record_path: "recording.usda".into(),
                selected: args.select.unwrap_or_default(),
                show_selected: args.select.is_some(),
                ..Default::default()
            },
            args,
            camera: OrbitCamera::default(),
            input: Input::default(),
            stats,
            recreate: false,
            minimized: false,
            frame: 0,
            tick: 0,
            last: Instant::now(),
            step_once: false,
            recorder: AppRecorder::default(),
            handle: None,
            exercise_start: None,
            exercise_rope_x: 0.0,
            rescued: None,
            owed: 0.0,
            screenshot: None,
            shot: None,
            pending_scene: None,
            wait_announced: false,
            last_rebuild: std::time::Duration::ZERO,
            history: None,
            pending_actions: Vec::new(),
        };
        // `viewer` owns what exists so far: a failure below is cleaned up by its Drop.
        viewer.init(scene)?;
        Ok(viewer)
    }

    fn init(&mut self, scene: Scene) -> Result<()> {
        let ctx = &self.ctx;
        for _ in 0..FRAME_SLOTS {
            self.frames.push(FrameSlot {
                cmd: CommandSlot::new(ctx, "frame")?,
                available: Semaphore::new(ctx)?,
                timestamps: TimestampPool::new(ctx, 3)?,
                used: false,
                simulated: false,
            });
        }
        let format = self.swapchain.as_ref().map(|s| s.format()).unwrap_or(Format::Bgra8Unorm);
        self.ui_renderer = Some(UiRenderer::new(ctx, &mut self.imgui, format, Format::Depth32, FRAME_SLOTS)?);
        let renderer =
            self.renderer.insert(SceneRenderer::new(ctx, format, Format::Depth32, &mut self.shaders)?);
        let started = std::time::Instant::now();
        self.host = Some(SimHost::new(ctx, scene, renderer, &mut self.shaders)?);
        self.last_rebuild = started.elapsed();
        if (self.args.screenshot.is_some() || self.args.record_frames.is_some()) && !self.args.paused {
            // Pictures of a running scene: calibrated before the first frame, without a notice
            // in them. (Paused, nothing moves: the frame after the notice calibrates, as in a
            // window.)
            self.calibrate_pending();
        }
        self.show_auto_pick();
        self.editor.shaders_note = self.shaders.status();
        log::info!("{}", self.editor.shaders_note);
        self.fit_camera();
        Ok(())
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    fn host(&self) -> &SimHost {
        self.host.as_ref().expect("the host exists after init")
    }

    /// Handles a window event; returns true when the app should quit.
    pub fn handle_event(&mut self, event: &WindowEvent) -> bool {
        if let WindowEvent::KeyboardInput { event: key, .. } = event {
            if let Some(text) = self.input.typed(key, self.imgui.io().want_text_input) {
                text.chars().for_each(|c| self.imgui.io_mut().add_input_character(c));
                return false;
            }
        }
        let wrapped: winit::event::Event<()> =
            winit::event::Event::WindowEvent { window_id: self.window.id(), event: event.clone() };
        self.platform.handle_event(self.imgui.io_mut(), &self.window, &wrapped);
        let io = self.imgui.io();
        let (ui_mouse, ui_keys) = (io.want_capture_mouse, io.want_capture_keyboard);
        let floor = self.host.as_ref().and_then(|h| h.scene().ground.as_ref()).map(|g| g.height as f32);
        let size = self.window.inner_size();
        let view = (floor, [size.width as f32, size.height as f32]);
        self.input.handle(event, &mut self.camera, view, ui_mouse, ui_keys);
        match event {
            WindowEvent::CloseRequested => return self.close_requested(),
            WindowEvent::Resized(size) => self.resized(*size),
            _ => {}
        }
        // Esc closes what is open (undo.rs `dismiss`), else asks to quit or quits.
        while let Some(k) = self.input.actions.iter().position(|a| *a == KeyAction::Escape) {
            self.input.actions.remove(k);
            if self.dismiss() {
                self.input.forget_quit();
            } else {
                let asked = self.input.escape(Instant::now());
                self.input.actions.push(asked);
            }
        }
        let quit = self.input.actions.contains(&KeyAction::Quit);
        if quit {
            self.keep_unsaved_on_quit();
        }
        quit
    }

    fn resized(&mut self, size: PhysicalSize<u32>) {
        self.minimized = size.width == 0 || size.height == 0;
        self.recreate = true;
    }

    fn message(&mut self, text: impl Into<String>, error: bool) {
        let text = text.into();
        if error {
            log::warn!("{text}");
        } else {
            log::info!("{text}");
        }
        self.editor.notices.push(&text, error);
    }

    fn run_action(&mut self, action: Action) {
        match action {
            Action::TogglePause => self.editor.paused = !self.editor.paused,
            Action::Step => {
                self.editor.paused = true;
                self.step_once = true;
            }
            Action::Reset => {
                if let Some(host) = self.host.as_mut() {
                    if let Err(e) = host.reset(&self.ctx) {
                        self.message(format!("reset failed: {e:#}"), true);
                    }
                }
            }
            Action::FitCamera => self.fit_camera(),
            Action::ResetCamera => self.camera = OrbitCamera::default(),
            Action::Undo => self.undo(false),
            Action::Redo => self.undo(true),
            Action::ToggleRecording(path) => {
                let said = match (self.recorder.frames(), self.host.as_ref()) {
                    (Some(_), _) => self.recorder.stop(),
                    (None, Some(host)) => {
                        let preset = crate::ui::resolve_preset(&self.editor.preset_path, "");
                        self.recorder.start(host, &path, &preset)
                    }
                    (None, None) => Ok("nothing to record".into()),
                };
                match said {
                    Ok(text) => self.message(text, false),
                    Err(e) => self.message(format!("{e:#}"), true),
                }
                self.editor.recording = self.recorder.status();
            }
            Action::Load(path) => match scene::load(&path, &[]) {
                Ok(loaded) => {
                    if self.apply(loaded) {
                        self.mark_saved();
                        // The field shows the file loaded (a shipped preset found by its bare
                        // name included), so that Save writes back to it.
                        self.editor.preset_path = path.display().to_string();
                    }
                    self.fit_camera();
                    self.message(format!("loaded {}", path.display()), false);
                }
                Err(e) => self.message(e.to_string(), true),
            },
            Action::Save(path) => match scene::save(self.host().scene(), &path) {
                Ok(()) => {
                    self.mark_saved();
                    self.message(format!("saved {}", path.display()), false)
                }
                Err(e) => self.message(format!("{e:#}"), true),
            },
            Action::AddClothFromPreset(path) => match scene::load(&path, &[]) {
                Ok(from) if from.cloths.is_empty() => {
                    self.message(format!("{} has no cloth", path.display()), true)
                }
                Ok(from) => {
                    let mut edited = self.host().scene().clone();
                    for mut c in from.cloths {
                        if edited.cloths.iter().any(|o| o.name == c.name)
                            || edited.ropes.iter().any(|o| o.name == c.name)
                            || edited.mesh_cloths.iter().any(|o| o.name == c.name)
                        {
                            c.name = crate::ui::unique_name(&edited, &c.name);
                        }
                        // Where the camera looks, clear of the scene, as a new cloth is.
                        scene::place::place_cloth(&edited, &mut c, self.camera.target.as_dvec3());
                        edited.cloths.push(c);
                    }
                    self.apply(edited);
                }
                Err(e) => self.message(e.to_string(), true),
            },
        }
    }

    /// Recompiles shaders changed on disk and swaps their pipelines; the old pipelines wait in
    /// `retired` for the frames recorded before this one.
    fn hot_reload(&mut self) {
        let changes = self.shaders.changes();
        if changes.shaders.is_empty() {
            return;
        }
        let (Some(host), Some(renderer)) = (self.host.as_mut(), self.renderer.as_mut()) else { return };
        let (mut reloaded, old) = host.sim_mut().reload(&self.ctx, &mut self.shaders, &changes.shaders);
        self.retired.push(self.frame, old);
        let (scene_reloaded, old) = renderer.reload(&self.ctx, &mut self.shaders, &changes.shaders);
        self.retired.push(self.frame, old);
        if scene_reloaded {
            reloaded.extend(["mesh.vert".to_string(), "mesh.frag".to_string()]);
        }
        reloaded.retain(|n| changes.shaders.contains(n));
        if !reloaded.is_empty() {
            self.reload_pending = Some((reloaded, changes.since.unwrap_or_else(Instant::now)));
        }
        // A save that broke a shader: a notice and an entry in the Log window, besides the
        // errors' overlay (the shader set has logged it).
        let broken: Vec<String> = (self.shaders.errors())
            .filter(|(name, _)| changes.shaders.contains(*name))
            .map(|(name, e)| format!("{name} does not compile; its last good version runs: {e}"))
            .collect();
        for e in broken {
            self.editor.notices.push(&e, true);
        }
    }

    fn key_actions(&mut self) -> bool {
        let mut quit = false;
        let mut deferred = Vec::new();
        for a in std::mem::take(&mut self.input.actions) {
            match a {
                KeyAction::TogglePause => self.run_action(Action::TogglePause),
                KeyAction::Step => self.run_action(Action::Step),
                KeyAction::Reset => self.run_action(Action::Reset),
                KeyAction::Fit => self.fit_camera(),
                KeyAction::ResetCamera => self.camera = OrbitCamera::default(),
                KeyAction::Screenshot => self.shot = Some((screenshot_name(), true)),
                KeyAction::Help => self.editor.show_help = !self.editor.show_help,
                KeyAction::Record => {
                    self.run_action(Action::ToggleRecording(PathBuf::from(&self.editor.record_path)))
                }
                KeyAction::Escape => {} // resolved as it came (handle_event)
                KeyAction::QuitAsk => {
                    self.observe_edits();
                    let lost = if self.editor.unsaved {
                        " (the unsaved edits are saved to msdsim-rescued-*.toml in the current folder)"
                    } else {
                        ""
                    };
                    let text =
                        format!("press Esc again within {} s to quit{lost}", super::input::QUIT_CONFIRM);
                    self.message(text, false)
                }
                // (Not while an edit waits to be applied: the next frame, after it.)
                KeyAction::Undo | KeyAction::Redo if self.wait_announced => deferred.push(a),
                KeyAction::Undo => self.undo(false),
                KeyAction::Redo => self.undo(true),
                KeyAction::Quit => quit = true,
            }
        }
        self.input.actions.extend(deferred);
        quit
    }

    /// One frame: UI, edits, simulation, drawing, presentation.
    pub fn frame(&mut self) -> Result<Outcome> {
        self.tick += 1;
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f64();
        self.last = now;
        self.stats.cpu_frame_ms = if self.stats.cpu_frame_ms == 0.0 {
            dt * 1e3
        } else {
            0.9 * self.stats.cpu_frame_ms + 0.1 * dt * 1e3
        };
        if self.args.exercise_window && self.exercise() == Outcome::Exit {
            return Ok(Outcome::Exit);
        }
        if self.args.exercise_editor && self.exercise_editor()? == Outcome::Exit {
            return Ok(Outcome::Exit);
        }
        if self.key_actions() {
            return Ok(Outcome::Exit);
        }
        if self.minimized {
            return Ok(Outcome::Continue);
        }
        if self.recreate || self.swapchain.is_none() {
            let size = self.window.inner_size();
            if size.width == 0 || size.height == 0 {
                self.minimized = true;
                return Ok(Outcome::Continue);
            }
            self.ctx.wait_idle()?;
            let old = self.swapchain.take();
            self.swapchain =
                Some(Swapchain::new(&self.ctx, [size.width, size.height], self.args.vsync, old)?);
            self.recreate = false;
        }

        let slot = (self.frame % FRAME_SLOTS as u64) as usize;
        self.frames[slot].cmd.wait(&self.ctx)?;
        self.read_timings(slot)?;
        // Every frame before the previous one has been waited for (this slot now, the other at
        // the previous frame): retired pipelines they used can go.
        self.retired.release(&self.ctx, self.frame.saturating_sub(1));
        self.hot_reload();

        let swapchain = self.swapchain.as_ref().expect("created above");
        let image = match swapchain.acquire(&self.ctx, &self.frames[slot].available)? {
            Acquired::Image(i) => i,
            Acquired::OutOfDate => {
                self.recreate = true;
                return Ok(Outcome::Continue);
            }
        };

        // Edits and actions from the previous frame's UI (unless they wait a frame for the
        // notice that the window will wait: a calibration or a slow rebuild), then input.
        if !self.edits_wait() {
            self.calibrate_pending();
            if let Some(edited) = self.pending_scene.take() {
                self.apply(edited);
            }
            for a in std::mem::take(&mut self.pending_actions) {
                self.run_action(a);
            }
        }
        self.input.fly(&mut self.camera, dt as f32);
        self.update_grab();
        self.observe_edits();

        // (Not while a scene waits to calibrate: this frame says so, the next calibrates.)
        let run_sim = (!self.editor.paused || std::mem::take(&mut self.step_once))
            && !self.host().calibration_pending();
        // Simulated frames this drawn frame: one, or in real-time mode as many frame_dt as the
        // wall clock has run since the last (at most REAL_TIME_MOST; a device that cannot keep
        // up falls behind, and the stats say by how much). A recording takes one a drawn frame
        // (each recorded frame is read back after its drawn frame).
        let real_time = self.editor.real_time && !self.editor.paused && self.recorder.frames().is_none();
        let sim_frames = match (run_sim, real_time) {
            (false, _) => 0,
            (true, false) => 1,
            (true, true) => {
                let frame_dt = self.host().model().frame_dt;
                self.owed = (self.owed + dt).min(REAL_TIME_MOST as f64 * frame_dt);
                let n = (self.owed / frame_dt).floor() as u32;
                self.owed -= n as f64 * frame_dt;
                n
            }
        };
        let run_sim = sim_frames > 0;
        let extent = self.swapchain.as_ref().expect("created above").extent();
        let camera = view::camera_uniform(&self.camera, extent, self.host().scene());
        let items = self.draw_items();
        self.renderer.as_mut().expect("renderer").set_camera(slot, &camera)?;
        if let Some(dir) = &self.args.record_frames {
            self.shot = Some((dir.join(format!("frame_{:05}.png", self.frame)), false));
        }
        let capture = self.screenshot_due() || self.shot.is_some();
        if capture && self.screenshot.is_none() {
            let bytes = extent[0] as u64 * extent[1] as u64 * 4;
            self.screenshot = Some(Buffer::new(
                &self.ctx,
                "screenshot",
                bytes,
                BufferUsage::TRANSFER_DST,
                MemoryKind::Readback,
            )?);
        }

        // The UI edits a copy of the scene, applied at the start of the next frame. From here on
        // `draw_data` borrows `self.imgui`, so only other fields are touched.
        self.platform.prepare_frame(self.imgui.io_mut(), &self.window).context("preparing the UI frame")?;
        let ui = self.imgui.new_frame();
        // (Edits that wait a frame are shown and edited further.)
        let mut edited =
            (self.pending_scene.clone()).unwrap_or_else(|| self.host.as_ref().expect("host").scene().clone());
        self.editor.shader_errors = self.shaders.errors().map(|(_, e)| e.clone()).collect();
        self.editor.look_at = self.camera.target.as_dvec3().to_array();
        let actions = ui::build(ui, &mut self.editor, &mut edited, &self.stats);
        self.pending_actions.extend(actions);
        // (An edit that waits and is then put back is dropped.)
        self.pending_scene = (edited != *self.host.as_ref().expect("host").scene()).then_some(edited);
        self.platform.prepare_render(ui, &self.window);
        let draw_data = self.imgui.render();

        let frame = &mut self.frames[slot];
        let mut rec = frame.cmd.begin(&self.ctx)?;
        let host = self.host.as_mut().expect("host");
        if run_sim {
            for _ in 0..sim_frames {
                host.sim_mut().record_frame(&mut rec, Access::VertexInput, slot)?;
            }
        } else if host.sim_mut().take_surface_stale() {
            // Paused after a reset (or a rebuild): show the new state at once.
            host.sim().record_surface(&mut rec, Access::VertexInput);
        }
        let swapchain = self.swapchain.as_ref().expect("created above");
        if let Some(pool) = &frame.timestamps {
            rec.reset_timestamps(pool);
            rec.timestamp_after_drawing(pool, 0);
        }
        rec.image_barrier(&[
            ImageBarrier::new(swapchain.image(image), Access::Acquired, Access::ColorAttachment),
            ImageBarrier::discarding(
                swapchain.depth().image(),
                Access::DepthAttachment,
                Access::DepthAttachment,
            ),
        ]);
        rec.begin_rendering(swapchain.view(image), swapchain.depth().view(), extent, SKY);
        let ground = view::ground(host.scene());
        self.renderer.as_ref().expect("renderer").record(&mut rec, slot, host.sim(), &items, ground);
        if let Some(pool) = &frame.timestamps {
            rec.timestamp_after_drawing(pool, 1);
        }
        self.ui_renderer.as_mut().expect("ui renderer").draw(&mut rec, draw_data)?;
        rec.end_rendering();
        if let Some(pool) = &frame.timestamps {
            rec.timestamp_after_drawing(pool, 2);
        }
        match (&self.screenshot, capture) {
            (Some(buffer), true) => {
                rec.image_barrier(&[ImageBarrier::new(
                    swapchain.image(image),
                    Access::ColorAttachment,
                    Access::TransferRead,
                )]);
                rec.copy_image_to_buffer(swapchain.image(image), extent, buffer);
                rec.image_barrier(&[ImageBarrier::new(
                    swapchain.image(image),
                    Access::TransferRead,
                    Access::Present,
                )]);
                rec.barrier(&[BufferBarrier::new(buffer, Access::TransferWrite, Access::HostRead)]);
            }
            _ => rec.image_barrier(&[ImageBarrier::new(
                swapchain.image(image),
                Access::ColorAttachment,
                Access::Present,
            )]),
        }
        frame.cmd.submit_with(&self.ctx, rec, Some(&frame.available), Some(swapchain.finished(image)))?;
        frame.used = true;
        frame.simulated = run_sim;
        let reloaded = self.reload_pending.take();
        if !swapchain.present(&self.ctx, image)? {
            self.recreate = true;
        }
        if let Some((names, since)) = reloaded {
            let ms = since.elapsed().as_secs_f64() * 1e3;
            self.message(format!("hot reload: {} in use {ms:.0} ms after the save", names.join(", ")), false);
        }
        self.frame += 1;
        if run_sim && self.recorder.frames().is_some() {
            let host = self.host.as_mut().expect("host");
            if let Err(e) = self.recorder.capture(&self.ctx, host) {
                self.message(e, true);
            }
            self.editor.recording = self.recorder.status();
        }
        let host = self.host.as_ref().expect("host");
        self.stats.simulated_time = host.sim().time();
        // Simulated time against the wall clock, averaged like the frame time (in real-time
        // mode a drawn frame simulates 0 to REAL_TIME_MOST frames).
        let now = sim_frames as f64 * host.model().frame_dt / dt.max(1e-6);
        let speed = match self.stats.speed {
            Some(before) => 0.9 * before + 0.1 * now,
            None => now,
        };
        self.stats.speed = (!self.editor.paused).then_some(speed);
        self.stats.particles = host.model().objects.iter().map(|o| o.particle_count() as u64).sum();

        if capture {
            self.frames[slot].cmd.wait(&self.ctx)?;
            let bgra = swapchain_is_bgra(self.swapchain.as_ref());
            if self.screenshot_due() {
                if let Some(path) = self.args.screenshot.clone() {
                    self.write_screenshot(&path, extent, bgra)?;
                }
                return Ok(Outcome::Exit);
            }
            if let Some((path, announce)) = self.shot.take() {
                // A failed write is reported, not fatal.
                match self.write_screenshot(&path, extent, bgra) {
                    Ok(()) if announce => {
                        self.message(format!("screenshot saved to {}", path.display()), false)
                    }
                    Ok(()) => {}
                    Err(e) => self.message(format!("screenshot {}: {e:#}", path.display()), true),
                }
                // Its frame has completed; the next one is sized for the window then.
                if let Some(buffer) = self.screenshot.take() {
                    buffer.destroy(&self.ctx);
                }
            }
        }
        if self.args.frames.is_some_and(|n| self.frame >= n) && self.args.screenshot.is_none() {
            return Ok(Outcome::Exit);
        }
        Ok(Outcome::Continue)
    }

    fn read_timings(&mut self, slot: usize) -> Result<()> {
        let (used, simulated) = (self.frames[slot].used, self.frames[slot].simulated);
        if !used {
            return Ok(());
        }
        if let Some(pool) = &self.frames[slot].timestamps {
            let t = pool.read_ns(&self.ctx, 3)?;
            self.stats.render_ms = Some((t[1] - t[0]).max(0.0) * 1e-6);
            self.stats.ui_ms = Some((t[2] - t[1]).max(0.0) * 1e-6);
        }
        if simulated {
            self.stats.sim = self.host().sim().read_timing(&self.ctx, slot)?;
            // The runtime guard: an unstable simulation pauses with what happened and what to
            // change. (The guard is shared by the frames in flight; a trip the other frame sets
            // while this one clears it is reported by the next frame, since the state stays bad.)
            let sim = self.host.as_mut().expect("host").sim_mut();
            let trip = match sim.check_guard()? {
                Some(trip) => Some(trip),
                None => sim.check_energy(&self.ctx)?,
            };
            if let Some(trip) = trip {
                self.editor.paused = true;
                self.message(trip.to_string(), true);
            }
            if let Some(warning) = self.host.as_mut().expect("host").sim_mut().take_warning() {
                self.message(warning, true);
            }
        }
        Ok(())
    }

    /// Waits for the GPU and frees everything in order (also run by Drop).
    fn teardown(&mut self) {
        let _ = self.ctx.wait_idle();
        // A recording still running is written, not lost.
        if self.recorder.frames().is_some() {
            match self.recorder.stop() {
                Ok(text) => log::info!("{text}"),
                Err(e) => log::error!("{e:#}"),
            }
        }
        if let Some(u) = self.ui_renderer.take() {
            u.destroy(&self.ctx);
        }
        if let Some(h) = self.host.take() {
            h.destroy(&self.ctx);
        }
        if let Some(r) = self.renderer.take() {
            r.destroy(&self.ctx);
        }
        if let Some(b) = self.screenshot.take() {
            b.destroy(&self.ctx);
        }
        std::mem::take(&mut self.retired).destroy(&self.ctx);
        for f in self.frames.drain(..) {
            f.cmd.destroy(&self.ctx);
            f.available.destroy(&self.ctx);
            if let Some(t) = f.timestamps {
                t.destroy(&self.ctx);
            }
        }
        if let Some(s) = self.swapchain.take() {
            s.destroy(&self.ctx);
        }
    }

    /// Validation messages so far and allocations still alive after teardown.
    pub fn finish(mut self) -> (u32, Option<String>, Vec<String>) {
        self.teardown();
        let canary = self.ctx.canary();
        (canary.count(), canary.messages().first().cloned(), self.ctx.live_allocations())
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        self.teardown();
    }
}

mod edits;
mod exercise;
mod grab;
mod items;
mod layout;
mod screenshot;
mod undo;

pub use screenshot::write_png;
use screenshot::{screenshot_name, swapchain_is_bgra};

/// Real-time mode simulates at most this many frames per drawn frame.
const REAL_TIME_MOST: u32 = 4;

/// The path shown in the editor's preset field for a preset argument.
pub fn preset_label(path: Option<&PathBuf>) -> String {
    path.map(|p| p.display().to_string()).unwrap_or_else(|| "presets/playground.toml".into())
}
