//! Small ImGui helpers for editing f64 scene values through f32 widgets; each shows its
//! label's tooltip (`help`) when hovered. A number typed into a field (an int field, or a drag
//! field after Ctrl+click or a double-click) applies on Enter or when the field loses focus,
//! not on every keystroke: typing 200000 must not apply 2, 20, 200 on the way (`commit`).
//! Dragging and the step buttons apply live.

use super::help::help;
use imgui::{Drag, Ui};
use std::cell::RefCell;

thread_local! {
    /// The value typed into the field being edited, by its label, until it is committed.
    static TYPED: RefCell<Option<(String, [f64; 3])>> = const { RefCell::new(None) };
}

/// What the widget just drawn applies this frame, given whether it reported a change and the
/// value it holds: a change made by typing is kept aside until the field is left (Enter, a
/// click elsewhere, Tab), then applied; any other change (a drag, a step button, Enter's own
/// frame) applies at once. Esc in the field reverts it and applies nothing new.
fn commit(ui: &Ui, label: &str, changed: bool, edited: [f64; 3]) -> Option<[f64; 3]> {
    // ImGui reports a field left by Esc as deactivated after an edit, like Enter: the key
    // tells the two apart, and what was typed is dropped.
    if ui.is_key_pressed(imgui::Key::Escape) && (ui.is_item_active() || ui.is_item_deactivated()) {
        TYPED.with(|t| t.borrow_mut().take());
        return None;
    }
    let typing = ui.is_item_active() && ui.io().want_text_input;
    if changed && typing {
        TYPED.with(|t| *t.borrow_mut() = Some((label.to_string(), edited)));
        return None;
    }
    if changed {
        TYPED.with(|t| t.borrow_mut().take());
        return Some(edited);
    }
    if ui.is_item_deactivated_after_edit() {
        return TYPED.with(|t| match t.borrow_mut().take() {
            Some((typed, v)) if typed == label => Some(v),
            _ => None,
        });
    }
    None
}

/// An f32 widget value as the f64 it shows: the shortest decimal that gives back the f32
/// (0.2, not 0.20000000298023224), so that saved presets read as typed.
pub fn shown(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(v as f64)
}

/// A drag field for an f64 in [min, max]; returns true when it changed.
pub fn drag(ui: &Ui, label: &str, value: &mut f64, speed: f32, min: f64, max: f64) -> bool {
    let mut v = *value as f32;
    let changed = Drag::new(label).speed(speed).range(min as f32, max as f32).build(ui, &mut v);
    let applied = commit(ui, label, changed, [shown(v), 0.0, 0.0]);
    explain(ui, label);
    if let Some([v, _, _]) = applied {
        *value = v.clamp(min, max);
    }
    applied.is_some()
}

/// A drag field for an [f64; 3].
pub fn drag3(ui: &Ui, label: &str, value: &mut [f64; 3], speed: f32) -> bool {
    let mut v = value.map(|x| x as f32);
    let changed = Drag::new(label).speed(speed).build_array(ui, &mut v);
    let applied = commit(ui, label, changed, v.map(shown));
    explain(ui, label);
    if let Some(v) = applied {
        *value = v;
    }
    applied.is_some()
}

/// An RGB colour picker for an [f64; 3] in 0..1.
pub fn color(ui: &Ui, label: &str, value: &mut [f64; 3]) -> bool {
    let mut v = value.map(|x| x as f32);
    let changed = ui.color_edit3(label, &mut v);
    explain(ui, label);
    if changed {
        *value = v.map(|x| shown(x).clamp(0.0, 1.0));
    }
    changed
}

/// A u32 field in [min, max].
pub fn int(ui: &Ui, label: &str, value: &mut u32, min: u32, max: u32) -> bool {
    let mut v = *value as i32;
    let changed = ui.input_int(label, &mut v).build();
    let applied = commit(ui, label, changed, [v as f64, 0.0, 0.0]);
    explain(ui, label);
    if let Some([v, _, _]) = applied {
        *value = (v.max(0.0) as u32).clamp(min, max);
    }
    applied.is_some()
}

