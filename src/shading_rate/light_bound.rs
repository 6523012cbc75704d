//! The bound for one light: its ambient, diffuse and specular parts, each the smaller of its
//! interval's width and the Taylor bound, plus the rounding allowance.

use super::falloff::attenuation_jet;
use super::jet::{Jet, U, UnitJet, mulz, normal_cosine, plain_cosine};
use super::triangle::{Triangle, cosine_allowance, distance_to_triangle};
use crate::SpecularGate;
use crate::light::{Light, LightSource};
use crate::material::Material;
use crate::math;
use crate::model::Model;
use crate::normalization::Normalization;
use crate::normalize_or_zero;
use crate::pow::PowStrategy;
use crate::shade::Viewer;
use glam::Vec3;

/// The bound for one light; see [`gouraud_error_bound`].
pub(super) fn light_bound(
    model: &Model,
    material: &Material,
    light: &Light,
    viewer: Viewer,
    tri: &Triangle,
) -> f32 {
    let (p, n, r2, normal) = (tri.p, tri.n, tri.r2, tri.normal.as_ref());
    let colors = light.colors();
    let wa = (colors.ambient() * material.ambient()).max_element();
    let wd = (colors.diffuse() * material.diffuse()).max_element();
    let ws = (colors.specular() * material.specular()).max_element();
    let s = material.shininess();
    let d_viewer = match viewer {
        Viewer::At(eye) => distance_to_triangle(eye, p),
        Viewer::Infinite(_) => f32::INFINITY,
    };
    // A point light's distance, as `shade` computes it, is off by the point's rounding and its
    // own (the square root of a rounded sum of squares: 2u relative).
    let distance_allowance = |d1: f32| 3.0 * U * tri.pmax + 2.0 * U * d1;

    // The attenuation × spot factor f, the light direction's jet and the cosines' allowance.
    let (factor, l_jet, l_at, eta) = match light {
        Light::Directional(d) => (
            Jet::constant(1.0),
            UnitJet::FIXED,
            [d.direction(); 3],
            cosine_allowance(tri, f32::INFINITY, d_viewer),
        ),
        Light::Point(pl) => {
            let d0 = distance_to_triangle(pl.position(), p);
            let d1 = p
                .map(|q| crate::length(pl.position() - q))
                .into_iter()
                .fold(0.0, f32::max);
            let e = distance_allowance(d1);
            let f = attenuation_jet(
                &pl.attenuation(),
                (d0 - e).max(0.0),
                d1 * (1.0 + 1e-6) + e,
                e,
            );
            (
                f,
                UnitJet::toward_point(d0),
                p.map(|q| light.sample(q).direction),
                cosine_allowance(tri, d0, d_viewer),
            )
        }
        Light::Spot(sl) => {
            let d0 = distance_to_triangle(sl.position(), p);
            let d1 = p
                .map(|q| crate::length(sl.position() - q))
                .into_iter()
                .fold(0.0, f32::max);
            let e = distance_allowance(d1);
            let f = attenuation_jet(
                &sl.attenuation(),
                (d0 - e).max(0.0),
                d1 * (1.0 + 1e-6) + e,
                e,
            );
            let lj = UnitJet::toward_point(d0);
            let eta = cosine_allowance(tri, d0, d_viewer);
            let dirs = p.map(|q| normalize_or_zero(sl.position() - q));
            // q = −L·D has |q'| ≤ |L'|, |q''| ≤ |L''|.
            let q = Jet::around(
                dirs.map(|l| -l.dot(sl.axis())),
                lj.a,
                lj.b,
                r2,
                -1.0,
                1.0,
                eta,
            );
            let e = sl.exponent();
            let spot = if sl.cone().is_none() {
                // OpenGL's 180° cutoff: the factor is 1 in every direction.
                Jet::constant(1.0)
            } else if q.hi < sl.cos_cutoff() {
                Jet::ZERO
            } else if q.lo >= sl.cos_cutoff() && q.lo > 0.0 {
                // The spot factor's power is `powf` (PowStrategy::Exact).
                q.lobe_pow(e, PowStrategy::Exact)
            } else {
                Jet::rough(
                    0.0,
                    if e == 0.0 {
                        1.0
                    } else {
                        math::powf(q.hi.clamp(0.0, 1.0), e)
                    },
                )
            };
            (f.mul(spot), lj, dirs, eta)
        }
    };
    if factor.is_zero() {
        return 0.0;
    }
    let ambient = factor.scale(wa);
    let no_direction = l_at.iter().all(|l| *l == Vec3::ZERO);
    if no_direction || matches!(light, Light::Directional(_)) && l_at[0] == Vec3::ZERO {
        return finish(ambient, r2, s);
    }
    let Some(nj) = normal else {
        // No smooth normal: only the interval of the whole contribution.
        let (dmax, smax) = lobe_maxima(model, s);
        let total = factor.mul(Jet::rough(wa, wa + wd * dmax + ws * smax));
        return finish(total, r2, s);
    };

    let c1 = normal_cosine(
        [n[0].dot(l_at[0]), n[1].dot(l_at[1]), n[2].dot(l_at[2])],
        nj,
        l_jet,
        r2,
        eta,
    );
    let diffuse = c1.positive_part();
    let (gate, normalization, pow, has_specular, blinn) = match model {
        Model::Lambert(m) => (
            SpecularGate::Step,
            m.normalization,
            PowStrategy::Exact,
            false,
            false,
        ),
        Model::Phong(m) => (m.gate, m.normalization, m.pow, true, false),
        Model::BlinnPhong(m) => (m.gate, m.normalization, m.pow, true, true),
    };
    let wd = if normalization.is_normalized() {
        wd * (1.0 / core::f32::consts::PI)
    } else {
        wd
    };
    // The parts are bounded apart: the error of a sum is at most the sum of the errors, and
    // min(width, Taylor) taken per part is never larger than taken for the sum.
    let mut total = finish(factor.scale(wa), r2, 0.0);
    let diffuse_jet = finish(factor.mul(diffuse.scale(wd)), r2, 0.0);
    total += match light {
        Light::Directional(_) => {
            // The exact-arithmetic bound, plus each evaluation's cosine off by up to η (the
            // diffuse lobe is 1-Lipschitz in it) and the products' rounding.
            let c = [n[0].dot(l_at[0]), n[1].dot(l_at[1]), n[2].dot(l_at[2])];
            let sharp =
                wd * (directional_diffuse_error(c, tri.mu) + 2.0 * eta) + 32.0 * f32::EPSILON * wd;
            sharp.min(diffuse_jet)
        }
        _ => diffuse_jet,
    };

    let v_at = match viewer {
        Viewer::At(eye) => p.map(|q| normalize_or_zero(eye - q)),
        Viewer::Infinite(dir) => [normalize_or_zero(dir); 3],
    };
    let v_jet = match viewer {
        Viewer::At(eye) => UnitJet::toward_point(distance_to_triangle(eye, p)),
        Viewer::Infinite(_) => UnitJet::FIXED,
    };
    if has_specular && ws > 0.0 && v_at.iter().any(|v| *v != Vec3::ZERO) {
        let c2 = normal_cosine(
            [n[0].dot(v_at[0]), n[1].dot(v_at[1]), n[2].dot(v_at[2])],
            nj,
            v_jet,
            r2,
            eta,
        );
        let c3 = plain_cosine(
            [
                l_at[0].dot(v_at[0]),
                l_at[1].dot(v_at[1]),
                l_at[2].dot(v_at[2]),
            ],
            l_jet,
            v_jet,
            r2,
            eta,
        );
        let lobe = if blinn {
            // N·H = (N·L + N·V) / √(2 + 2 L·V); g(x) = (2 + 2x)^(−1/2) is decreasing and convex.
            let base = 2.0 + 2.0 * c3.lo;
            if base > 1e-6 {
                let g_hi = 1.0 / math::sqrt(base);
                let g_lo = 1.0 / math::sqrt(2.0 + 2.0 * c3.hi.max(c3.lo));
                let p1 = g_hi * g_hi * g_hi;
                let p2 = 3.0 * p1 * g_hi * g_hi;
                let g = c3.compose(g_lo, g_hi, p1, p2);
                let mut nh = c1.add(c2).mul(g);
                nh.lo = nh.lo.max(-1.0);
                nh.hi = nh.hi.min(1.0);
                nh.lobe_pow(s, pow)
            } else {
                Jet::rough(0.0, 1.0)
            }
        } else {
            // R·V = 2(N·L)(N·V) − L·V.
            let mut rv = c1.mul(c2).scale(2.0).sub(c3);
            rv.lo = rv.lo.max(-1.0);
            rv.hi = rv.hi.min(1.0);
            rv.lobe_pow(s, pow)
        };
        let specular = if normalization.is_normalized() {
            let k = if blinn {
                normalization.blinn_factor(s)
            } else {
                normalization.phong_factor(s)
            };
            lobe.mul(c1.positive_part()).scale(k)
        } else {
            match gate {
                SpecularGate::Step => lobe.mul(c1.step()),
                SpecularGate::Cosine => lobe.mul(c1.positive_part()),
                SpecularGate::None => lobe,
            }
        };
        total += finish(factor.mul(specular.scale(ws)), r2, s);
    }
    total
}

