//! The iterative methods at the large steps they exist for: a stiff cloth at one 1/60 s
//! substep, against its static equilibrium found independently (Newton's method on the total
//! energy, f64, here in the test).

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::cpu::CpuSim;
use msdsim::sim::model::{Integrator, ObjectModel, SimModel};

const N: u32 = STIFF_N;
const SPACING: f64 = STIFF_SPACING;

/// The springs of the grid, each once: (i, j, stiffness, rest length).
fn spring_list(o: &ObjectModel) -> Vec<(usize, usize, f64, f64)> {
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    let mut out = Vec::new();
    let kinds: [(usize, &[(i64, i64)]); 3] =
        [(0, &[(1, 0), (0, 1)]), (1, &[(1, 1), (1, -1)]), (2, &[(2, 0), (0, 2)])];
    for r in 0..rows {
        for c in 0..cols {
            for (kind, offsets) in kinds {
                for &(dc, dr) in offsets {
                    let (nc, nr) = (c + dc, r + dr);
                    if nc < 0 || nr < 0 || nc >= cols || nr >= rows {
                        continue;
                    }
                    let rest = ((dc as f64 * o.spacing[0]).powi(2) + (dr as f64 * o.spacing[1]).powi(2))
                        .sqrt()
                        * o.rest_scale[kind];
                    out.push(((c + r * cols) as usize, (nc + nr * cols) as usize, o.stiffness[kind], rest));
                }
            }
        }
    }
    out
}

/// Net force on every particle at x (gravity and springs; pinned ones zero) [N].
fn net_force(m: &SimModel, o: &ObjectModel, springs: &[(usize, usize, f64, f64)], x: &[DVec3]) -> Vec<DVec3> {
    let mut f: Vec<DVec3> = vec![m.gravity * o.mass; x.len()];
    for &(i, j, k, rest) in springs {
        let d = x[j] - x[i];
        let len = d.length();
        let t = d / len * (k * (len - rest));
        f[i] += t;
        f[j] -= t;
    }
    for (i, f) in f.iter_mut().enumerate() {
        if o.pinned[i] {
            *f = DVec3::ZERO;
        }
    }
    f
}

/// The static equilibrium near `x`: Newton's method on the total energy with each spring's
/// Hessian made positive semi-definite (its transverse term clamped at zero) and a
/// Levenberg-Marquardt shift (raised where the Hessian is indefinite), until the largest net force is below 1e-8 N (a millionth of a particle's weight). Panics if it does
/// not get there.
fn equilibrium(m: &SimModel, start: &[DVec3]) -> Vec<DVec3> {
    let o = &m.objects[0];
    let springs = spring_list(o);
    let n = start.len();
    let mut x = start.to_vec();
    let mut shift = 1e-3;
    let worst = |f: &[DVec3]| f.iter().map(|f| f.length()).fold(0.0, f64::max);
    let energy = |x: &[DVec3]| {
        let mut e = 0.0;
        for p in x {
            e -= o.mass * m.gravity.dot(*p);
        }
        for &(i, j, k, rest) in &springs {
            e += 0.5 * k * ((x[j] - x[i]).length() - rest).powi(2);
        }
        e
    };
    for _ in 0..200 {
        let f = net_force(m, o, &springs, &x);
        if worst(&f) < 1e-8 {
            return x;
        }
        let dim = 3 * n;
        let mut a = vec![0.0f64; dim * dim];
        for &(i, j, k, rest) in &springs {
            let d = x[j] - x[i];
            let len = d.length();
            let u = d / len;
            let t = 1.0 - rest / len;
            for r in 0..3 {
                for c in 0..3 {
                    let nn = u[r] * u[c];
                    let h = k * (nn + t * (if r == c { 1.0 } else { 0.0 } - nn));
                    for (p, q, s) in [(i, i, 1.0), (j, j, 1.0), (i, j, -1.0), (j, i, -1.0)] {
                        a[(3 * p + r) * dim + 3 * q + c] += s * h;
                    }
                }
            }
        }
        loop {
            let mut h = a.clone();
            let mut b = vec![0.0; dim];
            for (i, fi) in f.iter().enumerate() {
                for (r, fr) in fi.to_array().into_iter().enumerate() {
                    let row = 3 * i + r;
                    if o.pinned[i] {
                        for c in 0..dim {
                            h[row * dim + c] = 0.0;
                            h[c * dim + row] = 0.0;
                        }
                        h[row * dim + row] = 1.0;
                    } else {
                        h[row * dim + row] += shift;
                        b[row] = fr;
                    }
                }
            }
            let Some(step) = solve_spd(&mut h, &mut b, dim) else {
                shift *= 10.0;
                continue;
            };
            let trial: Vec<DVec3> =
                (0..n).map(|i| x[i] + DVec3::new(step[3 * i], step[3 * i + 1], step[3 * i + 2])).collect();
            if energy(&trial) <= energy(&x) {
                x = trial;
                shift = (shift * 0.3).max(1e-9);
                break;
            }
            shift *= 10.0;
            assert!(shift < 1e12, "the reference's Newton iteration stalled");
        }
    }
    panic!("the reference's Newton iteration did not reach 1e-8 N");
}

