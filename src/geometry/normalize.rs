//! Normalisation and length over the whole finite `f32` range.
//!
//! The textbook `v / ‖v‖` fails at both ends of the range: `v·v` overflows to `+∞` for components
//! above about 1.8e19 (giving a zero vector), and underflows to zero or a subnormal for components
//! below about 1e-19 (giving NaN or a wrong direction). GLSL's `normalize` (measured in Mesa) has both
//! failures. The functions here rescale by a power of two first, which is exact, so the answer is the
//! correctly scaled direction for every finite input.

use glam::Vec3;

use crate::math;

/// Squared lengths in `[LO, HI]` are normalised directly; outside it the vector is rescaled first.
const LO: f32 = 1.0e-30;
const HI: f32 = 1.0e30;

/// `l2 ∈ [LO, HI]` in one integer compare: for `l2 ≥ 0` the bit patterns of floats are ordered
/// like the floats, and the subtraction wraps everything below `LO` (and NaN, `+∞`, which lie above
/// `HI`) past the bound. One test and one branch per normalisation on the hot path.
#[inline(always)]
fn in_common_range(l2: f32) -> bool {
    l2.to_bits().wrapping_sub(LO.to_bits()) <= HI.to_bits() - LO.to_bits()
}

/// The narrower common range of the normalisations that also return their vector for Phong's
/// squared base ([`Scaled`]): squared lengths in `[2⁻²⁵, 2²⁵]`. Inside it the vector is returned
/// as it is, and the base's divisor `‖n‖⁴‖l‖²‖v‖²` stays in `[2⁻¹⁰⁰, 2¹⁰⁰]` (its floor in
/// `ResolvedModel::phong_base_squared` is `2⁻¹⁰⁰`, where `2²⁴` over it is still finite) and
/// `num²` below `9·2¹⁰⁰`; outside it the full-range path scales it.
const LOBE_LO: f32 = 1.0 / 33_554_432.0;
const LOBE_HI: f32 = 33_554_432.0;

/// `l2 ∈ [LOBE_LO, LOBE_HI]` in one integer compare, as [`in_common_range`].
#[inline(always)]
fn in_lobe_range(l2: f32) -> bool {
    l2.to_bits().wrapping_sub(LOBE_LO.to_bits()) <= LOBE_HI.to_bits() - LOBE_LO.to_bits()
}

/// Multiplies by 2^k exactly by rescaling so the largest component lands in [1, 2).
#[inline]
fn rescaled(v: Vec3) -> Vec3 {
    let m = math::abs(v.x).max(math::abs(v.y)).max(math::abs(v.z));
    // Exponent of m, and a power of two 2^-e that brings m into [1, 2). For subnormal m the
    // exponent field is 0: scale by 2^64 first, then once more.
    let mut v = v;
    let mut m = m;
    if m < f32::MIN_POSITIVE {
        v *= 18_446_744_073_709_551_616.0; // 2^64, exact
        m *= 18_446_744_073_709_551_616.0;
    }
    // 2^-e must be a normal f32: exponent field 127 - e in [1, 254], so e in [-127, 126]. For
    // e = 127 (m ≥ 2^127) that leaves m scaled into [2, 4): still safe to square.
    let e = (((m.to_bits() >> 23) & 0xff) as i32 - 127).min(126);
    let scale = f32::from_bits(((127 - e) as u32) << 23);
    v * scale
}

/// The unit vector in the direction of `v`, or the zero vector when `v` is zero or not finite.
///
/// ```text
/// normalize_or_zero(v) = v / ‖v‖    (v ≠ 0, finite)
///                      = 0          (v = 0, or any component NaN/±∞)
/// ```
///
/// **Domain:** any `Vec3`. Unlike `v.normalize_or_zero()` in glam or `normalize` in GLSL, it is exact
/// (to a few ulps) for huge components (up to `f32::MAX`) and for tiny and subnormal ones: it first
/// scales `v` by a power of two, which changes no digit.
///
/// **Degenerate input:** the zero vector for `v = 0`, or for a non-finite component.
///
/// ```
/// use glam::Vec3;
/// let n = phong::normalize_or_zero(Vec3::new(1e-30, 0.0, 1e-30));
/// assert!((n.length() - 1.0).abs() < 1e-6);
/// assert_eq!(phong::normalize_or_zero(Vec3::ZERO), Vec3::ZERO);
/// assert_eq!(phong::normalize_or_zero(Vec3::new(3e38, 0.0, 0.0)), Vec3::X);
/// ```
#[must_use]
#[inline(always)]
pub fn normalize_or_zero(v: Vec3) -> Vec3 {
    normalize_flagged(v).0
}

