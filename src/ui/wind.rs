//! The editor's wind panel: the cone, the model, and the aerodynamic wind's air, drag, lift
//! and turbulence (tooltips in `help.rs`).

use super::widgets::{check, choice, drag, drag3, int};
use crate::scene::{Wind, WindKind};
use imgui::Ui;

pub(super) fn wind_panel(ui: &Ui, w: &mut Wind) {
    check(ui, "enabled##wind", &mut w.enabled);
    drag3(ui, "origin [m]##wind", &mut w.origin, 0.01);
    drag3(ui, "direction##wind", &mut w.direction, 0.01);
    let model = w.model;
    choice(ui, "model##wind", &mut w.model, &[WindKind::Paper, WindKind::Aerodynamic]);
    // The other model's own setting goes with it, so that the scene stays valid (validation
    // refuses a force on the aerodynamic wind and turbulence on the paper's) and a saved
    // preset says only what the wind does.
    if w.model != model {
        match w.model {
            WindKind::Aerodynamic => w.force = 0.0,
            WindKind::Paper => w.turbulence = 0.0,
        }
    }
    if w.model == WindKind::Aerodynamic {
        drag(ui, "air speed [m/s]", &mut w.speed, 0.05, 0.0, 100.0);
        drag(ui, "air density [kg/m^3]", &mut w.density, 0.01, 0.001, 100.0);
        drag(ui, "normal drag", &mut w.normal_drag, 0.01, 0.0, 10.0);
        drag(ui, "tangential drag", &mut w.tangential_drag, 0.001, 0.0, 10.0);
        drag(ui, "lift", &mut w.lift, 0.01, 0.0, 10.0);
        drag(ui, "turbulence [m/s]", &mut w.turbulence, 0.02, 0.0, 100.0);
        if w.turbulence > 0.0 {
            drag(ui, "eddy size [m]", &mut w.turbulence_scale, 0.01, 0.01, 100.0);
            drag(ui, "eddy frequency [Hz]", &mut w.turbulence_frequency, 0.01, 0.0, 100.0);
            int(ui, "seed##wind", &mut w.seed, 0, i32::MAX as u32);
        }
    } else {
        drag(ui, "force [N]##wind", &mut w.force, 0.001, -10.0, 10.0);
    }
    drag(ui, "full-force radius [m]", &mut w.full_force_radius, 0.01, 0.0, 100.0);
    drag(ui, "attenuation radius [m]", &mut w.attenuation_radius, 0.01, 0.0, 100.0);
    drag(ui, "reference distance [m]", &mut w.reference_distance, 0.01, 0.01, 100.0);
}
