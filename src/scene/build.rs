//! Scene preset -> simulation model: initial positions, pins, derived wind cone.

use super::{Cloth, ClothPins, Orientation, Rope, RopePins, Scene, SelfContact};
use crate::sim::collider::{ColliderModel, Motion, Shape};
use crate::sim::model::{default_ring_weights, ObjectKind, ObjectModel, ObjectShape, SimModel, WindModel};
use crate::sim::pins::PinMotion;
use crate::sim::turn::Turn;
use glam::{DQuat, DVec3, EulerRot};

/// The size of every object of a validated scene, cloths first, without building particles.
pub fn shapes(scene: &Scene) -> Vec<ObjectShape> {
    let cloths = scene.cloths.iter().map(|c| ObjectShape {
        kind: ObjectKind::Cloth,
        name: c.name.clone(),
        dims: c.resolution,
        mesh: None,
    });
    let ropes = scene.ropes.iter().map(|r| ObjectShape {
        kind: ObjectKind::Rope,
        name: r.name.clone(),
        dims: [r.nodes, 1],
        mesh: None,
    });
    // (a mesh cloth's particles are its vertices once welded: built, as `to_model` leaves
    // out one that does not build)
    let meshes = scene.mesh_cloths.iter().filter_map(|c| Some(mesh_cloth(c).ok()?.shape()));
    cloths.chain(ropes).chain(meshes).collect()
}

/// The turbulence of an aerodynamic wind `w`, if it has any (the simulation's, and the gusts
/// the app draws).
pub fn turbulence_of(w: &crate::scene::Wind) -> Option<crate::sim::turbulence::Turbulence> {
    let aerodynamic = w.model == crate::scene::WindKind::Aerodynamic;
    (aerodynamic && w.turbulence > 0.0).then(|| {
        let mean = DVec3::from_array(w.direction).normalize_or_zero() * w.speed;
        let t = crate::sim::turbulence::Turbulence::new;
        t(w.turbulence, w.turbulence_scale, w.turbulence_frequency, mean, w.seed)
    })
}

/// Builds the model of a validated scene.
pub fn to_model(scene: &Scene) -> SimModel {
    let w = &scene.wind;
    let wind = w.enabled.then(|| {
        let cone_cos = |radius: f64| w.reference_distance / w.reference_distance.hypot(radius);
        WindModel {
            origin: DVec3::from_array(w.origin),
            direction: DVec3::from_array(w.direction).normalize(),
            force: w.force,
            cos_full: cone_cos(w.full_force_radius),
            cos_att: cone_cos(w.full_force_radius + w.attenuation_radius),
            air: (w.model == crate::scene::WindKind::Aerodynamic).then_some(crate::sim::model::AirModel {
                speed: w.speed,
                normal: 0.5 * w.density * w.normal_drag,
                tangent: 0.5 * w.density * w.tangential_drag,
                lift: w.density * w.lift,
                turbulence: turbulence_of(w),
            }),
        }
    });
    SimModel {
        gravity: DVec3::from_array(scene.sim.gravity),
        frame_dt: scene.sim.frame_dt,
        substeps: scene.sim.substeps,
        wind,
        colliders: colliders(scene),
        // (a mesh cloth that does not build, which validation prevents, is left out)
        objects: (scene.cloths.iter().map(cloth))
            .chain(scene.ropes.iter().map(rope))
            .chain(scene.mesh_cloths.iter().filter_map(|c| mesh_cloth(c).ok()))
            .collect(),
        self_collision: scene.sim.self_collision,
        max_speed: scene.sim.max_speed,
        max_strain: scene.sim.max_strain,
        max_energy_gain: scene.sim.max_energy_gain,
        // "auto" starts from the paper's method; the calibration (study::integrator_choice) replaces it.
        integrator: scene.sim.integrator.method().unwrap_or_default(),
        iterations: scene.sim.iterations,
        relaxation: scene.sim.relaxation,
        inter_object: scene.sim.inter_object,
        inter_object_edges: scene.sim.inter_object_edges,
        contact_iterations: scene.sim.contact_iterations,
    }
}

