//! The aerodynamic wind against closed forms: a free square plate face-on to a uniform stream
//! (no gravity) is pushed by normal drag k (u - V)^2 with k = 1/2 rho C_n A / M, so its speed is
//! V(t) = u - 1 / (1/u + k t) and its travel X(t) = u t - ln(1 + k u t) / k; the same plate
//! edge-on feels only the tangential drag (C_t / C_n = 1/60 of it) and travels a small fraction
//! of that. CPU reference and both GPU paths. On lavapipe with validation and synchronization
//! validation.

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::integrator::Integrator;
use msdsim::sim::model::{AirModel, SimModel};

const SPEED: f64 = 5.0;
const FRAMES: usize = 30; // 0.5 s

/// An 8 x 8 plate 0.35 m wide (5 cm spacing, 64 g), stiff in bending too so it stays flat, in the plane spanned by `along` and
/// `across`, in a uniform stream of 5 m/s along -z (a cone wide enough to cover it fully).
fn plate(along: DVec3, across: DVec3) -> SimModel {
    let n = 8u32;
    let mut c = cloth(n, n, 0.05);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i as u32 % n) as f64 - 3.5, (i as u32 / n) as f64 - 3.5);
        *p = along * (col * 0.05) + across * (row * 0.05) + DVec3::new(0.0, 1.0, 0.0);
    }
    c.stiffness = [2000.0, 500.0, 2000.0];
    c.damping = 0.05;
    c.mass = 0.001;
    let mut s = scene(vec![c]);
    s.substeps = 64; // the stiff plate's stability limit is 0.44 ms
    let mut w = wind([0.0, 1.0, 10.0], [0.0, 0.0, -1.0], 0.0, 1.0, 1.2);
    w.air = Some(AirModel {
        speed: SPEED,
        normal: 0.5 * 1.2 * 1.2,
        tangent: 0.5 * 1.2 * 0.02,
        lift: 0.0,
        turbulence: None,
    });
    s.wind = Some(w);
    s
}

/// Travel of the plate's centre along the wind after `FRAMES` frames: CPU, fused, per stage.
fn travel(s: &SimModel) -> Vec<(&'static str, f64)> {
    let centre = |x: &[DVec3]| -(x.iter().sum::<DVec3>() / x.len() as f64).z;
    let start = centre(&s.objects[0].positions);
    let ctx = gpu();
    let out =
        every_path(&ctx, s, FRAMES).into_iter().map(|(path, x, _)| (path, centre(&x) - start)).collect();
    assert_clean(&ctx);
    out
}

/// Face-on within 2% of the rigid plate's closed form (the stream is uniform over it; its edge
/// particles carry half the area for the same mass, so it bows a little: 5 mm, 0.9% less
/// travel measured). Edge-on at most a fifth as far (the bound), and within 10% of
/// tangential drag alone on a plate that barely moves, X = 1/2 k (C_t / C_n) u^2 t^2 (measured
/// 0.069 against 0.072 m: it does move a little), 0.05 of the face-on travel.
#[test]
fn a_plate_face_on_follows_the_drag_law_and_edge_on_barely_moves() {
    check_plate(Integrator::SymplecticEuler);
}

/// The same with an iterative method (the wind enters its BDF2 prediction).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn the_drag_law_holds_with_an_iterative_method() {
    check_plate(Integrator::Vbd);
}

fn check_plate(method: Integrator) {
    let with = |mut s: SimModel| {
        s.integrator = method;
        if method != Integrator::SymplecticEuler {
            s.substeps = 16; // stable at any stiffness
        }
        s
    };
    let face = travel(&with(plate(DVec3::X, DVec3::Y)));
    let area = 0.35 * 0.35;
    let k = 0.5 * 1.2 * 1.2 * area / 0.064;
    let t = FRAMES as f64 / 60.0;
    let expected = SPEED * t - (1.0 + k * SPEED * t).ln() / k;
    for &(path, x) in &face {
        assert!((x / expected - 1.0).abs() < 0.02, "{path}: face-on travel {x} m against {expected} m");
    }
    let edge = travel(&with(plate(DVec3::X, DVec3::Z)));
    for (&(path, e), &(_, f)) in edge.iter().zip(&face) {
        println!("{method:?} {path}: face-on {f:.4} m, edge-on {e:.5} m ({:.3})", e / f);
        assert!(e.abs() <= 0.2 * f, "{path}: edge-on travel {e} m against face-on {f} m");
        let tangential = 0.5 * k * (0.02 / 1.2) * SPEED * SPEED * t * t;
        assert!((e / tangential - 1.0).abs() < 0.1, "{path}: edge-on travel {e} m against {tangential} m");
    }
}

