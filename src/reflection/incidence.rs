//! The three cosines every lobe in the Phong family is built from.

use glam::Vec3;

/// The cosines every lobe is built from, computed once at a point and shared by the diffuse and
/// specular lobes.
///
/// ```text
/// n_dot_l = N·L,   n_dot_v = N·V,   l_dot_v = L·V
/// n_dot_h_sq = (N·H)² = max(N·(L+V), 0)² / ‖L+V‖²        (H = (L+V)/‖L+V‖)
/// ```
///
/// With unit vectors Phong needs no vector at all, `R·V = 2(N·L)(N·V) − L·V`
/// ([`r_dot_v`](Self::r_dot_v)), and Blinn's `(N·H)²` equals `max(N·L + N·V, 0)² / (2 + 2 L·V)`.
/// That last form is *not* used when the vectors are at hand: as `L → −V` (a grazing light seen
/// in the mirror direction, e.g. a low sun's glint on a floor) `2 + 2 L·V` cancels catastrophically
/// once `L·V` has been rounded to `f32`, while `L + V` and `‖L+V‖²` computed from the vectors keep
/// full relative precision. So [`new`](Self::new) computes `n_dot_h_sq` from the vectors (still
/// without a square root), and [`from_cosines`](Self::from_cosines) uses the cosine form for
/// callers who only have cosines. Measured errors of both are in docs/accuracy.md; derivations in
/// docs/derivations.md, section "Dot-product forms of the lobes".
///
/// **Domain:** every direction points away from the surface (to the light, to the viewer) and is
/// unit, or the zero vector meaning "no such direction". The fields are public so batch code and
/// renderers with their own cosines can fill them directly; keep them in `[−1, 1]` (and
/// `n_dot_h_sq` in `[0, 1]`).
///
/// **A missing direction** (a zero `N`, `L` or `V` given to [`new`](Self::new)) gives cosines for
/// which every lobe of every model is 0, and the diffuse lobe too when `N` or `L` is missing: the
/// viewer at the point has no highlight and a light at the point lights nothing, as in Mesa. Every
/// cosine involving the missing vector is 0 (its dot product with anything), `n_dot_h_sq` is 0
/// (no halfway vector without both `L` and `V`), and without a normal there is no surface, so
/// `l_dot_v` is 0 as well (otherwise Phong's `R·V = 2(N·L)(N·V) − L·V` would read `−L·V`, a
/// highlight at `L = −V` with no surface to reflect it). In general: cosines with
/// `l_dot_v = n_dot_h_sq = 0` and `n_dot_l = 0` or `n_dot_v = 0` have both specular lobes 0,
/// which is also the state [`Incidence::default`] is in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Incidence {
    /// `N·L`, the cosine of the angle of incidence.
    pub n_dot_l: f32,
    /// `N·V`, the cosine of the viewing angle.
    pub n_dot_v: f32,
    /// `L·V`, the cosine between the light and the view direction.
    pub l_dot_v: f32,
    /// `(N·H)²` for the clamped cosine, in `[0, 1]`; 0 when `L = −V` (no halfway vector exists).
    pub n_dot_h_sq: f32,
}

impl Incidence {
    /// The cosines of unit `n`, `l`, `v` (debug builds assert unit length or zero).
    ///
    /// ```text
    /// (N·L, N·V, L·V),   (N·H)² = max(N·(L+V), 0)² / ‖L+V‖²  (0 if L + V = 0)
    /// ```
    ///
    /// **Degenerate input:** a zero vector is a missing direction (see the type's docs): its
    /// cosines are 0, `(N·H)²` is 0 when `L` or `V` is missing, and `L·V` is 0 when `N` is, so
    /// every specular lobe is 0, and the diffuse lobe too for a missing `N` or `L`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{BlinnPhong, Incidence, Phong, ReflectionModel};
    /// let g = Incidence::new(Vec3::Z, Vec3::Z, Vec3::X);
    /// assert_eq!((g.n_dot_l, g.n_dot_v, g.l_dot_v), (1.0, 0.0, 0.0));
    /// assert!((g.n_dot_h_sq - 0.5).abs() < 1e-7);
    /// // The viewer at the point: no highlight, whatever the model.
    /// let at_eye = Incidence::new(Vec3::Z, Vec3::Z, Vec3::ZERO);
    /// assert_eq!(BlinnPhong::default().specular(&at_eye, 16.0), 0.0);
    /// assert_eq!(Phong::default().specular(&at_eye, 16.0), 0.0);
    /// assert_eq!(Phong::default().diffuse(&at_eye), 1.0);
    /// ```
    #[must_use]
    #[inline]
    pub fn new(n: Vec3, l: Vec3, v: Vec3) -> Self {
        debug_assert!(unit_or_zero(n), "Incidence::new: n must be unit, got {n}");
        debug_assert!(unit_or_zero(l), "Incidence::new: l must be unit, got {l}");
        debug_assert!(unit_or_zero(v), "Incidence::new: v must be unit, got {v}");
        let sum = l + v;
        let t = crate::math::max_or(n.dot(sum), 0.0);
        let d = sum.length_squared();
        // ‖L+V‖² below the smallest normal f32 means L = −V to within 1e-19: no halfway vector.
        // Nor is there one when L or V is missing (L + V would be the other one alone). A missing
        // N already gives t = 0.
        let both = l != Vec3::ZERO && v != Vec3::ZERO;
        let n_dot_h_sq = if d >= f32::MIN_POSITIVE && both {
            crate::math::min_or(t * t / d, 1.0)
        } else {
            0.0
        };
        // Without a surface no lobe exists: L·V is read as 0 so R·V = 2(N·L)(N·V) − L·V is 0 too.
        let l_dot_v = if n != Vec3::ZERO { l.dot(v) } else { 0.0 };
        Incidence {
            n_dot_l: n.dot(l),
            n_dot_v: n.dot(v),
            l_dot_v,
            n_dot_h_sq,
        }
    }

