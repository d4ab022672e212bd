//! Range checks on a parsed scene. The first violation is reported as one line:
//! `key = value: what is allowed (unit)`.

use super::{Cloth, Rope, Scene};

/// Largest grid side / rope length accepted before the device-memory check; beyond this the
/// particle index arithmetic (32-bit) would overflow.
const MAX_PARTICLES: u64 = 1 << 28;

type Check = Result<(), String>;

/// The ranges of the quantities the GPU receives in f32 (24-bit mantissa, magnitudes up to
/// 3.4e38 and down to 1.2e-38 before precision is lost). Each bound leaves the arithmetic of a
/// substep (squares of lengths, k dt^2 / m, forces summed over 12 springs) well inside f32 and
/// a value outside it meaningless for cloth and ropes: a position of 1e5 m is resolved to 8 mm.
/// Positions and coordinates [m].
const MAX_COORDINATE: f64 = 1e5;
/// Lengths: sizes, radii, distances [m].
const LENGTH: (f64, f64) = (1e-6, 1e5);
/// Particle masses [kg].
const MASS: (f64, f64) = (1e-9, 1e9);
/// Spring stiffness [N/m], damping and drag [N s/m], forces [N], accelerations [m/s^2] and
/// speeds [m/s]: at most this.
const MAX_STIFFNESS: f64 = 1e12;
const MAX_DAMPING: f64 = 1e9;
const MAX_FORCE: f64 = 1e9;
const MAX_ACCELERATION: f64 = 1e5;
const MAX_SPEED: f64 = 1e8;
/// The largest tube vertex offset, in units of the rope's radius (1e300 became inf in f32).
const MAX_RING_WEIGHT: f64 = 100.0;
/// The most passes over a cloth's self-contacts a substep (each costs about as much as the first's
/// application).
const MAX_CONTACT_ITERATIONS: u32 = 64;
/// Most objects (cloths and ropes) a scene may have: each has buffers and descriptor sets of
/// its own and takes part in every pass, so past this a frame takes seconds even of tiny ones.
pub const MAX_OBJECTS: usize = 1024;
/// Most colliders (spheres, boxes, capsules and the ground) a scene may have: every particle
/// tests every collider each substep.
pub const MAX_COLLIDERS: usize = 1024;