/// A free rod (a rope of two nodes 0.3 m apart: one spring keeps it straight) across the same
/// stream follows the same law with its area the diameter times its length (k = 1/2 rho C_n
/// 2 r L / M), within 2%; along the stream it feels only the tangential drag and travels at
/// most a fifth as far. (A longer rope bows into a U, its end nodes carrying half the area
/// for the same mass, as a string in the wind does.) CPU and both GPU paths.
#[test]
fn a_rope_across_the_stream_follows_the_drag_law() {
    let line = |dir: DVec3| {
        let mut r = rope(2, 0.3);
        for (i, p) in r.positions.iter_mut().enumerate() {
            *p = dir * ((i as f64 - 0.5) * 0.3) + DVec3::new(0.0, 1.0, 0.0);
        }
        r.stiffness = [2000.0, 0.0, 0.0];
        r.mass = 0.011;
        r.rope_radius = 0.02;
        let mut s = plate(DVec3::X, DVec3::Y);
        s.objects = vec![r];
        s
    };
    let across = travel(&line(DVec3::X));
    let k = 0.5 * 1.2 * 1.2 * (2.0 * 0.02 * 0.3) / 0.022;
    let t = FRAMES as f64 / 60.0;
    let expected = SPEED * t - (1.0 + k * SPEED * t).ln() / k;
    let along = travel(&line(DVec3::Z));
    for (&(path, x), &(_, a)) in across.iter().zip(&along) {
        println!("{path}: across {x:.4} m, along {a:.5} m");
        assert!((x / expected - 1.0).abs() < 0.02, "{path}: travel across {x} m against {expected} m");
        assert!(a.abs() <= 0.2 * x, "{path}: travel along {a} m against {x} m across");
    }
}