/// The exact Gouraud error of a directional light's diffuse lobe, bounded: with `L` constant,
/// `m·L = Σ bᵢcᵢ` is affine in `b`, so with `a = m·L`
///
/// ```text
/// G − F = Σ bᵢ max(cᵢ, 0) − max(a, 0)/‖m‖
///       = [Σ bᵢ max(cᵢ, 0) − max(a, 0)]  +  max(a, 0)·(1 − 1/‖m‖)
/// ```
///
/// The first bracket is the Jensen gap of `max(x, 0)` for `cᵢ ∈ [−A, B]`, in `[0, AB/(A+B)]`; the
/// second is in `[−B(1/μ − 1), 0]`. Their sum is at most the larger of the two in magnitude.
pub(super) fn directional_diffuse_error(c: [f32; 3], mu: f32) -> f32 {
    let b = c[0].max(c[1]).max(c[2]).max(0.0);
    let a = (-c[0]).max(-c[1]).max(-c[2]).max(0.0);
    if b == 0.0 {
        return 0.0;
    }
    if !(mu > 1e-6) {
        return 1.0;
    }
    let shrink = b * (1.0 / mu - 1.0);
    let jensen = if a > 0.0 { a * b / (a + b) } else { 0.0 };
    shrink.max(jensen).min(1.0)
}

