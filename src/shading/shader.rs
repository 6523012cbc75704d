//! A model, a material and a scene prepared once, then many points shaded one at a time.

use glam::{Vec3, Vec3A};

use crate::incidence::Incidence;
use crate::light::{FlatLight, LightSource, sanitize_colour};
use crate::lobe_pow::{self, LobePow, lobe_power, lobe_power_selected};
use crate::material::Material;
use crate::math;
use crate::model::ReflectionModel;
use crate::normalize::{
    Scaled, direction_between, direction_between_scaled, normalize_flagged,
    normalize_flagged_scaled, normalize_full_between_scaled, normalize_full_scaled,
};
use crate::normalize_or_zero;
use crate::pow::{
    P7_CONSTS, Poly, PolyConsts, PowPlan, PowStrategy, auto_split, auto_split_per_point,
};
use crate::resolved_model::{Lobe, ResolvedModel, SpecularPlan};
use crate::shade::{Scene, Viewer};
use crate::surface::Surface;
use crate::terms::Terms;
use crate::visibility::{Unshadowed, Visibility};

/// Shades points one at a time under a scene, with everything that depends only on the model, the
/// material and the scene worked out once in [`new`](Self::new).
///
/// ```text
/// ambient  = Ka ⊙ (Ia + Σᵢ fᵢ·Laᵢ)
/// diffuse  = Kd ⊙ Σᵢ fᵢ·visᵢ · Ldᵢ · diffuse(Nᐧ Lᵢ)
/// specular = Ks ⊙ Σᵢ fᵢ·visᵢ · Lsᵢ · specular(N, Lᵢ, V, s)
/// emission = Ke
/// ```
///
/// `fᵢ` is light `i`'s attenuation × spot factor at the point, `visᵢ` its [`Visibility`] (1 without
/// shadows), `N = normalize(normal)`, `Lᵢ` the unit direction to the light, `V` the unit direction
/// to the viewer. This is the equation of [`shade`](crate::shade), which is `Shader::new(…).shade(…)`.
///
/// What is prepared: the model's lobe, gate and normalisation (a [`ResolvedModel`]), the pow plan
/// for the material's shininess (e.g. five squarings for `s = 32` under
/// [`PowStrategy::Auto`](crate::PowStrategy::Auto)), the sanitised material colours, the scene
/// ambient, and an infinite viewer's direction. Per point and light what remains is straight-line
/// arithmetic on cosines: no reflect or halfway vector is built, a Phong model computes no `(N·H)²`,
/// and rare inputs (zero or huge vectors) leave the common path in one range test per
/// normalisation.
///
/// **Domain:** any finite position and normal (the normal need not be unit); lights, material and
/// scene as documented on their types. **Degenerate input** is documented on [`shade`](crate::shade)
/// and holds for every method here: no NaN and no panic from finite input, overflow saturates at
/// `f32::MAX`.
///
/// Cheap to build (a few dozen instructions, no allocation): a ray tracer whose viewer changes with
/// every ray builds one per hit.
///
/// **Loops the compiler can vectorise.** With one [`DirectionalLight`](crate::DirectionalLight)
/// or [`PointLight`](crate::PointLight) (or a [`Light`](crate::Light) holding one) and one of the
/// crate's models, a point's code has no loop, no call and no branch on the data: rare inputs are
/// selects, not fallbacks. So a loop over points that builds its scene where it shades (the light
/// count is then visible to the compiler, as in the example above) is vectorised by LLVM like
/// hand-written shading code, four points per instruction on any x86-64; for one material
/// ([`shade`](Self::shade), [`shade_visible`](Self::shade_visible)) a whole shininess then also
/// skips the polynomial form of [`PowStrategy::Auto`](crate::PowStrategy::Auto), whose choice
/// becomes a branch in the compiled loop. Two or more lights, a
/// [`SpotLight`](crate::SpotLight), a light or model from outside the crate, or a scene the
/// compiler cannot see into take the light loop, one point at a time. Both give the same result
/// (bit for bit wherever no squared length under- or overflows `f32`). docs/performance.md measures
/// both shapes.
///
/// **One point per call.** Where the caller's loop cannot be vectorised (a recursive ray tracer,
/// a per-fragment callback that samples textures between points), the branch-free form pays for
/// every rare case at every point: take [`one_at_a_time`](Self::one_at_a_time), which tests them
/// with branches instead. [`with_viewer`](Self::with_viewer), a ray tracer's call per hit,
/// returns that form.
///
/// ```
/// use glam::{Vec3, Vec3A};
/// use phong::{Attenuation, BlinnPhong, LightColors, Material, PointLight, Scene, Shader, Viewer};
///
/// let lamp = PointLight::try_new(
///     Vec3::new(1.2, 1.0, 2.0),
///     Attenuation::try_polynomial(1.0, 0.09, 0.032)?,
///     LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5)?,
/// )?;
/// let scene = Scene { lights: &[lamp], ambient: Vec3::ZERO, viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)) };
/// let coral = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0)?;
/// let shader = Shader::new(BlinnPhong::default(), &coral, &scene);
/// for (p, n) in [(Vec3::ZERO, Vec3::Z), (Vec3::X, Vec3::Y)] {
///     let rgb = shader.shade(p, n).total();
///     assert_eq!(rgb, phong::shade(&BlinnPhong::default(), &coral, &scene, p, n).total());
/// }
/// # Ok::<(), phong::PhongError>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Shader<'a, M, L> {
    model: M,
    resolved: Option<ResolvedModel>,
    lights: &'a [L],
    ambient_light: Vec3,
    viewer: Viewer,
    emission: Vec3,
    /// Upper bounds of the three light sums over every point: `Ia + Σ fmax·La`, `Σ fmax·Ld`,
    /// `Σ fmax·Ls` (`fmax` = [`LightSource::max_factor`]), saturated at `f32::MAX`.
    bounds: [Vec3; 3],
    prepared: Prepared,
    /// The scene's one light, when it has exactly one and it is a directional or point light, in
    /// the form [`Shader::one_light`] evaluates with no branch.
    one: Option<OneLight>,
}

