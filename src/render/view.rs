//! What the app draws of a scene, shared by the window and the offscreen end-to-end benchmark:
//! the draw list (surfaces, colliders, light, wind), the camera uniform and the bounds the
//! camera is fitted to.

use super::camera::OrbitCamera;
use super::{DrawItem, Shape};
use crate::scene::{self, Scene};
use crate::sim::collider;
use crate::sim::gpu_types::Camera;
use crate::sim::model::SimModel;
use glam::{Mat4, Quat, Vec3};

/// The background colour.
pub const SKY: [f32; 4] = [0.09, 0.10, 0.12, 1.0];

/// The scene's draws at simulated time `time`: every object's surface, the colliders (where
/// they have moved to; the collider `tinted`, an index of `scene::colliders`, the selected one,
/// tinted as a selected surface is), the light and the wind cone.
pub fn scene_items(scene: &Scene, time: f64, tinted: Option<usize>) -> Vec<DrawItem> {
    let f = |c: [f64; 3]| c.map(|x| x as f32);
    let v = |c: [f64; 3]| Vec3::from_array(f(c));
    let placed =
        |scale: Vec3, rotation: Quat, at: Vec3| Mat4::from_scale_rotation_translation(scale, rotation, at);
    let mut items = Vec::new();
    for (i, c) in scene.cloths.iter().enumerate() {
        items.push(DrawItem {
            shape: Shape::Surface(i),
            model: Mat4::IDENTITY,
            front: f(c.color),
            back: f(c.back_color),
            lit: true,
        });
    }
    for (j, r) in scene.ropes.iter().enumerate() {
        items.push(DrawItem::solid(Shape::Surface(scene.cloths.len() + j), Mat4::IDENTITY, f(r.color), true));
    }
    let grids = scene.cloths.len() + scene.ropes.len();
    for (k, c) in scene.mesh_cloths.iter().enumerate() {
        let (front, back) = (f(c.color), f(c.back_color));
        items.push(DrawItem {
            shape: Shape::Surface(grids + k),
            model: Mat4::IDENTITY,
            front,
            back,
            lit: true,
        });
    }
    for (k, c) in scene::colliders(scene).iter().enumerate() {
        let mut shapes = collider_items(&c.shape_at(time));
        if tinted == Some(k) {
            shapes.iter_mut().for_each(|item| (item.front, item.back) = (tint(item.front), tint(item.back)));
        }
        items.extend(shapes);
    }
    let light = placed(Vec3::splat(0.06), Quat::IDENTITY, v(scene.light.position));
    items.push(DrawItem::solid(Shape::Sphere, light, [1.0, 0.9, 0.5], false));
    if scene.wind.enabled {
        let dir = v(scene.wind.direction).normalize_or(Vec3::Z);
        let (r, l) = (WIND_CONE_RADIUS, WIND_CONE_LENGTH);
        let model = placed(Vec3::new(r, r, l), Quat::from_rotation_arc(Vec3::Z, dir), v(scene.wind.origin));
        items.push(DrawItem::solid(Shape::Cone, model, [0.25, 0.45, 0.95], true));
        items.extend(gust_items(&scene.wind, time));
    }
    items
}

/// The turbulent wind's gusts at `time`: small cones across the wind cone at its reference
/// distance (its axis and a ring at half the full-strength radius), each along the air's
/// velocity there and as long as its speed against the mean's (none without turbulence).
fn gust_items(w: &scene::Wind, time: f64) -> Vec<DrawItem> {
    let Some(turbulence) = scene::turbulence_of(w) else { return Vec::new() };
    let axis = glam::DVec3::from_array(w.direction).normalize_or(glam::DVec3::Z);
    let (side, up) = axis.any_orthonormal_pair();
    let centre = glam::DVec3::from_array(w.origin) + axis * w.reference_distance;
    let ring = 0.5 * w.full_force_radius;
    let points = std::iter::once(centre).chain((0..GUST_RING).map(|k| {
        let a = std::f64::consts::TAU * k as f64 / GUST_RING as f64;
        centre + (side * a.cos() + up * a.sin()) * ring
    }));
    points
        .map(|p| {
            let u = (axis * w.speed + turbulence.velocity(p, time)).as_vec3();
            let length = WIND_CONE_LENGTH * 0.5 * u.length() / w.speed.max(1e-6) as f32;
            let turn = Quat::from_rotation_arc(Vec3::Z, u.normalize_or(Vec3::Z));
            let r = WIND_CONE_RADIUS * 0.25;
            let model = Mat4::from_scale_rotation_translation(Vec3::new(r, r, length), turn, p.as_vec3());
            DrawItem::solid(Shape::Cone, model, [0.45, 0.65, 1.0], true)
        })
        .collect()
}

