//! The specular exponent as a value the shading code calls inline: one small type per pow plan.
//!
//! The shading loops take the plan as a type implementing [`LobePow`] rather than as a closure.
//! A closure's body is inlined only when the optimiser judges it worth it, and when it is not
//! (a second instance of the same loop in the caller's crate is enough to tip the balance), the
//! call inside the caller's loop over points stops the compiler from vectorising that loop, which
//! made per-point shading four times slower. Each `pow` here is `#[inline(always)]`.

use crate::math;
use crate::pow::{PolyConsts, PowPlan, auto_pow, auto_pow_fixed, pow_u32, pow_u32_fixed};

/// `x^e` on `[0, 1]` for one lobe's exponent `e`, evaluated inline.
pub(crate) trait LobePow: Copy {
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
/// bits) when `frac = 0`, else the degree-7 polynomial.
#[derive(Clone, Copy)]
pub(crate) struct Auto {
    pub(crate) n: u32,
    pub(crate) frac: f32,
}

impl LobePow for Auto {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        auto_pow(x, self.n, self.frac)
    }

    #[inline(always)]
    fn lobe(self, x: f32) -> f32 {
        lobe_by_branch(x, |b| auto_pow(b, self.n, self.frac))
    }
}

/// `PowStrategy::Auto`'s plan as straight-line code, for loops the compiler vectorises across
/// points (see `auto_pow_fixed`); `SHARED`: the exponent is the same at every point.
#[derive(Clone, Copy)]
pub(crate) struct AutoFixed<'a, const SHARED: bool> {
    pub(crate) n: u32,
    pub(crate) frac: f32,
    pub(crate) consts: &'a PolyConsts<7, 5>,
}

impl<const SHARED: bool> LobePow for AutoFixed<'_, SHARED> {
    #[inline(always)]
    fn pow(self, x: f32) -> f32 {
        auto_pow_fixed::<SHARED>(x, self.n, self.frac, self.consts)
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