/// An optional f64 behind a checkbox (`None` when unticked).
pub fn optional(ui: &Ui, label: &str, value: &mut Option<f64>, default: f64, speed: f32, max: f64) -> bool {
    let mut on = value.is_some();
    let mut changed = ui.checkbox(format!("##{label}_on"), &mut on);
    explain(ui, label);
    ui.same_line();
    let mut v = value.unwrap_or(default);
    if on {
        changed |= drag(ui, label, &mut v, speed, 0.0, max);
    } else {
        ui.text_disabled(label.split("##").next().unwrap_or(label));
        explain(ui, label);
    }
    if changed {
        *value = on.then_some(v);
    }
    changed
}

/// A combo box over the variants of a serde enum, by their snake_case names.
pub fn choice<T: Copy + PartialEq + serde::Serialize>(
    ui: &Ui,
    label: &str,
    value: &mut T,
    all: &[T],
) -> bool {
    let names: Vec<String> = all
        .iter()
        .map(|v| toml::Value::try_from(v).ok().and_then(|t| t.as_str().map(String::from)).unwrap_or_default())
        .collect();
    let mut index = all.iter().position(|v| v == value).unwrap_or(0);
    let changed = ui.combo_simple_string(label, &mut index, &names);
    explain(ui, label);
    if changed {
        *value = all[index];
    }
    changed
}

/// A tooltip for the widget just drawn: what it means and its units. Not while the widget is
/// in use (a number being typed or dragged): the tooltip would cover the next row.
pub fn tip(ui: &Ui, text: &str) -> bool {
    let shown = ui.is_item_hovered() && !ui.is_item_active();
    if shown {
        ui.tooltip_text(text);
    }
    shown
}

/// A checkbox.
pub fn check(ui: &Ui, label: &str, value: &mut bool) -> bool {
    let changed = ui.checkbox(label, value);
    explain(ui, label);
    changed
}

/// A button with its tooltip; whether it was pressed.
pub fn button(ui: &Ui, label: &str) -> bool {
    let pressed = ui.button(label);
    explain(ui, label);
    pressed
}