/// A scene's only light, reduced for [`Shader::one_light`].
#[derive(Clone, Copy, Debug)]
struct OneLight {
    flat: FlatLight,
    /// `Auto`'s polynomial constants, opaque (see [`PolyConsts`]).
    poly: PolyConsts<7, 5>,
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
    /// Whether the light's sums (`Ia + f·La`, `f·vis·wd·Ld`, `f·vis·ws·Ls`) stay below
    /// `f32::MAX / 4` at every point for every per-point surface: the light's bounds allow it and
    /// the model's specular scale is 1 at any shininess (no normalisation). A per-point surface
    /// then saturates its products only, not the sums, which cannot reach `f32::MAX`.
    sums_below: bool,
}

/// A surface with its specular constants, sanitised, ready for the per-light loop.
#[derive(Clone, Copy, Debug)]
struct Prepared {
    ka: Vec3,
    kd: Vec3,
    ks: Vec3,
    s: f32,
    specular: SpecularPlan,
    /// Whether no sum, product or total of the equation can reach `f32::MAX` at any point for
    /// this surface, so the per-point saturation can be skipped (see [`Shader::prepare`]).
    safe: bool,
}

impl<'a, M: ReflectionModel, L: LightSource> Shader<'a, M, L> {
    /// Prepares `model`, `material` and `scene` for shading many points.
    ///
    /// The model is taken by value (the crate's models are small `Copy` types); a reference to a
    /// model works too, since `&M` is a [`ReflectionModel`] wherever `M` is.
    ///
    /// **Domain:** as [`shade`](crate::shade). The scene's ambient light is sanitised (NaN and
    /// negatives read as 0) and an infinite viewer's direction normalised here.
    #[must_use]
    #[inline]
    pub fn new(model: M, material: &Material, scene: &Scene<'a, L>) -> Self {
        Self::with_bounds(model, material, scene, true)
    }

    /// [`new`](Self::new) for a single point ([`shade`](crate::shade)): without the pass over
    /// the lights that bounds their sums, which only pays off over many points. Such a shader
    /// always saturates (the bounds read `+∞`, so `Prepared::safe` is false).
    #[inline]
    pub(crate) fn for_one_point(model: M, material: &Material, scene: &Scene<'a, L>) -> Self {
        Self::with_bounds(model, material, scene, false)
    }

    #[inline(always)]
    fn with_bounds(model: M, material: &Material, scene: &Scene<'a, L>, bound: bool) -> Self {
        let resolved = model.resolve();
        let viewer = match scene.viewer {
            Viewer::At(eye) => Viewer::At(eye),
            Viewer::Infinite(dir) => Viewer::Infinite(normalize_or_zero(dir)),
        };
        let ambient_light = sanitize_colour(scene.ambient);
        let bounds = if bound {
            let mut b = [ambient_light, Vec3::ZERO, Vec3::ZERO];
            for light in scene.lights {
                let f = light.max_factor();
                let c = light.colors();
                b[0] += c.ambient() * f;
                b[1] += c.diffuse() * f;
                b[2] += c.specular() * f;
            }
            b
        } else {
            [Vec3::INFINITY; 3]
        };
        let mut shader = Shader {
            model,
            resolved,
            lights: scene.lights,
            ambient_light,
            viewer,
            emission: material.emission(),
            bounds: bounds.map(|b| b.min(Vec3::splat(math::MAX))),
            // Only worth its preparation over many points (and `for_one_point` shades one).
            one: match scene.lights {
                [light] if bound => light.flat().map(|flat| OneLight {
                    flat,
                    poly: P7_CONSTS.opaque(),
                    ambient: light.colors().ambient(),
                    diffuse: light.colors().diffuse(),
                    specular: light.colors().specular(),
                    sums_below: resolved.is_some_and(|r| {
                        !r.normalization.is_normalized()
                            && scaled_sums(r, &bounds, 1.0).into_iter().all(below_quarter)
                    }),
                }),
                _ => None,
            },
            prepared: Prepared {
                ka: Vec3::ZERO,
                kd: Vec3::ZERO,
                ks: Vec3::ZERO,
                s: 0.0,
                specular: plan_for(None, 0.0, true),
                safe: false,
            },
        };
        shader.prepared = shader.prepare(
            material.ambient(),
            material.diffuse(),
            material.specular(),
            material.shininess(),
            true,
        );
        shader
    }

    /// The per-surface constants for sanitised reflectances and shininess `s ≥ 0`.
    ///
    /// `safe` holds when `A`, `d·D`, `k·S` and `Ka·A + Kd·d·D + Ks·k·S + Ke` are all below
    /// `f32::MAX / 4` per channel, with `A, D, S` the light sums' bounds, `d` the diffuse scale and `k` the specular scale (normalisation)
    /// of a crate model: every lobe and gate is at most 1 plus a few ulps, and each visibility at
    /// most 1, so no sum or product can then overflow, and the saturating `min`s are skipped. A
    /// product that overflows here is `+∞`, which fails the test: the check itself cannot
    /// misjudge. Models from outside the crate and per-point surfaces are never `safe`.
    #[inline(always)]
    fn prepare(&self, ka: Vec3, kd: Vec3, ks: Vec3, s: f32, shared: bool) -> Prepared {
        let specular = plan_for(self.resolved, s, shared);
        // A per-point surface always saturates: the test would cost more at every point than the
        // `min`s it could skip (a fifth of a textured point's instructions in the light loop).
        let safe = shared
            && self.resolved.is_some_and(|r| {
                // The sums themselves (before the reflectances scale them), then the total.
                let sums = scaled_sums(r, &self.bounds, specular.scale);
                let most = ka * sums[0] + kd * sums[1] + ks * sums[2] + self.emission;
                sums.into_iter().all(below_quarter) && below_quarter(most)
            });
        Prepared {
            ka,
            kd,
            ks,
            s,
            specular,
            safe,
        }
    }