/// A value as the user would write it: in exponent form when very large or small.
fn num(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// |v| <= max.
fn finite(key: &str, v: f64, max: f64, unit: &str) -> Check {
    if !v.is_finite() {
        Err(format!("{key} = {}: must be a finite number ({unit})", num(v)))
    } else if v.abs() > max {
        Err(format!("{key} = {}: must be between -{max:e} and {max:e} ({unit})", num(v)))
    } else {
        Ok(())
    }
}

/// lo <= v <= hi, lo > 0.
fn positive(key: &str, v: f64, (lo, hi): (f64, f64), unit: &str) -> Check {
    if !v.is_finite() {
        Err(format!("{key} = {}: must be a finite number > 0 ({unit})", num(v)))
    } else if v < lo || v > hi {
        Err(format!("{key} = {}: must be between {lo:e} and {hi:e} ({unit})", num(v)))
    } else {
        Ok(())
    }
}

/// 0 <= v <= max.
fn non_negative(key: &str, v: f64, max: f64, unit: &str) -> Check {
    if !v.is_finite() {
        Err(format!("{key} = {}: must be a finite number >= 0 ({unit})", num(v)))
    } else if !(0.0..=max).contains(&v) {
        Err(format!("{key} = {}: must be between 0 and {max:e} ({unit})", num(v)))
    } else {
        Ok(())
    }
}

/// A distance that is 0 (off) or a length within LENGTH: a search reach, whose cells of that
/// size must stay countable.
fn off_or_length(key: &str, v: f64) -> Check {
    non_negative(key, v, LENGTH.1, "m")?;
    if v > 0.0 && v < LENGTH.0 {
        return Err(format!("{key} = {}: must be 0 (off) or at least {:e} m", num(v), LENGTH.0));
    }
    Ok(())
}

/// The largest friction coefficient accepted (rubber on dry concrete is about 1).
pub const MAX_FRICTION: f64 = 10.0;

/// A Coulomb friction coefficient mu, 0 <= mu <= MAX_FRICTION.
fn friction(key: &str, v: f64) -> Check {
    non_negative(key, v, MAX_FRICTION, "Coulomb friction coefficient mu")
}

fn unit_interval(key: &str, v: f64) -> Check {
    if (0.0..=1.0).contains(&v) {
        Ok(())
    } else {
        Err(format!("{key} = {}: must be between 0 and 1", num(v)))
    }
}

/// Every component |x| <= max.
fn vector(key: &str, v: [f64; 3], max: f64, unit: &str) -> Check {
    if v.iter().all(|x| x.is_finite() && x.abs() <= max) {
        Ok(())
    } else {
        let shown: Vec<String> = v.iter().map(|&x| num(x)).collect();
        Err(format!(
            "{key} = [{}]: each component must be a finite number between -{max:e} and {max:e} ({unit})",
            shown.join(", ")
        ))
    }
}

fn color(key: &str, c: [f64; 3]) -> Check {
    if c.iter().all(|x| (0.0..=1.0).contains(x)) {
        Ok(())
    } else {
        Err(format!("{key} = {c:?}: each channel must be between 0 and 1"))
    }
}

/// The shortest frame [s]: 10 microseconds, whose smallest substep (1 / 4096 of it) is still
/// far above f32's resolution of the simulated time.
pub const MIN_FRAME_DT: f64 = 1e-5;

/// Checks every range of a scene; the error names the first key out of range.
pub fn check(scene: &Scene) -> Check {
    let s = &scene.sim;
    use crate::sim::stability::MAX_SUBSTEPS;
    if !(1..=MAX_SUBSTEPS).contains(&s.substeps) {
        return Err(format!("sim.substeps = {}: must be between 1 and {MAX_SUBSTEPS}", s.substeps));
    }
    if !(s.frame_dt.is_finite() && (MIN_FRAME_DT..=1.0).contains(&s.frame_dt)) {
        return Err(format!(
            "sim.frame_dt = {}: must be between {MIN_FRAME_DT:e} and 1 (s)",
            num(s.frame_dt)
        ));
    }
    vector("sim.gravity", s.gravity, MAX_ACCELERATION, "m/s^2")?;
    positive("sim.max_speed", s.max_speed, (1e-6, MAX_SPEED), "m/s")?;
    if !(s.max_strain.is_finite() && (0.0..=1e3).contains(&s.max_strain)) {
        return Err(format!("sim.max_strain = {}: must be between 0 (no check) and 1000", num(s.max_strain)));
    }
    if !(s.max_energy_gain.is_finite() && (0.0..=1e3).contains(&s.max_energy_gain)) {
        return Err(format!(
            "sim.max_energy_gain = {}: must be between 0 (no check) and 1000",
            num(s.max_energy_gain)
        ));
    }
    if !(1..=1000).contains(&s.iterations) {
        return Err(format!("sim.iterations = {}: must be between 1 and 1000", s.iterations));
    }
    if !(1..=MAX_CONTACT_ITERATIONS).contains(&s.contact_iterations) {
        return Err(format!(
            "sim.contact_iterations = {}: must be between 1 and {MAX_CONTACT_ITERATIONS}",
            s.contact_iterations
        ));
    }
    if !(s.relaxation > 0.0 && s.relaxation < 2.0) {
        return Err(format!("sim.relaxation = {}: must be between 0 and 2 (exclusive)", num(s.relaxation)));
    }
    if !(s.tolerance.is_finite() && s.tolerance > 0.0 && s.tolerance < 1.0) {
        return Err(format!(
            "sim.tolerance = {}: must be greater than 0 and less than 1 (a fraction of the object's size)",
            num(s.tolerance)
        ));
    }

    let w = &scene.wind;
    vector("wind.origin", w.origin, MAX_COORDINATE, "m")?;
    vector("wind.direction", w.direction, MAX_COORDINATE, "a direction")?;
    finite("wind.force", w.force, MAX_FORCE, "N")?;
    non_negative("wind.speed", w.speed, 1e3, "m/s")?;
    if w.enabled && w.model == super::WindKind::Aerodynamic && w.speed <= 0.0 {
        return Err(format!(
            "wind.speed = {}: the aerodynamic wind (the default) needs an air speed > 0 (m/s); for the paper's force on every particle (wind.force), set model = \"paper\"",
            num(w.speed)
        ));
    }
    // A force on an aerodynamic wind would be dropped without a word (a preset written for the
    // paper's wind before aerodynamic became the default): say which model uses it.
    if w.enabled && w.model == super::WindKind::Aerodynamic && w.force != 0.0 {
        return Err(format!(
            "wind.force = {}: the aerodynamic wind (the default) pushes with its air (wind.speed) and has no force; set model = \"paper\" for the paper's force on every particle, or remove force",
            num(w.force)
        ));
    }
    positive("wind.density", w.density, (1e-6, 1e5), "kg/m^3")?;
    non_negative("wind.normal_drag", w.normal_drag, 100.0, "a drag coefficient")?;
    non_negative("wind.tangential_drag", w.tangential_drag, 100.0, "a drag coefficient")?;
    non_negative("wind.lift", w.lift, 100.0, "a lift coefficient")?;
    non_negative("wind.turbulence", w.turbulence, 1e3, "m/s")?;
    positive("wind.turbulence_scale", w.turbulence_scale, LENGTH, "m")?;
    non_negative("wind.turbulence_frequency", w.turbulence_frequency, 1e3, "Hz")?;
    if w.enabled && w.model == super::WindKind::Paper && w.turbulence > 0.0 {
        return Err(format!(
            "wind.turbulence = {}: turbulence is the air's, for the aerodynamic wind (remove model = \"paper\", and set wind.speed)",
            num(w.turbulence)
        ));
    }
    non_negative("wind.full_force_radius", w.full_force_radius, LENGTH.1, "m")?;
    non_negative("wind.attenuation_radius", w.attenuation_radius, LENGTH.1, "m")?;
    positive("wind.reference_distance", w.reference_distance, LENGTH, "m")?;
    if w.enabled && w.direction.iter().map(|x| x * x).sum::<f64>() == 0.0 {
        return Err("wind.direction = [0, 0, 0]: must not be zero".into());
    }

    vector("light.position", scene.light.position, MAX_COORDINATE, "m")?;
    color("light.color", scene.light.color)?;
    unit_interval("light.ambient", scene.light.ambient)?;

    let colliders = scene.spheres.len()
        + scene.boxes.len()
        + scene.capsules.len()
        + scene.meshes.len()
        + scene.ground.iter().count();
    if colliders > MAX_COLLIDERS {
        return Err(format!(
            "{colliders} colliders ({} spheres, {} boxes, {} capsules, {} meshes): a scene may have at most {MAX_COLLIDERS} \
             (every particle tests every collider each substep)",
            scene.spheres.len(),
            scene.boxes.len(),
            scene.capsules.len(),
            scene.meshes.len()
        ));
    }
    let objects = scene.cloths.len() + scene.ropes.len() + scene.mesh_cloths.len();
    if objects > MAX_OBJECTS {
        return Err(format!(
            "{objects} objects ({} cloths, {} ropes, {} mesh cloths): a scene may have at most {MAX_OBJECTS} \
             (each has its own buffers and takes part in every pass; a larger cloth costs far less)",
            scene.cloths.len(),
            scene.ropes.len(),
            scene.mesh_cloths.len()
        ));
    }
    let substep = scene.sim.frame_dt / scene.sim.substeps as f64;
    for (i, sphere) in scene.spheres.iter().enumerate() {
        vector(&format!("sphere[{i}].center"), sphere.center, MAX_COORDINATE, "m")?;
        positive(&format!("sphere[{i}].radius"), sphere.radius, LENGTH, "m")?;
        check_motion(&format!("sphere[{i}].motion"), &sphere.motion, (substep, scene.sim.frame_dt))?;
    }
    if let Some(g) = &scene.ground {
        finite("ground.height", g.height, MAX_COORDINATE, "m")?;
        if let Some(f) = g.friction {
            friction("ground.friction", f)?;
        }
    }
    for (i, b) in scene.boxes.iter().enumerate() {
        vector(&format!("box[{i}].center"), b.center, MAX_COORDINATE, "m")?;
        for (axis, h) in ["x", "y", "z"].iter().zip(b.half_extents) {
            positive(&format!("box[{i}].half_extents.{axis}"), h, LENGTH, "m")?;
        }
        vector(&format!("box[{i}].rotation"), b.rotation, 360.0, "degrees")?;
        check_motion(&format!("box[{i}].motion"), &b.motion, (substep, scene.sim.frame_dt))?;
    }
    for (i, c) in scene.capsules.iter().enumerate() {
        vector(&format!("capsule[{i}].start"), c.start, MAX_COORDINATE, "m")?;
        vector(&format!("capsule[{i}].end"), c.end, MAX_COORDINATE, "m")?;
        positive(&format!("capsule[{i}].radius"), c.radius, LENGTH, "m")?;
        check_motion(&format!("capsule[{i}].motion"), &c.motion, (substep, scene.sim.frame_dt))?;
    }
    // A particle is found within a mesh's reach of its triangles: past every object's margin
    // (a cloth's collision_margin, a rope's radius), or a resting one would not be.
    let widest = scene.widest_margin();
    for (i, m) in scene.meshes.iter().enumerate() {
        if m.file.trim().is_empty() {
            return Err(format!("mesh[{i}].file is empty: name an .obj, .gltf or .glb file"));
        }
        vector(&format!("mesh[{i}].center"), m.center, MAX_COORDINATE, "m")?;
        vector(&format!("mesh[{i}].rotation"), m.rotation, 360.0, "degrees")?;
        positive(&format!("mesh[{i}].scale"), m.scale, (1e-6, 1e6), "m per file unit")?;
        non_negative(&format!("mesh[{i}].thickness"), m.thickness, LENGTH.1, "m")?;
        // (a reach wider than the mesh puts every triangle in every cell: each particle would
        // walk them all)
        positive(&format!("mesh[{i}].reach"), m.reach, (LENGTH.0, 10.0), "m")?;
        if m.reach <= m.thickness + widest {
            return Err(format!(
                "mesh[{i}].reach = {} m: must be more than its thickness ({} m) plus the widest margin of an object ({} m)",
                m.reach, m.thickness, widest
            ));
        }
        check_motion(&format!("mesh[{i}].motion"), &m.motion, (substep, scene.sim.frame_dt))?;
        if let Some(file) = &m.loaded {
            let (lo, hi) = crate::sim::collider_mesh::bounds(&file.vertices);
            let far = lo.abs().max(hi.abs()).max_element() * m.scale;
            if far > MAX_COORDINATE {
                return Err(format!(
                    "mesh[{i}].scale = {}: its vertices reach {far:.3e} m from its origin, past {MAX_COORDINATE} m",
                    m.scale
                ));
            }
        }
    }

    let mut names = std::collections::HashSet::new();
    for (i, c) in scene.cloths.iter().enumerate() {
        check_cloth(&format!("cloth[{i}]"), c)?;
        if !names.insert(c.name.as_str()) {
            return Err(format!("cloth[{i}].name = \"{}\": another object has this name", c.name));
        }
    }
    // A rope's nodes meet others' through contact between objects, where there are others.
    let between = scene.sim.inter_object && scene.cloths.len() + scene.ropes.len() > 1;
    for (i, r) in scene.ropes.iter().enumerate() {
        check_rope(&format!("rope[{i}]"), r, between)?;
        if !names.insert(r.name.as_str()) {
            return Err(format!("rope[{i}].name = \"{}\": another object has this name", r.name));
        }
    }
    for (i, c) in scene.mesh_cloths.iter().enumerate() {
        check_mesh_cloth(&format!("mesh_cloth[{i}]"), c, scene)?;
        if !names.insert(c.name.as_str()) {
            return Err(format!("mesh_cloth[{i}].name = \"{}\": another object has this name", c.name));
        }
    }
    // (objects whose pins, or some group's, are given a motion)
    fn moves<P>(own: &Option<super::Motion>, groups: &[super::PinGroup<P>]) -> bool {
        own.is_some() || groups.iter().any(|g| g.pin_motion.is_some())
    }
    let moving = (scene.cloths.iter().enumerate())
        .filter(|(_, c)| moves(&c.pin_motion, &c.pin_groups))
        .map(|(i, c)| (format!("cloth[{i}]"), super::build::cloth(c)))
        .chain(
            (scene.ropes.iter().enumerate())
                .filter(|(_, r)| moves(&r.pin_motion, &r.pin_groups))
                .map(|(i, r)| (format!("rope[{i}]"), super::build::rope(r))),
        )
        .chain(
            (scene.mesh_cloths.iter().enumerate())
                .filter(|(_, c)| moves(&c.pin_motion, &c.pin_groups))
                .filter_map(|(i, c)| Some((format!("mesh_cloth[{i}]"), super::build::mesh_cloth(c).ok()?))),
        );
    for (object, o) in moving {
        for (g, motion) in o.pin_motions().enumerate() {
            let at = match g {
                0 => format!("{object}.pin_motion"),
                g => format!("{object}.pin_group[{}].pin_motion", g - 1),
            };
            check_half_turn(&at, &motion.turn, (substep, scene.sim.frame_dt))?;
            let pins: Vec<_> = (0..o.positions.len())
                .filter(|&i| o.pinned[i] && o.group_of(i) == g)
                .map(|i| o.positions[i])
                .collect();
            let fastest = motion.top_speed(&pins);
            if fastest > scene.sim.max_speed {
                return Err(format!(
                    "{at}: its pins would move at up to {} m/s, past sim.max_speed = {} m/s (the runtime guard would stop the run at once): raise sim.max_speed or slow the pins",
                    num(fastest),
                    num(scene.sim.max_speed)
                ));
            }
        }
    }
    Ok(())
}

/// A collider's motion: a translation (`check_translation`), a turn about its centre
/// (`check_turn`; under half a turn a substep, a keyed one a frame, as the pins'), or both.
fn check_motion(at: &str, m: &Option<super::Motion>, (substep, frame_dt): (f64, f64)) -> Check {
    let Some(m) = m else { return Ok(()) };
    if m.pivot.is_some() {
        return Err(format!(
            "{at}.pivot: a collider turns about its centre (pivot is for a cloth's or rope's pin_motion)"
        ));
    }
    if !check_turn(at, m)? {
        return check_translation(at, m);
    }
    check_half_turn(at, &super::build::turn(m), (substep, frame_dt))?;
    if m.velocity.is_none() && m.keyframes.is_empty() {
        return check_interpolation(at, m); // (a turn alone)
    }
    check_translation(at, m)
}

/// A turn (a collider's or pins') under half a turn a substep: a substep's turn is a rotation,
/// and past half a turn it would turn the other way; a keyed turn is taken a frame at a time
/// (`Turn::frame_spin`), so under half a turn a frame.
fn check_half_turn(at: &str, turn: &crate::sim::turn::Turn, (substep, frame_dt): (f64, f64)) -> Check {
    let (key, per, step, or) = match turn.rotation.is_moving() {
        true => ("rotation_keyframes", "frame", frame_dt, ""),
        false => ("angular_velocity", "substep", substep, " or more substeps"),
    };
    let most = turn.top_spin() * step;
    if most >= 0.5 * std::f64::consts::TAU {
        return Err(format!(
            "{at}.{key}: up to {} degrees a {per}, half a turn or more (the {per}'s turn would go the other way): a slower turn{or}",
            num(most.to_degrees())
        ));
    }
    Ok(())
}

/// A motion's turn (a collider's or pins'): `angular_velocity` or `rotation_keyframes`, not
/// both, each in range. Whether it turns.
fn check_turn(at: &str, m: &super::Motion) -> Result<bool, String> {
    if let Some(w) = m.angular_velocity {
        vector(&format!("{at}.angular_velocity"), w, MAX_TURN, "degrees/s")?;
        if !m.rotation_keyframes.is_empty() {
            return Err(format!("{at}: give angular_velocity or rotation_keyframes, not both"));
        }
    }
    check_times(
        &format!("{at}.rotation_keyframes"),
        &m.rotation_keyframes,
        ("angles", MAX_ANGLE, "degrees"),
    )?;
    Ok(m.angular_velocity.is_some() || !m.rotation_keyframes.is_empty())
}

/// A motion's translation (a collider's, or an object's pins'): a velocity or keyframes (not
/// both, not neither), keyframe times finite, at least 0 and increasing.
fn check_translation(at: &str, m: &super::Motion) -> Check {
    check_interpolation(at, m)?;
    match (m.velocity, m.keyframes.is_empty()) {
        (Some(_), false) => return Err(format!("{at}: give a velocity or keyframes, not both")),
        (None, true) => return Err(format!("{at}: give a velocity or keyframes")),
        (Some(v), true) => vector(&format!("{at}.velocity"), v, MAX_SPEED, "m/s")?,
        (None, false) => {
            check_times(&format!("{at}.keyframes"), &m.keyframes, ("position", MAX_COORDINATE, "m"))?
        }
    }
    Ok(())
}

/// An object's name: not empty, and no control characters (a name reaches the terminal in
/// messages, where an escape sequence could rewrite what the user reads).
fn check_name(at: &str, name: &str) -> Check {
    if name.trim().is_empty() {
        return Err(format!("{at}.name: must not be empty"));
    }
    if name.trim().parse::<u64>().is_ok() {
        return Err(format!(
            "{at}.name = \"{name}\": must not be a number (--set cloth.1.mass means the cloth at index 1)"
        ));
    }
    if name.chars().any(char::is_control) {
        return Err(format!("{at}.name = {}: must not contain control characters", name.escape_debug()));
    }
    Ok(())
}

/// How many grid spacings a cloth's self-collision distance may span (a rope's reach may span
/// four times as many node spacings, its contacts being along one line): past it each particle
/// is in contact with hundreds or thousands of others at rest, and the contact search grows
/// with their number (a rope of 21,000 nodes on 0.5 m with a 2 cm radius, 1,700 a node, took
/// over 60 s a frame on lavapipe), for a result no finer than at the bound.
const MAX_CONTACT_SPAN: f64 = 16.0;

/// A cloth's springs: stiffness per type, rest lengths (`rest_unit`: what they multiply), the
/// dashpots and the drag.
fn check_springs(
    at: &str,
    (stiffness, rest_scale, rest_unit): (super::PerSpring, super::PerSpring, &str),
    damping: f64,
    drag: f64,
) -> Check {
    let names = ["structural", "shear", "bending"];
    for (name, k) in names.iter().zip(stiffness.to_array()) {
        non_negative(&format!("{at}.stiffness.{name}"), k, MAX_STIFFNESS, "N/m")?;
    }
    for (name, k) in names.iter().zip(rest_scale.to_array()) {
        positive(&format!("{at}.rest_scale.{name}"), k, (1e-3, 1e3), rest_unit)?;
    }
    non_negative(&format!("{at}.damping"), damping, MAX_DAMPING, "N s/m")?;
    non_negative(&format!("{at}.drag"), drag, MAX_DAMPING, "N s/m")
}

fn check_cloth(at: &str, c: &Cloth) -> Check {
    check_name(at, &c.name)?;
    let [cols, rows] = c.resolution;
    if cols < 2 || rows < 2 {
        return Err(format!("{at}.resolution = [{cols}, {rows}]: each side must be at least 2 particles"));
    }
    if cols as u64 * rows as u64 > MAX_PARTICLES {
        return Err(format!(
            "{at}.resolution = [{cols}, {rows}]: {} particles is more than the {MAX_PARTICLES} an object may have",
            cols as u64 * rows as u64
        ));
    }
    positive(&format!("{at}.size[0]"), c.size[0], LENGTH, "m")?;
    positive(&format!("{at}.size[1]"), c.size[1], LENGTH, "m")?;
    vector(&format!("{at}.origin"), c.origin, MAX_COORDINATE, "m")?;
    positive(&format!("{at}.mass"), c.mass, MASS, "kg per particle")?;
    check_springs(at, (c.stiffness, c.rest_scale, "multiple of the grid distance"), c.damping, c.drag)?;
    if let Some(l) = c.stretch_limit {
        non_negative(&format!("{at}.stretch_limit"), l, 1e3, "fraction of rest length")?;
    }
    friction(&format!("{at}.friction"), c.friction)?;
    non_negative(&format!("{at}.collision_margin"), c.collision_margin, LENGTH.1, "m")?;
    if let Some(d) = c.self_collision_distance {
        positive(&format!("{at}.self_collision_distance"), d, LENGTH, "m")?;
    }
    if c.self_collision {
        let d = c.self_collision_distance.unwrap_or_else(|| c.default_self_collision_distance());
        let spacing = c.spacing()[0].min(c.spacing()[1]);
        if d / spacing > MAX_CONTACT_SPAN {
            return Err(format!(
                "{at}.self_collision_distance = {} m: {:.0} times the grid spacing ({spacing:.3e} m), so each particle would be in contact with thousands of others and contact search would take minutes a frame; keep it at most {MAX_CONTACT_SPAN} spacings ({:.3e} m), or use a coarser grid",
                num(d),
                d / spacing,
                MAX_CONTACT_SPAN * spacing
            ));
        }
    }
    color(&format!("{at}.color"), c.color)?;
    color(&format!("{at}.back_color"), c.back_color)?;
    for (k, p) in c.pinned.iter().enumerate() {
        if p[0] >= cols || p[1] >= rows {
            return Err(format!("{at}.pinned[{k}] = [{}, {}]: outside the {cols} x {rows} grid", p[0], p[1]));
        }
    }
    // (built where a box or a group asks, without its groups, whose lists are checked below)
    let own = std::cell::OnceCell::new();
    let own =
        || own.get_or_init(|| super::build::cloth(&super::Cloth { pin_groups: Vec::new(), ..c.clone() }));
    check_pin_box(at, &c.pin_box, || &own().positions)?;
    check_pin_motion(at, &c.pin_motion, c.has_pins())?;
    if c.pin_groups.is_empty() {
        return Ok(());
    }
    let own = own();
    let index = |p: [u32; 2]| match p[0] < cols && p[1] < rows {
        true => Ok((p[0] + p[1] * cols) as usize),
        false => Err(format!("[{}, {}]: outside the {cols} x {rows} grid", p[0], p[1])),
    };
    let name = |i: usize| format!("particle [{}, {}]", i as u32 % cols, i as u32 / cols);
    check_pin_groups(at, &c.pin_groups, index, name, (&own.positions, &own.pinned))
}

fn check_mesh_cloth(at: &str, c: &super::MeshCloth, scene: &Scene) -> Check {
    check_name(at, &c.name)?;
    if c.file.trim().is_empty() {
        return Err(format!("{at}.file is empty: name an .obj, .gltf or .glb file"));
    }
    vector(&format!("{at}.center"), c.center, MAX_COORDINATE, "m")?;
    vector(&format!("{at}.rotation"), c.rotation, 360.0, "degrees")?;
    positive(&format!("{at}.scale"), c.scale, (1e-6, 1e6), "m per file unit")?;
    off_or_length(&format!("{at}.weld"), c.weld)?;
    positive(&format!("{at}.density"), c.density, (1e-6, 1e3), "kg/m^2")?;
    check_springs(at, (c.stiffness, c.rest_scale, "multiple of the mesh's length"), c.damping, c.drag)?;
    if let Some(l) = c.stretch_limit {
        non_negative(&format!("{at}.stretch_limit"), l, 1e3, "fraction of rest length")?;
    }
    friction(&format!("{at}.friction"), c.friction)?;
    non_negative(&format!("{at}.collision_margin"), c.collision_margin, LENGTH.1, "m")?;
    color(&format!("{at}.color"), c.color)?;
    color(&format!("{at}.back_color"), c.back_color)?;
    non_negative(&format!("{at}.seam_stiffness"), c.seam_stiffness, MAX_STIFFNESS, "N/m")?;
    off_or_length(&format!("{at}.sew"), c.sew)?;
    if !c.seams.is_empty() && c.seam_stiffness == 0.0 {
        return Err(format!("{at}.seam: its seams need a seam_stiffness (N/m) to close"));
    }
    if c.sew > 0.0 && c.seam_stiffness == 0.0 {
        return Err(format!("{at}.sew: the seams it finds need a seam_stiffness (N/m) to close"));
    }
    if let Some(m) = scene.sim.integrator.method().filter(|m| !crate::sim::cloth_mesh::METHODS.contains(m)) {
        return Err(format!(
            "{at}: a mesh cloth runs with sim.integrator = {}, not \"{}\"",
            crate::sim::model::Integrator::named(crate::sim::cloth_mesh::METHODS),
            m.label()
        ));
    }
    if scene.sim.inter_object && scene.cloths.len() + scene.ropes.len() + scene.mesh_cloths.len() > 1 {
        return Err(format!(
            "{at}: a mesh cloth does not take part in contact between objects yet; set sim.inter_object = false or leave the other objects out"
        ));
    }
    if let Some(h) = c.self_collision_distance {
        positive(&format!("{at}.self_collision_distance"), h, LENGTH, "m")?;
    }
    let Some(file) = &c.loaded else { return Ok(()) };
    let (lo, hi) = crate::sim::collider_mesh::bounds(&file.vertices);
    let far = lo.abs().max(hi.abs()).max_element() * c.scale;
    if far > MAX_COORDINATE {
        return Err(format!(
            "{at}.scale = {}: its vertices reach {far:.3e} m from its origin, past {MAX_COORDINATE} m",
            c.scale
        ));
    }
    let own = super::build::mesh_cloth(&super::MeshCloth { pin_groups: Vec::new(), ..c.clone() })
        .map_err(|e| format!("{at}: {} {e}", file.path.display()))?;
    if let (Some(mesh), Some(h)) = (&own.mesh, own.self_distance) {
        crate::sim::cloth_mesh::thin_enough(mesh, &own.positions, h).map_err(|e| format!("{at}: {e}"))?;
    }
    check_pin_box(at, &c.pin_box, || &own.positions)?;
    check_pin_motion(at, &c.pin_motion, c.has_pins())?;
    let n = own.positions.len();
    let index = |i: u32| match (i as usize) < n {
        true => Ok(i as usize),
        false => Err(format!("{i}: past its {n} vertices")),
    };
    let name = |i: usize| format!("vertex {i}");
    check_pin_groups(at, &c.pin_groups, index, name, (&own.positions, &own.pinned))
}

/// An object's `pin_group` entries: at most `PIN_GROUPS` - 1; each holds a particle (its
/// list in range, `index`; its box as a `pin_box`), none that its object's own pins
/// (`pinned`, placed at `positions`) or an earlier entry hold, and moves by a pin motion.
fn check_pin_groups<P: Copy>(
    at: &str,
    groups: &[super::PinGroup<P>],
    index: impl Fn(P) -> Result<usize, String>,
    name: impl Fn(usize) -> String,
    (positions, pinned): (&[glam::DVec3], &[bool]),
) -> Check {
    let most = crate::sim::model::PIN_GROUPS - 1;
    if groups.len() > most {
        return Err(format!(
            "{at}.pin_group: {} groups, at most {most} (and the object's own pins)",
            groups.len()
        ));
    }
    let mut held_by: Vec<Option<usize>> = pinned.iter().map(|&p| p.then_some(0)).collect();
    for (g, group) in groups.iter().enumerate() {
        let at = format!("{at}.pin_group[{g}]");
        for (k, &p) in group.pinned.iter().enumerate() {
            index(p).map_err(|e| format!("{at}.pinned[{k}] = {e}"))?;
        }
        check_pin_box(&at, &group.pin_box, || positions)?;
        let mask = super::build::group_mask(group, |&p| index(p).ok(), positions);
        if !mask.contains(&true) {
            return Err(format!("{at}: holds no particle (give it `pinned` or a `pin_box`)"));
        }
        for (i, _) in mask.iter().enumerate().filter(|(_, &m)| m) {
            if let Some(other) = held_by[i] {
                let by = match other {
                    0 => "its object's own pins (pin, pinned or pin_box)".to_string(),
                    o => format!("pin_group[{}]", o - 1),
                };
                return Err(format!(
                    "{at}: {} is pinned by {by} already: a particle follows one group",
                    name(i)
                ));
            }
            held_by[i] = Some(g + 1);
        }
        check_pin_motion(&at, &group.pin_motion, true)?;
    }
    Ok(())
}

/// An object's `pin_box`: its corners finite and in order, and some particle (at `positions`,
/// where the object places them) inside it.
fn check_pin_box<'a>(
    at: &str,
    b: &Option<super::PinBox>,
    positions: impl FnOnce() -> &'a [glam::DVec3],
) -> Check {
    let Some(b) = b else { return Ok(()) };
    vector(&format!("{at}.pin_box.min"), b.min, MAX_COORDINATE, "m")?;
    vector(&format!("{at}.pin_box.max"), b.max, MAX_COORDINATE, "m")?;
    if (0..3).any(|k| b.min[k] > b.max[k]) {
        return Err(format!(
            "{at}.pin_box: min {:?} is past max {:?} along some axis (min is the lowest corner)",
            b.min, b.max
        ));
    }
    if !positions().iter().any(|&x| b.contains(x)) {
        return Err(format!("{at}.pin_box: no particle is placed inside it (leave it out, or move it)"));
    }
    Ok(())
}