/// The scene's colliders in the model: the ground, then spheres, boxes, capsules and meshes.
pub fn colliders(scene: &Scene) -> Vec<ColliderModel> {
    let v = DVec3::from_array;
    let moving = |shape: Shape, m: &Option<super::Motion>| ColliderModel {
        motion: motion(&shape, m),
        shape,
        friction: None,
        turn: m.as_ref().map(turn).unwrap_or_default(),
    };
    let ground = scene.ground.iter().map(|g| ColliderModel {
        shape: Shape::Ground { height: g.height },
        friction: g.friction,
        motion: Motion::Fixed,
        turn: Turn::default(),
    });
    let spheres = scene
        .spheres
        .iter()
        .map(|s| moving(Shape::Sphere { center: v(s.center), radius: s.radius }, &s.motion));
    let boxes = scene.boxes.iter().map(|b| {
        let [x, y, z] = b.rotation.map(f64::to_radians);
        let rotation = DQuat::from_euler(EulerRot::XYZ, x, y, z);
        moving(Shape::Box { center: v(b.center), half_extents: v(b.half_extents), rotation }, &b.motion)
    });
    let capsules = scene
        .capsules
        .iter()
        .map(|c| moving(Shape::Capsule { a: v(c.start), b: v(c.end), radius: c.radius }, &c.motion));
    // (a mesh whose file was not read, which `load_meshes` prevents, is left out)
    let meshes = scene.meshes.iter().filter_map(|m| {
        let file = m.loaded.as_ref()?;
        let [x, y, z] = m.rotation.map(f64::to_radians);
        let rotation = DQuat::from_euler(EulerRot::XYZ, x, y, z);
        let mesh = file.built(m.scale, m.reach);
        Some(moving(Shape::Mesh { center: v(m.center), rotation, thickness: m.thickness, mesh }, &m.motion))
    });
    ground.chain(spheres).chain(boxes).chain(capsules).chain(meshes).collect()
}

/// A validated preset motion in the model: keyframes become offsets from the shape's placement.
fn motion(shape: &Shape, m: &Option<super::Motion>) -> Motion {
    let Some(m) = m else { return Motion::Fixed };
    if let Some(v) = m.velocity {
        return Motion::Velocity(DVec3::from_array(v));
    }
    if m.keyframes.is_empty() {
        return Motion::Fixed;
    }
    let at = shape.reference_point();
    keyed(m, at)
}

/// The keyframes of `m` (validated, not empty) as offsets from `at`, joined as `m` asks.
fn keyed(m: &super::Motion, at: DVec3) -> Motion {
    let keys = m.keyframes.iter().map(|k| (k[0], DVec3::new(k[1], k[2], k[3]) - at)).collect();
    match m.interpolation {
        super::Interpolation::Linear => Motion::Keyframes(keys),
        super::Interpolation::Smooth => Motion::Smooth(keys),
    }
}

pub(super) fn cloth(c: &Cloth) -> ObjectModel {
    let [cols, rows] = c.resolution;
    let spacing = c.spacing();
    let down = match c.orientation {
        Orientation::Vertical => DVec3::NEG_Y,
        Orientation::Horizontal => DVec3::Z,
    };
    let origin = DVec3::from_array(c.origin);
    let n = cols as usize * rows as usize;
    let mut positions = Vec::with_capacity(n);
    let mut pinned = Vec::with_capacity(n);
    for r in 0..rows {
        for col in 0..cols {
            positions.push(origin + DVec3::X * (col as f64 * spacing[0]) + down * (r as f64 * spacing[1]));
            let (left, right, top, bottom) = (col == 0, col == cols - 1, r == 0, r == rows - 1);
            pinned.push(match c.pin {
                ClothPins::None => false,
                ClothPins::TopRow => top,
                ClothPins::TopCorners => top && (left || right),
                ClothPins::LeftColumn => left,
                ClothPins::Corners => (top || bottom) && (left || right),
            });
        }
    }
    for p in &c.pinned {
        pinned[(p[0] + p[1] * cols) as usize] = true;
    }
    pin_inside(&c.pin_box, &positions, &mut pinned);
    let own_motion = pin_motion(&c.pin_motion, &positions, &pinned);
    let (pin_group, pin_groups) = groups(
        &c.pin_groups,
        |p| (p[0] < cols && p[1] < rows).then(|| p[0] as usize + p[1] as usize * cols as usize),
        &positions,
        &mut pinned,
    );
    ObjectModel {
        kind: ObjectKind::Cloth,
        name: c.name.clone(),
        dims: c.resolution,
        spacing,
        stiffness: c.stiffness.to_array(),
        rest_scale: c.rest_scale.to_array(),
        seam: 0.0,
        damping: c.damping,
        mass: c.mass,
        drag: c.drag,
        friction: c.friction,
        margin: c.collision_margin,
        stretch_limit: c.stretch_limit,
        self_distance: c
            .self_collision
            .then(|| c.self_collision_distance.unwrap_or_else(|| c.default_self_collision_distance())),
        triangle_contact: c.self_contact.triangles(),
        edge_contact: c.self_contact == SelfContact::TrianglesAndEdges,
        rope_radius: 0.0,
        ring_weights: default_ring_weights(),
        velocities: vec![DVec3::ZERO; n],
        pin_motion: own_motion,
        pin_groups,
        pin_group,
        positions,
        pinned,
        mesh: None,
    }
}