/// `(normalize_or_zero(v), normalize_or_zero(v) != 0)`: the flag costs nothing on the common
/// path, where the vector is non-zero by the range test, so a caller that masks on a missing
/// direction (the light loop's zero-normal mask) does not compare three components at every point.
#[inline(always)]
pub(crate) fn normalize_flagged(v: Vec3) -> (Vec3, bool) {
    let (d, present, _) = normalize_flagged_in::<false>(v);
    (d, present)
}

/// [`normalize_flagged_in`] with Phong's squared base's range (`LOBE`).
#[inline(always)]
pub(crate) fn normalize_flagged_scaled(v: Vec3) -> (Vec3, bool, Scaled) {
    normalize_flagged_in::<true>(v)
}

/// [`normalize_flagged`] and `v` [`Scaled`]: as it is where `v·v` lies in the common range of
/// `LOBE` ([`in_range`]; with `LOBE`, `[2⁻²⁵, 2²⁵]`, the range Phong's squared base needs), else
/// by the full-range path's power of two (the zero vector where the direction is zero). The same
/// direction, bit for bit, either way; the plain form is this one without `LOBE`, the
/// [`Scaled`] dropped, which costs it nothing.
#[inline(always)]
fn normalize_flagged_in<const LOBE: bool>(v: Vec3) -> (Vec3, bool, Scaled) {
    let l2 = v.length_squared();
    if in_range::<LOBE>(l2) {
        return (v * (1.0 / math::sqrt(l2)), true, Scaled { w: v, ww: l2 });
    }
    let (d, _, w) = full_range_scaled(v);
    (d, d != Vec3::ZERO, w)
}

/// The common range of the plain normalisations ([`in_common_range`]), or with `LOBE` the
/// narrower one of those that return their vector for Phong's squared base ([`in_lobe_range`]).
#[inline(always)]
fn in_range<const LOBE: bool>(l2: f32) -> bool {
    if LOBE {
        in_lobe_range(l2)
    } else {
        in_common_range(l2)
    }
}

/// A vector times a power of two `c`, and its squared length `ww = ‖c·v‖²`: what Phong's squared
/// lobe base reads in place of a unit vector (see
/// [`ResolvedModel::phong_base_squared`](crate::reflection::resolved_model::ResolvedModel::phong_base_squared)).
///
/// The scale is exact, so any two scalings of the same vector give ratios such as
/// `(a·b)² / (‖a‖²‖b‖²)` the same bits, as long as no product under- or overflows: the one-light
/// form scales its largest component into `[2, 4)`, the light loop keeps a vector whose squared
/// length lies in `[2⁻²⁵, 2²⁵]` as it is (`c = 1`) and scales the others as the one-light form
/// does, and their lobes agree bit for bit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Scaled {
    /// `c·v`.
    pub(crate) w: Vec3,
    /// `‖c·v‖²`.
    pub(crate) ww: f32,
}

impl Scaled {
    /// A unit vector as it is (`c = 1`), its squared length taken as 1: for directions the caller
    /// gives as unit (an infinite viewer, a directional light), in both forms alike.
    #[inline(always)]
    pub(crate) fn unit(v: Vec3) -> Self {
        Self { w: v, ww: 1.0 }
    }
}

/// `(normalize_or_zero(v), length(v))` for any `v`, inline and without a branch or a call: the
/// rare cases of the functions here, and the whole of [`normalize_full_scaled`]; and the scaled
/// vector it normalised ([`Scaled`]; zero where the direction is).
///
/// Scales `v` by the power of two `2^(127−e)` that brings its largest component (`e` from its
/// biased exponent, see [`scales`]) into `[2, 4)`. The scaling is exact, so the direction is the
/// correctly scaled one for every finite input (and, where `v·v` neither overflows nor
/// underflows, the same bits as `v · (1/√(v·v))`); the squared length lies in `[2⁻⁴⁶, 48)`.
/// Zero, NaN and infinite components give `(0, 0)`.
#[inline(always)]
fn full_range_scaled(v: Vec3) -> (Vec3, f32, Scaled) {
    // A NaN or infinite component leaves a NaN or `+∞` in `w` (see `scales`), which `valid`
    // rejects.
    let (scale, unscale) = scales(v);
    let w = v * scale;
    let w2 = w.length_squared();
    // NaN fails both tests; a zero vector gives 0.
    let valid = (w2 > 0.0) & (w2 < f32::INFINITY);
    let root = math::sqrt(w2);
    let len = math::min_or(root * unscale, math::MAX);
    let dir = w * (1.0 / root);
    if valid {
        (dir, len, Scaled { w, ww: w2 })
    } else {
        (Vec3::ZERO, 0.0, Scaled::unit(Vec3::ZERO))
    }
}

