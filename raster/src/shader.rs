//! The crate's lighting as a [`SurfaceShader`]: one term or the sum, optional texture maps, the
//! shading-rate advisor for adaptive mode, and light culling by attenuation radius.

use std::cell::Cell;

use glam::{Vec2, Vec3};
use phong::{Light, LightSource, Material, Model, Scene, Terms};

use crate::SurfaceShader;

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

/// Shades with [`phong::shade`].
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
        let lobe = match self.model {
            Model::Phong(p) => p.normalization.phong_factor(s),
            Model::BlinnPhong(b) => b.normalization.blinn_factor(s),
            Model::Lambert(_) => 0.0,
        }
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

    fn per_vertex_ok(&self, positions: [Vec3; 3], normals: [Vec3; 3]) -> bool {
        self.texture.is_none()
            && phong::shading_rate::gouraud_within_tolerance(
                self.model,
                &self.material,
                &self.scene,
                positions,
                normals,
                self.tolerance,
            )
    }
}
