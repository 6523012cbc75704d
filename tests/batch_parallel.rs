//! The batch module's "Many cores" promise: a batch cut into parts (at any indices, shaded on any
//! threads) gives exactly the bits of one serial call, at every dispatch level. Each point is
//! shaded from its own inputs and the call's constants, so nothing may depend on where a part
//! starts, how long it is (tails shorter than 16 lanes included) or which thread runs it.

use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Level, Light, LightColors, Material, Model, Phong,
    PointLight, PowStrategy, Scene, SoaRgb, SoaVec3, SpotCone, SpotLight, Viewer,
};
use proptest::prelude::*;

use phong_tools::rng::Rng;

/// Positions and normals as SoA columns, with some degenerate points (zero normal, a point at the
/// first light, a huge coordinate) among ordinary ones.
fn points(n: usize, seed: u64, light_at: Vec3) -> ([Vec<f32>; 3], [Vec<f32>; 3]) {
    let mut rng = Rng::new(seed);
    let mut next = move || rng.unit_f32() * 2.0 - 1.0;
    let (mut p, mut nn): ([Vec<f32>; 3], [Vec<f32>; 3]) = Default::default();
    for i in 0..n {
        let (mut pos, mut nor) = (
            Vec3::new(next() * 3.0, next() * 3.0, next() * 3.0),
            Vec3::new(next(), next(), next()),
        );
        match i % 23 {
            5 => nor = Vec3::ZERO,
            11 => pos = light_at,
            17 => pos.x = 3e30,
            _ => {}
        }
        for k in 0..3 {
            p[k].push(pos[k]);
            nn[k].push(nor[k]);
        }
    }
    (p, nn)
}

/// One call over `[lo, hi)` of every column.
fn shade_part(
    level: Level,
    model: &Model,
    material: &Material,
    scene: &Scene<'_, Light>,
    (p, nn): (&[Vec<f32>; 3], &[Vec<f32>; 3]),
    (lo, hi): (usize, usize),
    out: [&mut [f32]; 3],
) {
    let [r, g, b] = out;
    phong::shade_batch_with_level(
        level,
        model,
        material,
        scene,
        SoaVec3::new(&p[0][lo..hi], &p[1][lo..hi], &p[2][lo..hi]),
        SoaVec3::new(&nn[0][lo..hi], &nn[1][lo..hi], &nn[2][lo..hi]),
        SoaRgb::new(r, g, b),
    )
    .unwrap();
}

fn scenes() -> Vec<(Model, Vec<Light>)> {
    let colors = LightColors::try_from_strengths(Vec3::new(1.0, 0.9, 0.8), 0.1, 0.9, 0.6).unwrap();
    let point = PointLight::try_new(
        Vec3::new(1.0, 2.0, 2.0),
        Attenuation::polynomial(1.0, 0.09, 0.032),
        colors,
    )
    .unwrap();
    let sun = DirectionalLight::try_new(Vec3::new(-1.0, 1.0, 0.5), colors).unwrap();
    let spot = SpotLight::try_with_cone(
        Vec3::new(0.0, 4.0, 0.0),
        -Vec3::Y,
        SpotCone::degrees(40.0).with_exponent(4.0),
        Attenuation::try_unreal(20.0).unwrap(),
        colors,
    )
    .unwrap();
    vec![
        // The vector kernels' case: point and directional lights.
        (Phong::default().into(), vec![point.into(), sun.into()]),
        (
            BlinnPhong {
                pow: PowStrategy::Auto,
                ..BlinnPhong::default()
            }
            .into(),
            vec![point.into()],
        ),
        // A spot light takes the kernel's falloff lanes: the same promise holds there.
        (Phong::default().into(), vec![point.into(), spot.into()]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_split_on_any_threads_gives_the_serial_bits(
        n in 1usize..300,
        cuts in prop::collection::vec(0usize..300, 0..6),
        shininess in prop_oneof![Just(32.0f32), 1.0f32..100.0],
        seed in any::<u64>(),
    ) {
        let material = Material::try_from_color(Vec3::new(0.8, 0.4, 0.2), shininess).unwrap();
        for (model, lights) in scenes() {
            let (p, nn) = points(n, seed, lights[0].sample_position());
            let scene = Scene { lights: &lights, ambient: Vec3::splat(0.02), viewer: Viewer::At(Vec3::new(0.0, 1.0, 5.0)) };
            let mut bounds: Vec<usize> = cuts.iter().map(|c| c % (n + 1)).collect();
            bounds.extend([0, n]);
            bounds.sort_unstable();
            bounds.dedup();
            for level in Level::supported() {
                let mut serial = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
                {
                    let [r, g, b] = &mut serial;
                    shade_part(level, &model, &material, &scene, (&p, &nn), (0, n), [r, g, b]);
                }
                let mut parts = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
                {
                    let [r, g, b] = &mut parts;
                    let (mut r, mut g, mut b) = (&mut r[..], &mut g[..], &mut b[..]);
                    std::thread::scope(|s| {
                        for w in bounds.windows(2) {
                            let (lo, hi) = (w[0], w[1]);
                            let (rh, rt) = std::mem::take(&mut r).split_at_mut(hi - lo);
                            let (gh, gt) = std::mem::take(&mut g).split_at_mut(hi - lo);
                            let (bh, bt) = std::mem::take(&mut b).split_at_mut(hi - lo);
                            (r, g, b) = (rt, gt, bt);
                            let (model, material, scene, p, nn) = (&model, &material, &scene, &p, &nn);
                            s.spawn(move || {
                                shade_part(level, model, material, scene, (p, nn), (lo, hi), [rh, gh, bh]);
                            });
                        }
                    });
                }
                for c in 0..3 {
                    for i in 0..n {
                        prop_assert_eq!(
                            serial[c][i].to_bits(), parts[c][i].to_bits(),
                            "{} channel {} point {} of {} cut at {:?}", level, c, i, n, bounds
                        );
                    }
                }
            }
        }
    }
}

/// The position of a light for placing a point on it (the origin for directional lights).
trait SamplePosition {
    fn sample_position(&self) -> Vec3;
}

impl SamplePosition for Light {
    fn sample_position(&self) -> Vec3 {
        match self {
            Light::Point(l) => l.position(),
            Light::Spot(l) => l.position(),
            Light::Directional(_) => Vec3::ZERO,
        }
    }
}