/// The power of two `2^(127−e)` for the largest magnitude `m` of `v`, and its inverse
/// `2^(e−127)`, with `e = max(E, 2) − 1` for `m`'s biased exponent `E`: it brings `m` into
/// `[2, 4)` (into `[2⁻²³, 2)` for `m < 2⁻¹²⁵`, zero and subnormals included), and both are normal
/// powers of two for every finite `m`. Where a component is infinite the scale is 0 (so
/// `m · scale` is NaN); a NaN component is skipped by the `max`es and stays NaN in `v · scale`.
///
/// Short, because every normalisation's chain of dependent operations starts here, and in the
/// one-light shader's vectorised loop that chain is what a point costs: the `max`es are IEEE
/// `maxNum` ([`f32::max`]) from a constant floor, which compiles to one `maxps` each even where the
/// components are loaded from memory (a compare-and-select of two values that may be NaN became a
/// compare and a blend per `max` in SSE2), and the scale's exponent field `254 − e = 255 − E` is
/// the bitwise complement of `m`'s, one `andnps` with the exponent mask (it was a halving, an
/// `and`, an `or` and an integer subtraction). The inverse subtracts one from `m`'s exponent
/// field, which cannot borrow past it, since the floor `2⁻¹²⁵` keeps `E ≥ 2`; it is off that
/// chain (only a distance reads it).
#[inline(always)]
fn scales(v: Vec3) -> (f32, f32) {
    scales_of_largest(largest_magnitude(v))
}

/// [`scales`] of the saturated difference `sub_saturating(to, from)`, from the unsaturated one
/// `d = to − from`: its largest magnitude saturated at `f32::MAX` is the saturated difference's,
/// and this order puts the saturation after the `max`es, where it waits for one operand rather
/// than for the difference's two clamps (the chain from the difference to the scale is one
/// operation shorter).
#[inline(always)]
fn scales_of_difference(d: Vec3) -> (f32, f32) {
    scales_of_largest(largest_magnitude(d).min(math::MAX))
}

/// `max(|x|, |y|, |z|, 2⁻¹²⁵)`: NaN components skipped, `+∞` kept.
#[inline(always)]
fn largest_magnitude(v: Vec3) -> f32 {
    const FLOOR: f32 = 2.0 * f32::MIN_POSITIVE; // 2⁻¹²⁵, biased exponent 2
    let (ax, ay, az) = (math::abs(v.x), math::abs(v.y), math::abs(v.z));
    az.max(ay.max(ax.max(FLOOR)))
}

/// [`scales`] for the largest magnitude `m ≥ 2⁻¹²⁵`.
#[inline(always)]
fn scales_of_largest(m: f32) -> (f32, f32) {
    let bits = m.to_bits();
    // The scale's field `254 − e = 255 − E` is the complement of `E`: one `andnps` of `m`'s bits
    // with the exponent mask, in the floating-point domain.
    (
        f32::from_bits(!bits & 0x7f80_0000),
        f32::from_bits(bits.wrapping_sub(0x0080_0000) & 0x7f80_0000),
    )
}

/// [`normalize_or_zero`] of a *finite* `v` by the full-range formula alone: no range test, no
/// branch and no call, and no test for non-finite input (the zero vector still gives zero).
///
/// The same answer (bit for bit where `v·v` neither overflows nor underflows) for more arithmetic
/// on the common path: what a loop that the compiler vectorises across points wants, since there
/// every branch is computed both ways.
///
/// Also returns the vector it normalised, [`Scaled`] (its largest component in `[2, 4)`).
#[inline(always)]
pub(crate) fn normalize_full_scaled(v: Vec3) -> (Vec3, Scaled) {
    let (scale, _) = scales(v);
    unit_of_scaled(v * scale)
}

