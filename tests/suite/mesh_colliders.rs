//! Mesh colliders against physics: a closed mesh of a box's 12 triangles holds a cloth as the
//! analytic box does (the box's signed distance is a closed form the mesh's is independent
//! of), and a cloth falling onto a mesh that is not convex (a step: two blocks) never leaves a
//! particle inside it, judged by a ray-parity test that does not use the collider's grid. On
//! the CPU reference and both GPU paths, with validation.

use crate::common::*;
use glam::DVec3;
use msdsim::sim::model::SimModel;
use std::path::Path;

/// The 8 corners and 6 faces (quads wound counter-clockwise from outside) of the block from
/// `lo` to `hi` as OBJ lines, its vertices numbered from `first` (1-based).
fn block_obj(lo: DVec3, hi: DVec3, first: usize) -> String {
    let (corners, quads) = block(lo, hi);
    let mut out = String::new();
    for p in corners {
        out += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for q in quads {
        out += &format!("f {} {} {} {}\n", q[0] + first, q[1] + first, q[2] + first, q[3] + first);
    }
    out
}

/// A 12 x 12 cloth of 2.5 cm spacing held flat above `top`, over a collider `collider` (preset
/// text), falling under gravity; VBD at 4 iterations, 16 substeps.
fn cloth_over(collider: &str, top: f64, dir: &Path) -> SimModel {
    let text = format!(
        r#"
[sim]
substeps = 16
integrator = "vbd"
iterations = 4
{collider}
[[cloth]]
name = "draped"
resolution = [12, 12]
size = [0.275, 0.275]
origin = [-0.15, {}, -0.12]
orientation = "horizontal"
mass = 0.002
stiffness = {{ structural = 400.0, shear = 100.0, bending = 0.5 }}
damping = 0.01
collision_margin = 0.005
friction = 0.3
self_collision = false
pin = "none"
"#,
        top + 0.05
    );
    let preset = dir.join("scene.toml");
    std::fs::write(&preset, text).unwrap();
    let scene = msdsim::scene::load(&preset, &[]).expect("the scene loads");
    msdsim::scene::to_model(&scene)
}

/// A box turned 20 degrees about y and its mesh twin (a cube OBJ scaled to its size, placed
/// and turned the same way): the cloth falls on a corner of the top face and drapes over two
/// edges. After 1 s every particle of the mesh run is within 1e-3 m of the box run on each
/// path (4% of the spacing). On the f64 reference the two agree to 4e-13 m; in f32 the two
/// distances round differently and the draping contact amplifies it (measured 2.7e-4 m on
/// lavapipe, as far as the GPU's box run is from the reference's box run).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_cloth_on_a_cube_mesh_lies_as_on_the_box() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), block_obj(DVec3::splat(-1.0), DVec3::splat(1.0), 1)).unwrap();
    let boxed =
        "[[box]]\ncenter = [0.1, 0.2, 0.0]\nhalf_extents = [0.2, 0.2, 0.2]\nrotation = [0.0, 20.0, 0.0]\n";
    let meshed =
        "[[mesh]]\nfile = \"cube.obj\"\ncenter = [0.1, 0.2, 0.0]\nscale = 0.2\nrotation = [0.0, 20.0, 0.0]\n";
    let (a, b) = (cloth_over(boxed, 0.4, dir.path()), cloth_over(meshed, 0.4, dir.path()));
    let ctx = gpu();
    const FRAMES: usize = 60;
    let (on_box, on_mesh) = (every_path(&ctx, &a, FRAMES), every_path(&ctx, &b, FRAMES));
    let gpu_box = on_box[1].1.iter().zip(&on_box[0].1).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max);
    println!("the GPU's box run at most {gpu_box:.2e} m from the reference's");
    let mut worst: Vec<(&str, f64, f64)> = Vec::new();
    for ((label, xa, _), (_, xb, _)) in on_box.iter().zip(&on_mesh) {
        let apart = xa.iter().zip(xb).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max);
        let lowest = xb.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let box_lowest = xa.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        println!("{label}: the mesh run at most {apart:.2e} m from the box run; lowest particle y {lowest:.3} (box {box_lowest:.3})");
        worst.push((label, apart, lowest));
    }
    for (label, apart, lowest) in worst {
        assert!(apart < 1e-3, "{label}: {apart:.2e} m from the box run");
        // It rests on the block (top at 0.4), draped over its edges, not fallen through.
        assert!(lowest > 0.0, "{label}: a particle at y {lowest}");
    }
    assert_clean(&ctx);
}

/// Whether `p` is inside the closed mesh (`vertices`, `triangles`), by the parity of a ray's
/// crossings (a ray along a direction no face is parallel to).
fn inside(p: DVec3, vertices: &[DVec3], triangles: &[[usize; 3]]) -> bool {
    let dir = DVec3::new(0.5773, 0.5774, 0.5775).normalize();
    let far = p + dir * 100.0;
    triangles.iter().filter(|t| segment_through(p, far, t.map(|k| vertices[k]))).count() % 2 == 1
}

/// A cloth falls on a step (two blocks side by side, one higher: a closed mesh that is not
/// convex, 24 triangles) and drapes over its edges and its inner corner. At every frame's end
/// no particle is inside the mesh by more than f32 rounding (the ray-parity test, which does
/// not use the collider's grid, against the mesh shrunk by 1e-5 m), on every path; and the
/// cloth rests on it (no particle below the floor of the step).
#[test]
fn a_cloth_on_a_step_mesh_stays_outside_it() {
    let dir = tempfile::tempdir().unwrap();
    let (lo1, hi1) = (DVec3::new(-0.2, 0.0, -0.2), DVec3::new(0.0, 0.3, 0.2));
    let (lo2, hi2) = (DVec3::new(0.0, 0.0, -0.2), DVec3::new(0.2, 0.15, 0.2));
    let obj = format!("{}{}", block_obj(lo1, hi1, 1), block_obj(lo2, hi2, 9));
    std::fs::write(dir.path().join("step.obj"), obj).unwrap();
    let m = cloth_over("[[mesh]]\nfile = \"step.obj\"\n", 0.3, dir.path());
    // The blocks shrunk by the slack, for the parity test.
    let slack = 1e-5;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for (lo, hi) in [(lo1, hi1), (lo2, hi2)] {
        triangles.extend(block_triangles(vertices.len()));
        vertices.extend(block(lo + slack, hi - slack).0);
    }
    let ctx = gpu();
    for (label, frames) in every_path_each_frame(&ctx, &m, 90) {
        let mut worst = 0;
        for x in &frames {
            worst = worst.max(x.iter().filter(|&&p| inside(p, &vertices, &triangles)).count());
        }
        let last = frames.last().unwrap();
        let lowest = last.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        println!("{label}: at most {worst} particles inside the step; lowest at the end y {lowest:.3}");
        assert_eq!(worst, 0, "{label}: particles inside the step");
        assert!(lowest > 0.1, "{label}: a particle at y {lowest}, below the step's lower top");
    }
    assert_clean(&ctx);
}
