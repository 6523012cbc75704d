//! The crate's lighting as a [`SurfaceShader`]: one term or the sum, optional texture maps, the
//! shading-rate advisor for adaptive mode, and light culling by attenuation radius. Deferred
//! per-pixel shading of the sum goes through the crate's batch path ([`phong::shade_gbuffer`]).

use std::cell::Cell;

use glam::{Vec2, Vec3};
use phong::{
    GBuffer, Light, LightSource, Material, Model, Scene, SoaRgb, SoaSurface, SoaVec3, Terms,
};

use crate::{SurfaceShader, shade_each};

/// Which part of [`Terms`] a shader outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Term {
    /// `Ka ⊙ (Ia + Σ La·f)`.
    Ambient,
    /// `Σ f · Kd ⊙ Ld · diffuse lobe`.
    Diffuse,
    /// `Σ f · Ks ⊙ Ls · specular lobe`.
    Specular,
    /// The sum of all four terms. The default.
    #[default]
    Total,
}

impl Term {
    /// This term of `t`.
    #[must_use]
    pub fn of(self, t: &Terms) -> Vec3 {
        match self {
            Term::Ambient => t.ambient,
            Term::Diffuse => t.diffuse,
            Term::Specular => t.specular,
            Term::Total => t.total(),
        }
    }
}

/// A procedural texture: `uv → (diffuse texel, specular texel)`, linear colours.
pub type Texture = fn(Vec2) -> (Vec3, Vec3);

/// The most lights one point can be shaded with when culling is on.
pub const MAX_LIGHTS: usize = 32;

/// Shades with [`phong::shade`] point by point, and many points at once
/// ([`SurfaceShader::shade_many`], what deferred per-pixel drawing calls) with the batch path
/// [`phong::shade_gbuffer`]: the sum of the terms, a texture as a per-point surface. The batch
/// agrees with `shade` within its documented error (about 1e-6 relative); one term alone, or
/// culling, shades point by point.
#[derive(Clone, Debug)]
pub struct PhongShader<'a> {
    /// The reflection model.
    pub model: Model,
    /// The material (overridden per pixel by `texture`, through [`Material::textured`]).
    pub material: Material,
    /// Lights, ambient and viewer.
    pub scene: Scene<'a, Light>,
    /// Which term to output.
    pub term: Term,
    /// Diffuse and specular maps, if any.
    pub texture: Option<Texture>,
    /// Adaptive mode's tolerance (linear units, per channel) for
    /// [`phong::shading_rate::gouraud_within_tolerance`].
    pub tolerance: f32,
    /// Per-light cull distances ([`phong::Attenuation::cull_radius`]); lights farther than
    /// their distance from a point are skipped there. Empty: no culling.
    pub cull: Vec<f32>,
    /// Light evaluations made (`shade` calls × lights used).
    pub evaluations: Cell<u64>,
    /// Light evaluations skipped by culling.
    pub skipped: Cell<u64>,
}

impl<'a> PhongShader<'a> {
    /// A shader for the sum of the terms, no texture, tolerance 2/255, no culling.
    #[must_use]
    pub fn new(model: impl Into<Model>, material: Material, scene: Scene<'a, Light>) -> Self {
        PhongShader {
            model: model.into(),
            material,
            scene,
            term: Term::Total,
            texture: None,
            tolerance: 2.0 / 255.0,
            cull: Vec::new(),
            evaluations: Cell::new(0),
            skipped: Cell::new(0),
        }
    }

    /// The same shader outputting only `term`.
    #[must_use]
    pub fn with_term(mut self, term: Term) -> Self {
        self.term = term;
        self
    }

    /// Turns on light culling: light `i` is skipped beyond the distance where its attenuation
    /// falls below `threshold / cᵢ`, `cᵢ` the most the light can add to a channel at attenuation 1
    /// (its colours times the material's, with the largest lobe values), so a skipped light
    /// changes no channel by more than `threshold`. Directional lights are never skipped.
    /// Texture maps are assumed to stay within the material's colours.
    #[must_use]
    pub fn with_culling(mut self, threshold: f32) -> Self {
        let m = &self.material;
        let k = m.ambient().max(m.diffuse()).max(m.specular()).max_element();
        // Energy-normalised specular lobes can exceed 1.
        let s = m.shininess();
        let lobe = phong::ResolvedModel::from(self.model)
            .specular_scale(s)
            .max(1.0);
        self.cull = self
            .scene
            .lights
            .iter()
            .map(|l| {
                let c = l.colors();
                let bright = c.ambient() + c.diffuse() + c.specular() * lobe;
                let t = threshold / (bright.max_element() * k).max(f32::MIN_POSITIVE);
                match l {
                    Light::Directional(_) => f32::INFINITY,
                    Light::Point(p) => p.attenuation().cull_radius(t),
                    Light::Spot(s) => s.attenuation().cull_radius(t),
                }
            })
            .collect();
        self
    }

