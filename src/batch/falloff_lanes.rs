//! Spot lights and the falloffs other than the polynomial one, sixteen lanes at a time: each
//! lane's direction, distance and attenuation factor by the scalar path's own operations, so they
//! are `shade`'s bit for bit, and the spot cone's power by the kernel's own (tested below at every
//! level).
//!
//! ```text
//! d² = (dx·dx + dy·dy) + dz·dz          (`length_squared`'s order, unfused)
//! d  = √d²,   L = (dx, dy, dz) · (1/d)   (IEEE square root and division)
//! f  = Attenuation::factor(d)            (FlatAttenuation::factor_in: one source for both)
//! c  = −(L·D)                            (the spot's cosine to its axis D)
//! spot = 0 where c < cos(cutoff) or c ≤ 0;  1 for no cone;  min(c, 1)^e otherwise
//! factor = min(f · spot, f32::MAX) where spot > 0, else 0
//! ```
//!
//! The power `min(c, 1)^e` is [`PowStrategy::Auto`](crate::PowStrategy::Auto)'s for `e`
//! (squaring for a whole `e ≤ 1024`, the degree-7 polynomial otherwise), within its
//! `max_relative_error` of `c^e` relative to `max(c^e, 2⁻²⁴)`, where `shade` calls `powf`:
//! `powf` lane by lane took half of a spot light's time in the kernel. The exponents 0 and 1 give
//! `powf`'s bits (1 and `c`).

use super::kernel::{SpotPow, pow};
use super::simd::Simd;
use crate::attenuation::{FactorArith, FlatAttenuation};
use crate::light::SpotLight;
use crate::math;

/// [`FactorArith`] on a level's sixteen lanes: plain (unfused) products and sums, the level's
/// `min`/`max`, whose NaN rule is `math::min_or`'s and `math::max_or`'s.
#[derive(Clone, Copy)]
pub(super) struct LaneArith<S>(pub(super) S);

impl<S: Simd> FactorArith for LaneArith<S> {
    type V = S::V;
    #[inline(always)]
    fn splat(self, x: f32) -> S::V {
        self.0.splat(x)
    }
    #[inline(always)]
    fn add(self, a: S::V, b: S::V) -> S::V {
        self.0.add(a, b)
    }
    #[inline(always)]
    fn sub(self, a: S::V, b: S::V) -> S::V {
        self.0.sub(a, b)
    }
    #[inline(always)]
    fn mul(self, a: S::V, b: S::V) -> S::V {
        self.0.mul(a, b)
    }
    #[inline(always)]
    fn div(self, a: S::V, b: S::V) -> S::V {
        self.0.div(a, b)
    }
    #[inline(always)]
    fn max_or(self, x: S::V, lo: S::V) -> S::V {
        self.0.max(x, lo)
    }
    #[inline(always)]
    fn min_or(self, x: S::V, hi: S::V) -> S::V {
        self.0.min(x, hi)
    }
    #[inline(always)]
    fn select_lt(self, a: S::V, b: S::V, x: S::V, y: S::V) -> S::V {
        self.0.select(self.0.lt(a, b), x, y)
    }
}

/// A falloff light's unit direction and factor per lane, from `d = light − p` (see the module
/// docs). Lanes whose squared distance leaves the kernel's range are flagged by the caller and
/// re-shaded by the scalar path: their values here (NaN or ∞ at `d = 0`) are discarded.
#[inline(always)]
pub(super) fn falloff<S: Simd>(
    s: S,
    d: &[S::V; 3],
    flat: &FlatAttenuation,
    spot: Option<(&SpotLight, SpotPow)>,
) -> ([S::V; 3], S::V) {
    let zero = s.splat(0.0);
    let max = s.splat(math::MAX);
    let dd = s.add(
        s.add(s.mul(d[0], d[0]), s.mul(d[1], d[1])),
        s.mul(d[2], d[2]),
    );
    let dist = s.sqrt(dd);
    let inv = s.div(s.splat(1.0), dist);
    let l = [s.mul(d[0], inv), s.mul(d[1], inv), s.mul(d[2], inv)];
    // `clamp_or_lo(dist, 0, MAX)`: a discarded lane's NaN or ∞ kept in the factor's domain.
    let f = flat.factor_in(LaneArith(s), s.min(s.max(dist, zero), max));
    let att = match spot {
        None => f,
        Some((spot, power)) => {
            let c = spot_factor(s, spot, power, &l);
            s.select(s.gt(c, zero), s.min(s.mul(f, c), max), zero)
        }
    };
    (l, att)
}

