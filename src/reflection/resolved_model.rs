//! A built-in model's meaning, resolved once: which lobe, how it is gated, how it is scaled.

use crate::gate::SpecularGate;
use crate::math;
use crate::normalization::Normalization;
use crate::normalize::Scaled;
use crate::pow::{PowPlan, PowStrategy};
use crate::{BlinnPhong, Lambert, Model, Phong};

/// Which specular lobe a model has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lobe {
    /// No specular lobe ([`Lambert`]).
    None,
    /// `max(R·V, 0)^s` with `R·V = 2(N·L)(N·V) − L·V`.
    Phong,
    /// `((N·H)²)^(s/2)`.
    Blinn,
}

/// One of the crate's models with every choice it makes resolved: the lobe, the gate, the
/// normalisation and the pow strategy.
///
/// ```text
/// diffuse  = diffuse_scale · max(N·L, 0)
/// specular = scale(s) · gate(N·L) · base^(k·s)
///   Lambert:      no specular
///   Phong:        base = clamp(R·V, 0, 1),  k = 1,    scale = 1 or (s+2)/2π
///   Blinn-Phong:  base = (N·H)²,            k = 1/2,  scale = 1 or the Blinn factor
/// gate(c) = step·[c > 0] + cosine·max(c, 0) + none        (exactly one of the three is 1)
/// ```
///
/// A normalised lobe carries its own `max(N·L, 0)`, so its gate is the cosine whatever the model's
/// [`SpecularGate`] says. [`shade`](crate::shade), [`Shader`](crate::Shader) and the built-in
/// models' [`ReflectionModel`](crate::ReflectionModel) impls all evaluate this one description, so
/// the meaning of a model is written once.
///
/// Obtained from [`ReflectionModel::resolve`](crate::ReflectionModel::resolve) or `From` a model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResolvedModel {
    pub(crate) lobe: Lobe,
    pub(crate) normalization: Normalization,
    pub(crate) pow: PowStrategy,
    /// Gate weights: `step·[N·L > 0] + cosine·max(N·L, 0) + none`.
    pub(crate) gate: [f32; 3],
    /// 1, or `1/π` when normalised.
    pub(crate) diffuse_scale: f32,
}

impl ResolvedModel {
    fn new(lobe: Lobe, gate: SpecularGate, normalization: Normalization, pow: PowStrategy) -> Self {
        let gate = if normalization.is_normalized() {
            SpecularGate::Cosine
        } else {
            gate
        };
        ResolvedModel {
            lobe,
            normalization,
            pow,
            gate: match gate {
                SpecularGate::Step => [1.0, 0.0, 0.0],
                SpecularGate::Cosine => [0.0, 1.0, 0.0],
                SpecularGate::None => [0.0, 0.0, 1.0],
            },
            diffuse_scale: normalization.diffuse(1.0),
        }
    }

    /// Whether the model has a specular lobe at all.
    #[must_use]
    #[inline]
    pub fn has_specular(&self) -> bool {
        self.lobe != Lobe::None
    }

    /// The diffuse lobe for `N·L`: `diffuse_scale · max(N·L, 0)`, in `[0, 1]`.
    #[must_use]
    #[inline(always)]
    pub fn diffuse(&self, n_dot_l: f32) -> f32 {
        self.diffuse_scale * math::max_or(n_dot_l, 0.0)
    }

    /// The specular lobe's normalisation factor at shininess `s`: 1 for a classic lobe,
    /// `(s + 2)/(2π)` for a normalised Phong lobe, `(s + 8)/(8π)` (`Energy`) or
    /// `(s + 2)(s + 4) / (8π (2^(−s/2) + s))` (`EnergyExact`) for a normalised Blinn-Phong lobe,
    /// and 0 for a model without one (Lambert). It multiplies the lobe, so it bounds the
    /// specular weight: what a light-culling or error bound needs.
    ///
    /// **Domain:** any `s`; NaN and negatives are read as 0, `+∞` as `f32::MAX`. **Returns** a
    /// finite value `≥ 0`, saturated at `f32::MAX`.
    ///
    /// ```
    /// use phong::{BlinnPhong, Lambert, Normalization, Phong, ResolvedModel};
    /// let inv_pi = 1.0 / std::f32::consts::PI;
    /// let energy = |n| ResolvedModel::from(Phong { normalization: n, ..Phong::default() });
    /// assert_eq!(energy(Normalization::None).specular_scale(100.0), 1.0);
    /// assert!((energy(Normalization::Energy).specular_scale(0.0) - inv_pi).abs() < 1e-7);
    /// // Blinn-Phong's exact factor is the Lambertian 1/π at s = 0 too.
    /// let exact = ResolvedModel::from(BlinnPhong { normalization: Normalization::EnergyExact, ..BlinnPhong::default() });
    /// assert!((exact.specular_scale(0.0) - inv_pi).abs() < 1e-7);
    /// assert_eq!(ResolvedModel::from(Lambert::default()).specular_scale(32.0), 0.0);
    /// ```
    #[must_use]
    #[inline]
    pub fn specular_scale(&self, s: f32) -> f32 {
        self.at_shininess(s).scale
    }