/// [`normalize_full_scaled`] of `sub_saturating(to, from)` for finite points, the same bits,
/// with the shorter chain of [`scales_of_difference`].
#[inline(always)]
pub(crate) fn normalize_full_between_scaled(to: Vec3, from: Vec3) -> (Vec3, Scaled) {
    unit_of_scaled(scaled_difference(to, from).0)
}

/// `sub_saturating(to, from)` times its [`scales`] scale, and the inverse scale, by
/// [`scales_of_difference`].
#[inline(always)]
fn scaled_difference(to: Vec3, from: Vec3) -> (Vec3, f32) {
    let d = to - from;
    let (scale, unscale) = scales_of_difference(d);
    (saturate(d) * scale, unscale)
}

/// `w / ‖w‖` for a `w` scaled by [`scales`], and 0 for `w = 0`; and `w` itself.
#[inline(always)]
fn unit_of_scaled(w: Vec3) -> (Vec3, Scaled) {
    let ww = w.length_squared();
    // √(w·w) ≥ 2⁻²³ for any non-zero finite v; the floor only keeps 0 · (1/0) out for v = 0.
    (
        w * (1.0 / math::max_or(math::sqrt(ww), f32::MIN_POSITIVE)),
        Scaled { w, ww },
    )
}

/// [`direction_and_distance`] of finite points by the full-range formula alone (see
/// [`normalize_full_scaled`]): the same answer, bit for bit where `‖to − from‖²` neither
/// overflows nor underflows; and the difference [`Scaled`] (its largest component in `[2, 4)`).
#[inline(always)]
pub(crate) fn direction_and_distance_full_scaled(to: Vec3, from: Vec3) -> (Vec3, f32, Scaled) {
    let (w, unscale) = scaled_difference(to, from);
    let ww = w.length_squared();
    let root = math::max_or(math::sqrt(ww), f32::MIN_POSITIVE);
    (
        w * (1.0 / root),
        math::min_or(root * unscale, math::MAX),
        Scaled { w, ww },
    )
}

/// `Some(v / ‖v‖)`, or `None` when `v` is zero or not finite. See [`normalize_or_zero`].
///
/// ```
/// use glam::Vec3;
/// assert_eq!(phong::try_normalize(Vec3::ZERO), None);
/// assert_eq!(phong::try_normalize(Vec3::new(0.0, 2.0, 0.0)), Some(Vec3::Y));
/// ```
#[must_use]
#[inline]
pub fn try_normalize(v: Vec3) -> Option<Vec3> {
    let n = normalize_or_zero(v);
    (n != Vec3::ZERO).then_some(n)
}

/// The length ‖v‖ = √(v·v), without overflow or underflow in `v·v`, saturated to `f32::MAX`.
///
/// **Domain:** any finite `Vec3`. **Returns** a finite value `≥ 0`: a true length above `f32::MAX`
/// (possible only when components are near `f32::MAX`) saturates to `f32::MAX`; a non-finite
/// component gives `f32::MAX` for ±∞ and 0 for NaN.
///
/// ```
/// use glam::Vec3;
/// assert_eq!(phong::length(Vec3::new(3e30, 4e30, 0.0)), 5e30);
/// assert_eq!(phong::length(Vec3::new(3e-30, 4e-30, 0.0)), 5e-30);
/// ```
#[must_use]
#[inline(always)]
pub fn length(v: Vec3) -> f32 {
    let l2 = v.length_squared();
    if in_common_range(l2) {
        return math::sqrt(l2);
    }
    length_rare(v)
}

/// The rare cases of [`length`], out of line.
#[cold]
#[inline(never)]
fn length_rare(v: Vec3) -> f32 {
    if v.is_nan() {
        return 0.0;
    }
    if !v.is_finite() {
        return math::MAX;
    }
    if v == Vec3::ZERO {
        return 0.0;
    }
    let m = math::abs(v.x).max(math::abs(v.y)).max(math::abs(v.z));
    let s = rescaled(v);
    // ‖v‖ = m' · ‖s‖ where s = v·2^-e; recover 2^e from m / |largest component of s|.
    let ms = math::abs(s.x).max(math::abs(s.y)).max(math::abs(s.z));
    let l = math::sqrt(s.length_squared()) * (m / ms);
    if l.is_finite() { l } else { math::MAX }
}

/// `a − b` with each component saturated to `[−f32::MAX, f32::MAX]`.
///
/// Differences of finite points can overflow (e.g. `3e38 − (−3e38)`); the total paths use this so
/// the direction stays finite. The direction of a saturated difference is approximate.
#[inline(always)]
pub(crate) fn sub_saturating(a: Vec3, b: Vec3) -> Vec3 {
    saturate(a - b)
}