/// Solves H s = b for a symmetric positive definite H (Cholesky, in place).
fn solve_spd(h: &mut [f64], b: &mut [f64], n: usize) -> Option<Vec<f64>> {
    for j in 0..n {
        let mut d = h[j * n + j];
        for k in 0..j {
            d -= h[j * n + k] * h[j * n + k];
        }
        if d <= 0.0 {
            return None;
        }
        let d = d.sqrt();
        h[j * n + j] = d;
        for i in j + 1..n {
            let mut s = h[i * n + j];
            for k in 0..j {
                s -= h[i * n + k] * h[j * n + k];
            }
            h[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= h[i * n + k] * b[k];
        }
        b[i] = s / h[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= h[k * n + i] * b[k];
        }
        b[i] = s / h[i * n + i];
    }
    Some(b.to_vec())
}

/// Mean height of the cloth below its corners (its sag) [m].
fn sag(x: &[DVec3]) -> f64 {
    1.0 - x.iter().map(|p| p.y).sum::<f64>() / x.len() as f64
}

/// Largest speed among the particles [m/s].
fn fastest(v: &[DVec3]) -> f64 {
    v.iter().map(|v| v.length()).fold(0.0, f64::max)
}

/// VBD and the implicit method at ONE 1/60 s substep and 10 iterations, the setting they
/// exist for, on a cloth stiff enough that Verlet needs hundreds of substeps (1e4 and 1e5 N/m,
/// 1 g particles): after 4 s the sag is within 5% of the static equilibrium (Newton's method,
/// above) and every particle is at rest (below 1 mm/s), on the CPU reference and both GPU
/// paths. Started from the prediction y every substep, as until 2026-11-24, VBD hung 21% and
/// 167% too low (its 10 iterations take back only part of each substep's pull of gravity) and
/// at 4 iterations jittered at up to 1 m/s; the implicit method by projective dynamics (Jacobi
/// sweeps, until 2026-11-26) hung 877% too low at 1e4 N/m. Measured with the adaptive start
/// (`held_fraction`) and the implicit method's Newton steps of conjugate gradients: within
/// 0.1% (CPU; GPU in the assertion message) and speeds below 3e-4 m/s. 4 s, not 3: at 1e5 N/m
/// VBD's unconverged solve settles the sag mode more slowly than the converged one (the
/// fastest particle at 3 s: 8.9e-4 m/s, at 4 s 2.4e-4).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn the_large_step_methods_settle_at_the_equilibrium_sag_at_one_substep() {
    let ctx = gpu();
    for (k, method) in [1e4, 1e5].into_iter().flat_map(|k| [(k, Integrator::Vbd), (k, Integrator::Implicit)])
    {
        let mut m = stiff_cloth(k);
        m.integrator = method;
        m.iterations = 10;
        let results = every_path(&ctx, &m, 240);
        let exact = sag(&equilibrium(&m, &results[0].1));
        for (label, x, v) in &results {
            let error = sag(x) / exact - 1.0;
            let speed = fastest(v);
            println!(
                "k = {k}, {method:?}: {label}: sag {:.6} m against {exact:.6} ({:+.2}%), fastest {speed:.2e} m/s",
                sag(x),
                100.0 * error
            );
            assert!(
                error.abs() < 0.05,
                "k = {k}, {method:?}, {label}: sag {:.6} m, {:+.1}% off the equilibrium's {exact:.6}",
                sag(x),
                100.0 * error
            );
            assert!(speed < 1e-3, "k = {k}, {method:?}, {label}: not at rest, a particle at {speed:.2e} m/s");
        }
    }
    assert_clean(&ctx);
}

/// Mean of the vectors.
fn mean(v: &[DVec3]) -> DVec3 {
    v.iter().sum::<DVec3>() / v.len() as f64
}

