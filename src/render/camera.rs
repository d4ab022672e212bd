//! An orbit camera: it looks at `target` from `distance` along a direction given by yaw and
//! pitch. Dragging orbits (the eye kept above the ground), shift-dragging pans, the wheel zooms
//! towards the cursor, WASD/QE fly the target.

use glam::{Mat4, Vec2, Vec3, Vec4};

/// How far above the ground an orbit keeps the eye [m].
pub const EYE_CLEARANCE: f32 = 0.02;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    pub target: Vec3,
    /// Radians around +y.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    /// Metres from the target.
    pub distance: f32,
    /// Vertical field of view, radians.
    pub fov: f32,
    /// Where the target appears, in normalised device coordinates (0, 0: the middle of the
    /// view): a lens shift, so a fit can frame the scene in the part of the window that panels
    /// leave free and orbiting still turns about the scene.
    pub shift: Vec2,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        Self {
            target: Vec3::new(0.0, 1.0, 0.0),
            yaw: 0.35,
            pitch: 0.25,
            distance: 4.5,
            fov: 45f32.to_radians(),
            shift: Vec2::ZERO,
        }
    }
}

impl OrbitCamera {
    /// Unit vector from the target to the eye.
    fn back(&self) -> Vec3 {
        Vec3::new(self.pitch.cos() * self.yaw.sin(), self.pitch.sin(), self.pitch.cos() * self.yaw.cos())
    }

    pub fn eye(&self) -> Vec3 {
        self.target + self.back() * self.distance
    }

    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Y)
    }

    /// Projection for Vulkan clip space (y down, depth 0..1).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        glam::camera::rh::proj::vulkan::perspective(self.fov, aspect.max(1e-3), 0.02, 200.0)
    }

    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        Mat4::from_translation(self.shift.extend(0.0)) * self.projection(aspect) * self.view()
    }

    /// Orbits by a drag of (dx, dy) pixels; with a `floor` (the ground's height) the eye stays
    /// above it.
    pub fn orbit(&mut self, dx: f32, dy: f32, floor: Option<f32>) {
        self.yaw -= dx * 0.008;
        self.pitch = (self.pitch + dy * 0.008).clamp(-1.55, 1.55);
        if let Some(floor) = floor {
            self.keep_above(floor);
        }
    }

    /// Raises the pitch, if it must, so that the eye is `EYE_CLEARANCE` above height `floor`.
    pub fn keep_above(&mut self, floor: f32) {
        let lowest = ((floor + EYE_CLEARANCE - self.target.y) / self.distance).clamp(-1.0, 1.0).asin();
        self.pitch = self.pitch.max(lowest.min(1.55));
    }

    /// Pans by a drag of (dx, dy) pixels, moving the target in the view plane.
    pub fn pan(&mut self, dx: f32, dy: f32) {
        let right = self.back().cross(Vec3::Y).normalize_or_zero();
        let up = right.cross(self.back()).normalize_or_zero();
        let scale = self.distance * 0.0015;
        self.target += (right * dx - up * dy) * scale;
    }

    /// Zooms by wheel `steps` (positive: closer) towards the target.
    pub fn zoom(&mut self, steps: f32) {
        self.distance = (self.distance * 0.9f32.powf(steps)).clamp(0.05, 500.0);
    }

    /// Zooms by wheel `steps` towards what is under `pixel` of a view of `size` pixels: the
    /// point of the target's depth under the cursor stays under it (the eye moves along the
    /// line from it; the view keeps its direction).
    /// With a `floor`, the eye stays above it.
    pub fn zoom_at(&mut self, steps: f32, pixel: [f32; 2], size: [f32; 2], floor: Option<f32>) {
        let (origin, dir) = self.ray(pixel, size);
        let before = self.distance;
        self.zoom(steps);
        let factor = self.distance / before;
        let normal = self.back();
        let facing = dir.dot(normal);
        if facing.abs() < 1e-6 {
            return;
        }
        let under = origin + dir * ((self.target - origin).dot(normal) / facing);
        if under.is_finite() {
            self.target = under + (self.target - under) * factor;
        }
        if let Some(floor) = floor {
            self.keep_above(floor);
        }
    }

    /// Moves the target along the view: `forward`, `right`, `up` in -1..1, for `dt` seconds.
    pub fn fly(&mut self, forward: f32, right: f32, up: f32, dt: f32) {
        let ahead = -Vec3::new(self.back().x, 0.0, self.back().z).normalize_or_zero();
        let side = ahead.cross(Vec3::Y);
        let speed = self.distance.max(0.5) * 0.8;
        self.target += (ahead * forward + side * right + Vec3::Y * up) * speed * dt;
    }

    /// Frames the box [min, max] from the current direction in the whole view.
    pub fn fit(&mut self, min: Vec3, max: Vec3) {
        self.fit_in(min, max, [0.0, 0.0, 1.0, 1.0], [1.0, 1.0]);
    }

    /// Frames the box [min, max] from the current direction within the rectangle `free`
    /// (x0, y0, x1, y1 in pixels) of a view of `size` pixels: the box's bounding sphere fits the
    /// rectangle's narrower angle and its centre appears at the rectangle's centre.
    pub fn fit_in(&mut self, min: Vec3, max: Vec3, free: [f32; 4], size: [f32; 2]) {
        let [w, h] = size.map(|s| s.max(1.0));
        let [x0, y0, x1, y1] =
            [free[0].clamp(0.0, w), free[1].clamp(0.0, h), free[2].clamp(0.0, w), free[3].clamp(0.0, h)];
        let (x1, y1) = (x1.max(x0 + 1.0), y1.max(y0 + 1.0));
        self.target = (min + max) * 0.5;
        self.shift = Vec2::new((x0 + x1) / w - 1.0, (y0 + y1) / h - 1.0);
        let tan = (self.fov * 0.5).tan();
        let half_angle = (tan * (y1 - y0) / h).atan().min((tan * (w / h) * (x1 - x0) / w).atan());
        let radius = ((max - min).length() * 0.5).max(0.1);
        self.distance = radius / half_angle.sin() * 1.1;
    }

    /// The size of one pixel at one metre in front of the camera, for a view `height` pixels
    /// high [m].
    pub fn pixel_size(&self, height: f32) -> f32 {
        2.0 * (self.fov * 0.5).tan() / height.max(1.0)
    }

    /// The world-space ray through a pixel: (origin, unit direction).
    pub fn ray(&self, pixel: [f32; 2], size: [f32; 2]) -> (Vec3, Vec3) {
        let ndc = [2.0 * pixel[0] / size[0].max(1.0) - 1.0, 2.0 * pixel[1] / size[1].max(1.0) - 1.0];
        let inverse = self.view_proj(size[0] / size[1].max(1.0)).inverse();
        let near = inverse * Vec4::new(ndc[0], ndc[1], 0.0, 1.0);
        let far = inverse * Vec4::new(ndc[0], ndc[1], 1.0, 1.0);
        let (near, far) = (near.truncate() / near.w, far.truncate() / far.w);
        (near, (far - near).normalize_or_zero())
    }
}