/// Each particle's group of `groups` (1 + its index; 0 where none has it) and their motions,
/// the particles they hold pinned too (where two hold one, the later: scene validation
/// refuses it).
fn groups<P>(
    groups: &[super::PinGroup<P>],
    index: impl Fn(&P) -> Option<usize>,
    positions: &[DVec3],
    pinned: &mut [bool],
) -> (Vec<u8>, Vec<PinMotion>) {
    if groups.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let mut of = vec![0u8; positions.len()];
    let motions = (groups.iter().enumerate())
        .map(|(g, group)| {
            let held = group_mask(group, &index, positions);
            for (i, _) in held.iter().enumerate().filter(|(_, &h)| h) {
                pinned[i] = true;
                of[i] = (g + 1) as u8;
            }
            pin_motion(&group.pin_motion, positions, &held)
        })
        .collect();
    (of, motions)
}

/// The particles a pin group holds: those it lists (`index` of each; `None` outside the object,
/// which scene validation refuses: left out, so that an editor's scene not yet valid builds)
/// and those in its box.
pub(super) fn group_mask<P>(
    group: &super::PinGroup<P>,
    index: impl Fn(&P) -> Option<usize>,
    positions: &[DVec3],
) -> Vec<bool> {
    let mut held = vec![false; positions.len()];
    for i in group.pinned.iter().filter_map(&index) {
        if let Some(h) = held.get_mut(i) {
            *h = true;
        }
    }
    pin_inside(&group.pin_box, positions, &mut held);
    held
}

/// A validated `pin_motion` in the model: keyframes are already displacements; the turn in
/// radians, about the pinned particles' centre where no pivot is given.
fn pin_motion(m: &Option<super::Motion>, positions: &[DVec3], pinned: &[bool]) -> PinMotion {
    let Some(m) = m else { return PinMotion::default() };
    let translation = match (m.velocity, m.keyframes.is_empty()) {
        (Some(v), _) => Motion::Velocity(DVec3::from_array(v)),
        (None, false) => keyed(m, DVec3::ZERO),
        (None, true) => Motion::Fixed,
    };
    let held: Vec<DVec3> = positions.iter().zip(pinned).filter(|(_, &p)| p).map(|(x, _)| *x).collect();
    let centre = held.iter().sum::<DVec3>() / held.len().max(1) as f64;
    PinMotion { translation, turn: turn(m), pivot: m.pivot.map_or(centre, DVec3::from_array) }
}

/// A validated motion's turn: steady (`angular_velocity`, degrees/s) or keyed
/// (`rotation_keyframes`, degrees), in radians.
pub(super) fn turn(m: &super::Motion) -> Turn {
    let rotation = if m.rotation_keyframes.is_empty() {
        Motion::Fixed
    } else {
        let angles = super::Motion {
            keyframes: m
                .rotation_keyframes
                .iter()
                .map(|k| [k[0], k[1].to_radians(), k[2].to_radians(), k[3].to_radians()])
                .collect(),
            ..m.clone()
        };
        keyed(&angles, DVec3::ZERO)
    };
    let spin = m.angular_velocity.map_or(DVec3::ZERO, |w| DVec3::from_array(w.map(f64::to_radians)));
    Turn { spin, rotation }
}

/// Pins the particles at `positions` inside `pin_box`, if any.
fn pin_inside(pin_box: &Option<super::PinBox>, positions: &[DVec3], pinned: &mut [bool]) {
    if let Some(b) = pin_box {
        for (p, x) in pinned.iter_mut().zip(positions) {
            *p |= b.contains(*x);
        }
    }
}

