//! Studies of the simulation's behaviour: the accuracy metric, the stability map, and the
//! integrators' runtime choice (`integrator = "auto"`: `integrator_choice`), which runs them.

pub mod accuracy;
pub mod chart;
pub mod integrator_choice;
pub mod stability_map;
