//! The integrators on the CPU reference (f64): convergence order against a converged
//! reference, unconditional stability of the implicit method, energy behaviour.

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::model::{Integrator, SimModel};
use msdsim::study::accuracy::{self, cpu_run, error};

/// A chain of 10 nodes, 5 cm apart, pinned at one end, starting horizontal and swinging under
/// gravity; undamped.
fn chain(k: f64) -> SimModel {
    let mut r = rope(10, 0.05);
    r.stiffness = [k, 0.0, 0.1 * k];
    r.pinned[0] = true;
    let mut m = scene(vec![r]);
    m.gravity = DVec3::new(0.0, -9.81, 0.0);
    m
}

fn with(base: &SimModel, method: Integrator, substeps: u32, iterations: u32) -> SimModel {
    let mut m = base.clone();
    m.integrator = method;
    m.substeps = substeps;
    m.iterations = iterations;
    m
}

/// Each method's error at t = 0.5 s against Verlet at 1024 substeps per frame, as the substep
/// halves from 1/960 s to 1/3840 s: the measured order log2(e(dt) / e(dt/2)) must be within 0.3
/// of the method's order. The iterative methods run enough iterations to converge (their
/// limit is BDF2, order 2; measured 1.96 for XPBD). The reference's own error is checked to be
/// far below the errors measured.
#[test]
fn each_integrator_converges_at_its_order() {
    let base = chain(50.0);
    let times = [0.5];
    let reference = accuracy::reference(&base, &times, 1024);
    for method in Integrator::ALL {
        let iterations = if method.few_iterations() == 1 { 60 } else { 20 };
        let errors: Vec<f64> = [16, 32, 64]
            .iter()
            .map(|&n| {
                let m = with(&base, method, n, iterations);
                error(&m, &cpu_run(&m, &times).samples[0], &reference.samples[0]).rms
            })
            .collect();
        assert!(
            reference.check < 0.05 * errors[2],
            "{method:?}: the reference (check {:.2e}) is not converged enough for errors {errors:?}",
            reference.check
        );
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!(
                (order - method.order()).abs() <= 0.3,
                "{method:?}: measured order {order:.2} (errors {errors:?}), expected {}",
                method.order()
            );
        }
    }
}

/// A 6 x 6 cloth, 5 cm apart, lying flat and pinned at its two far corners, swinging down
/// under gravity; every spring type, with `stiffness` (structural, shear, bending) and
/// dashpots `damping`.
fn swinging_cloth(stiffness: [f64; 3], damping: f64) -> SimModel {
    let mut c = cloth(6, 6, 0.05);
    for p in &mut c.positions {
        *p = DVec3::new(p.x, 1.0, 1.0 - p.y);
    }
    c.stiffness = stiffness;
    c.damping = damping;
    c.pinned[0] = true;
    c.pinned[5] = true;
    let mut m = scene(vec![c]);
    m.gravity = DVec3::new(0.0, -9.81, 0.0);
    m
}

/// The iterations users run (the table's `few_iterations`: XPBD 1 either way, the other
/// iterative methods 4).
fn users_iterations(method: Integrator) -> u32 {
    method.few_iterations()
}

/// The substep counts the convergence tests step through, 4x apart.
const SUBSTEPS: [u32; 3] = [16, 64, 256];

/// Errors at `times[0]` of `method` at `SUBSTEPS`, with the iterations users run, against
/// `reference(i)` for the i-th count; asserts each falls at least 3 times per 4 times more
/// substeps until it is below `floor`.
fn assert_falls_3x_per_4x_substeps<'a>(
    base: &SimModel,
    method: Integrator,
    times: &[f64],
    reference: impl Fn(usize) -> &'a [Vec<DVec3>],
    floor: f64,
) {
    let iterations = users_iterations(method);
    let errors: Vec<f64> = SUBSTEPS
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let m = with(base, method, n, iterations);
            error(&m, &cpu_run(&m, times).samples[0], reference(i)).rms
        })
        .collect();
    for pair in errors.windows(2).filter(|p| p[0] > floor) {
        assert!(
            pair[0] / pair[1] >= 3.0,
            "{method:?} ({iterations} iterations): the error fell only {:.2}x for 4x the substeps (errors {errors:?})",
            pair[0] / pair[1]
        );
    }
}