/// The adaptive start must not hold back a falling cloth: the same stiff cloth, unpinned,
/// falls at one substep a frame with VBD and the implicit method at 4 and 10 iterations (the
/// methods that start adaptively); nothing but gravity acts on
/// it from outside, so its centre of mass gains g t of speed: from 0.25 s to 0.5 s (after the
/// start, whose first substep is taken as implicit Euler's) within 1e-5 of g x 0.25 s (measured: 1.3e-7, f32 rounding), on the
/// CPU reference and both GPU paths. (Starting from the prediction less the whole pull, with
/// no adaptation, it fell 60 to 82% short.)
#[test]
fn a_stiff_cloth_falls_freely_at_a_large_step() {
    let ctx = gpu();
    for (k, method) in [1e4, 1e5].into_iter().flat_map(|k| [(k, Integrator::Vbd), (k, Integrator::Implicit)])
    {
        let mut m = stiff_cloth(k);
        m.objects[0].pinned.iter_mut().for_each(|p| *p = false);
        m.objects[0].drag = 0.0;
        m.integrator = method;
        for iterations in [4, 10] {
            m.iterations = iterations;
            let (early, late) = (every_path(&ctx, &m, 15), every_path(&ctx, &m, 30));
            for ((label, _, v0), (_, _, v1)) in early.iter().zip(&late) {
                let gained = (mean(v1) - mean(v0)).dot(DVec3::NEG_Y);
                let error = gained / (9.81 * 0.25) - 1.0;
                println!("k = {k}, {method:?}, {iterations} iterations, {label}: gained {gained:.6} m/s ({error:+.2e})");
                assert!(error.abs() < 1e-5, "k = {k}, {method:?}, {iterations} iterations, {label}: the centre of mass gained {gained:.5} m/s in 0.25 s, {error:+.2e} off g t");
            }
        }
    }
    assert_clean(&ctx);
}

/// A 10 x 10 cloth, 7.5 cm apart, lying flat and pinned at two corners of one edge, swinging
/// down under gravity: the curtain preset's springs (400, 100, 40 N/m), dashpots and drag.
fn swinging_cloth() -> SimModel {
    let mut c = cloth(10, 10, 0.075);
    for p in &mut c.positions {
        *p = DVec3::new(p.x - 0.3375, 1.5, 1.0 - p.y);
    }
    c.stiffness = [400.0, 100.0, 40.0];
    c.damping = 0.005;
    c.drag = 0.002;
    c.pinned[0] = true;
    c.pinned[9] = true;
    let mut m = scene(vec![c]);
    m.gravity = DVec3::new(0.0, -9.81, 0.0);
    m
}

/// RMS error over the object's size at t = 0.5 s on the GPU (fused or per stage) against
/// `reference`, and the largest structural strain seen at any frame.
fn gpu_error(
    ctx: &msdsim::vk::GpuContext,
    m: &SimModel,
    fused: bool,
    reference: &[Vec<DVec3>],
) -> (f64, f64) {
    let mut gpu = msdsim::sim::gpu::GpuSim::new(ctx, m).expect("creating the GPU simulation");
    gpu.set_fused(ctx, fused).unwrap();
    let mut strain = 0.0f64;
    let mut last = Vec::new();
    for _ in 0..30 {
        gpu.step_frame(ctx).expect("GPU frame");
        last = gpu.read_states(ctx).expect("readback")[0].positions();
        strain = strain.max(msdsim::sim::cpu::max_strain(&m.objects[0], &last));
    }
    gpu.destroy(ctx);
    (msdsim::study::accuracy::error(m, &[last], reference).rms, strain)
}

/// The f32 floor of the BDF2 methods on the GPU on `swinging_cloth` at t = 0.5 s: measured at
/// 256 substeps, VBD 5.7e-5, XPBD 5.6e-5, the implicit method 8.4e-5 (fused) and 5.9e-5 (per
/// stage), where GPU Verlet has 6.6e-6 and the f64 reference's implicit method 4e-6.
const BDF2_F32_FLOOR: f64 = 1e-4;

/// The implicit method converges as the substep shrinks, on the GPU, at the iterations users
/// run and at many: its error at t = 0.5 s on the swinging cloth against Verlet at 512
/// substeps (f64) falls at least 3 times per 4 times more substeps, 16 to 64 and 64 to 256,
/// until it is below the f32 floor (`BDF2_F32_FLOOR`), and its largest strain stays within
/// 0.01 of the f64 reference's (0.274). Fused at 4 and 30 iterations; per stage, which runs
/// three dispatches a CG iteration, at 4 iterations to 64 substeps. Measured: 2.4e-4, 3.5e-5,
/// 5.7e-5 (fused, 4 and 30 iterations), 2.4e-4, 3.5e-5 (per stage). Before 2026-11-24 the
/// fused kernel's projective dynamics at 30 iterations and 256 substeps stretched the cloth by
/// up to 59% (a Chebyshev weight computed by a loop inside the iteration loop came out wrong on
/// lavapipe); since 2026-11-26 the method is Newton's with conjugate gradients.
/// The default tier takes 4 iterations fused and per stage, the exhaustive tier 30 fused.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn the_implicit_method_converges_as_the_substep_shrinks_on_the_gpu() {
    implicit_converges_on_the_gpu(&[(true, 4, &[16, 64, 256]), (false, 4, &[16, 64])]);
}