    /// The same shader with another viewer: what a ray tracer changes at every hit, where the
    /// viewer is [`Viewer::along_ray`] of the ray that hit. Cheap: a copy and, for an infinite
    /// viewer, one normalisation.
    ///
    /// The shader it returns is also [`one_at_a_time`](Self::one_at_a_time), the faster form
    /// where each call shades one hit: a viewer that changes per point belongs to a ray tracer,
    /// whose recursion the compiler cannot vectorise. A loop over arrays under one fixed viewer
    /// should put that viewer in the [`Scene`] given to [`new`](Self::new) instead, which keeps
    /// the form the compiler vectorises.
    ///
    /// ```
    /// use glam::{Vec3, Vec3A};
    /// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Viewer};
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ZERO, Vec3::ONE)?)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let m = Material::try_from_color(Vec3::ONE, 64.0)?;
    /// let shader = Shader::new(Phong::default(), &m, &scene);
    /// // A ray travelling straight down onto a floor facing the sun sees the highlight.
    /// let hit = shader.with_viewer(Viewer::along_ray(-Vec3::Z)).shade(Vec3::ZERO, Vec3::Z);
    /// assert_eq!(hit.specular, Vec3::ONE);
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    #[inline]
    pub fn with_viewer(&self, viewer: Viewer) -> Self
    where
        M: Copy,
    {
        Shader {
            viewer: match viewer {
                Viewer::At(eye) => Viewer::At(eye),
                Viewer::Infinite(dir) => Viewer::Infinite(normalize_or_zero(dir)),
            },
            one: None,
            ..*self
        }
    }

    /// The same shader in the form for code that shades one point per call, from a loop the
    /// compiler cannot vectorise: a recursive ray tracer, a rasterizer's per-fragment callback,
    /// anything that samples a texture or traces a shadow ray between points.
    ///
    /// **Why there are two forms.** With one directional or point light, [`new`](Self::new)
    /// prepares a branch-free form of the equation (see "Loops the compiler can vectorise"
    /// above). Inside a loop over arrays the compiler runs it four or eight points per
    /// instruction, but a lone point pays for every rare case at every call. This form tests
    /// the rare cases (huge or tiny vectors, an overflowing falloff) with branches the processor
    /// predicts, as the light loop of a scene with several lights always does. Same results, bit
    /// for bit wherever no squared length under- or overflows `f32` (tests/shader.rs), and the
    /// same guarantees. [`with_viewer`](Self::with_viewer) returns this form already.
    ///
    /// **Domain and degenerate input:** as [`shade`](crate::shade); every method of the returned
    /// shader keeps its documented answers (no NaN and no panic from finite input).
    ///
    /// docs/performance.md measures both forms in both kinds of loop (`scalar`, `scalar_opaque`
    /// and `scalar_lone`, `raytrace_one_light`).
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Viewer};
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ONE)?)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)) };
    /// let m = Material::try_from_color(Vec3::ONE, 32.0)?;
    /// let looped = Shader::new(Phong::default(), &m, &scene);
    /// let lone = looped.one_at_a_time();
    /// let (p, n) = (Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.3, 1.0));
    /// assert_eq!(lone.shade(p, n), looped.shade(p, n));
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    #[inline]
    pub fn one_at_a_time(self) -> Self {
        Shader { one: None, ..self }
    }

    /// The four terms at `position` with surface normal `normal`, every light unshadowed.
    ///
    /// **Domain:** finite `position` and `normal` (any length). With only directional lights and an
    /// infinite viewer the position is not used: pass any finite point, e.g. `Vec3::ZERO`.
    #[must_use]
    #[inline(always)]
    pub fn shade(&self, position: Vec3, normal: Vec3) -> Terms {
        self.shade_visible(position, normal, Unshadowed)
    }

    /// The four terms with each light's diffuse and specular parts scaled by its visibility
    /// (shadows); ambient parts are not shadowed.
    ///
    /// ```text
    /// diffuseᵢ, specularᵢ ← clamp(visᵢ, 0, 1) · (diffuseᵢ, specularᵢ)      (NaN reads as 0)
    /// ```
    ///
    /// **Domain:** as [`shade`](Self::shade); visibilities in `[0, 1]` (see [`Visibility`]).
    ///
    /// ```
    /// use glam::{Vec3, Vec3A};
    /// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Viewer};
    /// let colors = LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE)?;
    /// let suns = [DirectionalLight::try_new(Vec3::Z, colors)?, DirectionalLight::try_new(Vec3::Y, colors)?];
    /// let scene = Scene { lights: &suns, ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let m = Material::try_from_color(Vec3::ONE, 16.0)?;
    /// let shader = Shader::new(Phong::default(), &m, &scene);
    /// let (p, n) = (Vec3::ZERO, Vec3::new(0.0, 1.0, 1.0));
    /// // A shadow on the second light: the result is the first light alone, plus both ambients.
    /// let shadowed = shader.shade_visible(p, n, [1.0, 0.0]);
    /// let first = Shader::new(Phong::default(), &m, &Scene { lights: &suns[..1], ..scene }).shade(p, n);
    /// assert_eq!(shadowed.diffuse, first.diffuse);
    /// assert_eq!(shadowed.ambient, Vec3::splat(0.2));
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    #[inline(always)]
    pub fn shade_visible(
        &self,
        position: Vec3,
        normal: Vec3,
        visibility: impl Visibility,
    ) -> Terms {
        self.run::<true>(&self.prepared, position, normal, visibility)
    }

    /// The four terms with a per-point [`Surface`] in place of the material's reflectances and
    /// shininess (texture maps), and per-light visibility. The material's emission is kept.
    ///
    /// Nothing is validated: release builds sanitise the surface (see [`Surface`]) and debug builds
    /// assert it. The pow plan for the point's shininess is chosen here, per point. Under
    /// [`PowStrategy::Auto`](crate::PowStrategy::Auto) a point's own exponent always takes the
    /// degree-7 polynomial (`Poly7`), whole exponents included: choosing squaring for whole ones
    /// would run both forms at every point of a vectorised loop. Its error is `Poly7`'s (8-bit
    /// output as exact as `powf`). Phong's lobe then reads the squared base: `(R·V)^s` is
    /// evaluated as `((R·V)²)^(s/2)`, with `(R·V)²` formed from the normal and the offsets to the
    /// light and the viewer before they are normalised, so that the power, the longest part of a
    /// textured point's work, waits for no square root or division (Blinn-Phong's `(N·H)²` is
    /// already a square). A [`Surface`] equal to the material with a fractional shininess gives
    /// exactly [`shade_visible`](Self::shade_visible)'s terms, except Phong's specular term under
    /// `Auto`, which differs from it by the rounding of the two bases: at most
    /// `(16·s + 64)·2⁻²⁴ · Ks ⊙ Σ f·Ls` (tests/shader.rs).
    ///
    /// ```
    /// use glam::{Vec3, Vec3A};
    /// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Surface, Unshadowed, Viewer};
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE)?)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let base = Material::try_from_color(Vec3::ONE, 16.0)?;
    /// let shader = Shader::new(Phong::default(), &base, &scene);
    /// let texel = Surface::textured(Vec3::new(0.5, 0.25, 0.0), Vec3::splat(0.5), 40.0);
    /// let t = shader.shade_surface(Vec3::ZERO, Vec3::Z, &texel, Unshadowed);
    /// assert_eq!(t.diffuse, Vec3::new(0.5, 0.25, 0.0));
    /// assert_eq!(t.specular, Vec3::splat(0.5)); // V = R: the lobe is 1 at any shininess
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    #[inline(always)]
    pub fn shade_surface(
        &self,
        position: Vec3,
        normal: Vec3,
        surface: &Surface,
        visibility: impl Visibility,
    ) -> Terms {
        debug_assert!(
            surface.is_valid(),
            "Shader::shade_surface: surface outside its domain: {surface:?}"
        );
        let s = math::clamp_or_lo(surface.shininess, 0.0, math::MAX);
        let p = self.prepare(
            sanitize_colour(surface.ambient),
            sanitize_colour(surface.diffuse),
            sanitize_colour(surface.specular),
            s,
            false,
        );
        self.run::<false>(&p, position, normal, visibility)
    }

    /// The cosines [`shade`](Self::shade) forms for light `index` at a point, with the light's
    /// sample: what a debug view or a custom lobe needs. `None` when `index` is out of range.
    ///
    /// **Returns** the [`Incidence`] of `N = normalize(normal)`, the unit direction to the light and
    /// the unit direction to the viewer (each the zero vector where it does not exist: a zero
    /// normal, the point at the light, the viewer at the point), and the light's
    /// attenuation × spot factor.
    ///
    /// ```
    /// use glam::{Vec3, Vec3A};
    /// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Viewer};
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::BLACK)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Y) };
    /// let m = Material::try_from_color(Vec3::ONE, 1.0)?;
    /// let (g, f) = Shader::new(Phong::default(), &m, &scene).incidence(Vec3::ZERO, Vec3::Z, 0).unwrap();
    /// assert_eq!((g.n_dot_l, g.n_dot_v, f), (1.0, 0.0, 1.0));
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    pub fn incidence(
        &self,
        position: Vec3,
        normal: Vec3,
        index: usize,
    ) -> Option<(Incidence, f32)> {
        let light = self.lights.get(index)?;
        let sample = light.sample(position);
        let n = normalize_or_zero(normal);
        let v = self.view_direction(position);
        Some((Incidence::new(n, sample.direction, v), sample.factor))
    }

    #[inline(always)]
    fn view_direction(&self, position: Vec3) -> Vec3 {
        match self.viewer {
            Viewer::At(eye) => direction_between(eye, position),
            Viewer::Infinite(dir) => dir,
        }
    }

    /// The point's unit normal and direction to the viewer; with `squared` (Phong's squared
    /// base) also the two vectors before normalisation, [`Scaled`], by the normalisations that
    /// return them (whose common range is narrower, see [`normalize_flagged_scaled`]). Two
    /// branches rather than one body generic over `squared`: that form cost the one-point-per-call
    /// light loop about 2.5 cycles a fragment (87 → 89, probe of `fragment`'s callback).
    #[inline(always)]
    fn frame(&self, pt: Point, squared: bool) -> Frame {
        let Point { position, normal } = pt;
        if squared {
            let (n, n_present, n_scaled) = normalize_flagged_scaled(normal);
            let (v, v_scaled) = match self.viewer {
                Viewer::At(eye) => direction_between_scaled(eye, position),
                Viewer::Infinite(dir) => (dir, Scaled::unit(dir)),
            };
            Frame {
                n,
                v,
                n_present,
                n_scaled,
                v_scaled,
            }
        } else {
            let (n, n_present) = normalize_flagged(normal);
            Frame {
                n,
                v: self.view_direction(position),
                n_present,
                n_scaled: Scaled::unit(Vec3::ZERO),
                v_scaled: Scaled::unit(Vec3::ZERO),
            }
        }
    }

    /// `SHARED`: `surface` is the shader's own, the same at every point.
    #[inline(always)]
    fn run<const SHARED: bool>(
        &self,
        surface: &Prepared,
        position: Vec3,
        normal: Vec3,
        visibility: impl Visibility,
    ) -> Terms {
        if let (Some(one), Some(r)) = (self.one, self.resolved) {
            return self.one_light::<SHARED>(r, surface, one, position, normal, visibility);
        }
        // One loop per lobe, chosen once per point: each stays small enough to keep its values in
        // registers, where one loop branching per light on the lobe kind spilled to the stack.
        let pt = Point { position, normal };
        let (ambient, diffuse, specular) = match self.resolved {
            Some(r) if !M::HAS_SPECULAR || r.lobe == Lobe::None => {
                self.light_loop::<NO_LOBE, _>(r, surface, pt, visibility, lobe_pow::NoLobe)
            }
            // The pow plan is chosen here too, so the loop runs the plan's code inline and calls
            // nothing: a call inside it would force every live value out of the vector registers.
            Some(r) => match surface.specular.plan {
                // `Auto`'s plan (see `plan_for`).
                PowPlan::Split {
                    n,
                    frac,
                    poly: Poly::P7,
                } => {
                    // A point's own exponent is for Phong's squared base (see `plan_for`).
                    if SHARED {
                        self.lobe_loop(
                            r,
                            surface,
                            pt,
                            visibility,
                            lobe_pow::Auto::<false> { n, frac },
                        )
                    } else {
                        self.lobe_loop(
                            r,
                            surface,
                            pt,
                            visibility,
                            lobe_pow::Auto::<true> { n, frac },
                        )
                    }
                }
                PowPlan::Squaring { n } => {
                    self.lobe_loop(r, surface, pt, visibility, lobe_pow::Squaring(n))
                }
                PowPlan::Exact { s } => {
                    self.lobe_loop(r, surface, pt, visibility, lobe_pow::Exact(s))
                }
                plan => self.lobe_loop(r, surface, pt, visibility, lobe_pow::Plan(plan)),
            },
            None => self.custom_loop(surface, pt, visibility),
        };
        let (ka, kd, ks) = (
            Vec3A::from(surface.ka),
            Vec3A::from(surface.kd),
            Vec3A::from(surface.ks),
        );
        if surface.safe {
            // Nothing can reach f32::MAX (see `prepare`): the products as they are.
            return Terms {
                ambient: (ka * ambient).into(),
                diffuse: (kd * diffuse).into(),
                specular: (ks * specular).into(),
                emission: self.emission,
            };
        }
        let sat = Vec3A::splat(math::MAX);
        Terms {
            ambient: (ka * ambient.min(sat)).min(sat).into(),
            diffuse: (kd * diffuse.min(sat)).min(sat).into(),
            specular: (ks * specular.min(sat)).min(sat).into(),
            emission: self.emission,
        }
    }

    /// The whole equation for a scene with one directional or point light and a crate model, as
    /// straight-line code: no loop, no call, and no branch on the data, only on what is the same
    /// for every point (the lobe, the pow plan, the viewer's kind), so a caller's loop over points
    /// that inlines it can be vectorised by the compiler (as it vectorises hand-written shading
    /// code). Every rare case is a select: the normal, the view direction and the direction to the
    /// light by the full-range formula (no range test), an overflowing attenuation denominator in
    /// `f64`, each missing direction masked.
    ///
    /// The same answer as the light loop, bit for bit wherever no squared length under- or
    /// overflows `f32` (there the full-range formula is the more exact one): the same operations
    /// in the same order, `FlatAttenuation` being `Attenuation::factor`'s own. Phong's squared
    /// base for a point's own exponent is formed from vectors scaled by other powers of two than
    /// the light loop's, and has the same bits (`ResolvedModel::phong_base_squared`). Tested in
    /// tests/shader.rs for every model, falloff, viewer, visibility and per-point surface, with
    /// points and normals on both sides of either form's ranges.
    ///
    /// `SHARED`: `surface` is the shader's own, so its exponent is the same at every point, which
    /// lets a whole one skip the polynomial (see `auto_pow_fixed`).
    #[inline(always)]
    fn one_light<const SHARED: bool>(
        &self,
        r: ResolvedModel,
        surface: &Prepared,
        one: OneLight,
        position: Vec3,
        normal: Vec3,
        mut visibility: impl Visibility,
    ) -> Terms {
        let blinn = M::HAS_SPECULAR && r.lobe == Lobe::Blinn;
        let phong = M::HAS_SPECULAR && r.lobe == Lobe::Phong;
        let (n, n_scaled) = normalize_full_scaled(normal);
        let (v, v_scaled) = match self.viewer {
            Viewer::At(eye) => normalize_full_between_scaled(eye, position),
            Viewer::Infinite(dir) => (dir, Scaled::unit(dir)),
        };
        let (sample, l_scaled) = one.flat.sample_scaled(position);
        let (l, f) = (sample.direction, sample.factor);
        let vis = visibility.visibility(0);
        debug_assert!(
            (0.0..=1.0).contains(&vis),
            "visibility of light 0 must lie in [0, 1], got {vis}"
        );
        let fv = f * math::clamp_or_lo(vis, 0.0, 1.0);
        let n_dot_l = n.dot(l);
        let wd = r.diffuse(n_dot_l);
        // A missing direction (zero vector) means no highlight: Phong's base needs the mask for
        // a zero N only (a zero L or V gives R·V = 0), Blinn-Phong's for all three. A step or
        // cosine gate is already 0 where N or L is zero (N·L = 0 there), so with one of those
        // only Blinn-Phong's V needs it. The gate is the same at every point: the compiler keeps
        // this a branch, and the tests it skips are not run.
        let gated = r.closes_at_zero();
        let ws = if phong || blinn {
            let (base, present) = if blinn {
                let present = if gated {
                    v != Vec3::ZERO
                } else {
                    n != Vec3::ZERO && v != Vec3::ZERO && l != Vec3::ZERO
                };
                (n_dot_h_squared(n, l, v), present)
            } else {
                let base = ResolvedModel::phong_base(n_dot_l, n.dot(v), l.dot(v));
                (base, gated || n != Vec3::ZERO)
            };
            let p = match surface.specular.plan {
                PowPlan::Split {
                    n: whole,
                    frac,
                    poly: Poly::P7,
                } => {
                    let pow = lobe_pow::AutoFixed::<SHARED> {
                        n: whole,
                        frac,
                        consts: &one.poly,
                    };
                    if phong {
                        // A point's own exponent reads Phong's squared base (see `plan_for`).
                        let xs = ResolvedModel::phong_base_squared(n_scaled, l_scaled, v_scaled);
                        pow.phong_lobe(base, xs)
                    } else {
                        lobe_power(base, pow)
                    }
                }
                PowPlan::Squaring { n: whole } => lobe_power(base, lobe_pow::SquaringFixed(whole)),
                PowPlan::Exact { s } => lobe_power(base, lobe_pow::Exact(s)),
                plan => lobe_power(base, lobe_pow::Plan(plan)),
            };
            let ws = surface.specular.scale * r.gate(n_dot_l) * p;
            if present { ws } else { 0.0 }
        } else {
            0.0
        };
        let ambient = self.ambient_light + one.ambient * f;
        let diffuse = one.diffuse * math::min_or(fv * wd, math::MAX);
        let specular = one.specular * math::min_or(fv * ws, math::MAX);
        let (ka, kd, ks) = (surface.ka, surface.kd, surface.ks);
        if SHARED && surface.safe {
            // Nothing reaches f32::MAX (see `prepare`), so the `min`s below would change nothing.
            // `safe` is the same at every point: in a vectorised loop this is a branch.
            return Terms {
                ambient: ka * ambient,
                diffuse: kd * diffuse,
                specular: ks * specular,
                emission: self.emission,
            };
        }
        // Otherwise (a per-point surface, whose test would cost more at every point than the
        // `min`s, or sums that may reach f32::MAX) saturated; `min` leaves every value below
        // f32::MAX as it is, so the bits are the light loop's either way. Per component with the
        // machine's `min` (`Vec3::min` would add IEEE minNum's NaN test).
        let min = |v: Vec3| {
            Vec3::new(
                math::min_or(v.x, math::MAX),
                math::min_or(v.y, math::MAX),
                math::min_or(v.z, math::MAX),
            )
        };
        if !SHARED && one.sums_below {
            // A per-point surface under a light whose sums stay below f32::MAX / 4 (see
            // `OneLight::sums_below`): the `min`s on the sums would change nothing, and only the
            // products with the surface's reflectances (each up to f32::MAX) can overflow. The
            // condition is the same at every point: in a vectorised loop this is a branch.
            return Terms {
                ambient: min(ka * ambient),
                diffuse: min(kd * (one.diffuse * (fv * wd))),
                specular: min(ks * (one.specular * (fv * ws))),
                emission: self.emission,
            };
        }
        Terms {
            ambient: min(ka * min(ambient)),
            diffuse: min(kd * min(diffuse)),
            specular: min(ks * min(specular)),
            emission: self.emission,
        }
    }

    /// [`light_loop`](Self::light_loop) for the model's lobe.
    #[inline(always)]
    fn lobe_loop(
        &self,
        r: ResolvedModel,
        surface: &Prepared,
        pt: Point,
        visibility: impl Visibility,
        pow: impl LobePow,
    ) -> (Vec3A, Vec3A, Vec3A) {
        if r.lobe == Lobe::Blinn {
            self.light_loop::<BLINN, _>(r, surface, pt, visibility, pow)
        } else {
            self.light_loop::<PHONG, _>(r, surface, pt, visibility, pow)
        }
    }

    /// The light sums `(Ia + Σ f·La, Σ f·vis·wd·Ld, Σ f·vis·ws·Ls)` for a crate model whose lobe is
    /// `LOBE`, with `pow(x) = x^e` on `(0, 1]` for the lobe's exponent `e`.
    #[inline(always)]
    fn light_loop<const LOBE: u8, P: LobePow>(
        &self,
        r: ResolvedModel,
        surface: &Prepared,
        pt: Point,
        mut visibility: impl Visibility,
        pow: P,
    ) -> (Vec3A, Vec3A, Vec3A) {
        let position = pt.position;
        let Frame {
            n,
            v,
            n_present,
            n_scaled,
            v_scaled,
        } = self.frame(pt, LOBE == PHONG && P::SQUARED_BASE);
        let n_dot_v = n.dot(v);
        // A missing direction (zero vector) means no highlight. For Phong a zero L or V already
        // gives a base R·V = 0, so only a zero N needs the mask; Blinn-Phong's (N·H)² needs all
        // three, and L is tested per light below.
        let present = n_present && (LOBE != BLINN || v != Vec3::ZERO);
        let specular_scale = if present { surface.specular.scale } else { 0.0 };
        let sums = (Vec3A::from(self.ambient_light), Vec3A::ZERO, Vec3A::ZERO);
        let k = LightConsts {
            r,
            position,
            n,
            v,
            n_dot_v,
            specular_scale,
            n_scaled,
            v_scaled,
        };
        // One light, the commonest case, without a loop: straight-line code, so a caller's loop
        // over points has no inner loop and the compiler can vectorise it across points.
        if let [light] = self.lights {
            return Self::add_light::<LOBE, _>(&k, sums, 0, light, visibility.visibility(0), pow);
        }
        let mut sums = sums;
        for (i, light) in self.lights.iter().enumerate() {
            sums = Self::add_light::<LOBE, _>(&k, sums, i, light, visibility.visibility(i), pow);
        }
        sums
    }

    /// Adds one light's parts to the sums `(ambient, diffuse, specular)`.
    #[inline(always)]
    fn add_light<const LOBE: u8, P: LobePow>(
        k: &LightConsts,
        sums: (Vec3A, Vec3A, Vec3A),
        i: usize,
        light: &L,
        vis: f32,
        pow: P,
    ) -> (Vec3A, Vec3A, Vec3A) {
        let LightConsts {
            r,
            position,
            n,
            v,
            n_dot_v,
            specular_scale,
            n_scaled,
            v_scaled,
        } = *k;
        let (mut ambient, mut diffuse, mut specular) = sums;
        // Phong's squared base (`Auto`'s plans) reads the offset to the light as it is.
        let squared = LOBE == PHONG && P::SQUARED_BASE;
        let (sample, l_scaled) = if squared {
            let (sample, w, ww) = light.sample_scaled(position);
            (sample, Scaled { w, ww })
        } else {
            (light.sample(position), Scaled::unit(Vec3::ZERO))
        };
        debug_assert!(
            (0.0..=1.0).contains(&vis),
            "visibility of light {i} must lie in [0, 1], got {vis}"
        );
        let f = sample.factor;
        let vis = math::clamp_or_lo(vis, 0.0, 1.0);
        let fv = f * vis;
        let l = sample.direction;
        let n_dot_l = n.dot(l);
        let wd = r.diffuse(n_dot_l);
        let ws = match LOBE {
            PHONG => {
                // A shadowed light (visibility 0) adds `fv·ws = 0` whatever the lobe: its base
                // is taken as 0, so that the lobe's own branch skips the power for it as for a
                // base `≤ 0`, with the same bits. Tested on the visibility, known early, rather
                // than on `fv`, which waits for the attenuation's division.
                let lobe = if squared {
                    // A point's own exponent reads the squared base (see `plan_for`).
                    let xs = ResolvedModel::phong_base_squared(n_scaled, l_scaled, v_scaled);
                    pow.phong_lobe(0.0, if vis > 0.0 { xs } else { 0.0 })
                } else {
                    let base = ResolvedModel::phong_base(n_dot_l, n_dot_v, l.dot(v));
                    lobe_power(if vis > 0.0 { base } else { 0.0 }, pow)
                };
                specular_scale * r.gate(n_dot_l) * lobe
            }
            // As Phong's, but by a branch of its own: `(N·H)²` is rarely `≤ 0`, so the lobe
            // selects rather than branches on it, and only the visibility skips the power (a
            // shadowed light falls to the last arm).
            BLINN if vis > 0.0 => {
                let base = n_dot_h_squared(n, l, v);
                let ws = specular_scale * r.gate(n_dot_l) * lobe_power_selected(base, pow);
                if l != Vec3::ZERO { ws } else { 0.0 }
            }
            _ => 0.0,
        };
        // Scalar weights first and saturated: finite × finite never gives NaN, and every colour
        // is finite and ≥ 0, so the sums below can reach +∞ (saturated at the end) but never NaN.
        let colors = light.colors();
        ambient += Vec3A::from(colors.ambient()) * f;
        diffuse += Vec3A::from(colors.diffuse()) * math::min_or(fv * wd, math::MAX);
        if LOBE != NO_LOBE {
            specular += Vec3A::from(colors.specular()) * math::min_or(fv * ws, math::MAX);
        }
        (ambient, diffuse, specular)
    }

    /// The light sums for a model that does not resolve (one defined outside this crate), through
    /// its trait methods on an [`Incidence`]; out of line, so the crate's own models' loops stay
    /// small.
    #[inline(never)]
    fn custom_loop(
        &self,
        surface: &Prepared,
        pt: Point,
        mut visibility: impl Visibility,
    ) -> (Vec3A, Vec3A, Vec3A) {
        let position = pt.position;
        let Frame {
            n, v, n_present, ..
        } = self.frame(pt, false);
        let specular_on = M::HAS_SPECULAR && n_present && v != Vec3::ZERO;
        let mut ambient = Vec3A::from(self.ambient_light);
        let mut diffuse = Vec3A::ZERO;
        let mut specular = Vec3A::ZERO;
        for (i, light) in self.lights.iter().enumerate() {
            let sample = light.sample(position);
            let vis = visibility.visibility(i);
            debug_assert!(
                (0.0..=1.0).contains(&vis),
                "visibility of light {i} must lie in [0, 1], got {vis}"
            );
            let f = sample.factor;
            let fv = f * math::clamp_or_lo(vis, 0.0, 1.0);
            let l = sample.direction;
            let (wd, ws) = if l == Vec3::ZERO {
                (0.0, 0.0)
            } else {
                let g = Incidence::new(n, l, v);
                let ws = if specular_on {
                    self.model.specular(&g, surface.s)
                } else {
                    0.0
                };
                (self.model.diffuse(&g), ws)
            };
            let colors = light.colors();
            ambient += Vec3A::from(colors.ambient()) * f;
            diffuse += Vec3A::from(colors.diffuse()) * math::min_or(fv * wd, math::MAX);
            specular += Vec3A::from(colors.specular()) * math::min_or(fv * ws, math::MAX);
        }
        (ambient, diffuse, specular)
    }
}