/// The iterations users run (XPBD 1, implicit and VBD 4) converge to the right motion as the
/// substep shrinks: each method's error at t = 1 s against Verlet at 4096 substeps per frame
/// falls at least 3 times per 4 times more substeps, from 16 to 64 and from 64 to 256 (first
/// order gives 4), on a soft cloth (50 N/m) with strong dashpots (b / k = 4 ms). Measured:
/// 3.8 to 4.5 for every method but VBD (12 and 3.0, at the reference's floor by 256
/// substeps): the dashpots make the reference itself, and every method here, first order.
/// The f64 reference's own error (about `check`) is checked to be below a tenth of the errors
/// measured. (XPBD dividing each particle's correction by its spring count, or implicit sweeps
/// damped by a fixed 1/2, fail this: a fixed fraction of every spring force is lost, whatever
/// the substep.) The next two tests take a stiff cloth, where the order shows.
#[test]
fn iterative_methods_converge_at_the_iterations_users_run() {
    let base = swinging_cloth([50.0, 10.0, 2.0], 0.2);
    let times = [1.0];
    let reference = accuracy::reference(&base, &times, 4096);
    let smallest = 9e-5; // Verlet's error at 256 substeps here
    assert!(
        reference.check < 0.1 * smallest,
        "the reference (check {:.2e}) is not converged",
        reference.check
    );
    for method in Integrator::ALL {
        assert_falls_3x_per_4x_substeps(&base, method, &times, |_| &reference.samples[0], 0.0);
    }
}

/// On a cloth as stiff as the presets' (500 N/m, weak dashpots), the iterative methods at the
/// iterations users run converge to their converged solve, BDF2 itself (VBD at 30 iterations),
/// as the substep shrinks: the distance at t = 0.5 s falls at least 3 times per 4 times more
/// substeps (measured: XPBD 15x and 12x; implicit 17x and 16x, since 2026-11-26 when its
/// dashpots became implicit as VBD's (6.1x and 4.0x before, first order: the explicit
/// dashpots' O(dt) difference); VBD at 4 iterations is already within 2e-9, then at the f64
/// floor).
#[test]
fn iterative_methods_converge_to_their_solve_on_a_stiff_cloth() {
    let base = swinging_cloth([500.0, 100.0, 20.0], 0.01);
    let times = [0.5];
    let converged: Vec<Vec<Vec<DVec3>>> = SUBSTEPS
        .iter()
        .map(|&n| cpu_run(&with(&base, Integrator::Vbd, n, 30), &times).samples[0].clone())
        .collect();
    for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
        // Below 1e-9 of the size, rounding (f64, over thousands of substeps) is the floor.
        assert_falls_3x_per_4x_substeps(&base, method, &times, |i| &converged[i], 1e-9);
    }
}

/// Against the exact motion on the same stiff cloth (Verlet at 4096 substeps a frame, t = 1 s),
/// at the iterations users run, the iterative methods are second order and as accurate as the
/// explicit methods where those are stable: (a) each one's error falls at least 8 times per 4
/// times more substeps from 16 to 64 and 64 to 256 (second order gives 16; measured XPBD 14.3
/// and 11.9, implicit 38 and 17 (Newton-CG; 23 and 21 by projective dynamics), VBD 39 and 17;
/// symplectic Euler 6.5 and 4.7), and (b) at 256 substeps it is within 3 times symplectic
/// Euler's error (measured 0.62, 0.63 and 0.61 times its 6.9e-5). XPBD by Jacobi at one iteration falls 16.1 and 5.8 times (1.6 times symplectic
/// Euler's error at 256): each spring's dashpot sees its neighbours' prediction, not their
/// update, a first-order term that shows once the rest is small (undamped it falls 12.0 and
/// 17.4), so it is held to first order (4x) here. On implicit Euler, which they were built on
/// before BDF2, (a) fell 1.2 to 2.5 times and (b) was 40 times: its damping of the stretch
/// modes, w^2 dt / 2 a second, is the error on a stiff, lightly damped cloth. The reference's own error (`check`, 1.1e-6) is
/// checked to be below a tenth of the errors measured.
#[test]
fn iterative_methods_are_second_order_on_a_stiff_cloth() {
    let base = swinging_cloth([500.0, 100.0, 20.0], 0.01);
    let times = [1.0];
    let reference = accuracy::reference(&base, &times, 4096);
    let errors = |method| -> Vec<f64> {
        let iterations = users_iterations(method);
        SUBSTEPS
            .iter()
            .map(|&n| {
                let m = with(&base, method, n, iterations);
                error(&m, &cpu_run(&m, &times).samples[0], &reference.samples[0]).rms
            })
            .collect()
    };
    let euler = errors(Integrator::SymplecticEuler);
    for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
        let e = errors(method);
        assert!(
            reference.check < 0.1 * e[2],
            "the reference (check {:.2e}) is not converged",
            reference.check
        );
        let least = if method == Integrator::XpbdJacobi { 4.0 } else { 8.0 };
        for pair in e.windows(2) {
            assert!(
                pair[0] / pair[1] >= least,
                "{method:?}: the error fell only {:.1}x for 4x the substeps (errors {e:?})",
                pair[0] / pair[1]
            );
        }
        assert!(
            e[2] <= 3.0 * euler[2],
            "{method:?} at 256 substeps: error {:.2e}, symplectic Euler's {:.2e}",
            e[2],
            euler[2]
        );
    }
}