/// The largest diffuse and specular lobes a model can produce at shininess `s`.
pub(super) fn lobe_maxima(model: &Model, s: f32) -> (f32, f32) {
    let (norm, spec, blinn) = match model {
        Model::Lambert(m) => (m.normalization, false, false),
        Model::Phong(m) => (m.normalization, true, false),
        Model::BlinnPhong(m) => (m.normalization, true, true),
    };
    let d = if norm == Normalization::None {
        1.0
    } else {
        1.0 / core::f32::consts::PI
    };
    let sp = match (spec, blinn) {
        (false, _) => 0.0,
        (true, true) => norm.blinn_factor(s),
        (true, false) => norm.phong_factor(s),
    };
    (d, sp)
}

/// `min(interval width, ½·d2·r²)` plus the rounding allowance.
pub(super) fn finish(f: Jet, r2: f32, s: f32) -> f32 {
    // Both shadings' values lie in the interval, perturbed inputs included; or: the exact values
    // differ by at most ½·d2·r², and each computed value is within s1 of its exact one (the
    // Gouraud value interpolates three computed values, so it is within s1 too).
    let width = (f.hi - f.lo).max(0.0);
    let taylor = 0.5 * mulz(f.d2, r2) + 2.0 * f.s1;
    let b = if taylor.is_finite() {
        width.min(taylor)
    } else {
        width
    };
    // f32 evaluation of both shadings: a few ulps per operation of the products and sums,
    // amplified by the power s.
    let rounding = f.abs_max() * (32.0 + 4.0 * s) * f32::EPSILON;
    let out = b + rounding;
    if out.is_finite() { out } else { f32::MAX }
}