#[test]
#[ignore = "exhaustive tier: 30 iterations"]
fn the_implicit_method_converges_as_the_substep_shrinks_on_the_gpu_at_many_iterations() {
    implicit_converges_on_the_gpu(&[(true, 30, &[16, 64, 256])]);
}

/// (fused, iterations, substep counts) for each run of the test above.
type ConvergenceRuns<'a> = [(bool, u32, &'a [u32])];

fn implicit_converges_on_the_gpu(settings: &ConvergenceRuns) {
    let ctx = gpu();
    let base = swinging_cloth();
    let reference = msdsim::study::accuracy::reference(&base, &[0.5], 512);
    let f64_strain = {
        let mut m = base.clone();
        m.integrator = Integrator::Verlet;
        m.substeps = 64;
        msdsim::study::accuracy::cpu_run(&m, &[0.5]).max_strain
    };
    for &(fused, iterations, counts) in settings {
        let runs: Vec<(f64, f64)> = counts
            .iter()
            .map(|&n| {
                let mut m = base.clone();
                m.integrator = Integrator::Implicit;
                m.substeps = n;
                m.iterations = iterations;
                gpu_error(&ctx, &m, fused, &reference.samples[0])
            })
            .collect();
        let errors: Vec<String> = runs.iter().map(|(e, _)| format!("{e:.2e}")).collect();
        println!("fused {fused}, {iterations} iterations, substeps {counts:?}: errors {errors:?}, strains {runs:.4?} (f64 {f64_strain:.4})");
        for pair in runs.windows(2).filter(|p| p[1].0 > BDF2_F32_FLOOR) {
            assert!(
                pair[0].0 / pair[1].0 >= 3.0,
                "fused {fused}, {iterations} iterations: the error fell only {:.2}x for 4x the substeps ({errors:?} at {counts:?})",
                pair[0].0 / pair[1].0
            );
        }
        for (n, (_, strain)) in counts.iter().zip(&runs) {
            assert!(
                (strain - f64_strain).abs() < 0.01,
                "fused {fused}, {iterations} iterations, {n} substeps: largest strain {strain:.3}, the reference's {f64_strain:.3}"
            );
        }
    }
    assert_clean(&ctx);
}

/// How one run of the large-step matrix settled: the method's run of `stiff_cloth` at one
/// 1/60 s substep over 4 s on the f64 reference.
struct Settled {
    /// The most the energy rose above the lowest it had before, over the guard's scale.
    rise: f64,
    /// The sag against the static equilibrium's, less one.
    sag: f64,
    /// The fastest particle at the end [m/s].
    fastest: f64,
    /// ... and a second before the end.
    fastest_before: f64,
}

/// `m` (a `stiff_cloth`) settled, against the equilibrium's sag `exact`.
fn settle(m: &SimModel, exact: f64) -> Settled {
    let o = &m.objects[0];
    // The energy guard's scale: the weight times the diagonal (sim::gpu::energy).
    let scale = o.mass * o.positions.len() as f64 * 9.81 * (SPACING * (N - 1) as f64) * 2f64.sqrt();
    let mut cpu = CpuSim::new(m);
    let (mut lowest, mut rise) = (f64::INFINITY, 0.0f64);
    let mut fastest_before = 0.0;
    for frame in 0..240 {
        cpu.step_frame();
        let c = &cpu.objects()[0];
        if frame == 179 {
            fastest_before = fastest(&c.v);
        }
        let e = msdsim::sim::cpu::energy(m, o, &c.x, &c.v);
        assert!(e.is_finite(), "{:?}: the energy is {e}", m.integrator);
        lowest = lowest.min(e);
        rise = rise.max(e - lowest);
    }
    let c = &cpu.objects()[0];
    Settled { rise: rise / scale, sag: sag(&c.x) / exact - 1.0, fastest: fastest(&c.v), fastest_before }
}