/// A mesh cloth's model: its file's vertices welded and placed, its springs and triangles
/// (`sim::cloth_mesh`). The error says what is wrong with the mesh or the pins.
pub(super) fn mesh_cloth(c: &super::MeshCloth) -> Result<ObjectModel, String> {
    let file = c.loaded.as_ref().ok_or("its file is not read")?;
    for (k, seam) in c.seams.iter().enumerate() {
        if seam.from.len() != seam.to.len() || seam.from.is_empty() {
            return Err(format!(
                "seam[{k}]: from has {} vertices and to {}: a seam pairs as many, at least one",
                seam.from.len(),
                seam.to.len()
            ));
        }
    }
    let placed = file.built(c)?;
    let (positions, mesh) = (placed.0.clone(), placed.1.clone());
    let n = positions.len();
    let mut pinned = vec![false; n];
    for (k, &i) in c.pinned.iter().enumerate() {
        *pinned.get_mut(i as usize).ok_or(format!("pinned[{k}] = {i}: past its {n} vertices"))? = true;
    }
    pin_inside(&c.pin_box, &positions, &mut pinned);
    let own_motion = pin_motion(&c.pin_motion, &positions, &pinned);
    let (pin_group, pin_groups) =
        groups(&c.pin_groups, |&i| (i < n as u32).then_some(i as usize), &positions, &mut pinned);
    Ok(ObjectModel {
        kind: ObjectKind::Cloth,
        name: c.name.clone(),
        dims: [n as u32, 1],
        // (what a grid's spacing bounds: a shear diagonal, sqrt 2 spacings, is its longest
        // edge; `collide_edges` reaches that far)
        spacing: [mesh.longest / std::f64::consts::SQRT_2; 2],
        stiffness: c.stiffness.to_array(),
        rest_scale: c.rest_scale.to_array(),
        seam: c.seam_stiffness,
        damping: c.damping,
        mass: c.density * mesh.area / n as f64,
        drag: c.drag,
        friction: c.friction,
        margin: c.collision_margin,
        stretch_limit: c.stretch_limit,
        self_distance: c.self_collision.then(|| c.self_collision_distance.unwrap_or(0.5 * mesh.mean_edge)),
        triangle_contact: true,
        edge_contact: false,
        rope_radius: 0.0,
        ring_weights: default_ring_weights(),
        velocities: vec![DVec3::ZERO; n],
        pin_motion: own_motion,
        pin_groups,
        pin_group,
        positions,
        pinned,
        mesh: Some(mesh),
    })
}

pub(super) fn rope(r: &Rope) -> ObjectModel {
    let n = r.nodes as usize;
    let (start, end) = (DVec3::from_array(r.start), DVec3::from_array(r.end));
    let segment = start.distance(end) / (n - 1) as f64;
    let positions: Vec<DVec3> = (0..n).map(|i| start.lerp(end, i as f64 / (n - 1) as f64)).collect();
    let mut pinned: Vec<bool> = (0..n)
        .map(|i| match r.pin {
            RopePins::None => false,
            RopePins::First => i == 0,
            RopePins::Last => i == n - 1,
            RopePins::Both => i == 0 || i == n - 1,
        })
        .collect();
    for &p in &r.pinned {
        pinned[p as usize] = true;
    }
    pin_inside(&r.pin_box, &positions, &mut pinned);
    let own_motion = pin_motion(&r.pin_motion, &positions, &pinned);
    let (pin_group, pin_groups) =
        groups(&r.pin_groups, |&p| (p < r.nodes).then_some(p as usize), &positions, &mut pinned);
    let mut ring_weights = default_ring_weights();
    if let Some(w) = &r.ring_weights {
        for (dst, src) in ring_weights.iter_mut().zip(w) {
            *dst = *src;
        }
    }
    ObjectModel {
        kind: ObjectKind::Rope,
        name: r.name.clone(),
        dims: [r.nodes, 1],
        spacing: [segment, segment],
        stiffness: r.stiffness_array(),
        rest_scale: [r.rest_scale, 1.0, r.rest_scale],
        seam: 0.0,
        damping: r.damping,
        mass: r.mass,
        drag: r.drag,
        friction: r.friction,
        margin: r.radius,
        stretch_limit: r.stretch_limit,
        self_distance: r.self_collision.then(|| r.self_collision_distance.unwrap_or(2.0 * r.radius)),
        // (its segments against its segments, as capsules: ObjectModel::has_segment_pairs; its
        // edge pairs follow from that, has_edge_pairs)
        triangle_contact: true,
        edge_contact: false,
        rope_radius: r.radius,
        ring_weights,
        velocities: vec![DVec3::ZERO; n],
        pin_motion: own_motion,
        pin_groups,
        pin_group,
        positions,
        pinned,
        mesh: None,
    }
}
