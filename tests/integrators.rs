//! The integrators on the CPU reference (f64): convergence order against a converged
//! reference, unconditional stability of the implicit method, energy behaviour.

mod common;

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
/// limit is implicit Euler, order 1). The reference's own error is checked to be far below
/// the errors measured.
#[test]
fn each_integrator_converges_at_its_order() {
    let base = chain(50.0);
    let times = [0.5];
    let reference = accuracy::reference(&base, &times, 1024);
    for method in Integrator::ALL {
        let iterations = if method == Integrator::Xpbd { 60 } else { 20 };
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

/// The implicit method at one substep of 1/60 s (10 iterations) stays finite, its energy does
/// not blow up (it may rise a little: at 1e5 N/m the unconverged solve leaves the chain
/// stretched, 1.4 -> 2.9 J of mostly elastic energy) and its strain stays bounded, for stiffness
/// over four decades (100 to 1e6 N/m), where symplectic Euler, past its predicted limit over the
/// whole range, blows up.
#[test]
fn implicit_is_stable_over_four_decades_at_a_sixtieth() {
    for k in [100.0, 1e3, 1e4, 1e5, 1e6] {
        let mut m = with(&chain(k), Integrator::Implicit, 1, 10);
        m.objects[0].positions.iter_mut().enumerate().for_each(|(i, p)| p.y += 0.01 * (i % 2) as f64);
        let run = cpu_run(&m, &[2.0]);
        let (e0, e1) = run.energy;
        assert!(run.finite, "k = {k}: non-finite state");
        assert!(e1 <= 10.0 * e0.abs(), "k = {k}: energy blew up from {e0} to {e1} J");
        assert!(run.max_strain < 1.0, "k = {k}: strain {}", run.max_strain);
        let euler = cpu_run(&with(&chain(k), Integrator::SymplecticEuler, 1, 1), &[2.0]);
        assert!(!euler.finite || euler.max_strain > 1.0, "k = {k}: symplectic Euler did not blow up");
    }
}

/// Undamped, Verlet keeps the energy to a small drift; implicit Euler dissipates.
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
    assert!(implicit < -1e-3, "implicit Euler should dissipate, drift {implicit:.2e}");
}

/// Few iterations leave the implicit solve unconverged (the cloth sags and stretches) but must
/// not blow up: a 16 x 16 cloth hanging from two corners at one 1/60 s substep, 1 to 5
/// iterations, 1e2 and 1e4 N/m, 2 s: every velocity stays finite and below the guard's default
/// 100 m/s. (Undamped Jacobi sweeps blew up here at 1 and 3 iterations, Chebyshev from the first
/// iteration at 2 and 3: see sim::stability::JACOBI_DAMPING.)
#[test]
fn implicit_with_few_iterations_does_not_blow_up() {
    use msdsim::sim::cpu::CpuSim;
    for iterations in [1, 2, 3, 5] {
        for k in [1e2, 1e4] {
            let mut c = cloth(16, 16, 0.05);
            c.stiffness = [k, k / 4.0, k / 10.0];
            c.pinned[0] = true;
            c.pinned[15] = true;
            let mut m = with(&scene(vec![c]), Integrator::Implicit, 1, iterations);
            m.gravity = DVec3::new(0.0, -9.81, 0.0);
            let mut sim = CpuSim::new(&m);
            for _ in 0..120 {
                sim.step_frame();
            }
            let fastest = sim.objects()[0].v.iter().map(|v| v.length()).fold(0.0, f64::max);
            assert!(fastest < 100.0, "{iterations} iterations, k = {k}: a particle at {fastest} m/s");
        }
    }
}
