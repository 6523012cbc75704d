//! The specular exponent as a value the shading code calls inline: one small type per pow plan.
//!
//! The shading loops take the plan as a type implementing [`LobePow`] rather than as a closure.
//! A closure's body is inlined only when the optimiser judges it worth it, and when it is not
//! (a second instance of the same loop in the caller's crate is enough to tip the balance), the
//! call inside the caller's loop over points stops the compiler from vectorising that loop, which
//! made per-point shading four times slower. Each `pow` here is `#[inline(always)]`.

use crate::math;
use crate::pow::{
    P7_CONSTS, PolyConsts, PowPlan, auto_pow, auto_pow_fixed, poly_pow_of_scaled, pow_u32,
    pow_u32_fixed,
};

/// `x^e` on `[0, 1]` for one lobe's exponent `e`, evaluated inline.
pub(crate) trait LobePow: Copy {
    /// Whether Phong's lobe under this plan may read the squared base (`PowStrategy::Auto`'s
    /// plans, whose polynomial exponent is half the shininess: see `plan_for` in shader.rs), so
    /// that the shading loop must form it; see [`phong_lobe`](Self::phong_lobe).
    const SQUARED_BASE: bool = false;

    /// `x^e` for `x ∈ [0, 1]`.
    fn pow(self, x: f32) -> f32;

    /// The lobe for a raw base `x` (any value, NaN included): `pow(min(x, 1))` where `x > 0`, else
    /// 0. This default is written without a branch in `x`, for the forms a loop over points
    /// vectorises: `pow` runs on the clamped base and is selected away. The forms for one point
    /// at a time override it with a branch (see [`lobe_by_branch`]); Blinn-Phong's light loop
    /// calls [`lobe_power_selected`] instead, a select the compiler keeps.
    #[inline(always)]
    fn lobe(self, x: f32) -> f32 {
        let p = self.pow(math::clamp_or_lo(x, 0.0, 1.0));
        if x > 0.0 { p } else { 0.0 }
    }

    /// Phong's lobe from either of its bases: `x = R·V` (raw, any value) and
    /// `xs = 2^24·(R·V)²` (`ResolvedModel::phong_base_squared`, read only where
    /// [`SQUARED_BASE`](Self::SQUARED_BASE) holds). The default is [`lobe`](Self::lobe)`(x)`;
    /// `Auto`'s plans take `xs` where their exponent is the polynomial's (half the shininess), so
    /// that the power does not wait for the unit vectors, and `x` for a whole shininess, which
    /// they square.
    #[inline(always)]
    fn phong_lobe(self, x: f32, xs: f32) -> f32 {
        let _ = xs;
        self.lobe(x)
    }
}

/// The lobe of a base `x` as [`LobePow::lobe`] defines it, for code that shades one point at a
/// time: `x ≤ 0` (about half of all bases) skips `pow` by a branch. A select there made the
/// processor evaluate the power at every point (for a per-point exponent, the polynomial's two
/// chains), and where LLVM paired the clamp's `max` with the visibility's clamp (SLP), the pair
/// became a mask move and three branches per light. Measured on probes of a textured fragment
/// callback and a three-light ray tracer (x86-64 baseline, callgrind and timing).
#[inline(always)]
fn lobe_by_branch(x: f32, pow: impl Fn(f32) -> f32) -> f32 {
    if x > 0.0 {
        pow(math::min_or(x, 1.0))
    } else {
        0.0
    }
}

/// No specular lobe: never read.
#[derive(Clone, Copy)]
pub(crate) struct NoLobe;

impl LobePow for NoLobe {
    #[inline(always)]
    fn pow(self, _: f32) -> f32 {
        0.0
    }
}

/// `PowStrategy::Auto`'s plan for one point at a time: squaring (with a loop over the exponent's
/// bits) when `frac = 0`, else the degree-7 polynomial. `SQUARED`: a point's own exponent, whose
/// Phong lobe reads the squared base (see [`LobePow::phong_lobe`]).
#[derive(Clone, Copy)]
pub(crate) struct Auto<const SQUARED: bool> {
    pub(crate) n: u32,
    pub(crate) frac: f32,
}

