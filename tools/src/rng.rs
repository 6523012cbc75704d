//! A small seeded generator (SplitMix64) and the named input strategies of the measurements, so
//! every run of the `accuracy` tool and the accuracy test sees the same inputs.

use glam::{DVec3, Vec3};

/// SplitMix64 (Steele, Lea & Flood 2014): tiny, fast, and good enough for sampling.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// The generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` in `f32`: the top 24 bits of the next output.
    pub fn unit_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[a, b)` in `f32` arithmetic.
    pub fn range_f32(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.unit_f32()
    }

    /// Each component uniform in `[a, b)`, by [`range_f32`](Self::range_f32), `x` first.
    pub fn vec3_in(&mut self, a: f32, b: f32) -> Vec3 {
        let x = self.range_f32(a, b);
        let y = self.range_f32(a, b);
        let z = self.range_f32(a, b);
        Vec3::new(x, y, z)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[a, b)`.
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }

    /// Log-uniform in `[a, b)`, `0 < a < b`.
    pub fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.unit()).exp()
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// An index below `n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform on the unit sphere, in `f64`.
    pub fn unit_dvec3(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, 2.0 * core::f64::consts::PI);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// A unit `f32` vector: a uniform direction rounded to `f32` (unit to within an ulp).
    pub fn unit_vec3(&mut self) -> Vec3 {
        self.unit_dvec3().as_vec3()
    }

    /// A unit `f32` vector in the hemisphere around unit `n` (uniform over the hemisphere).
    pub fn hemisphere(&mut self, n: Vec3) -> Vec3 {
        let v = self.unit_dvec3();
        let v = if v.dot(n.as_dvec3()) < 0.0 { -v } else { v };
        v.as_vec3()
    }

    /// A unit `f32` vector at angle `θ` from unit `n`, at a random azimuth.
    pub fn at_angle(&mut self, n: Vec3, theta: f64) -> Vec3 {
        let n = n.as_dvec3().normalize();
        let t = self.unit_dvec3().reject_from_normalized(n).normalize();
        (theta.cos() * n + theta.sin() * t).as_vec3()
    }

    /// A value spread over the whole positive finite `f32` range, subnormals included.
    pub fn any_magnitude(&mut self) -> f32 {
        self.log_range(1e-45, 3.4e38) as f32
    }

    /// A vector whose components have independent random magnitudes over the whole `f32` range
    /// (and random signs; zero now and then).
    pub fn wild_vec3(&mut self) -> Vec3 {
        let mut c = [0f32; 3];
        for x in &mut c {
            *x = if self.chance(0.1) {
                0.0
            } else {
                let m = self.any_magnitude();
                if self.chance(0.5) { -m } else { m }
            };
        }
        Vec3::from_array(c)
    }
}
