//! Turbulence of the aerodynamic wind: a sum of random Fourier modes (Kraichnan 1970),
//! u'(x, t) = sum_m a_m sin(k_m . x + phi_m - c_m t) with each amplitude a_m across its wave
//! vector k_m, so the field has no divergence (div u' = sum_m (a_m . k_m) cos(...) = 0
//! exactly) and a mean of zero: the preset's wind stays the mean. The modes travel with the
//! mean wind U (c_m = k_m . U + omega_m: eddies carried downwind, Taylor's frozen turbulence)
//! and change at about the frequency asked. All of it comes from the seed, so a run repeats;
//! the GPU reads the modes from the globals (glsl/include/air.glsl's `turbulence`), with the
//! phases at each frame's start taken modulo 2 pi here in f64.

use glam::DVec3;

/// Modes of the field (`TURBULENCE_MODES` in glsl/include/layout.glsl): eight give eddies
/// of a few sizes and directions at a cost of eight sines a particle and force evaluation.
pub const TURBULENCE_MODES: usize = 8;

/// One Fourier mode: wave vector `k` [1/m], amplitude `a` [m/s] (across k), phase `phase` at
/// t = 0 and its rate `rate` = k . U + omega [1/s].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    pub k: DVec3,
    pub a: DVec3,
    pub phase: f64,
    pub rate: f64,
}

/// The turbulent part of the air's velocity (`sim::model::AirModel::turbulence`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turbulence {
    pub modes: [Mode; TURBULENCE_MODES],
}

/// SplitMix64 (Steele et al. 2014): a few lines, the same stream on every platform.
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

impl Turbulence {
    /// A field of root-mean-square speed `strength` [m/s], eddies of about `scale` [m]
    /// (wavelengths from half to twice it), changing at about `frequency` [Hz] as they are
    /// carried along by the mean wind `mean` [m/s]; `seed` picks the modes.
    pub fn new(strength: f64, scale: f64, frequency: f64, mean: DVec3, seed: u32) -> Self {
        let mut s = Stream(u64::from(seed) ^ 0x6D73_6473_696D_7475);
        let tau = std::f64::consts::TAU;
        // Each mode's mean square is a^2 / 2: the modes' sum is strength^2.
        let amplitude = strength * (2.0 / TURBULENCE_MODES as f64).sqrt();
        let modes = std::array::from_fn(|_| {
            let z = 2.0 * s.next() - 1.0;
            let around = tau * s.next();
            let r = (1.0 - z * z).max(0.0).sqrt();
            let dir = DVec3::new(r * around.cos(), r * around.sin(), z);
            let k = dir * (tau / scale * 2f64.powf(2.0 * s.next() - 1.0));
            let (e1, e2) = dir.any_orthonormal_pair();
            let turn = tau * s.next();
            let a = (e1 * turn.cos() + e2 * turn.sin()) * amplitude;
            let omega = tau * frequency * (0.5 + s.next());
            Mode { k, a, phase: tau * s.next(), rate: k.dot(mean) + omega }
        });
        Self { modes }
    }

    /// The turbulent velocity at `x` and time `t` [m/s].
    pub fn velocity(&self, x: DVec3, t: f64) -> DVec3 {
        self.modes.iter().map(|m| m.a * (m.k.dot(x) + m.phase - m.rate * t).sin()).sum()
    }