/// A chain hanging at rest (no bending springs) must stretch as the closed form says, each
/// spring by the weight below it over k, within 1% for every method at 64 substeps and the
/// iterations users run (XPBD 1, the others 4). XPBD's one iteration leaves a bias of
/// 2 (k h^2 + b h) / m with its solve's step h = 2 dt / 3: 0.1% here (measured 0.095%); the
/// others converge at rest. Run 2 s: the drag settles the
/// chain to 1e-13 of its initial motion.
#[test]
fn a_hanging_chain_stretches_by_its_weight() {
    for method in Integrator::ALL {
        let m = hanging_chain(method);
        let run = cpu_run(&m, &[2.0]);
        let e = static_stretch_error(&m, &run.samples[0][0]);
        assert!(e < 0.01, "{method:?}: the stretch is {:.2}% off the closed form", 100.0 * e);
    }
}

/// The iterative methods at one substep of 1/60 s (10 iterations) stay finite, their energy
/// does not blow up (it may rise a little: at 1e5 N/m the implicit method's unconverged solve
/// leaves the chain stretched, 1.4 -> 2.9 J of mostly elastic energy) and their strain stays
/// bounded, for stiffness over four decades (100 to 1e6 N/m), where symplectic Euler, past its
/// predicted limit over the whole range, blows up.
#[test]
fn iterative_methods_are_stable_over_four_decades_at_a_sixtieth() {
    let iterative = Integrator::ALL.into_iter().filter(|m| m.iterative());
    for (k, method) in
        [100.0, 1e3, 1e4, 1e5, 1e6].into_iter().flat_map(|k| iterative.clone().map(move |m| (k, m)))
    {
        let mut m = with(&chain(k), method, 1, 10);
        m.objects[0].positions.iter_mut().enumerate().for_each(|(i, p)| p.y += 0.01 * (i % 2) as f64);
        let run = cpu_run(&m, &[2.0]);
        let (e0, e1) = run.energy;
        assert!(run.finite, "{method:?}, k = {k}: non-finite state");
        assert!(e1 <= 10.0 * e0.abs(), "{method:?}, k = {k}: energy blew up from {e0} to {e1} J");
        assert!(run.max_strain < 1.0, "{method:?}, k = {k}: strain {}", run.max_strain);
        let euler = cpu_run(&with(&chain(k), Integrator::SymplecticEuler, 1, 1), &[2.0]);
        assert!(!euler.finite || euler.max_strain > 1.0, "k = {k}: symplectic Euler did not blow up");
    }
}

/// Undamped, Verlet keeps the energy to a small drift; the implicit method (BDF2) dissipates.
#[test]
fn energy_drift_is_small_for_verlet_and_negative_for_implicit() {
    let base = chain(50.0);
    let drift = |method| {
        let m = with(&base, method, 16, 20);
        let (e0, e1) = cpu_run(&m, &[2.0]).energy;
        (e1 - e0) / e0.abs()
    };
    let verlet = drift(Integrator::Verlet);
    let implicit = drift(Integrator::Implicit);
    assert!(verlet.abs() < 1e-3, "Verlet energy drift {verlet:.2e}");
    assert!(implicit < -1e-3, "the implicit method (BDF2) should dissipate, drift {implicit:.2e}");
}

/// Few iterations leave the implicit solve unconverged (the cloth sags and stretches) but must
/// not blow up: a 16 x 16 cloth hanging from two corners at one 1/60 s substep, 1 to 5
/// iterations, 1e2 and 1e4 N/m, 2 s: every velocity stays finite and below the guard's default
/// 100 m/s. (When the implicit method was projective dynamics, its undamped Jacobi sweeps blew
/// up here at 1 and 3 iterations, and Chebyshev from the first iteration at 2 and 3.) Every
/// iterative method: XPBD by Jacobi without its step bound (beta = 1, plain Jacobi) blows up
/// here at every count.
#[test]
fn iterative_methods_with_few_iterations_do_not_blow_up() {
    use msdsim::sim::cpu::CpuSim;
    for iterations in [1, 2, 3, 5] {
        for k in [1e2, 1e4] {
            let mut c = cloth(16, 16, 0.05);
            c.stiffness = [k, k / 4.0, k / 10.0];
            c.pinned[0] = true;
            c.pinned[15] = true;
            for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
                let mut m = with(&scene(vec![c.clone()]), method, 1, iterations);
                m.gravity = DVec3::new(0.0, -9.81, 0.0);
                let mut sim = CpuSim::new(&m);
                for _ in 0..120 {
                    sim.step_frame();
                }
                let fastest = sim.objects()[0].v.iter().map(|v| v.length()).fold(0.0, f64::max);
                assert!(
                    fastest < 100.0,
                    "{method:?}, {iterations} iterations, k = {k}: a particle at {fastest} m/s"
                );
            }
        }
    }
}