/// Lift against the flat plate's closed form 1/2 rho C_L sin(2 alpha) |u|^2 A, across the
/// stream in the plane of the stream and the plate's normal: the plate of `plate`, 10 g
/// particles (0.64 kg: its speed after a frame is 1% of the stream's, so the relative wind
/// barely changes), no gravity, at angles of attack 0 (edge-on), 30, 45, 60 and 90 degrees
/// (face-on), one frame with the lift coefficient 1 and one with 0: the difference of the
/// plate's momentum is the lift's impulse. It must be 1/2 rho sin(2 alpha) |u|^2 A t across the
/// stream within 3% of the largest (the rest of the wind moves the plate a little within the
/// frame), and its part along the stream under 3% of it: so none edge-on or face-on (measured
/// 1.4%, 1.0% and 0.4% short at 30, 45 and 60 degrees, along it at most 0.3%, edge-on 0 and
/// face-on 2e-6 of it). CPU reference and both GPU paths.
#[test]
fn lift_is_a_flat_plates_across_the_stream() {
    let ctx = gpu();
    let area = 0.35 * 0.35;
    let impulse = 0.5 * 1.2 * SPEED * SPEED * area / 60.0; // at sin(2 alpha) = 1, C_L = 1
    let mut failures = Vec::new();
    for degrees in [0.0f64, 30.0, 45.0, 60.0, 90.0] {
        let a = degrees.to_radians();
        let momentum = |lift: f64| -> Vec<(&'static str, DVec3)> {
            let mut s = plate(DVec3::X, DVec3::new(0.0, a.sin(), -a.cos()));
            s.objects[0].mass = 0.01;
            let w = s.wind.as_mut().unwrap();
            w.air.as_mut().unwrap().lift = 1.2 * lift;
            let m = s.objects[0].mass;
            every_path(&ctx, &s, 1)
                .into_iter()
                .map(|(path, _, v)| (path, v.iter().sum::<DVec3>() * m))
                .collect()
        };
        let want = impulse * (2.0 * a).sin();
        for ((path, with), (_, without)) in momentum(1.0).into_iter().zip(momentum(0.0)) {
            let lift = with - without;
            let (across, along) = (lift.y.abs(), lift.z.abs());
            let what = format!(
                "{degrees} degrees, {path}: lift impulse {:?} N s, across {across:.5e} against {want:.5e}, along {along:.1e}",
                lift.to_array()
            );
            println!("{what}");
            if (across - want).abs() > 0.03 * impulse
                || along > 0.03 * impulse
                || lift.x.abs() > 1e-6 * impulse
            {
                failures.push(what);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_clean(&ctx);
}

/// At the default settings (normal drag 1.2, tangential 0.02, no lift) a plate edge-on to the
/// air feels at most 5% of the push it feels face-on: the momentum the plate of
/// `lift_is_a_flat_plates_across_the_stream` (10 g particles, so its speed stays 1% of the
/// stream's) takes in one frame, edge-on against face-on, is C_t / C_n = 1/60 (within 3% of it:
/// the plate moves a little within the frame). CPU reference and both GPU paths.
#[test]
fn edge_on_a_plate_feels_a_sixtieth_of_the_face_on_push() {
    let ctx = gpu();
    let push = |across: DVec3| -> Vec<(&'static str, f64)> {
        let mut s = plate(DVec3::X, across);
        s.objects[0].mass = 0.01;
        let m = s.objects[0].mass;
        every_path(&ctx, &s, 1)
            .into_iter()
            .map(|(path, _, v)| (path, -v.iter().sum::<DVec3>().z * m))
            .collect()
    };
    for ((path, edge), (_, face)) in push(DVec3::Z).into_iter().zip(push(DVec3::Y)) {
        let ratio = edge / face;
        println!("{path}: edge-on {edge:.4e} N s, face-on {face:.4e} N s, ratio {ratio:.4}");
        assert!(ratio <= 0.05, "{path}: edge-on the plate feels {ratio} of the face-on push");
        assert!((ratio * 60.0 - 1.0).abs() < 0.03, "{path}: {ratio} against 1/60");
    }
    assert_clean(&ctx);
}

/// The wind's turbulence (`sim::turbulence`: its divergence, mean and strength are checked
/// there) moves the face-on plate as the reference has it, on both GPU paths, with the explicit
/// and an iterative method (the wind enters its prediction): every particle within 1 mm of the
/// reference after 0.5 s (the plate travels about 1 m; f32 against f64), where turbulence of
/// 2 m/s in eddies of 0.3 m moves particles 5 cm and more from where the steady wind puts them.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn turbulence_moves_the_plate_as_the_reference_has_it() {
    let ctx = gpu();
    for method in [Integrator::SymplecticEuler, Integrator::Vbd] {
        let with = |turbulent: bool| {
            let mut s = plate(DVec3::X, DVec3::Y);
            s.integrator = method;
            if method != Integrator::SymplecticEuler {
                s.substeps = 16;
            }
            let w = s.wind.as_mut().unwrap();
            let mean = w.direction * SPEED;
            let t = msdsim::sim::turbulence::Turbulence::new(2.0, 0.3, 2.0, mean, 3);
            w.air.as_mut().unwrap().turbulence = turbulent.then_some(t);
            every_path(&ctx, &s, FRAMES)
        };
        let (steady, turbulent) = (with(false), with(true));
        let apart =
            |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
        let reference = &turbulent[0].1;
        let moved = apart(reference, &steady[0].1);
        println!("{method:?}: turbulence moves the plate up to {moved:.4} m from the steady wind's");
        assert!(moved > 0.05, "{method:?}: turbulence moved the plate only {moved} m");
        for (path, x, _) in &turbulent[1..] {
            let off = apart(x, reference);
            println!("{method:?}, {path}: {off:.2e} m from the reference");
            assert!(off < 1e-3, "{method:?}, {path}: {off} m from the reference");
        }
    }
    assert_clean(&ctx);
}

/// How the flag preset flutters over `frames` frames from the second second on: the free edge's
/// amplitude across the wind (half of its max - min) [m], the dominant frequency [Hz] of its
/// motion across the wind, the share of the motion's power (its mean taken out) within two bins
/// of that frequency, and the phase [rad] at that frequency of each quarter of the flag's length
/// (the columns a quarter, a half, three quarters and all the way from the pole), each column
/// taken as its particles' mean. Across the wind is horizontal and square to the wind's axis.
fn flag_flutter(overrides: &[&str], frames: usize) -> Flutter {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let scene =
        msdsim::scene::load(std::path::Path::new("presets/flag.toml"), &overrides).expect("the preset loads");
    let model = msdsim::scene::to_model(&scene);
    let axis = model.wind.as_ref().expect("the flag has wind").direction;
    let across = DVec3::Y.cross(axis).normalize();
    let cols = model.objects[0].dims[0] as usize;
    let columns = [cols / 4, cols / 2, 3 * cols / 4, cols - 1];
    let ctx = gpu();
    let mut signals: [Vec<f64>; 4] = Default::default();
    run_gpu(&ctx, &model, frames, |f, states| {
        let x = states[0].positions();
        for (signal, &c) in signals.iter_mut().zip(&columns) {
            let column: Vec<DVec3> = x.iter().skip(c).step_by(cols).copied().collect();
            if f >= 60 {
                signal.push((column.iter().sum::<DVec3>() / column.len() as f64).dot(across));
            }
        }
    });
    assert_clean(&ctx);
    // Each signal's Fourier coefficients at k / T (60 samples a second), its mean taken out.
    let n = signals[3].len();
    let spectrum = |signal: &[f64]| -> Vec<(f64, f64)> {
        let mean = signal.iter().sum::<f64>() / n as f64;
        (1..n / 2)
            .map(|k| {
                signal.iter().enumerate().fold((0.0, 0.0), |(re, im), (j, s)| {
                    let a = std::f64::consts::TAU * (k * j) as f64 / n as f64;
                    (re + (s - mean) * a.cos(), im + (s - mean) * a.sin())
                })
            })
            .collect()
    };
    let edge = spectrum(&signals[3]);
    let power: Vec<f64> = edge.iter().map(|(re, im)| re * re + im * im).collect();
    let peak = (0..power.len()).max_by(|&a, &b| power[a].total_cmp(&power[b])).unwrap();
    let total: f64 = power.iter().sum();
    let band: f64 = power[peak.saturating_sub(2)..(peak + 3).min(power.len())].iter().sum();
    let phases = signals.each_ref().map(|s| {
        let (re, im) = spectrum(s)[peak];
        im.atan2(re)
    });
    let (lo, hi) = signals[3].iter().fold((f64::MAX, f64::MIN), |(lo, hi), &s| (lo.min(s), hi.max(s)));
    Flutter {
        amplitude: 0.5 * (hi - lo),
        frequency: (peak + 1) as f64 * 60.0 / n as f64,
        share: band / total,
        phases,
    }
}

/// What `flag_flutter` measures.
struct Flutter {
    amplitude: f64,
    frequency: f64,
    share: f64,
    phases: [f64; 4],
}

/// The flag preset flies in its default (aerodynamic) wind: over 7 s (from the second second
/// on, 60 samples a second) its free edge swings across the wind by at least a tenth of the
/// flag's 1 m height (measured 0.40 m), at a dominant frequency (the band of five bins, 0.71
/// Hz, around the peak holds at least 30% of the motion's power, where a broadband motion
/// would give 5 of 210 bins: measured 38% at 1.14 Hz) with waves running from the pole to the
/// free edge (at that frequency the phase grows from each quarter of the length to the next:
/// measured -2.11, -1.74, -1.56, -1.22 rad), and the guard never stops it. (The flutter is not
/// one tone: over 15 to 21 s the same band holds 23 to 29%.)
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn the_flag_flutters_with_waves_running_to_its_free_edge() {
    let Flutter { amplitude, frequency, share, phases } = flag_flutter(&[], 480);
    println!("amplitude {amplitude:.3} m, {frequency:.2} Hz, share {share:.2}, phases {phases:.2?} rad");
    assert!(amplitude >= 0.1, "the free edge swings only {amplitude} m");
    assert!(
        share >= 0.3 && (0.5..5.0).contains(&frequency),
        "no dominant frequency: {share} of the power at {frequency} Hz"
    );
    for (q, pair) in phases.windows(2).enumerate() {
        let lag = (pair[1] - pair[0] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(
            lag > 0.0,
            "quarter {} leads quarter {} by {} rad: no wave runs to the free edge ({phases:?})",
            q + 2,
            q + 1,
            -lag
        );
    }
}
