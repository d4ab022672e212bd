//! Studies of the simulation's behaviour: the stability map (stiffness x substep sweep).

pub mod stability_map;