/// What every light's evaluation at one point shares.
#[derive(Clone, Copy)]
struct LightConsts {
    r: ResolvedModel,
    position: Vec3,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    specular_scale: f32,
    /// The normal and the offset to the viewer before normalisation, for Phong's squared base.
    n_scaled: Scaled,
    v_scaled: Scaled,
}

/// The point being shaded, as the caller gives it.
#[derive(Clone, Copy)]
struct Point {
    position: Vec3,
    normal: Vec3,
}

/// A point's unit (or zero) normal and direction to the viewer ([`Shader::frame`]).
#[derive(Clone, Copy)]
struct Frame {
    n: Vec3,
    v: Vec3,
    /// `n != 0`, known without a test on the common path (see [`normalize_flagged`]).
    n_present: bool,
    /// The normal and the offset to the viewer before normalisation, for Phong's squared base
    /// (zero vectors where it is not read).
    n_scaled: Scaled,
    v_scaled: Scaled,
}

/// The lobe kinds as const-generic parameters of [`Shader::light_loop`].
const NO_LOBE: u8 = 0;
const PHONG: u8 = 1;
const BLINN: u8 = 2;

/// `(N·H)²` from the vectors, as [`Incidence::new`] computes it: `max(N·(L+V), 0)² / ‖L+V‖²`, 0 where
/// `L + V` vanishes. Formed from `L + V` rather than `2 + 2 L·V`, which cancels as `L → −V`.
#[inline(always)]
fn n_dot_h_squared(n: Vec3, l: Vec3, v: Vec3) -> f32 {
    let sum = l + v;
    let t = math::max_or(n.dot(sum), 0.0);
    let d = sum.length_squared();
    let q = math::min_or(t * t / math::max_or(d, f32::MIN_POSITIVE), 1.0);
    if d >= f32::MIN_POSITIVE { q } else { 0.0 }
}