    fn light_position(l: &Light) -> Option<Vec3> {
        match l {
            Light::Directional(_) => None,
            Light::Point(p) => Some(p.position()),
            Light::Spot(s) => Some(s.position()),
        }
    }
}

impl SurfaceShader for PhongShader<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, uv: Vec2) -> Vec3 {
        let material = match self.texture {
            Some(tex) => {
                let (d, s) = tex(uv);
                self.material.textured(d, s)
            }
            None => self.material,
        };
        let lights = self.scene.lights;
        if self.cull.len() == lights.len() && !lights.is_empty() && lights.len() <= MAX_LIGHTS {
            let mut kept = [lights[0]; MAX_LIGHTS];
            let mut k = 0;
            for (l, r) in lights.iter().zip(&self.cull) {
                let far = Self::light_position(l)
                    .is_some_and(|p| (p - position).length_squared() > r * r);
                if far {
                    self.skipped.set(self.skipped.get() + 1);
                } else {
                    kept[k] = *l;
                    k += 1;
                }
            }
            self.evaluations.set(self.evaluations.get() + k as u64);
            let scene = Scene {
                lights: &kept[..k],
                ..self.scene
            };
            return self.term.of(&phong::shade(
                &self.model,
                &material,
                &scene,
                position,
                normal,
            ));
        }
        self.evaluations
            .set(self.evaluations.get() + lights.len() as u64);
        self.term.of(&phong::shade(
            &self.model,
            &material,
            &self.scene,
            position,
            normal,
        ))
    }

    fn shade_many(&self, positions: &[Vec3], normals: &[Vec3], uvs: &[Vec2], out: &mut [Vec3]) {
        // The batch has no per-point light culling and outputs the sum only.
        if self.term != Term::Total || !self.cull.is_empty() {
            return shade_each(self, positions, normals, uvs, out);
        }
        let n = out.len();
        debug_assert!(positions.len() == n && normals.len() == n && uvs.len() == n);
        // The G-buffer as structure-of-arrays planes: x, y, z of positions and normals, the
        // output's r, g, b, and with a texture the diffuse and specular texels and the shininess.
        let planes = if self.texture.is_some() { 16 } else { 9 };
        let mut buf = vec![0.0f32; planes * n];
        let mut plane = buf.chunks_exact_mut(n.max(1));
        let mut next = || plane.next().unwrap_or_default();
        let (px, py, pz) = (next(), next(), next());
        let (nx, ny, nz) = (next(), next(), next());
        let (r, g, b) = (next(), next(), next());
        for i in 0..n {
            (px[i], py[i], pz[i]) = positions[i].into();
            (nx[i], ny[i], nz[i]) = normals[i].into();
        }
        let mut gbuffer = GBuffer::new(SoaVec3::new(px, py, pz), SoaVec3::new(nx, ny, nz));
        let (dx, dy, dz, sx, sy, sz, shininess) =
            (next(), next(), next(), next(), next(), next(), next());
        if let Some(texture) = self.texture {
            // `Material::textured` per point: the diffuse texel is also the ambient reflectance.
            for i in 0..n {
                let (d, s) = texture(uvs[i]);
                (dx[i], dy[i], dz[i]) = d.into();
                (sx[i], sy[i], sz[i]) = s.into();
                shininess[i] = self.material.shininess();
            }
            let diffuse = SoaVec3::new(dx, dy, dz);
            gbuffer = gbuffer.with_surface(SoaSurface {
                ambient: diffuse,
                diffuse,
                specular: SoaVec3::new(sx, sy, sz),
                shininess,
            });
        }
        let shaded = phong::shade_gbuffer(
            &self.model,
            &self.material,
            &self.scene,
            &gbuffer,
            SoaRgb::new(r, g, b),
        );
        debug_assert_eq!(shaded, n);
        for i in 0..n {
            out[i] = Vec3::new(r[i], g[i], b[i]);
        }
        self.evaluations
            .set(self.evaluations.get() + (n * self.scene.lights.len()) as u64);
    }

    fn per_vertex_ok(&self, positions: [Vec3; 3], normals: [Vec3; 3]) -> bool {
        self.texture.is_none()
            && phong::shading_rate::gouraud_within_tolerance(
                &self.model,
                &self.material,
                &self.scene,
                positions,
                normals,
                self.tolerance,
            )
    }
}
