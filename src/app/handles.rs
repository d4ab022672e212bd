//! Translate handles in the viewport: when a sphere, box, capsule, the wind or the light is
//! selected in the editor, three arrows (x red, y green, z blue) stand at its position; a
//! left-drag on an arrow moves it along that axis, live, through the same path as an edit in
//! the Scene panel (a moving collider drags what it touches).

use crate::render::camera::OrbitCamera;
use crate::render::{DrawItem, Shape};
use crate::scene::Scene;
use crate::ui::Selection;
use glam::{Mat4, Quat, Vec2, Vec3, Vec4};

/// How near the cursor must come to an arrow to take it [pixels].
pub const HANDLE_PIXELS: f32 = 10.0;
/// An arrow's length as a fraction of the camera's distance to it (a constant size on screen).
const LENGTH: f32 = 0.15;
const AXES: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];
const COLOURS: [[f32; 3]; 3] = [[0.9, 0.25, 0.2], [0.3, 0.8, 0.3], [0.25, 0.45, 0.95]];

/// An arrow being dragged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drag {
    pub target: Selection,
    pub axis: usize,
    /// The target's position when the drag began.
    pub start: Vec3,
    /// Where along the axis (from `start`) the cursor's ray passed then [m].
    pub grip: f32,
    /// The farthest one drag moves the target: 4 times its distance from the eye then [m].
    pub reach: f32,
}

/// The position of a selection that has handles: a sphere's or box's centre, a capsule's
/// midpoint, the wind cone's apex, the light.
pub fn position(scene: &Scene, target: Selection) -> Option<Vec3> {
    let v = |p: [f64; 3]| Vec3::from_array(p.map(|x| x as f32));
    match target {
        Selection::Sphere(i) => scene.spheres.get(i).map(|s| v(s.center)),
        Selection::Box(i) => scene.boxes.get(i).map(|b| v(b.center)),
        Selection::Capsule(i) => scene.capsules.get(i).map(|c| (v(c.start) + v(c.end)) * 0.5),
        Selection::Mesh(i) => scene.meshes.get(i).map(|m| v(m.center)),
        Selection::Wind => Some(v(scene.wind.origin)),
        Selection::Light => Some(v(scene.light.position)),
        _ => None,
    }
}

/// The selection naming each of `scene::colliders`, in its order: the ground, then the
/// spheres, boxes, capsules and meshes (those whose file was read).
fn collider_selections(scene: &Scene) -> impl Iterator<Item = Selection> + '_ {
    let ground = scene.ground.is_some().then_some(Selection::Ground).into_iter();
    let spheres = (0..scene.spheres.len()).map(Selection::Sphere);
    let boxes = (0..scene.boxes.len()).map(Selection::Box);
    let capsules = (0..scene.capsules.len()).map(Selection::Capsule);
    let meshes = (0..scene.meshes.len()).filter(|&i| scene.meshes[i].loaded.is_some()).map(Selection::Mesh);
    ground.chain(spheres).chain(boxes).chain(capsules).chain(meshes)
}

/// The index of the collider a selection names among `scene::colliders`, for its tint in the
/// view.
pub fn collider_index(scene: &Scene, target: Selection) -> Option<usize> {
    collider_selections(scene).position(|s| s == target)
}

/// The sphere, box, capsule or mesh that the ray from `origin` along the unit vector `dir`
/// meets first, where they are at `time`, and how far along the ray [m]; found by sphere
/// tracing their signed distances (each a lower bound of the distance to the surface, a
/// mesh's far from its triangles too, so the march never passes it). Not the ground,
/// on which a click orbits the camera, nor one the eye is inside.
pub fn pick_collider(scene: &Scene, time: f64, origin: Vec3, dir: Vec3) -> Option<(Selection, f32)> {
    const STEPS: usize = 256;
    const FAR: f64 = 1e4;
    let (o, d) = (origin.as_dvec3(), dir.as_dvec3());
    let mut best: Option<(Selection, f32)> = None;
    let colliders = collider_selections(scene).zip(crate::scene::colliders(scene));
    for (target, c) in colliders.filter(|(s, _)| *s != Selection::Ground) {
        let shape = c.shape_at(time);
        let mut s = 0.0;
        let mut hit = None;
        for _ in 0..STEPS {
            let (dist, _) = shape.distance(o + d * s);
            if dist < 1e-5 * (1.0 + s) {
                hit = (s > 0.0).then_some(s);
                break;
            }
            s += dist;
            if s > FAR {
                break;
            }
        }
        let Some(s) = hit else { continue };
        if best.is_none_or(|(_, b)| (s as f32) < b) {
            best = Some((target, s as f32));
        }
    }
    best
}