/// The bounds of a light's three sums after the model's scales, `[A, d·D, k·S]`: `A`, `D`, `S`
/// the ambient, diffuse and specular sums' bounds, `d` the model's diffuse scale and `k` the
/// specular scale (`1` where the model does not normalise). What [`Shader::prepare`]'s `safe`
/// and [`OneLight::sums_below`] test against [`below_quarter`].
fn scaled_sums(r: ResolvedModel, bounds: &[Vec3; 3], k: f32) -> [Vec3; 3] {
    [bounds[0], r.diffuse(1.0) * bounds[1], k * bounds[2]]
}

/// Whether every channel of `v` is below `f32::MAX / 4`: the headroom under which the sums,
/// scaled by reflectances of at most 1 per lobe and gate (plus a few ulps) and visibilities of at
/// most 1, cannot overflow. `+∞` fails it.
fn below_quarter(v: Vec3) -> bool {
    v.max_element() < 0.25 * math::MAX
}

/// The specular constants for shininess `s`: from the resolved model, or unused (custom models
/// evaluate their own lobes).
#[inline(always)]
fn plan_for(resolved: Option<ResolvedModel>, s: f32, shared: bool) -> SpecularPlan {
    match resolved {
        // `Auto`: for one material's exponent (`shared`), squaring for a whole exponent and the
        // degree-7 polynomial otherwise (its meaning everywhere in the crate); for a point's own
        // exponent, the polynomial (see `auto_split_per_point`). One `Split` plan whose
        // evaluation has no branch on the shininess, decided inline, without `at_shininess`'s
        // general plan: `shade_surface` runs it per point.
        Some(r) if r.pow == PowStrategy::Auto => {
            // Both callers pass a sanitised shininess: a material's own, or a point's as
            // `shade_surface` clamps it. Clamping again here and in `auto_split_per_point` cost
            // a point's own exponent two more `max`/`min` pairs in a vectorised loop, where the
            // compiler cannot see that a clamp is idempotent.
            debug_assert!((0.0..=math::MAX).contains(&s), "plan_for: shininess {s}");
            // Blinn-Phong's base is `(N·H)²`: half the exponent. Phong's is `R·V` for one
            // material's exponent, and for a point's own the squared base `(R·V)²`, under half
            // the exponent too (`LobePow::phong_lobe`): the polynomial, the longest part of a
            // textured point's chain, then waits for no square root or division
            // (`ResolvedModel::phong_base_squared`).
            let (scale, e) = match r.lobe {
                Lobe::None => (0.0, 0.0),
                Lobe::Phong => (
                    r.normalization.phong_factor(s),
                    if shared { s } else { 0.5 * s },
                ),
                Lobe::Blinn => (r.normalization.blinn_factor(s), 0.5 * s),
            };
            let (n, frac) = if shared {
                auto_split(e)
            } else {
                auto_split_per_point(e)
            };
            SpecularPlan {
                scale,
                plan: PowPlan::Split {
                    n,
                    frac,
                    poly: Poly::P7,
                },
            }
        }
        Some(r) => r.at_shininess(s),
        None => SpecularPlan {
            scale: 0.0,
            plan: crate::pow::PowPlan::Squaring { n: 0 },
        },
    }
}