/// The large-step matrix (issue 68): each iterative method at one 1/60 s substep on the held
/// stiff cloth, structural stiffness 1e3 to 1e6 N/m, shear and bending a half and a tenth of it,
/// as stiff or a hundredth, dashpots none, light (5e-3 N s/m, the presets'), heavy (0.2, past
/// b dt / m = 1) and at a damping ratio of 2 (4 sqrt(k m)), iterations 1, 2, 4 and 10, on the
/// f64 reference. VBD: every run ends at rest (fastest particle under 1 cm/s after 4 s;
/// measured at most 3e-3), its energy rises at most 1e-6 of the guard's scale (BDF2 keeps a
/// norm of two steps from rising, not the energy itself; measured 6e-7), and at 10 iterations
/// the sag is within 10% of the equilibrium (measured 1%). The implicit method ends slower than
/// 5 cm/s (measured 1.9e-2 at 1 and 2 iterations with the weakest bending, under 1e-5 at 10),
/// at 10 iterations is within 10% (measured 0.0%), and at every iteration count its energy
/// rises at most 5e-3 of the scale (measured 1.8e-3 at 4 iterations, 4e-6 at 10; before its
/// line search, up to 17 times the scale below 10 iterations). XPBD and XPBD by Jacobi end at
/// rest too (under 1 cm/s; measured: XPBD at most 1.6e-8), XPBD by Jacobi or still slowing
/// (its fastest particle at least halved over the last second: at one iteration with the
/// weakest bending and a damping ratio of 2 it creeps at 1.6e-2 m/s, halving every 0.67 s). Before XPBD
/// swept its structural springs last (`xpbd_class_order`) it rang with dashpots at a damping
/// ratio of 2 and the weakest bending, up to 1.3 m/s after 4 s. Their sag and energy are
/// stated, not asserted (they hang long: a solve cut short pulls less than the springs'
/// stiffness, and the springs' energy at their stiffness is not the energy they integrate).
/// Before each particle of a held object started towards where it is (`toward_rest`), VBD
/// ended moving at 0.1 to 1 m/s in most runs below 10 iterations. The default tier runs the
/// corners (1e4 and 1e6 N/m, the default and the weakest bending, no dashpots and a damping
/// ratio of 2, VBD, the implicit method and XPBD at 1 and 10 iterations); the exhaustive tier
/// all of it.
#[test]
fn every_iterative_method_settles_at_one_substep() {
    settling_matrix(
        &[Integrator::Vbd, Integrator::Implicit, Integrator::Xpbd],
        &[1, 10],
        &[1e4, 1e6],
        &[None, Some(0.01)],
        &[0.0, -2.0],
    );
}

#[test]
#[ignore = "exhaustive tier: the whole matrix"]
fn every_iterative_method_settles_at_one_substep_over_the_whole_matrix() {
    let methods: Vec<_> = Integrator::ALL.into_iter().filter(|m| m.iterative()).collect();
    settling_matrix(
        &methods,
        &[1, 2, 4, 10],
        &[1e3, 1e4, 1e5, 1e6],
        &[None, Some(1.0), Some(0.01)],
        &[0.0, 5e-3, 0.2, -2.0],
    );
}