/// The BDF2 history and contacts: a flat 8 x 8 cloth dropped from 0.3 m, sliding at 1 m/s, onto
/// a frictionless ground (margin 1 cm), 16 substeps, 1.5 s. A history kept as positions and
/// velocities would remember the fall through the contact and kick the cloth back up (the
/// extrapolation 4 v_n - v_{n-1} with v_n = 0); kept as the solve's own increments, the contact
/// shifts it with the particle. Every method must land without a bounce (the mean height after
/// the first touch stays within 0.1 mm of the margin, where the contact leaves the explicit
/// methods) and keep sliding at 1 m/s (horizontal momentum, nothing acting along the ground:
/// within 1e-6 m/s). Measured: every method at the margin to the digits printed, 1.0000 m/s.
#[test]
fn iterative_methods_land_without_bouncing_and_keep_sliding() {
    use msdsim::sim::collider::{ColliderModel, Motion, Shape};
    use msdsim::sim::cpu::CpuSim;
    use msdsim::sim::turn::Turn;
    for method in Integrator::ALL {
        let n = 8;
        let mut c = cloth(n, n, 0.04);
        for (i, p) in c.positions.iter_mut().enumerate() {
            *p = DVec3::new((i as u32 % n) as f64 * 0.04 - 0.14, 0.3, (i as u32 / n) as f64 * 0.04 - 0.14);
        }
        c.velocities = vec![DVec3::new(1.0, 0.0, 0.0); c.positions.len()];
        c.stiffness = [200.0, 50.0, 5.0];
        c.damping = 0.02;
        c.margin = 0.01;
        c.friction = 0.0;
        let mut m = with(&scene(vec![c]), method, 16, users_iterations(method));
        m.gravity = DVec3::new(0.0, -9.81, 0.0);
        let ground = Shape::Ground { height: 0.0 };
        m.colliders = vec![ColliderModel {
            shape: ground,
            friction: None,
            motion: Motion::Fixed,
            turn: Turn::default(),
        }];
        let mut sim = CpuSim::new(&m);
        let (mut touched, mut highest) = (false, 0.0f64);
        for _ in 0..90 {
            sim.step_frame();
            let x = &sim.objects()[0].x;
            touched |= x.iter().any(|p| p.y < 0.0101);
            if touched {
                highest = highest.max(x.iter().map(|p| p.y).sum::<f64>() / x.len() as f64);
            }
        }
        assert!(touched, "{method:?}: the cloth never landed");
        assert!(highest < 0.0101, "{method:?}: bounced to a mean height of {highest} m");
        for v in &sim.objects()[0].v {
            assert!((v.x - 1.0).abs() < 1e-6 && v.y.abs() < 1e-6, "{method:?}: a particle at {v} m/s");
        }
    }
}

/// A particle without BDF2 history (the first substep, after a reset, an upload or a changed
/// substep) starts from one Jacobi step of implicit Euler (`sim::cpu::integrators::restart`):
/// a chain placed at rest exactly where the closed form says it hangs (each spring stretched
/// by the weight below it over k) must stay there, for every iterative method at the
/// iterations users run. Measured after one substep of 1/3840 s: 8.5e-4 m/s (g dt / 3) for
/// every method when the restart took the springs into account through the solve alone; now
/// 8.5e-8 for the implicit method and VBD, and 1.1e-5 for XPBD, whose one iteration does not
/// hold the chain exactly at the closed form (its bias, above). Bound: 5e-5 m/s, a
/// seventeenth of the old start.
#[test]
fn a_chain_at_rest_in_equilibrium_starts_at_rest() {
    for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
        let mut m = hanging_chain(method);
        let o = &mut m.objects[0];
        let (n, weight) = (o.positions.len(), o.mass * 9.81);
        let mut y = o.positions[0].y;
        for s in 1..n {
            y -= o.spacing[0] + (n - s) as f64 * weight / o.stiffness[0];
            o.positions[s].y = y;
        }
        m.frame_dt /= m.substeps as f64; // one frame, one substep of 1/3840 s
        m.substeps = 1;
        let mut cpu = msdsim::sim::cpu::CpuSim::new(&m);
        cpu.step_frame();
        let speed = cpu.objects()[0].v.iter().map(|v| v.length()).fold(0.0, f64::max);
        assert!(speed < 5e-5, "{method:?}: {speed} m/s after one substep");
    }
}