/// Each component saturated to `[−f32::MAX, f32::MAX]`.
#[inline(always)]
fn saturate(d: Vec3) -> Vec3 {
    d.max(Vec3::splat(-math::MAX)).min(Vec3::splat(math::MAX))
}

/// The unit direction from `from` to `to` and the distance, sharing one square root on the
/// common path: `(normalize_or_zero(to − from), length(to − from))` with the difference saturated
/// to `±f32::MAX` per component.
///
/// Returns `(0, 0)` when the points coincide; the distance saturates as in [`length`]. The common
/// path subtracts without saturating: a difference that overflows has an infinite squared length,
/// which fails the range test and is redone saturated out of line.
#[inline(always)]
pub(crate) fn direction_and_distance(to: Vec3, from: Vec3) -> (Vec3, f32) {
    let (direction, distance, _) = direction_and_distance_in::<false>(to, from);
    (direction, distance)
}

/// [`direction_and_distance`] and the saturated difference [`Scaled`] (as
/// [`normalize_flagged_in`] does with `LOBE`): the same direction and distance, bit for bit.
#[inline(always)]
pub(crate) fn direction_and_distance_scaled(to: Vec3, from: Vec3) -> (Vec3, f32, Scaled) {
    direction_and_distance_in::<true>(to, from)
}

/// [`direction_and_distance_scaled`] with the range of `LOBE` (see [`in_range`]): the body of
/// both forms.
#[inline(always)]
fn direction_and_distance_in<const LOBE: bool>(to: Vec3, from: Vec3) -> (Vec3, f32, Scaled) {
    let v = to - from;
    let l2 = v.length_squared();
    if in_range::<LOBE>(l2) {
        let d = math::sqrt(l2);
        return (v * (1.0 / d), d, Scaled { w: v, ww: l2 });
    }
    full_range_scaled(sub_saturating(to, from))
}

/// `normalize_or_zero(to − from)` with the difference saturated as in [`direction_and_distance`].
#[inline(always)]
pub(crate) fn direction_between(to: Vec3, from: Vec3) -> Vec3 {
    direction_between_in::<false>(to, from).0
}

/// [`direction_between_in`] with Phong's squared base's range (`LOBE`).
#[inline(always)]
pub(crate) fn direction_between_scaled(to: Vec3, from: Vec3) -> (Vec3, Scaled) {
    direction_between_in::<true>(to, from)
}