/// An object's `pin_motion`: a motion as a collider's (`check_motion`), on an object with a
/// pinned particle for it to move.
fn check_pin_motion(at: &str, m: &Option<super::Motion>, pins: bool) -> Check {
    let Some(motion) = m else { return Ok(()) };
    let at = format!("{at}.pin_motion");
    if !pins {
        return Err(format!(
            "{at}: no particle is pinned for it to move (set `pin`, `pinned` or `pin_box`, or leave pin_motion out)"
        ));
    }
    let turns = check_turn(&at, motion)?;
    if let Some(p) = motion.pivot {
        if !turns {
            return Err(format!(
                "{at}.pivot: there is no angular_velocity or rotation_keyframes to turn about it"
            ));
        }
        vector(&format!("{at}.pivot"), p, MAX_COORDINATE, "m")?;
    }
    check_interpolation(&at, motion)?;
    let translation = super::Motion {
        angular_velocity: None,
        pivot: None,
        rotation_keyframes: Vec::new(),
        interpolation: if motion.keyframes.is_empty() { Default::default() } else { motion.interpolation },
        ..motion.clone()
    };
    if turns && translation == super::Motion::default() {
        return Ok(()); // (a turn alone)
    }
    check_translation(&at, &translation)
}

/// A motion's `interpolation`: only where it has keyframes to join (a collider's; a pin
/// motion's, of positions or angles).
fn check_interpolation(at: &str, m: &super::Motion) -> Check {
    if m.interpolation != super::Interpolation::Linear
        && m.keyframes.is_empty()
        && m.rotation_keyframes.is_empty()
    {
        return Err(format!("{at}: interpolation joins keyframes; give keyframes or leave it out"));
    }
    Ok(())
}