/// `SpotLight::spot_factor` per lane for a unit `l` (never zero in a lane the kernel keeps),
/// with the power by `power`'s plan.
#[inline(always)]
fn spot_factor<S: Simd>(s: S, spot: &SpotLight, power: SpotPow, l: &[S::V; 3]) -> S::V {
    let zero = s.splat(0.0);
    let one = s.splat(1.0);
    let axis = spot.axis();
    // `−(L·D)` with glam's `dot` order; the product by −1 is an exact negation.
    let ld = s.add(
        s.add(s.mul(l[0], s.splat(axis.x)), s.mul(l[1], s.splat(axis.y))),
        s.mul(l[2], s.splat(axis.z)),
    );
    let c = s.mul(ld, s.splat(-1.0));
    let cut = spot.cos_cutoff();
    // `!(c < cut)`, as the scalar test: a NaN cosine passes it there too.
    let inside = s.ge(c, s.splat(cut));
    if cut < 0.0 {
        // No cone (or none that can exclude a unit `L`): 1 wherever the scalar test passes.
        return s.keep(inside, one);
    }
    let e = spot.exponent();
    // `lobe_pow(min(c, 1), e)`: 0 for `c ≤ 0`, and `c^0 = 1`, `c^1 = c` exactly.
    let lit = s.and(inside, s.gt(c, zero));
    if e == 0.0 {
        return s.keep(lit, one);
    }
    let c = s.min(c, one);
    if e == 1.0 {
        return s.keep(lit, c);
    }
    s.keep(lit, pow::<S, true>(s, power.plan, power.flush, c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attenuation::Attenuation;
    use crate::batch::kernel::tests::at_every_level;
    use crate::batch::kernel::{Lanes, W};
    use crate::batch::simd::portable::Portable;
    use crate::light::{LightColors, LightSource, SpotCone};
    use glam::Vec3;

    /// Distances across the range the kernel keeps (`d² ∈ [1e-30, 1e30]`) and both sides of each
    /// form's radius and `ε`.
    fn offsets() -> Vec<Vec3> {
        let mut v = Vec::new();
        let mut x = 0x1234_5678u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as f32 / u32::MAX as f32
        };
        for k in -14..=14 {
            let scale = 10f32.powi(k);
            for _ in 0..48 {
                let dir = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                v.push(dir * scale * (1.0 + next()));
            }
        }
        for r in [0.01f32, 3.0, 4.0, 6.0] {
            for t in [0.999f32, 0.99999, 1.0, 1.00001] {
                v.push(Vec3::new(0.6, -0.8, 0.0) * r * t);
            }
        }
        v
    }

    fn lights() -> Vec<(Attenuation, Option<SpotCone>)> {
        let falloffs = [
            Attenuation::None,
            Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
            Attenuation::try_polynomial(0.0, 0.0, 3.0e38).unwrap(),
            Attenuation::try_inverse_square(4.0).unwrap(),
            Attenuation::try_unreal(6.0).unwrap(),
            Attenuation::try_frostbite(3.0).unwrap(),
        ];
        let cones = [
            None,
            Some(SpotCone::NONE),
            Some(SpotCone::degrees(60.0).with_exponent(4.5)),
            Some(SpotCone::degrees(35.0).with_exponent(2.0)),
            Some(SpotCone::degrees(90.0)),
            Some(SpotCone::degrees(80.0).with_exponent(1.0)),
            Some(SpotCone::degrees(10.0).with_exponent(128.0)),
        ];
        let mut out = Vec::new();
        for a in falloffs {
            for c in cones {
                out.push((a, c));
            }
        }
        out
    }

    /// Every lane's direction is `LightSource::sample`'s bit for bit at every level, and so is
    /// its factor without a cone or with a spot exponent of 0 or 1: for each falloff form, over
    /// distances from 1e-14 to 1e15 and both sides of each radius. With another exponent (2, 4.5,
    /// 128) the factor is within the power's documented bound of `f · c^e` in `f64`, `f` the
    /// point light's factor.
    #[test]
    fn lanes_are_the_scalar_sample_at_every_level() {
        at_every_level!(agrees);
    }

    fn agrees<S: Simd>(s: S, level: &str) {
        let offsets = offsets();
        let axis = Vec3::new(0.3, -0.9, 0.2).normalize();
        let (mut exact, mut bounded) = (0, 0);
        for (attenuation, cone) in lights() {
            let point = PointLight::try_new(Vec3::ZERO, attenuation, LightColors::BLACK).unwrap();
            let spot = cone.map(|cone| {
                SpotLight::try_with_cone(Vec3::ZERO, axis, cone, attenuation, LightColors::BLACK)
                    .unwrap()
            });
            let flat = attenuation.flat();
            for chunk in offsets.chunks(W) {
                let mut d: [Lanes; 3] = [[1.0; W]; 3];
                for (i, o) in chunk.iter().enumerate() {
                    (d[0][i], d[1][i], d[2][i]) = (o.x, o.y, o.z);
                }
                let dv = [s.load(&d[0]), s.load(&d[1]), s.load(&d[2])];
                let power = spot.map(|spot| (spot, SpotPow::new(spot.exponent())));
                let (l, f) = falloff(s, &dv, &flat, power.as_ref().map(|(s, p)| (s, *p)));
                let (l, f) = ([s.store(l[0]), s.store(l[1]), s.store(l[2])], s.store(f));
                for (i, o) in chunk.iter().enumerate() {
                    // The light at the origin, the point at −o: `light − p = o`.
                    let want = match spot {
                        Some(spot) => spot.sample(-*o),
                        None => point.sample(-*o),
                    };
                    let got = Vec3::new(l[0][i], l[1][i], l[2][i]);
                    let what = || format!("{level}: {attenuation:?}, {cone:?}, offset {o}");
                    assert_eq!(
                        got.to_array().map(f32::to_bits),
                        want.direction.to_array().map(f32::to_bits),
                        "{}: direction {got}, want {}",
                        what(),
                        want.direction
                    );
                    let e = spot.map_or(0.0, |spot| spot.exponent());
                    if spot.is_none_or(|spot| spot.cos_cutoff() < 0.0) || e == 0.0 || e == 1.0 {
                        exact += 1;
                        assert_eq!(
                            f[i].to_bits(),
                            want.factor.to_bits(),
                            "{}: factor {}, want {}",
                            what(),
                            f[i],
                            want.factor
                        );
                        continue;
                    }
                    bounded += 1;
                    let spot = spot.unwrap();
                    let c = -want.direction.dot(spot.axis());
                    let exact_spot = if c >= spot.cos_cutoff() && c > 0.0 {
                        f64::from(c.min(1.0)).powf(f64::from(e))
                    } else {
                        0.0
                    };
                    let a = f64::from(point.sample(-*o).factor);
                    let eps = f64::from(PowStrategy::Auto.resolve(e).max_relative_error());
                    let floor = f64::from(PowStrategy::ERROR_FLOOR);
                    let exact_factor = a * exact_spot;
                    // The power's bound, and one rounding of the product (absolute, at most
                    // 2⁻¹⁵⁰, where the product is subnormal: gradual underflow).
                    let bound = a * eps * exact_spot.max(floor)
                        + exact_factor * f64::from(f32::EPSILON)
                        + f64::from(f32::from_bits(1));
                    assert!(
                        (f64::from(f[i]) - exact_factor).abs() <= bound,
                        "{}: factor {}, want {exact_factor} within {bound}",
                        what(),
                        f[i]
                    );
                }
            }
        }
        assert!(exact > 5000 && bounded > 5000, "{exact} {bounded}");
    }

    use crate::light::PointLight;
    use crate::pow::PowStrategy;
}