/// Gust markers on the ring around the axis (`gust_items`).
const GUST_RING: usize = 8;

/// Surface `surface` (the selected cloth or rope) drawn tinted towards `SELECTED`, so the
/// object the panel edits is seen in the view (colliders, the wind and the light get arrows).
pub fn mark_selected(items: &mut [DrawItem], surface: usize) {
    for item in items.iter_mut().filter(|it| it.shape == Shape::Surface(surface)) {
        item.front = tint(item.front);
        item.back = tint(item.back);
    }
}

/// The colour a selected surface is tinted towards.
const SELECTED: [f32; 3] = [1.0, 0.9, 0.35];

/// A selected item's colour: `c` taken part of the way towards `SELECTED`.
fn tint(c: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|k| c[k] + (SELECTED[k] - c[k]) * 0.45)
}

/// A marker (a small unlit sphere) on every pinned particle at `at`, seen from `eye`: its size a
/// third of the finest grid spacing in the scene, between 4 mm and 2 cm, and at least
/// `PIN_SIGHT` of its distance from the eye, so that it stays a few pixels wide from afar.
pub fn pin_items(at: &[Vec3], model: &SimModel, eye: Vec3) -> Vec<DrawItem> {
    let spacing =
        (model.objects.iter()).flat_map(|o| o.spacing).filter(|s| *s > 0.0).fold(f64::INFINITY, f64::min);
    let radius = if spacing.is_finite() { (spacing as f32 / 3.0).clamp(0.004, 0.02) } else { 0.01 };
    at.iter()
        .map(|&p| {
            let r = radius.max(PIN_SIGHT * p.distance(eye));
            let model = Mat4::from_scale_rotation_translation(Vec3::splat(r), Quat::IDENTITY, p);
            DrawItem::solid(Shape::Sphere, model, PIN_COLOR, false)
        })
        .collect()
}

/// The pin markers' colour: a green no cloth, rope, collider or gizmo has by default, and no
/// selection tint makes (the cloths' red was the markers' own before, which hid them).
const PIN_COLOR: [f32; 3] = [0.2, 0.95, 0.35];
/// A pin marker's least radius per metre from the eye: about 3 pixels at the default view of an
/// 800-pixel-high window (a 2 cm marker 4 m away was about 1 pixel).
const PIN_SIGHT: f32 = 0.004;

/// The wind cone's base radius and length [m]: a gizmo at the wind's origin along its axis.
const WIND_CONE_RADIUS: f32 = 0.12;
const WIND_CONE_LENGTH: f32 = 0.35;

/// The colour colliders are drawn in.
const COLLIDER_COLOR: [f32; 3] = [0.45, 0.5, 0.58];