/// The runs of `every_iterative_method_settles_at_one_substep` over the given values (shear and
/// bending k times a ratio, `None` the half and tenth; a negative damping is that damping ratio,
/// -z 2 sqrt(k m)), each against its bounds.
fn settling_matrix(
    methods: &[Integrator],
    iterations: &[u32],
    ks: &[f64],
    ratios: &[Option<f64>],
    dampings: &[f64],
) {
    let mut failures = Vec::new();
    for &k in ks {
        for &ratio in ratios {
            let mut m = stiff_cloth(k);
            if let Some(r) = ratio {
                m.objects[0].stiffness = [k, k * r, k * r];
            }
            let exact = sag(&equilibrium(&m, &m.objects[0].positions));
            for &damping in dampings {
                let b = if damping < 0.0 { -damping * 2.0 * (k * m.objects[0].mass).sqrt() } else { damping };
                m.objects[0].damping = b;
                for &method in methods {
                    for &it in iterations {
                        m.integrator = method;
                        m.iterations = it;
                        let s = settle(&m, exact);
                        let what = format!(
                            "{method:?}, {it} iterations, k {k:e}, shear and bending {ratio:?}, dashpots {b:.3}: energy rose {:.1e} of the scale, sag {:+.1}%, fastest {:.1e} m/s",
                            s.rise,
                            100.0 * s.sag,
                            s.fastest
                        );
                        println!("{what}");
                        let rise_allowed = match (method, it) {
                            (Integrator::Vbd, _) => Some(1e-6),
                            (Integrator::Implicit, _) => Some(5e-3),
                            _ => None,
                        };
                        let at_rest = match method {
                            Integrator::Implicit => 5e-2,
                            _ => 1e-2,
                        };
                        // (XPBD by Jacobi's slow creep with heavy dashpots: still slowing, at
                        // least halved over the last second)
                        let creeping = method == Integrator::XpbdJacobi && s.fastest < 0.5 * s.fastest_before;
                        let settling = s.fastest < at_rest || creeping;
                        let converged = it == 10 && matches!(method, Integrator::Vbd | Integrator::Implicit);
                        if !settling
                            || rise_allowed.is_some_and(|r| s.rise > r)
                            || (converged && s.sag.abs() > 0.1)
                        {
                            failures.push(what);
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The implicit method's line search (`sim::cpu::integrators::line_search`): the held stiff
/// cloth at 1e5 N/m, one 1/60 s substep of 2 iterations (one Newton step of two CG
/// iterations, cut short), 4 s. Without the search its energy rose 2.7 times the guard's
/// scale above its lowest on the way to rest (the CPU reference, 2026-12-05); with it the rise
/// stays under 1e-3 of the scale on the reference, both GPU paths and the per-stage path with
/// its partial sums totalled by passes of their own (measured: 0 to f32 noise), and every path
/// ends at rest (under 1 mm/s) with the sag within 1% of the reference's.
#[test]
fn the_implicit_methods_line_search_keeps_a_cut_short_solve_from_gaining_energy() {
    let ctx = gpu();
    let mut m = stiff_cloth(1e5);
    m.integrator = Integrator::Implicit;
    m.iterations = 2;
    assert!(
        msdsim::sim::cpu::implicit_searches(&m, &m.objects[0]),
        "the cloth must be stiff enough to search"
    );
    let o = &m.objects[0];
    let scale = o.mass * o.positions.len() as f64 * 9.81 * (SPACING * (N - 1) as f64) * 2f64.sqrt();
    const FRAMES: usize = 240;
    // (label, energy after each frame, final positions, final velocities)
    let mut runs = Vec::new();
    let mut cpu = CpuSim::new(&m);
    let mut energies = Vec::new();
    for _ in 0..FRAMES {
        cpu.step_frame();
        let c = &cpu.objects()[0];
        energies.push(msdsim::sim::cpu::energy(&m, o, &c.x, &c.v));
    }
    let c = &cpu.objects()[0];
    runs.push(("cpu", energies, c.x.clone(), c.v.clone()));
    for (label, fused, totals) in [
        ("gpu fused", true, None),
        ("gpu per stage", false, None),
        ("gpu per stage, totals passes", false, Some(0)),
    ] {
        let mut gpu = msdsim::sim::gpu::GpuSim::new(&ctx, &m).expect("creating the GPU simulation");
        gpu.set_fused(&ctx, fused).unwrap();
        if let Some(groups) = totals {
            gpu.set_cg_totals_above(groups);
        }
        let mut energies = Vec::new();
        let mut last = None;
        for _ in 0..FRAMES {
            gpu.step_frame(&ctx).expect("GPU frame");
            let state = gpu.read_states(&ctx).expect("readback").remove(0);
            energies.push(msdsim::sim::cpu::energy(&m, o, &state.positions(), &state.velocities()));
            last = Some(state);
        }
        gpu.destroy(&ctx);
        let last = last.unwrap();
        runs.push((label, energies, last.positions(), last.velocities()));
    }
    let reference_sag = sag(&runs[0].2);
    for (label, energies, x, v) in &runs {
        let mut lowest = f64::INFINITY;
        let mut rise = 0.0f64;
        for e in energies {
            lowest = lowest.min(*e);
            rise = rise.max(e - lowest);
        }
        let off = sag(x) / reference_sag - 1.0;
        println!(
            "{label}: energy rose {:.1e} of the scale, sag {:+.2e} off the reference's, fastest {:.1e} m/s",
            rise / scale,
            off,
            fastest(v)
        );
        assert!(rise / scale < 1e-3, "{label}: the energy rose {:.2e} of the guard's scale", rise / scale);
        assert!(fastest(v) < 1e-3, "{label}: not at rest, a particle at {:.2e} m/s", fastest(v));
        assert!(off.abs() < 0.01, "{label}: sag {:+.2}% off the reference's", 100.0 * off);
    }
    assert_clean(&ctx);
}

/// Pinning a particle of a free object in the app (Ctrl + click, `SimHost::set_pinned`) makes
/// the object held, which changes where the iterative methods start their solve (the
/// parameters' `OBJ_ANCHORED`, `sim::cpu::integrators::toward_rest`): the host rewrites the
/// object's parameters. The stiff cloth (1e5 N/m, VBD at one substep of 2 iterations) loaded
/// free, its four corners pinned through the host before the first frame, then 30 frames: its
/// particles end within 1e-5 m of the reference that had them pinned from the start (f32
/// against f64; measured 1.4e-7), where the same pins set without the rewrite end farther than
/// 1e-3 m from it (measured 7.9e-3: the solve starting from the free object's rigid move on a
/// held cloth; 2.5e-2 from the prediction, before free objects started so).
#[test]
fn pinning_in_the_app_rewrites_where_the_solve_starts() {
    use msdsim::app::SimHost;
    use msdsim::render::SceneRenderer;
    use msdsim::vk::Format;
    const FRAMES: usize = 30;
    let text = r#"
[sim]
substeps = 1
integrator = "vbd"
iterations = 2
max_energy_gain = 0.0
max_strain = 0.0
[[cloth]]
name = "stiff"
resolution = [12, 12]
size = [0.275, 0.275]
origin = [0.0, 1.0, 0.0]
orientation = "horizontal"
mass = 0.001
stiffness = { structural = 1e5, shear = 5e4, bending = 1e4 }
damping = 0.0
drag = 0.01
self_collision = false
pin = "none"
"#;
    let scene = msdsim::scene::parse(text, "test", &[]).expect("the test scene parses");
    let corners = [0u32, 11, 132, 143];
    let mut model = msdsim::scene::to_model(&scene);
    for &i in &corners {
        model.objects[0].pinned[i as usize] = true;
    }
    let mut cpu = CpuSim::new(&model);
    for _ in 0..FRAMES {
        cpu.step_frame();
    }
    let reference = cpu.objects()[0].x.clone();
    let ctx = gpu();
    let mut shaders = msdsim::shaders::ShaderSet::embedded();
    let mut renderer = SceneRenderer::new(&ctx, Format::Rgba8Unorm, Format::Depth32, &mut shaders).unwrap();
    let mut run = |rewrite: bool| -> f64 {
        let mut host = SimHost::new(&ctx, scene.clone(), &mut renderer, &mut shaders).unwrap();
        for &i in &corners {
            let at = model.objects[0].positions[i as usize].as_vec3().to_array();
            if rewrite {
                host.set_pinned(&ctx, 0, i, true, at).unwrap();
            } else {
                let pos = [at[0], at[1], at[2], 1.0];
                host.sim_mut().set_particle(0, i, msdsim::sim::gpu_types::Particle { pos, vel: [0.0; 4] });
            }
        }
        for _ in 0..FRAMES {
            host.sim_mut().step_frame(&ctx).expect("GPU frame");
        }
        let x = host.sim_mut().read_states(&ctx).unwrap()[0].positions();
        host.destroy(&ctx);
        x.iter().zip(&reference).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max)
    };
    let (with, without) = (run(true), run(false));
    println!("pinned through the host: {with:.2e} m from the reference; without the rewrite {without:.2e} m");
    renderer.destroy(&ctx);
    assert_clean(&ctx);
    assert!(with < 1e-5, "pinned through the host: {with} m from the reference");
    assert!(
        without > 1e-3,
        "without the rewrite only {without} m from the reference: the test would not see it"
    );
}

/// The stiff cloth free in space (no pins, no gravity, no drag), its springs' rest lengths
/// 1/1.05 of the grid (released stretched by 5%), bending a hundredth of the structural
/// springs, at one 1/60 s substep, moving at `v(q)` (q: the particle's offset from the centre).
fn free_stiff_cloth(k: f64, method: Integrator, iterations: u32, v: impl Fn(DVec3) -> DVec3) -> SimModel {
    let mut m = stiff_cloth(k);
    m.gravity = DVec3::ZERO;
    m.integrator = method;
    m.iterations = iterations;
    let o = &mut m.objects[0];
    o.pinned.iter_mut().for_each(|p| *p = false);
    o.drag = 0.0;
    o.stiffness = [k, k / 2.0, k / 100.0];
    o.rest_scale = [1.0 / 1.05; 3];
    let centre = mean(&o.positions);
    o.velocities = o.positions.iter().map(|x| v(*x - centre)).collect();
    m
}

/// Energy about the mean motion (the springs' at their stiffness and the kinetic energy less
/// the mean velocity's) [J], and the angular momentum about the centre [kg m^2/s].
fn internal_motion(m: &SimModel, x: &[DVec3], v: &[DVec3]) -> (f64, DVec3) {
    let o = &m.objects[0];
    let (c, u) = (mean(x), mean(v));
    let total = msdsim::sim::cpu::energy(m, o, x, v);
    let spin = x.iter().zip(v).map(|(x, v)| (*x - c).cross(*v - u) * o.mass).sum();
    (total - 0.5 * o.mass * x.len() as f64 * u.length_squared(), spin)
}

/// A free stiff object at one large substep must not gain energy (issue 68): the free stiff
/// cloth (`free_stiff_cloth`) thrown at 0.3 m/s with its particles' velocities scattered by
/// up to 0.5 m/s, 1e4 and 1e6 N/m, VBD and the implicit method at 1, 2, 4 and 10 iterations.
/// On the f64 reference, over 8 s, its energy about the mean motion never rises past its start
/// (by 1e-6 of it: rounding; measured: never above it) and it ends below 1e-3 of it (measured
/// at most 6.1e-5), and its momentum stays within 15% of its start (a solve cut short is not
/// exact in momentum: VBD's sweeps and the implicit method's Newton steps change it while the
/// stretched cloth springs back, measured 0.02% to 9.6%, docs/guide/limits.md); the GPU paths
/// end below 1e-3 of it
/// after 4 s (measured at most 5.6e-5). Before these objects took implicit Euler's step from
/// the exact rigid turn (`sim::cpu::integrators::RigidMove`), the implicit method's one Newton
/// step of 3 to 5 CG iterations on the 1e6 N/m cloth settled, then moved again from about
/// 4.5 s and sped up as a whole (at 3 iterations from 0.3 to 68 m/s in 8 s; on the GPU 8.5
/// times its starting energy within 4 s); started from the guess (before the rigid start at
/// all) the implicit method at one iteration ended with 2,300 times its starting energy. And
/// spun at 3 rad/s in its plane, unstretched, it keeps at least 99% of its angular momentum
/// over 2 s on every path (measured 0.9971 to 0.9988: the start turns it by the angle it
/// turned, `RigidMove`; with the linearised turn it kept 0.96, with its translation alone it
/// stopped, and with BDF2's step it gained 25%). The default tier runs the GPU paths at 1 and
/// 10 iterations, the exhaustive tier at all four.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_free_stiff_cloth_gains_no_energy_at_a_large_step() {
    free_stiff_cloths(&[1, 10]);
}

#[test]
#[ignore = "exhaustive tier: every iteration count on the GPU"]
fn a_free_stiff_cloth_gains_no_energy_at_a_large_step_at_every_iteration_count() {
    free_stiff_cloths(&[1, 2, 4, 10]);
}

/// `a_free_stiff_cloth_gains_no_energy_at_a_large_step` with the GPU paths at `on_gpu`
/// iterations (the reference at all).
fn free_stiff_cloths(on_gpu: &[u32]) {
    let ctx = gpu();
    let scatter = |q: DVec3| {
        let h = |a: f64| (a * 12.9898 + q.z * 78.233).sin() * 43758.5453 % 1.0;
        DVec3::new(0.3 + 0.5 * h(q.x), 0.5 * h(q.x + 1.0), 0.5 * h(q.x + 2.0))
    };
    for (k, method) in [1e4, 1e6].into_iter().flat_map(|k| [(k, Integrator::Vbd), (k, Integrator::Implicit)])
    {
        for iterations in [1, 2, 4, 10] {
            let m = free_stiff_cloth(k, method, iterations, scatter);
            let o = &m.objects[0];
            let (start, _) = internal_motion(&m, &o.positions, &o.velocities);
            let mut cpu = CpuSim::new(&m);
            let mut highest = start;
            let momentum = mean(&o.velocities);
            let mut drift: f64 = 0.0;
            for _ in 0..480 {
                cpu.step_frame();
                let c = &cpu.objects()[0];
                highest = highest.max(internal_motion(&m, &c.x, &c.v).0);
                drift = drift.max((mean(&c.v) - momentum).length() / momentum.length());
            }
            let case = format!("k = {k}, {method:?}, {iterations} iterations");
            println!(
                "{case}: cpu: start {start:.3e} J, highest {:.3e} of it, momentum within {drift:.2e}",
                highest / start - 1.0
            );
            assert!(
                highest <= start * (1.0 + 1e-6),
                "{case}: the energy rose to {:.3} times its start",
                highest / start
            );
            let end = internal_motion(&m, &cpu.objects()[0].x, &cpu.objects()[0].v).0 / start;
            assert!(end < 1e-3, "{case}, cpu: ends with {end:.3e} of its starting energy");
            assert!(drift < 0.15, "{case}, cpu: its momentum moved by {drift:.3e} of its start");
            if !on_gpu.contains(&iterations) {
                continue;
            }
            for (label, x, v) in every_path(&ctx, &m, 240).into_iter().skip(1) {
                let end = internal_motion(&m, &x, &v).0 / start;
                println!("{case}, {label}: ends with {end:.2e} of it");
                assert!(end < 1e-3, "{case}, {label}: ends with {end:.3e} of its starting energy");
            }
        }
        for &iterations in on_gpu {
            let mut m = free_stiff_cloth(k, method, iterations, |q| DVec3::Y.cross(q) * 3.0);
            m.objects[0].rest_scale = [1.0; 3];
            let o = &m.objects[0];
            let (_, spin0) = internal_motion(&m, &o.positions, &o.velocities);
            for (label, x, v) in every_path(&ctx, &m, 120) {
                let kept = internal_motion(&m, &x, &v).1.dot(spin0) / spin0.length_squared();
                println!("k = {k}, {method:?}, {iterations} iterations, {label}: spin kept {kept:.4}");
                assert!(
                    kept > 0.99,
                    "k = {k}, {method:?}, {iterations} iterations, {label}: kept {kept:.4} of its spin"
                );
            }
        }
    }
    assert_clean(&ctx);
}