    /// Whether [`gate`](Self::gate)`(0)` is 0 (the step and cosine gates): a zero normal or
    /// light direction, whose `N·L` is 0, then has no highlight whatever its lobe's base.
    #[inline(always)]
    pub(crate) fn closes_at_zero(&self) -> bool {
        self.gate[2] == 0.0
    }

    /// The gate's weight for `N·L`: `[N·L > 0]`, `max(N·L, 0)` or 1 (the cosine for normalised
    /// lobes). In `[0, 1]` for `N·L ≤ 1`; NaN reads as 0 for the step and cosine gates.
    #[must_use]
    #[inline(always)]
    pub fn gate(&self, n_dot_l: f32) -> f32 {
        let [step, cosine, none] = self.gate;
        let lit = if n_dot_l > 0.0 { step } else { 0.0 };
        lit + cosine * math::max_or(n_dot_l, 0.0) + none
    }

    /// The per-shininess constants: the normalisation factor and the pow plan for the exponent
    /// applied to the lobe's base (`s` for Phong, `s/2` for Blinn-Phong's `(N·H)²`).
    ///
    /// **Domain:** any `s`; NaN and negatives are read as 0, `+∞` as `f32::MAX`.
    #[must_use]
    #[inline]
    pub(crate) fn at_shininess(&self, s: f32) -> SpecularPlan {
        let s = math::clamp_or_lo(s, 0.0, math::MAX);
        let (scale, exponent) = match self.lobe {
            Lobe::None => (0.0, 0.0),
            Lobe::Phong => (self.normalization.phong_factor(s), s),
            Lobe::Blinn => (self.normalization.blinn_factor(s), 0.5 * s),
        };
        SpecularPlan {
            scale,
            plan: self.pow.plan(exponent),
        }
    }

    /// Phong's lobe base from the cosines: `R·V = 2(N·L)(N·V) − L·V`, unclamped.
    #[inline(always)]
    pub(crate) fn phong_base(n_dot_l: f32, n_dot_v: f32, l_dot_v: f32) -> f32 {
        2.0 * n_dot_l * n_dot_v - l_dot_v
    }

    /// Phong's lobe base squared and scaled for `log2`: `2^24·(R·V)²` where `R·V > 0`, else 0,
    /// from the normal, the offset to the light and the offset to the viewer as they are (each
    /// times any power of two):
    ///
    /// ```text
    /// R·V = 2(N·L)(N·V) − L·V = num / (‖n‖²‖l‖‖v‖)     N = n/‖n‖, L = l/‖l‖, V = v/‖v‖
    /// num = 2(n·l)(n·v) − ‖n‖²(l·v)
    /// 2^24·(R·V)² = num² · 2^24/(‖n‖⁴‖l‖²‖v‖²)
    /// ```
    ///
    /// `PowStrategy::Auto`'s polynomial takes it with half the exponent, as Blinn-Phong's `(N·H)²`
    /// is taken, and no square root or division waits in front of the power, where
    /// [`phong_base`](Self::phong_base) reads the three unit vectors. The factor `2^24` is the
    /// scale `log2`'s evaluation applies to its argument (`crate::pow::poly_pow_of_scaled`),
    /// folded into the reciprocal, which is ready by the time `num²` is.
    ///
    /// Scaling a vector by a power of two scales `num²` and the divisor alike and exactly, so the
    /// result has the same bits whatever the scales, wherever no product under- or overflows:
    /// the one-light form and the light loop scale differently and agree.
    ///
    /// **Domain:** [`Scaled`] vectors as the normalisations return them: a squared length in
    /// `[2⁻²⁵, 2²⁵]` or `[4, 48]`, 1 for a unit direction given as one, tiny only for vectors
    /// whose components are subnormal; the divisor is floored at `2⁻¹⁰⁰` so that its reciprocal
    /// stays finite. **Degenerate input:** a zero vector gives `num = 0`, so 0; a square that
    /// underflows is 0, as Blinn-Phong's `(N·H)²` can be; a `num` that is NaN gives 0. The result
    /// is finite: at most about `2^24` (more only by rounding; the power clamps it).
    #[inline(always)]
    pub(crate) fn phong_base_squared(n: Scaled, l: Scaled, v: Scaled) -> f32 {
        const TWO_24: f32 = 16_777_216.0;
        const FLOOR: f32 = 7.888_609e-31; // 2^-100
        let num = 2.0 * n.w.dot(l.w) * n.w.dot(v.w) - n.ww * l.w.dot(v.w);
        let den = n.ww * n.ww * (l.ww * v.ww);
        let xs = num * num * (TWO_24 / math::max_or(den, FLOOR));
        if num > 0.0 { xs } else { 0.0 }
    }
}