/// The draws of one collider (the ground is drawn as the grid, by `grid_height`): unit meshes
/// placed by their model matrices (recordings without shapes build their meshes from them).
pub(crate) fn collider_items(shape: &collider::Shape) -> Vec<DrawItem> {
    let v = |p: glam::DVec3| p.as_vec3();
    let solid = |shape, model| DrawItem::solid(shape, model, COLLIDER_COLOR, true);
    match *shape {
        collider::Shape::Sphere { center, radius } => {
            vec![solid(
                Shape::Sphere,
                Mat4::from_scale_rotation_translation(Vec3::splat(radius as f32), Quat::IDENTITY, v(center)),
            )]
        }
        collider::Shape::Ground { .. } => Vec::new(),
        collider::Shape::Box { center, half_extents, rotation } => vec![solid(
            Shape::Cube,
            Mat4::from_scale_rotation_translation(v(half_extents), rotation.as_quat(), v(center)),
        )],
        collider::Shape::Capsule { a, b, radius } => {
            let r = radius as f32;
            let axis = v(b - a);
            let turn = Quat::from_rotation_arc(Vec3::Z, axis.normalize_or(Vec3::Z));
            let side = Mat4::from_scale_rotation_translation(
                Vec3::new(r, r, axis.length() / 2.0),
                turn,
                v(a + b) / 2.0,
            );
            let cap = |p| Mat4::from_scale_rotation_translation(Vec3::splat(r), Quat::IDENTITY, v(p));
            vec![solid(Shape::Tube, side), solid(Shape::Sphere, cap(a)), solid(Shape::Sphere, cap(b))]
        }
        collider::Shape::Mesh { center, rotation, ref mesh, .. } => vec![solid(
            Shape::Mesh(super::scene_renderer::collider_mesh_key(mesh)),
            Mat4::from_rotation_translation(rotation.as_quat(), v(center)),
        )],
    }
}

/// The ground as drawn: its floor and grid, and the shadows the light casts on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    pub height: f32,
    /// The light is at least 5 cm above the ground (from lower, the projection degenerates).
    pub shadows: bool,
}

/// The scene's ground as drawn, where it has one.
pub fn ground(scene: &Scene) -> Option<Ground> {
    scene
        .ground
        .as_ref()
        .map(|g| Ground { height: g.height as f32, shadows: scene.light.position[1] > g.height + 0.05 })
}

/// The camera uniform for a view of `extent` pixels, lit by the scene's light.
pub fn camera_uniform(camera: &OrbitCamera, extent: [u32; 2], scene: &Scene) -> Camera {
    let light = &scene.light;
    Camera {
        view_proj: camera.view_proj(extent[0] as f32 / extent[1].max(1) as f32).to_cols_array_2d(),
        eye: camera.eye().extend(1.0).to_array(),
        light_pos: [light.position[0] as f32, light.position[1] as f32, light.position[2] as f32, 1.0],
        light_color: [
            light.color[0] as f32,
            light.color[1] as f32,
            light.color[2] as f32,
            light.ambient as f32,
        ],
    }
}

/// Fits `camera` to the model's particles and colliders in the whole view (unchanged for an
/// empty model).
pub fn fit_camera(camera: &mut OrbitCamera, model: &SimModel) {
    fit_camera_in(camera, model, [0.0, 0.0, 1.0, 1.0], [1.0, 1.0]);
}

/// Like `fit_camera`, within the rectangle `free` (x0, y0, x1, y1 pixels) of a view of `size`
/// pixels: the part that panels leave free. The wind cone counts as part of the scene.
pub fn fit_camera_in(camera: &mut OrbitCamera, model: &SimModel, free: [f32; 4], size: [f32; 2]) {
    let mut min = Vec3::splat(f32::MAX);
    let mut max = Vec3::splat(f32::MIN);
    for o in &model.objects {
        for p in &o.positions {
            min = min.min(p.as_vec3());
            max = max.max(p.as_vec3());
        }
    }
    for (lo, hi) in model.colliders.iter().filter_map(|c| c.shape.bounds()) {
        min = min.min(lo.as_vec3());
        max = max.max(hi.as_vec3());
    }
    if let Some(w) = &model.wind {
        let (origin, dir) = (w.origin.as_vec3(), w.direction.as_vec3());
        let base = origin + dir * WIND_CONE_LENGTH;
        min = min.min(origin).min(base - Vec3::splat(WIND_CONE_RADIUS));
        max = max.max(origin).max(base + Vec3::splat(WIND_CONE_RADIUS));
    }
    if min.x <= max.x {
        camera.fit_in(min, max, free, size);
    }
}