    /// The cosines when only the three cosines are known (no vectors): `(N·H)²` from the cosine form.
    ///
    /// ```text
    /// (N·H)² = max(N·L + N·V, 0)² / (2 + 2 L·V),   0 where 2 + 2 L·V ≤ 1e-12
    /// ```
    ///
    /// **Accuracy:** as good as [`new`](Self::new) except near `L = −V`, where `2 + 2 L·V` cancels
    /// (docs/accuracy.md measures it): prefer [`new`](Self::new) when the vectors are available.
    /// **Domain:** cosines in `[−1, 1]` of three *unit* vectors. **Returns** `n_dot_h_sq` in
    /// `[0, 1]`.
    ///
    /// **What it can represent:** three cosines do not say whether a vector was missing (`N·V = 0`
    /// and `L·V = 0` also describe a viewer on the horizon at right angles to the light, which has
    /// a halfway vector), so every input is read as the cosines of unit vectors. For a missing
    /// direction use [`new`](Self::new) with the zero vector, or build the cosines it documents
    /// (e.g. [`Incidence::default`], where every lobe is 0).
    ///
    /// ```
    /// let g = phong::Incidence::from_cosines(0.5, 1.0, 0.5);
    /// assert_eq!(g.n_dot_h_sq, 0.75);
    /// ```
    #[must_use]
    #[inline]
    pub fn from_cosines(n_dot_l: f32, n_dot_v: f32, l_dot_v: f32) -> Self {
        let t = (n_dot_l + n_dot_v).max(0.0);
        let den = 2.0 + 2.0 * l_dot_v;
        let n_dot_h_sq = if den > 1e-12 {
            (t * t / den).min(1.0)
        } else {
            0.0
        };
        Incidence {
            n_dot_l,
            n_dot_v,
            l_dot_v,
            n_dot_h_sq,
        }
    }

    /// The cosines after normalising each vector with [`normalize_or_zero`](crate::normalize_or_zero).
    /// Total: a zero or non-finite vector is a missing direction, as in [`new`](Self::new) (every
    /// specular lobe 0; the diffuse lobe 0 too if it is `n` or `l`).
    #[must_use]
    #[inline]
    pub fn from_unnormalized(n: Vec3, l: Vec3, v: Vec3) -> Self {
        use crate::normalize_or_zero as nz;
        Self::new(nz(n), nz(l), nz(v))
    }

    /// Phong's `R·V = 2(N·L)(N·V) − L·V`, clamped to `[−1, 1]` (rounding can push it past ±1).
    #[must_use]
    #[inline]
    pub fn r_dot_v(&self) -> f32 {
        crate::math::min_or(
            crate::math::max_or(2.0 * self.n_dot_l * self.n_dot_v - self.l_dot_v, -1.0),
            1.0,
        )
    }

    /// Blinn's `(N·H)²`: the field [`n_dot_h_sq`](Self::n_dot_h_sq), clamped to `[0, 1]`.
    ///
    /// **Degenerate input:** at `L = −V` the halfway vector does not exist and this is 0, the same
    /// answer as [`halfway_or_zero`](crate::halfway_or_zero) gives (the zero vector).
    #[must_use]
    #[inline]
    pub fn n_dot_h_squared(&self) -> f32 {
        crate::math::clamp_or_lo(self.n_dot_h_sq, 0.0, 1.0)
    }
}

fn unit_or_zero(v: Vec3) -> bool {
    let l2 = v.length_squared();
    l2 == 0.0 || (l2 - 1.0).abs() < 1e-3
}
