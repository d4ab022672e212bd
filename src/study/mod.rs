//! Studies of the simulation's behaviour: the accuracy metric, the stability map.

pub mod accuracy;
pub mod auto;
pub mod chart;
pub mod stability_map;