/// The tooltip of `label` for the widget just drawn, when it has one.
fn explain(ui: &Ui, label: &str) {
    if let Some(text) = help(label) {
        tip(ui, text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use imgui::{Condition, Context, Io, Key, MouseButton};

    /// ImGui allows one context at a time in a process: the tests take turns.
    static ONE_CONTEXT: std::sync::Mutex<()> = std::sync::Mutex::new(());

    /// An ImGui context without a window or renderer: a 400 x 300 display, fonts built; with
    /// the turn, to be dropped after it (`let (_turn, mut ctx) = context();`).
    fn context() -> (std::sync::MutexGuard<'static, ()>, Context) {
        let turn = ONE_CONTEXT.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let mut ctx = Context::create();
        ctx.set_ini_filename(None);
        ctx.io_mut().display_size = [400.0, 300.0];
        ctx.fonts().build_rgba32_texture();
        (turn, ctx)
    }

    /// One frame with `input` queued first: a window at the origin holding a drag field and an
    /// int field; returns what each reported.
    fn frame(
        ctx: &mut Context,
        value: &mut f64,
        count: &mut u32,
        input: impl FnOnce(&mut Io),
    ) -> (bool, bool) {
        input(ctx.io_mut());
        ctx.io_mut().delta_time = 1.0 / 60.0;
        let ui = ctx.new_frame();
        let mut changed = (false, false);
        ui.window("editor")
            .position([0.0, 0.0], Condition::Always)
            .size([400.0, 300.0], Condition::Always)
            .build(|| {
                changed.0 = drag(ui, "stiffness", value, 1.0, 0.0, 1e9);
                changed.1 = int(ui, "substeps", count, 1, 4096);
            });
        ctx.render();
        changed
    }

    /// Where the two fields are: the first row and the second below the title bar.
    const DRAG_AT: [f32; 2] = [60.0, 30.0];
    const INT_AT: [f32; 2] = [40.0, 54.0];
    const ELSEWHERE: [f32; 2] = [200.0, 250.0];

    fn click(ctx: &mut Context, value: &mut f64, count: &mut u32, at: [f32; 2], ctrl: bool) {
        frame(ctx, value, count, |io| io.add_mouse_pos_event(at));
        frame(ctx, value, count, |io| {
            if ctrl {
                io.add_key_event(Key::ModCtrl, true);
            }
            io.add_mouse_button_event(MouseButton::Left, true)
        });
        frame(ctx, value, count, |io| {
            io.add_mouse_button_event(MouseButton::Left, false);
            if ctrl {
                io.add_key_event(Key::ModCtrl, false);
            }
        });
    }

    fn type_text(ctx: &mut Context, value: &mut f64, count: &mut u32, text: &str) -> Vec<(f64, u32)> {
        let mut seen = Vec::new();
        for c in text.chars() {
            frame(ctx, value, count, |io| io.add_input_character(c));
            seen.push((*value, *count));
        }
        seen
    }

    fn enter(ctx: &mut Context, value: &mut f64, count: &mut u32) {
        frame(ctx, value, count, |io| io.add_key_event(Key::Enter, true));
        frame(ctx, value, count, |io| io.add_key_event(Key::Enter, false));
    }

    /// Widget values reach the scene as the decimals they show.
    #[test]
    fn values_are_the_shortest_decimals() {
        assert_eq!(shown(0.2), 0.2);
        assert_eq!(shown(200000.0), 200000.0);
        assert_eq!(shown(1e-6), 1e-6);
        assert_eq!(shown(0.1 + 0.2), 0.3);
    }

    /// Typed numbers apply on Enter or when the field loses focus, nothing on the way; a drag
    /// applies live.
    #[test]
    fn typed_numbers_apply_on_enter_or_focus_loss_drags_live() {
        let (_turn, mut ctx) = context();
        let (mut value, mut count) = (400.0, 16u32);
        for _ in 0..3 {
            frame(&mut ctx, &mut value, &mut count, |_| {});
        }
        // Ctrl+click turns the drag field into a text field; typing applies nothing.
        click(&mut ctx, &mut value, &mut count, DRAG_AT, true);
        let seen = type_text(&mut ctx, &mut value, &mut count, "200000");
        assert!(seen.iter().all(|&(v, _)| v == 400.0), "applied while typing: {seen:?}");
        enter(&mut ctx, &mut value, &mut count);
        assert_eq!(value, 200000.0, "Enter applies the typed value");
        // The int field: typing applies nothing until a click elsewhere takes its focus.
        click(&mut ctx, &mut value, &mut count, INT_AT, false);
        let seen = type_text(&mut ctx, &mut value, &mut count, "128");
        assert!(seen.iter().all(|&(_, n)| n == 16), "applied while typing: {seen:?}");
        click(&mut ctx, &mut value, &mut count, ELSEWHERE, false);
        assert_eq!(count, 128, "leaving the field applies what was typed");
        // A drag applies while the mouse moves, before it is released.
        let before = value;
        frame(&mut ctx, &mut value, &mut count, |io| io.add_mouse_pos_event(DRAG_AT));
        frame(&mut ctx, &mut value, &mut count, |io| io.add_mouse_button_event(MouseButton::Left, true));
        for k in 1..=10 {
            frame(&mut ctx, &mut value, &mut count, |io| {
                io.add_mouse_pos_event([DRAG_AT[0] + 4.0 * k as f32, DRAG_AT[1]])
            });
        }
        assert!(value > before, "a drag applies live ({before} -> {value})");
        frame(&mut ctx, &mut value, &mut count, |io| io.add_mouse_button_event(MouseButton::Left, false));
    }

    /// Three idle frames, then a click into the int field and Ctrl+A: what is typed next
    /// replaces its text.
    fn select_the_int_field(ctx: &mut Context, value: &mut f64, count: &mut u32) {
        for _ in 0..3 {
            frame(ctx, value, count, |_| {});
        }
        click(ctx, value, count, INT_AT, false);
        frame(ctx, value, count, |io| io.add_key_event(Key::ModCtrl, true));
        key(ctx, value, count, Key::A);
        frame(ctx, value, count, |io| io.add_key_event(Key::ModCtrl, false));
    }

    fn key(ctx: &mut Context, value: &mut f64, count: &mut u32, key: Key) -> (bool, bool) {
        let down = frame(ctx, value, count, |io| io.add_key_event(key, true));
        let up = frame(ctx, value, count, |io| io.add_key_event(key, false));
        (down.0 || up.0, down.1 || up.1)
    }

    /// A field's tooltip shows while the mouse rests on it, not while a number is typed into
    /// it (it covered the next row, issue 69 item 14).
    #[test]
    fn no_tooltip_over_a_field_being_typed_in() {
        let (_turn, mut ctx) = context();
        let tipped = |ctx: &mut Context, input: &dyn Fn(&mut Io)| -> bool {
            input(ctx.io_mut());
            ctx.io_mut().delta_time = 1.0 / 60.0;
            let ui = ctx.new_frame();
            let mut count = 16u32;
            let mut shown = false;
            ui.window("editor")
                .position([0.0, 0.0], Condition::Always)
                .size([400.0, 300.0], Condition::Always)
                .build(|| {
                    let mut value = 400.0;
                    drag(ui, "stiffness", &mut value, 1.0, 0.0, 1e9);
                    int(ui, "substeps", &mut count, 1, 4096);
                    shown = tip(ui, "what substeps are");
                });
            ctx.render();
            shown
        };
        for _ in 0..3 {
            tipped(&mut ctx, &|_| {});
        }
        assert!(tipped(&mut ctx, &|io| io.add_mouse_pos_event(INT_AT)), "hovered, no tooltip");
        tipped(&mut ctx, &|io| io.add_mouse_button_event(MouseButton::Left, true));
        tipped(&mut ctx, &|io| io.add_mouse_button_event(MouseButton::Left, false));
        let typing = ['1', '2', '8'].map(|c| tipped(&mut ctx, &|io| io.add_input_character(c)));
        assert_eq!(typing, [false; 3], "a tooltip over the field being typed in");
    }

    /// Why the app gives a field its typed characters without their keys' events
    /// (`app::input::Input::typed`): ImGui's queue ends a frame's input at a key event after
    /// text, so "128" and Enter typed between two frames, each digit with its key's press and
    /// release, took more than 6 frames to apply (seconds at a few frames a second: keystrokes
    /// looked lost); the characters alone are taken in one frame and Enter in the next two.
    #[test]
    fn typed_characters_without_their_keys_apply_within_three_frames() {
        let frames_to_apply = |with_keys: bool| -> usize {
            let (_turn, mut ctx) = context();
            let (mut value, mut count) = (400.0, 16u32);
            select_the_int_field(&mut ctx, &mut value, &mut count);
            frame(&mut ctx, &mut value, &mut count, |io| {
                for (c, k) in [('1', Key::Alpha1), ('2', Key::Alpha2), ('8', Key::Alpha8)] {
                    if with_keys {
                        io.add_key_event(k, true);
                    }
                    io.add_input_character(c);
                    if with_keys {
                        io.add_key_event(k, false);
                    }
                }
                io.add_key_event(Key::Enter, true);
                io.add_key_event(Key::Enter, false);
            });
            let mut frames = 1; // (the frame the input came in)
            while count != 128 && frames < 30 {
                frame(&mut ctx, &mut value, &mut count, |_| {});
                frames += 1;
            }
            frames
        };
        let (alone, with_keys) = (frames_to_apply(false), frames_to_apply(true));
        assert!(alone <= 3, "the characters alone applied after {alone} frames");
        assert!(
            with_keys > 6,
            "with their keys they applied after {with_keys} frames: does ImGui still trickle?"
        );
    }

    /// Esc in a typed field reverts it: nothing is applied and no change is reported (an
    /// applied edit would rebuild the simulation and take an undo step), in the int field and
    /// in a drag field turned into a text field; the next typed value still applies on Enter.
    #[test]
    fn esc_in_a_typed_field_applies_nothing() {
        let (_turn, mut ctx) = context();
        let (mut value, mut count) = (400.0, 16u32);
        select_the_int_field(&mut ctx, &mut value, &mut count);
        type_text(&mut ctx, &mut value, &mut count, "8");
        let reported = key(&mut ctx, &mut value, &mut count, Key::Escape);
        for _ in 0..3 {
            frame(&mut ctx, &mut value, &mut count, |_| {});
        }
        assert_eq!((count, reported.1), (16, false), "Esc applied the typed 8");
        click(&mut ctx, &mut value, &mut count, DRAG_AT, true);
        type_text(&mut ctx, &mut value, &mut count, "5");
        let reported = key(&mut ctx, &mut value, &mut count, Key::Escape);
        assert_eq!((value, reported.0), (400.0, false), "Esc applied the typed drag value");
        click(&mut ctx, &mut value, &mut count, ELSEWHERE, false);
        assert_eq!(value, 400.0, "leaving after Esc applied what was typed before it");
        click(&mut ctx, &mut value, &mut count, DRAG_AT, true);
        type_text(&mut ctx, &mut value, &mut count, "7");
        enter(&mut ctx, &mut value, &mut count);
        assert_eq!(value, 7.0, "Enter after an Esc applies");
    }
}