/// Keyframe rows [t, a, b, c] at `at`: times finite, at least 0 and increasing; the values
/// (`what`) within ±`most` (`unit`).
fn check_times(at: &str, keys: &[[f64; 4]], (what, most, unit): (&str, f64, &str)) -> Check {
    let mut last = -1.0;
    for (k, key) in keys.iter().enumerate() {
        let t = key[0];
        non_negative(&format!("{at}[{k}] time"), t, 1e9, "s")?;
        if t <= last {
            return Err(format!("{at}[{k}]: time {} s is not after the one before ({last} s)", num(t)));
        }
        last = t;
        vector(&format!("{at}[{k}] {what}"), [key[1], key[2], key[3]], most, unit)?;
    }
    Ok(())
}

/// The largest keyed pin angle [degrees]: a thousand turns.
const MAX_ANGLE: f64 = 360_000.0;

/// The fastest turn a pin motion takes [degrees/s]: ten turns a frame at 60 frames/s.
const MAX_TURN: f64 = 216_000.0;

fn check_rope(at: &str, r: &Rope, between: bool) -> Check {
    check_name(at, &r.name)?;
    if r.nodes < 2 || r.nodes as u64 > MAX_PARTICLES / 8 {
        return Err(format!("{at}.nodes = {}: must be between 2 and {}", r.nodes, MAX_PARTICLES / 8));
    }
    vector(&format!("{at}.start"), r.start, MAX_COORDINATE, "m")?;
    vector(&format!("{at}.end"), r.end, MAX_COORDINATE, "m")?;
    if r.start == r.end {
        return Err(format!("{at}.end = {:?}: must differ from start", r.end));
    }
    positive(&format!("{at}.mass"), r.mass, MASS, "kg per node")?;
    non_negative(&format!("{at}.stiffness"), r.stiffness, MAX_STIFFNESS, "N/m")?;
    non_negative(&format!("{at}.bending_stiffness"), r.bending_stiffness, MAX_STIFFNESS, "N/m")?;
    positive(&format!("{at}.rest_scale"), r.rest_scale, (1e-3, 1e3), "multiple of the node spacing")?;
    non_negative(&format!("{at}.damping"), r.damping, MAX_DAMPING, "N s/m")?;
    non_negative(&format!("{at}.drag"), r.drag, MAX_DAMPING, "N s/m")?;
    if let Some(l) = r.stretch_limit {
        non_negative(&format!("{at}.stretch_limit"), l, 1e3, "fraction of rest length")?;
    }
    friction(&format!("{at}.friction"), r.friction)?;
    positive(&format!("{at}.radius"), r.radius, LENGTH, "m")?;
    if let Some(w) = &r.ring_weights {
        if w.len() != 8 || w.iter().flatten().any(|x| !x.is_finite() || x.abs() > MAX_RING_WEIGHT) {
            return Err(format!(
                "{at}.ring_weights: must be 8 [side, up] pairs, each between -{MAX_RING_WEIGHT} and {MAX_RING_WEIGHT} (units of the radius)"
            ));
        }
    }
    if let Some(d) = r.self_collision_distance {
        positive(&format!("{at}.self_collision_distance"), d, LENGTH, "m")?;
    }
    // A node's contact reach (its tube's diameter, or the self-collision distance) against the
    // node spacing, where the rope has contacts: far past it, every node is in contact with
    // hundreds along its own rope.
    let length = r.start.iter().zip(r.end).map(|(a, b)| (b - a) * (b - a)).sum::<f64>().sqrt();
    let spacing = length / (r.nodes - 1) as f64;
    let own = if r.self_collision { r.self_collision_distance.unwrap_or(2.0 * r.radius) } else { 0.0 };
    let reach = if between { own.max(2.0 * r.radius) } else { own };
    if spacing > 0.0 && reach / spacing > 4.0 * MAX_CONTACT_SPAN {
        // What would work: fewer nodes (where two or more still fit), or a shorter reach.
        let most_nodes = (4.0 * MAX_CONTACT_SPAN * length / reach).floor() as u64 + 1;
        let fewer = if most_nodes >= 2 {
            format!("at most {most_nodes} nodes for this length and radius, or ")
        } else {
            String::new()
        };
        let longest = 4.0 * MAX_CONTACT_SPAN * spacing;
        let shorter = match r.self_collision_distance.filter(|&d| r.self_collision && d >= 2.0 * r.radius) {
            Some(_) => format!("a self_collision_distance of at most {longest:.3e} m"),
            None => format!("a radius of at most {:.3e} m", 0.5 * longest),
        };
        return Err(format!(
            "{at}.nodes = {}: nodes {spacing:.3e} m apart with a contact reach of {reach:.3e} m (twice the radius, or the self-collision distance) would each touch {:.0} others along the rope, and contact search would take minutes a frame; use {fewer}{shorter}",
            r.nodes,
            reach / spacing,
        ));
    }
    color(&format!("{at}.color"), r.color)?;
    for (k, &p) in r.pinned.iter().enumerate() {
        if p >= r.nodes {
            return Err(format!(
                "{at}.pinned[{k}] = {p}: a rope of {} nodes has indices 0..{}",
                r.nodes,
                r.nodes - 1
            ));
        }
    }
    let own = std::cell::OnceCell::new();
    let own = || own.get_or_init(|| super::build::rope(&super::Rope { pin_groups: Vec::new(), ..r.clone() }));
    check_pin_box(at, &r.pin_box, || &own().positions)?;
    check_pin_motion(at, &r.pin_motion, r.has_pins())?;
    if r.pin_groups.is_empty() {
        return Ok(());
    }
    let own = own();
    let nodes = r.nodes;
    let index = |p: u32| match p < nodes {
        true => Ok(p as usize),
        false => Err(format!("{p}: a rope of {nodes} nodes has indices 0..{}", nodes - 1)),
    };
    let name = |i: usize| format!("node {i}");
    check_pin_groups(at, &r.pin_groups, index, name, (&own.positions, &own.pinned))
}