/// [`direction_between`] and the saturated difference [`Scaled`], in the range of `LOBE` (as
/// [`normalize_flagged_in`]): the same direction, bit for bit, either way.
#[inline(always)]
fn direction_between_in<const LOBE: bool>(to: Vec3, from: Vec3) -> (Vec3, Scaled) {
    let v = to - from;
    let l2 = v.length_squared();
    if in_range::<LOBE>(l2) {
        return (v * (1.0 / math::sqrt(l2)), Scaled { w: v, ww: l2 });
    }
    let (d, _, w) = full_range_scaled(sub_saturating(to, from));
    (d, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(direction, length)` of the full-range path.
    fn full_range(v: Vec3) -> (Vec3, f32) {
        let (dir, len, _) = full_range_scaled(v);
        (dir, len)
    }

    /// The forms that also return their vector for Phong's squared base give the same direction
    /// and distance, bit for bit, as the plain ones, inside their narrower common range and on
    /// both sides of its bounds; the vector they return is the difference times a power of two.
    #[test]
    fn the_scaled_forms_keep_the_directions() {
        let mut checked = 0;
        for e in -70i32..=70 {
            for m in [1.0f32, 1.3, 1.99] {
                let s = m * 2f32.powi(e);
                for d in [Vec3::new(s, -0.3 * s, 0.7 * s), Vec3::new(0.0, 0.0, s)] {
                    let from = Vec3::new(0.5, -0.25, 2.0);
                    let to = from + d;
                    let (dir, dist) = direction_and_distance(to, from);
                    let (dir2, dist2, w) = direction_and_distance_scaled(to, from);
                    assert_eq!((dir, dist.to_bits()), (dir2, dist2.to_bits()), "{d}");
                    assert_eq!(
                        direction_between(to, from),
                        direction_between_in::<true>(to, from).0
                    );
                    let (n, present) = normalize_flagged(d);
                    let (n2, present2, w2) = normalize_flagged_in::<true>(d);
                    assert_eq!((n, present), (n2, present2), "{d}");
                    // `w` is `to − from` times a power of two, with its squared length.
                    let diff = to - from;
                    if diff == Vec3::ZERO {
                        continue;
                    }
                    let ratio = w.w.max_element().max(-w.w.min_element())
                        / diff.max_element().max(-diff.min_element());
                    assert_eq!(ratio, f32::from_bits(ratio.to_bits() & 0x7f80_0000), "{d}");
                    assert_eq!(w.ww, w.w.length_squared());
                    assert_eq!(w2.w.normalize(), n, "{d}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 500, "{checked}");
    }

    #[test]
    fn subnormal_and_huge_directions_are_exact() {
        let tiny = normalize_or_zero(Vec3::new(1e-40, -1e-40, 0.0));
        let expect = Vec3::new(1.0, -1.0, 0.0) / 2f32.sqrt();
        assert!((tiny - expect).length() < 1e-6, "{tiny}");
        let huge = normalize_or_zero(Vec3::new(f32::MAX, f32::MAX, f32::MAX));
        assert!((huge.length() - 1.0).abs() < 1e-6, "{huge}");
    }

    #[test]
    fn length_is_scaled_correctly_everywhere() {
        for &s in &[1e-44f32, 1e-38, 1e-20, 1.0, 1e20, 1e37] {
            let v = Vec3::new(3.0 * s, 4.0 * s, 0.0);
            let l = length(v);
            let rel = ((l as f64) - 5.0 * s as f64).abs() / (5.0 * s as f64);
            // Subnormal inputs carry few significant bits; 3·1e-44 has only ~5.
            let tol = if s < 1e-38 { 0.2 } else { 1e-6 };
            assert!(rel < tol, "s={s}: {l}");
        }
        assert_eq!(length(Vec3::splat(f32::MAX)), f32::MAX);
    }

    /// The full-range forms at every exponent of the largest component, subnormals and the top
    /// binade included, against an `f64` evaluation: the direction within 2 ulp-sized steps of
    /// `f32` (`4·2⁻²⁴` per component, plus the subnormal inputs' own rounding) and the length
    /// within the same relative error.
    #[test]
    fn full_range_forms_hold_at_every_exponent() {
        let mut checked = 0;
        for e in 0u32..=254 {
            for mantissa in [0u32, 1, 0x40_0000, 0x7f_ffff] {
                let big = f32::from_bits(e << 23 | mantissa);
                if big == 0.0 {
                    continue;
                }
                for (fy, fz) in [(0.0f32, 0.0f32), (-0.75, 0.5), (1.0, -1.0)] {
                    let v = Vec3::new(big, fy * big, fz * big);
                    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
                    let len = (x * x + y * y + z * z).sqrt();
                    // A subnormal component carries fewer bits than the f32 arithmetic.
                    let tol = 4.0 * f64::from(f32::EPSILON) + 2f64.powi(-149) / big.abs() as f64;
                    let (dir, l) = full_range(v);
                    let want = [x / len, y / len, z / len];
                    for (got, d) in [
                        (dir, "full_range"),
                        (normalize_full_scaled(v).0, "normalize_full_scaled"),
                    ] {
                        for (g, w) in got.to_array().into_iter().zip(want) {
                            assert!(
                                (g as f64 - w).abs() <= tol,
                                "{d}: v = {v:?}: {got} vs {want:?}"
                            );
                        }
                    }
                    let want_len = len.min(f32::MAX as f64);
                    assert!(
                        (l as f64 - want_len).abs() <= tol * want_len,
                        "v = {v:?}: {l:e}"
                    );
                    let (dir2, l2, _) = direction_and_distance_full_scaled(v, Vec3::ZERO);
                    assert_eq!((dir2, l2.to_bits()), (dir, l.to_bits()), "v = {v:?}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 3000, "{checked}");
        // Zero, NaN and infinite components.
        assert_eq!(full_range(Vec3::ZERO), (Vec3::ZERO, 0.0));
        assert_eq!(normalize_full_scaled(Vec3::ZERO).0, Vec3::ZERO);
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            for v in [
                Vec3::new(bad, 1.0, 0.0),
                Vec3::new(1.0, 0.0, bad),
                Vec3::splat(bad),
            ] {
                assert_eq!(full_range(v), (Vec3::ZERO, 0.0), "{v}");
            }
        }
    }
}