/// Moves `target` so that its position is `to`.
pub fn set_position(scene: &mut Scene, target: Selection, to: Vec3) {
    let Some(from) = position(scene, target) else { return };
    // Each coordinate kept as the shortest decimal of its f32 (the handle's precision), so a
    // saved preset reads 0.35, not 0.3499999940395355.
    let shift = |p: &mut [f64; 3]| {
        let d = to - from;
        let shortest = |x: f64| crate::ui::shown(x as f32);
        *p = [shortest(p[0] + d.x as f64), shortest(p[1] + d.y as f64), shortest(p[2] + d.z as f64)];
    };
    match target {
        Selection::Sphere(i) => shift(&mut scene.spheres[i].center),
        Selection::Box(i) => shift(&mut scene.boxes[i].center),
        Selection::Mesh(i) => shift(&mut scene.meshes[i].center),
        Selection::Capsule(i) => {
            shift(&mut scene.capsules[i].start);
            shift(&mut scene.capsules[i].end);
        }
        Selection::Wind => shift(&mut scene.wind.origin),
        Selection::Light => shift(&mut scene.light.position),
        _ => {}
    }
}

fn length(camera: &OrbitCamera, at: Vec3) -> f32 {
    (camera.eye() - at).length().max(0.05) * LENGTH
}

/// The arrows at `at` (`active`: the one being dragged, drawn highlighted).
pub fn items(camera: &OrbitCamera, at: Vec3, active: Option<usize>) -> Vec<DrawItem> {
    let l = length(camera, at);
    let mut items = Vec::new();
    for (k, axis) in AXES.into_iter().enumerate() {
        let colour = if active == Some(k) { [1.0, 0.85, 0.1] } else { COLOURS[k] };
        let turn = Quat::from_rotation_arc(Vec3::Z, axis);
        let shaft = Mat4::from_scale_rotation_translation(
            Vec3::new(0.012 * l, 0.012 * l, 0.4 * l),
            turn,
            at + axis * 0.4 * l,
        );
        // The cone's apex is at its origin and it opens along +z: turned to -axis at the tip.
        let head = Mat4::from_scale_rotation_translation(
            Vec3::new(0.06 * l, 0.06 * l, 0.2 * l),
            Quat::from_rotation_arc(Vec3::Z, -axis),
            at + axis * l,
        );
        items.push(DrawItem::solid(Shape::Tube, shaft, colour, false));
        items.push(DrawItem::solid(Shape::Cone, head, colour, false));
    }
    items
}

/// Where world point `p` appears in a view of `size` pixels, or `None` behind the camera.
fn to_screen(camera: &OrbitCamera, size: [f32; 2], p: Vec3) -> Option<Vec2> {
    let clip = camera.view_proj(size[0] / size[1].max(1.0)) * Vec4::new(p.x, p.y, p.z, 1.0);
    (clip.w > 1e-6)
        .then(|| Vec2::new((clip.x / clip.w + 1.0) * 0.5 * size[0], (clip.y / clip.w + 1.0) * 0.5 * size[1]))
}

/// Where the tip of arrow `axis` of the handles at `at` appears on screen [pixels].
pub fn screen_tip(camera: &OrbitCamera, size: [f32; 2], at: Vec3, axis: usize) -> Option<[f32; 2]> {
    to_screen(camera, size, at + AXES[axis] * length(camera, at)).map(|p| p.to_array())
}

/// The arrow of the handles at `at` under `cursor` (within `HANDLE_PIXELS`), the nearest one.
pub fn hit(camera: &OrbitCamera, size: [f32; 2], cursor: [f32; 2], at: Vec3) -> Option<usize> {
    let l = length(camera, at);
    let c = Vec2::from_array(cursor);
    let mut best: Option<(f32, usize)> = None;
    for (k, axis) in AXES.into_iter().enumerate() {
        let (Some(a), Some(b)) = (to_screen(camera, size, at), to_screen(camera, size, at + axis * l)) else {
            continue;
        };
        let ab = b - a;
        let t = ((c - a).dot(ab) / ab.length_squared().max(1e-6)).clamp(0.0, 1.0);
        let miss = (a + ab * t - c).length();
        if miss < HANDLE_PIXELS && best.is_none_or(|(m, _)| miss < m) {
            best = Some((miss, k));
        }
    }
    best.map(|(_, k)| k)
}

