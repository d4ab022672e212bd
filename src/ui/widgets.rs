//! Small ImGui helpers for editing f64 scene values through f32 widgets; each shows its
//! label's tooltip (`help`) when hovered.

use super::help::help;
use imgui::{Drag, Ui};

/// A drag field for an f64 in [min, max]; returns true when it changed.
pub fn drag(ui: &Ui, label: &str, value: &mut f64, speed: f32, min: f64, max: f64) -> bool {
    let mut v = *value as f32;
    let changed = Drag::new(label).speed(speed).range(min as f32, max as f32).build(ui, &mut v);
    explain(ui, label);
    if changed {
        *value = (v as f64).clamp(min, max);
    }
    changed
}

/// A drag field for an [f64; 3].
pub fn drag3(ui: &Ui, label: &str, value: &mut [f64; 3], speed: f32) -> bool {
    let mut v = value.map(|x| x as f32);
    let changed = Drag::new(label).speed(speed).build_array(ui, &mut v);
    explain(ui, label);
    if changed {
        *value = v.map(|x| x as f64);
    }
    changed
}

/// An RGB colour picker for an [f64; 3] in 0..1.
pub fn color(ui: &Ui, label: &str, value: &mut [f64; 3]) -> bool {
    let mut v = value.map(|x| x as f32);
    let changed = ui.color_edit3(label, &mut v);
    explain(ui, label);
    if changed {
        *value = v.map(|x| (x as f64).clamp(0.0, 1.0));
    }
    changed
}

/// A u32 field in [min, max].
pub fn int(ui: &Ui, label: &str, value: &mut u32, min: u32, max: u32) -> bool {
    let mut v = *value as i32;
    let changed = ui.input_int(label, &mut v).build();
    explain(ui, label);
    if changed {
        *value = (v.max(0) as u32).clamp(min, max);
    }
    changed
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

/// A tooltip for the widget just drawn: what it means and its units.
pub fn tip(ui: &Ui, text: &str) {
    if ui.is_item_hovered() {
        ui.tooltip_text(text);
    }
}

/// A checkbox.
pub fn check(ui: &Ui, label: &str, value: &mut bool) -> bool {
    let changed = ui.checkbox(label, value);
    explain(ui, label);
    changed
}

/// The tooltip of `label` for the widget just drawn, when it has one.
fn explain(ui: &Ui, label: &str) {
    if let Some(text) = help(label) {
        tip(ui, text);
    }
}