/// The specular constants of one shininess: the normalisation factor and the pow plan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SpecularPlan {
    /// 1, or the normalisation factor at this shininess (finite).
    pub(crate) scale: f32,
    pub(crate) plan: PowPlan,
}

impl From<Lambert> for ResolvedModel {
    fn from(m: Lambert) -> Self {
        ResolvedModel::new(
            Lobe::None,
            SpecularGate::None,
            m.normalization,
            PowStrategy::Exact,
        )
    }
}

impl From<Phong> for ResolvedModel {
    fn from(m: Phong) -> Self {
        ResolvedModel::new(Lobe::Phong, m.gate, m.normalization, m.pow)
    }
}

impl From<BlinnPhong> for ResolvedModel {
    fn from(m: BlinnPhong) -> Self {
        ResolvedModel::new(Lobe::Blinn, m.gate, m.normalization, m.pow)
    }
}

impl From<Model> for ResolvedModel {
    fn from(m: Model) -> Self {
        match m {
            Model::Lambert(m) => m.into(),
            Model::Phong(m) => m.into(),
            Model::BlinnPhong(m) => m.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn scaled(v: Vec3, c: f32) -> Scaled {
        let w = v * c;
        Scaled {
            w,
            ww: w.length_squared(),
        }
    }

    /// `2^24·(R·V)²` has the same bits whatever powers of two scale the three vectors, is close
    /// to the square of the unit vectors' `R·V`, and is 0 where `R·V ≤ 0` or a vector is zero.
    #[test]
    fn the_squared_base_is_the_same_at_every_scale() {
        let mut seed = 0x2545_f491_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        let mut positive = 0;
        for _ in 0..2000 {
            let n = Vec3::new(next(), next(), next());
            let l = Vec3::new(next(), next(), next()) * 7.0;
            let v = Vec3::new(next(), next(), next()) * 0.3;
            let base = phong_base_squared(scaled(n, 1.0), scaled(l, 1.0), scaled(v, 1.0));
            for (a, b, c) in [(4.0f32, 0.25, 1024.0), (2f32.powi(-20), 2f32.powi(12), 0.5)] {
                let other = phong_base_squared(scaled(n, a), scaled(l, b), scaled(v, c));
                assert_eq!(base.to_bits(), other.to_bits(), "{n} {l} {v}");
            }
            let (n1, l1, v1) = (n.normalize(), l.normalize(), v.normalize());
            let x = f64::from(ResolvedModel::phong_base(
                n1.dot(l1),
                n1.dot(v1),
                l1.dot(v1),
            ));
            if x > 1e-3 {
                positive += 1;
                let want = x * x * 16_777_216.0;
                // Both sides' `R·V` within a few roundings of 1 relative to the vectors' size.
                assert!(
                    (f64::from(base) - want).abs() <= 1e-4 * want.max(16_777_216.0 * 1e-3),
                    "{base} vs {want}"
                );
            } else if x < -1e-3 {
                assert_eq!(base, 0.0);
            }
        }
        assert!(positive > 500, "{positive}");
        let zero = scaled(Vec3::ZERO, 1.0);
        let some = scaled(Vec3::new(0.3, 1.0, 0.2), 1.0);
        for (n, l, v) in [(zero, some, some), (some, zero, some), (some, some, zero)] {
            assert_eq!(phong_base_squared(n, l, v), 0.0);
        }
    }

    fn phong_base_squared(n: Scaled, l: Scaled, v: Scaled) -> f32 {
        ResolvedModel::phong_base_squared(n, l, v)
    }
}