/// Where along the line (`origin`, unit `axis`) the ray (`from`, unit `dir`) passes nearest,
/// as a distance from `origin`; `None` when the ray runs within about 2.5 degrees of the line
/// (the point would jump by metres for a pixel) or the nearest point is behind the eye.
pub fn along(origin: Vec3, axis: Vec3, from: Vec3, dir: Vec3) -> Option<f32> {
    let w = origin - from;
    let b = axis.dot(dir);
    let denom = 1.0 - b * b;
    if denom < 2e-3 {
        return None;
    }
    let s = (b * dir.dot(w) - axis.dot(w)) / denom;
    let ray = (dir.dot(w) - b * axis.dot(w)) / denom; // the ray's own parameter there
    (ray > 0.0).then_some(s)
}

impl Drag {
    /// A drag of `axis` of the handles of `target` at `start`, taken where the cursor's ray
    /// (`from`, `dir`) passes.
    pub fn begin(target: Selection, axis: usize, start: Vec3, from: Vec3, dir: Vec3) -> Self {
        let grip = along(start, AXES[axis], from, dir).unwrap_or(0.0);
        Self { target, axis, start, grip, reach: 4.0 * (start - from).length() }
    }

    /// The target's position for the cursor's ray (`from`, `dir`) now; `None` (stay where it
    /// is) while the ray runs along the axis or points away from it.
    pub fn position(&self, from: Vec3, dir: Vec3) -> Option<Vec3> {
        let axis = AXES[self.axis];
        along(self.start, axis, from, dir)
            .map(|s| self.start + axis * (s - self.grip).clamp(-self.reach, self.reach))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The arrow under the cursor is found in screen space, and dragging it 80 pixels to the
    /// right moves a target along x only, by the distance those pixels span at its depth.
    #[test]
    fn dragging_the_x_arrow_moves_along_x() {
        let camera = OrbitCamera { yaw: 0.0, pitch: 0.0, ..Default::default() };
        let size = [800.0, 600.0];
        let at = camera.target;
        let tip = to_screen(&camera, size, at + Vec3::X * length(&camera, at)).unwrap();
        let grab = [tip.x - 5.0, tip.y + 3.0];
        assert_eq!(hit(&camera, size, grab, at), Some(0));
        assert_eq!(hit(&camera, size, [tip.x, tip.y + 40.0], at), None, "40 pixels off misses");
        let (from, dir) = camera.ray(grab, size);
        let drag = Drag::begin(Selection::Light, 0, at, from, dir);
        let (from, dir) = camera.ray([grab[0] + 80.0, grab[1]], size);
        let moved = drag.position(from, dir).expect("across the axis") - at;
        let expected = 80.0 * camera.pixel_size(size[1]) * camera.distance;
        assert!((moved.x - expected).abs() < 0.02 * expected, "{moved} against {expected}");
        assert!(moved.y.abs() < 1e-5 && moved.z.abs() < 1e-5, "{moved}");
    }

    /// Looking along an axis, its arrow does not move the target (it would jump by metres a
    /// pixel), and a drag never carries it past 4 times its distance from the eye.
    #[test]
    fn a_drag_along_the_view_or_too_far_is_refused_or_bounded() {
        let start = Vec3::ZERO;
        let eye = Vec3::new(0.0, 0.0, 5.0);
        let drag = Drag::begin(Selection::Light, 2, start, eye, Vec3::new(0.0, 0.3, -1.0).normalize());
        assert!(drag.position(eye, Vec3::NEG_Z).is_none(), "looking down the z axis");
        let x = Drag::begin(Selection::Light, 0, start, eye, Vec3::NEG_Z);
        let nearly_parallel = Vec3::new(1.0, 0.0, -0.06).normalize();
        let p = x.position(eye, nearly_parallel).expect("3.4 degrees off the axis");
        assert!(p.x <= x.reach + 1e-4 && x.reach <= 20.0 + 1e-4, "{p} beyond the reach {}", x.reach);
    }

    #[test]
    fn a_capsule_moves_whole() {
        let mut scene = Scene::default();
        scene.capsules.push(crate::scene::Capsule {
            start: [0.0, 0.0, 0.0],
            end: [1.0, 0.0, 0.0],
            radius: 0.1,
            motion: None,
        });
        set_position(&mut scene, Selection::Capsule(0), Vec3::new(0.5, 1.0, 0.0));
        assert_eq!(scene.capsules[0].start, [0.0, 1.0, 0.0]);
        assert_eq!(scene.capsules[0].end, [1.0, 1.0, 0.0]);
    }

    /// A click picks the collider its ray meets first, where it is at that time, against the
    /// closed form of a ray and a sphere (or a box's face); the ground never.
    #[test]
    fn a_click_picks_the_nearest_collider() {
        use crate::scene::{BoxCollider, Capsule, Ground, Motion, Sphere};
        let mut scene = Scene { ground: Some(Ground { height: 0.0, friction: None }), ..Default::default() };
        scene.spheres.push(Sphere { center: [0.0, 0.5, 0.0], radius: 0.2, motion: None });
        let moving = Motion { velocity: Some([1.0, 0.0, 0.0]), ..Default::default() };
        scene.spheres.push(Sphere { center: [-3.0, 0.5, 0.0], radius: 0.1, motion: Some(moving) });
        scene.boxes.push(BoxCollider {
            center: [2.0, 0.5, 0.0],
            half_extents: [0.3, 0.3, 0.3],
            rotation: [0.0; 3],
            motion: None,
        });
        scene.capsules.push(Capsule {
            start: [4.0, 0.2, 0.0],
            end: [4.0, 0.8, 0.0],
            radius: 0.1,
            motion: None,
        });
        let near = |a: f32, b: f32| (a - b).abs() < 1e-4;
        let toward = |x: f32| pick_collider(&scene, 0.0, Vec3::new(x, 0.5, 5.0), Vec3::NEG_Z);
        let (sel, t) = toward(0.0).unwrap();
        assert!(sel == Selection::Sphere(0) && near(t, 4.8), "{sel:?} at {t}");
        let (sel, t) = toward(2.0).unwrap();
        assert!(sel == Selection::Box(0) && near(t, 4.7), "{sel:?} at {t}");
        let (sel, t) = toward(4.0).unwrap();
        assert!(sel == Selection::Capsule(0) && near(t, 4.9), "{sel:?} at {t}");
        // Off-centre by 0.12 m: a chord of the sphere, depth 5 - sqrt(0.2^2 - 0.12^2) = 4.84.
        let (sel, t) = toward(0.12).unwrap();
        assert!(sel == Selection::Sphere(0) && near(t, 4.84), "{sel:?} at {t}");
        assert_eq!(toward(1.0), None, "between them the ray meets only the ground");
        // Along x the sphere comes before the box.
        let (sel, t) = pick_collider(&scene, 0.0, Vec3::new(-1.0, 0.5, 0.0), Vec3::X).unwrap();
        assert!(sel == Selection::Sphere(0) && near(t, 0.8), "{sel:?} at {t}");
        // The moving sphere is at x = -1 after 2 s.
        let (sel, _) = pick_collider(&scene, 2.0, Vec3::new(-1.0, 0.5, 5.0), Vec3::NEG_Z).unwrap();
        assert_eq!(sel, Selection::Sphere(1));
        assert_eq!(pick_collider(&scene, 0.0, Vec3::new(-1.0, 0.5, 5.0), Vec3::NEG_Z), None);
        assert_eq!(collider_index(&scene, Selection::Box(0)), Some(3));
        assert_eq!(collider_index(&scene, Selection::Capsule(0)), Some(4));
        assert_eq!(collider_index(&scene, Selection::Cloth(0)), None);
        // Without a ground the indices start at the spheres.
        scene.ground = None;
        assert_eq!(
            pick_collider(&scene, 0.0, Vec3::new(2.0, 0.5, 5.0), Vec3::NEG_Z).map(|h| h.0),
            Some(Selection::Box(0))
        );
        assert_eq!(collider_index(&scene, Selection::Sphere(0)), Some(0));
        assert_eq!(collider_index(&scene, Selection::Ground), None);
    }

    /// A dragged position keeps the shortest decimal of its f32 (what the preset then saves),
    /// not the f32's binary tail.
    #[test]
    fn a_drag_saves_short_decimals() {
        let mut scene = Scene::default();
        scene.spheres.push(crate::scene::Sphere { center: [0.0, 0.5, 0.0], radius: 0.2, motion: None });
        set_position(&mut scene, Selection::Sphere(0), Vec3::new(0.1, 0.35, -0.7));
        assert_eq!(scene.spheres[0].center, [0.1, 0.35, -0.7]);
    }
}