    /// The modes as the GPU reads them at a frame starting at `t`: per mode (k, rate) and
    /// (a, the phase at t modulo 2 pi), so that within the frame each phase is k . x plus a
    /// number under 2 pi less the rate times the time since the frame began.
    pub fn gpu(&self, t: f64) -> ([[f32; 4]; TURBULENCE_MODES], [[f32; 4]; TURBULENCE_MODES]) {
        let f = |v: DVec3, w: f64| [v.x as f32, v.y as f32, v.z as f32, w as f32];
        let waves = self.modes.map(|m| f(m.k, m.rate));
        // (the rate as the shaders have it, so that the phase at any time is the f32 rate's)
        let phase = |m: Mode| (m.phase - m.rate as f32 as f64 * t).rem_euclid(std::f64::consts::TAU);
        let amplitudes = self.modes.map(|m| f(m.a, phase(m)));
        (waves, amplitudes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field() -> Turbulence {
        Turbulence::new(2.0, 0.5, 1.0, DVec3::new(5.0, 0.0, 0.0), 7)
    }

    /// No divergence: central differences of the field on a grid (step 1 mm, eddies of 0.25
    /// to 1 m) sum to nothing but their truncation, O(h^2 |k|^2): below 1e-4 of the field's
    /// gradient.
    #[test]
    fn the_field_has_no_divergence() {
        let f = field();
        let h = 1e-3;
        let mut worst: f64 = 0.0;
        let mut gradient: f64 = 0.0;
        for i in 0..8 {
            for j in 0..8 {
                for k in 0..8 {
                    let x = DVec3::new(i as f64, j as f64, k as f64) * 0.13;
                    let t = 0.37 * (i + j + k) as f64;
                    let d =
                        |axis: DVec3| (f.velocity(x + axis * h, t) - f.velocity(x - axis * h, t)) / (2.0 * h);
                    let (dx, dy, dz) = (d(DVec3::X), d(DVec3::Y), d(DVec3::Z));
                    worst = worst.max((dx.x + dy.y + dz.z).abs());
                    gradient = gradient.max(dx.abs().max(dy.abs()).max(dz.abs()).max_element());
                }
            }
        }
        assert!(gradient > 1.0, "the field varies: {gradient} 1/s");
        assert!(worst < 1e-4 * gradient, "divergence {worst:e} against a gradient of {gradient}");
    }

    /// Zero mean and the asked strength: over a long time at one point (the modes' phases
    /// run through many periods) the mean is within 5% of the strength of zero and the root
    /// mean square within 10% of the strength.
    #[test]
    fn the_field_has_no_mean_and_the_asked_strength() {
        let f = field();
        let samples = 200_000;
        let (mut sum, mut square) = (DVec3::ZERO, 0.0);
        for s in 0..samples {
            let u = f.velocity(DVec3::new(0.3, 1.2, -0.4), s as f64 * 1e-3);
            sum += u;
            square += u.length_squared();
        }
        let mean = sum / samples as f64;
        let rms = (square / samples as f64).sqrt();
        assert!(mean.length() < 0.05 * 2.0, "mean {mean}");
        assert!((rms - 2.0).abs() < 0.2, "rms {rms}");
    }

    /// The seed picks the field: the same seed the same modes, another seed others.
    #[test]
    fn a_seed_repeats_its_field() {
        let mean = DVec3::new(5.0, 0.0, 0.0);
        assert_eq!(Turbulence::new(2.0, 0.5, 1.0, mean, 7), field());
        assert_ne!(Turbulence::new(2.0, 0.5, 1.0, mean, 8), field());
    }

    /// The GPU's phases at a frame's start, advanced by the time since, give the field whose
    /// rates are rounded to f32 as the shaders read them (the CPU reference's), after 20
    /// minutes too.
    #[test]
    fn the_gpu_phases_give_the_field() {
        let f = field();
        let rounded = Turbulence { modes: f.modes.map(|m| Mode { rate: m.rate as f32 as f64, ..m }) };
        let (t0, since, x) = (1234.5, 0.01, DVec3::new(0.2, 0.7, 0.1));
        let (waves, amplitudes) = f.gpu(t0);
        let u: DVec3 = (waves.iter().zip(&amplitudes))
            .map(|(k, a)| {
                let phase = DVec3::new(k[0] as f64, k[1] as f64, k[2] as f64).dot(x) + a[3] as f64
                    - k[3] as f64 * since;
                DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64) * phase.sin()
            })
            .sum();
        let exact = rounded.velocity(x, t0 + since);
        assert!((u - exact).length() < 1e-4 * 2.0, "{u} against {exact}");
    }
}