/// The largest rectangle of a view of `size` pixels that none of the `covered` rectangles
/// (x, y, width, height in pixels: the panels over the view) overlaps, as (x0, y0, x1, y1):
/// "largest" by its narrower side, which bounds how large a fitted scene appears, then by its
/// area. The whole view when nothing covers it, or when what is left is under a fifth of it
/// either way (a panel over most of a small window: fitting to the sliver would help nobody).
pub fn free_rect(size: [f32; 2], covered: &[[f32; 4]]) -> [f32; 4] {
    let [w, h] = size;
    let boxes: Vec<[f32; 4]> = covered
        .iter()
        .map(|&[x, y, cw, ch]| [x.max(0.0), y.max(0.0), (x + cw).min(w), (y + ch).min(h)])
        .filter(|b| b[0] < b[2] && b[1] < b[3])
        .collect();
    let mut xs0 = vec![0.0];
    let mut xs1 = vec![w];
    let mut ys0 = vec![0.0];
    let mut ys1 = vec![h];
    for b in &boxes {
        xs0.push(b[2]);
        xs1.push(b[0]);
        ys0.push(b[3]);
        ys1.push(b[1]);
    }
    let overlaps =
        |r: [f32; 4]| boxes.iter().any(|b| r[0] < b[2] && b[0] < r[2] && r[1] < b[3] && b[1] < r[3]);
    let score = |r: [f32; 4]| ((r[2] - r[0]).min(r[3] - r[1]), (r[2] - r[0]) * (r[3] - r[1]));
    let mut best: Option<[f32; 4]> = None;
    for &x0 in &xs0 {
        for &x1 in xs1.iter().filter(|&&x1| x1 > x0) {
            for &y0 in &ys0 {
                for &y1 in ys1.iter().filter(|&&y1| y1 > y0) {
                    let r = [x0, y0, x1, y1];
                    if !overlaps(r) && best.is_none_or(|b| score(r) > score(b)) {
                        best = Some(r);
                    }
                }
            }
        }
    }
    match best {
        Some(r) if r[2] - r[0] >= 0.2 * w && r[3] - r[1] >= 0.2 * h => r,
        _ => [0.0, 0.0, w, h],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ray_through_the_centre_hits_the_target() {
        let cam = OrbitCamera::default();
        let (origin, dir) = cam.ray([400.0, 300.0], [800.0, 600.0]);
        let to_target = cam.target - origin;
        assert!(to_target.cross(dir).length() < 1e-3 * to_target.length(), "{origin} {dir}");
        assert!(to_target.dot(dir) > 0.0);
    }

    /// Fitting into the right part of the view (a panel on the left) puts the scene's centre
    /// in the middle of that part, keeps the whole box inside it, and picking rays agree.
    #[test]
    fn a_fit_beside_a_panel_frames_the_box_in_the_free_part() {
        let mut cam = OrbitCamera::default();
        let (min, max) = (Vec3::new(-1.0, 0.0, -0.5), Vec3::new(1.0, 2.0, 0.5));
        let size = [1200.0, 800.0];
        cam.fit_in(min, max, [400.0, 0.0, 1200.0, 800.0], size);
        let project = |p: Vec3| {
            let c = cam.view_proj(size[0] / size[1]) * p.extend(1.0);
            [(c.x / c.w + 1.0) * 0.5 * size[0], (c.y / c.w + 1.0) * 0.5 * size[1]]
        };
        let centre = project((min + max) * 0.5);
        assert!((centre[0] - 800.0).abs() < 1.0 && (centre[1] - 400.0).abs() < 1.0, "{centre:?}");
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            );
            let [x, y] = project(corner);
            assert!((400.0..=1200.0).contains(&x) && (0.0..=800.0).contains(&y), "corner {i} at {x}, {y}");
        }
        let (origin, dir) = cam.ray(centre, size);
        let to_centre = (min + max) * 0.5 - origin;
        assert!(to_centre.cross(dir).length() < 1e-3 * to_centre.length(), "the ray through the centre");
    }

    /// The point under the cursor stays under it through a zoom (issue 28, item 9: the wheel
    /// zoomed to the orbit centre), also with a lens shift.
    #[test]
    fn zoom_keeps_the_point_under_the_cursor() {
        let mut c = OrbitCamera { shift: Vec2::new(0.2, -0.1), ..OrbitCamera::default() };
        let size = [800.0, 600.0];
        let pixel = [620.0, 140.0];
        let (o, d) = c.ray(pixel, size);
        let n = c.back();
        let under = o + d * ((c.target - o).dot(n) / d.dot(n));
        for steps in [3.0, -2.0, 5.0] {
            c.zoom_at(steps, pixel, size, None);
            let (o2, d2) = c.ray(pixel, size);
            let off = (under - o2) - d2 * (under - o2).dot(d2);
            assert!(off.length() < 1e-4 * c.distance.max(1.0), "{steps}: {off:?} off the cursor's ray");
        }
    }

    /// Orbiting down keeps the eye above the ground, from any target height and distance.
    #[test]
    fn orbit_keeps_the_eye_above_the_ground() {
        for (target_y, distance) in [(1.0, 4.5), (0.05, 10.0), (0.0, 0.5), (-0.3, 2.0)] {
            let mut c =
                OrbitCamera { target: Vec3::new(0.0, target_y, 0.0), distance, ..OrbitCamera::default() };
            for _ in 0..200 {
                c.orbit(3.0, -20.0, Some(0.0));
                assert!(c.eye().y >= EYE_CLEARANCE - 1e-5, "{target_y} {distance}: eye at {}", c.eye().y);
            }
            c.orbit(0.0, -400.0, None);
            assert!(c.pitch < -1.5, "without a floor (Alt held) the orbit goes below: {}", c.pitch);
        }
    }

    #[test]
    fn a_point_above_the_target_projects_above_the_centre() {
        let cam = OrbitCamera::default();
        let clip = cam.view_proj(1.0) * (cam.target + Vec3::Y * 0.1).extend(1.0);
        assert!(clip.y / clip.w < 0.0, "Vulkan clip space has y down");
    }

    /// The free part beside the Scene panel (left) and under the Stats window (top right) is
    /// the larger of the strip between them and the part under Stats; a panel over nearly all
    /// of the view leaves the whole view.
    #[test]
    fn the_free_rectangle_avoids_every_panel() {
        let scene = [10.0, 10.0, 360.0, 620.0];
        assert_eq!(free_rect([1280.0, 720.0], &[scene]), [370.0, 0.0, 1280.0, 720.0]);
        let stats = [940.0, 10.0, 330.0, 200.0];
        // Between them: 570 x 720; under Stats: 910 x 510. The narrower sides: 570 and 510.
        assert_eq!(free_rect([1280.0, 720.0], &[scene, stats]), [370.0, 0.0, 940.0, 720.0]);
        let tall_stats = [940.0, 10.0, 330.0, 600.0];
        assert_eq!(free_rect([1280.0, 720.0], &[scene, tall_stats]), [370.0, 0.0, 940.0, 720.0]);
        let wide_stats = [380.0, 10.0, 890.0, 150.0];
        assert_eq!(free_rect([1280.0, 720.0], &[scene, wide_stats]), [370.0, 160.0, 1280.0, 720.0]);
        assert_eq!(free_rect([400.0, 300.0], &[[0.0, 0.0, 380.0, 300.0]]), [0.0, 0.0, 400.0, 300.0]);
        assert_eq!(free_rect([800.0, 600.0], &[]), [0.0, 0.0, 800.0, 600.0]);
    }
}