impl<const SQUARED: bool> LobePow for Auto<SQUARED> {
    const SQUARED_BASE: bool = SQUARED;

    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        auto_pow(x, self.n, self.frac)
    }

    /// A whole exponent squares the clamped base at every point and selects (the ladder is a few
    /// products, cheaper than a mispredicted branch on the base's sign, which is random from one
    /// point to the next); a fractional one skips the polynomial's two chains by a branch
    /// ([`lobe_by_branch`]). The same bits either way: `auto_pow` is the ladder for `frac = 0`.
    #[inline(always)]
    fn lobe(self, x: f32) -> f32 {
        if self.frac == 0.0 {
            lobe_power_selected(x, Squaring(self.n))
        } else {
            lobe_by_branch(x, |b| auto_pow(b, self.n, self.frac))
        }
    }

    /// A point's own exponent: the polynomial on `xs` by a branch on its sign, as
    /// [`lobe_by_branch`] does on `x` (a zero exponent gives 1 where `xs > 0`, see
    /// [`AutoFixed`]'s).
    #[inline(always)]
    fn phong_lobe(self, x: f32, xs: f32) -> f32 {
        if !SQUARED {
            return self.lobe(x);
        }
        if xs > 0.0 {
            poly_pow_of_scaled::<true>(xs, self.frac, &P7_CONSTS)
        } else {
            0.0
        }
    }
}

/// `PowStrategy::Auto`'s plan as straight-line code, for loops the compiler vectorises across
/// points (see `auto_pow_fixed`); `SHARED`: the exponent is the same at every point. A point's
/// own exponent (`!SHARED`) is for Phong's squared base (see [`LobePow::phong_lobe`]).
#[derive(Clone, Copy)]
pub(crate) struct AutoFixed<'a, const SHARED: bool> {
    pub(crate) n: u32,
    pub(crate) frac: f32,
    pub(crate) consts: &'a PolyConsts<7, 5>,
}

impl<const SHARED: bool> LobePow for AutoFixed<'_, SHARED> {
    const SQUARED_BASE: bool = !SHARED;

    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        auto_pow_fixed::<SHARED>(x, self.n, self.frac, self.consts)
    }

    /// A point's own exponent: the polynomial on `xs`, without a branch on the data.
    #[inline(always)]
    fn phong_lobe(self, x: f32, xs: f32) -> f32 {
        if SHARED {
            return self.lobe(x);
        }
        debug_assert_eq!(self.n, 0, "a per-point exponent's plan never squares");
        // A zero exponent needs no select of its own: `0·log2 xs` is 0 for every `xs`, since
        // `log2` is finite there (about −151 at 0), and `exp2(0)` is exactly 1.
        let p = poly_pow_of_scaled::<false>(math::max_or(xs, 0.0), self.frac, self.consts);
        if xs > 0.0 { p } else { 0.0 }
    }
}

/// `x^n` by repeated squaring, with a loop over the bits of `n`.
#[derive(Clone, Copy)]
pub(crate) struct Squaring(pub(crate) u32);

impl LobePow for Squaring {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        pow_u32(x, self.0)
    }

    #[inline(always)]
    fn lobe(self, x: f32) -> f32 {
        lobe_by_branch(x, |b| pow_u32(b, self.0))
    }
}

/// `x^n` by repeated squaring as straight-line code (see `pow_u32_fixed`).
#[derive(Clone, Copy)]
pub(crate) struct SquaringFixed(pub(crate) u32);

impl LobePow for SquaringFixed {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        pow_u32_fixed(x, self.0)
    }
}

/// `powf(x, s)`, skipped for `x ≤ 0`: a call worth avoiding, since about half of all lobe bases
/// are `≤ 0`.
#[derive(Clone, Copy)]
pub(crate) struct Exact(pub(crate) f32);

impl LobePow for Exact {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        if x > 0.0 { math::powf(x, self.0) } else { 0.0 }
    }
}

/// Any other plan, through [`PowPlan::eval`].
#[derive(Clone, Copy)]
pub(crate) struct Plan(pub(crate) PowPlan);

impl LobePow for Plan {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        self.0.eval(x)
    }
}

/// `base^e` through `pow` for a lobe base: `x ≤ 0` or NaN gives 0, `x ≥ 1` gives `pow(1)` (so
/// `0^0 = 0`), by the plan's [`lobe`](LobePow::lobe).
#[inline(always)]
pub(crate) fn lobe_power(x: f32, pow: impl LobePow) -> f32 {
    pow.lobe(x)
}

/// [`lobe_power`] without a branch in `x`, whatever the plan: for Blinn-Phong's `(N·H)²` in the
/// light loop, which is exactly 0 wherever `N·(L + V) ≤ 0` (about half of all points, at
/// random). There the branch of the light loop's plans cost more than the power it skips: one
/// point at a time at `s = 32`, 4096 points took 163–168 µs with this select and 178 µs with the
/// branch (a probe of `blinn_4096`'s `scalar_lone`, tenth percentile of interleaved runs). Marked
/// unpredictable, or LLVM turns the select back into a branch around the power.
#[inline(always)]
pub(crate) fn lobe_power_selected(x: f32, pow: impl LobePow) -> f32 {
    let p = pow.pow(math::clamp_or_lo(x, 0.0, 1.0));
    core::hint::select_unpredictable(x > 0.0, p, 0.0)
}
