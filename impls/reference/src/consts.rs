//! The scene's constants encoded in one engine's number type, built once per
//! image from a [`Scene`] (Float316 constants are encoded by truncation).

use crate::engine::{outcome, Engine};
use crate::scene::{Scene, SceneError};
use crate::vec3::{self, V3};
use common::image_consts::BAYER;

/// Every constant the pipeline uses, in the engine's number type.
#[derive(Clone, Debug)]
pub struct Consts<N> {
    pub zero: N,
    pub one: N,
    pub half: N,
    /// Distance below which a ray hits.
    pub precision: N,
    /// Offset of the shadow ray's origin along the normal (twice the
    /// precision: 0.02).
    pub shadow_offset: N,
    pub max_distance: N,
    pub view_steps: u32,
    pub shadow_steps: u32,
    /// The normal estimate's offsets k1..k4.
    pub normal_k: [V3<N>; 4],
    pub sphere_centre: V3<N>,
    pub sphere_radius: N,
    pub sphere_colour: N,
    pub torus_centre: V3<N>,
    pub ring_radius: N,
    pub tube_radius: N,
    pub torus_colour: N,
    /// `-height` of the floor plane: `sd = add(p.y, floor_offset)`.
    pub floor_offset: N,
    pub floor_colour: N,
    pub floor_checker: N,
    pub light: V3<N>,
    pub camera: V3<N>,
    /// Camera matrix rows r1, r2, r3.
    pub rows: [V3<N>; 3],
    /// Shading factors of the float formulation.
    pub diffuse_k: N,
    pub diffuse_i: N,
    pub specular_k: N,
    pub specular_i: N,
    pub ambient_factor: N,
    /// Their truncated products, used by Float316 (0.63, 0.35, 0.167).
    pub diffuse_ki: N,
    pub specular_ki: N,
    pub ambient: N,
    pub background: N,
    /// Pixel coordinate offsets and scale: u = (x - 256) / 256,
    /// v = -((y - 128) / 256).
    pub half_width: N,
    pub half_height: N,
    pub pixel_scale: N,
    /// The z component of the view direction before normalising (-1).
    pub view_z: N,
    /// `B / 64` for each Bayer entry (float formulation).
    pub bayer: [N; 64],
    /// `(B - 32) / 64` for each Bayer entry (Float316 formulation).
    pub bayer_centred: [N; 64],
    /// The `dither-threshold` fault: white when the value is not below 0.5
    /// (instead of above it).
    pub dither_threshold_fault: bool,
}

fn enc<E: Engine>(field: &str, x: f64) -> Result<E::N, SceneError> {
    E::constant(x).ok_or_else(|| SceneError::Field {
        field: field.to_string(),
        value: x,
        reason: "cannot be encoded in this implementation's number type",
    })
}

fn enc3<E: Engine>(field: &str, v: [f64; 3]) -> Result<V3<E::N>, SceneError> {
    Ok(V3::new(
        enc::<E>(&format!("{field}[0]"), v[0])?,
        enc::<E>(&format!("{field}[1]"), v[1])?,
        enc::<E>(&format!("{field}[2]"), v[2])?,
    ))
}

fn exact<E: Engine>(x: f64) -> E::N {
    E::constant(x).expect("a small dyadic constant is representable in every engine")
}

impl<N: Copy> Consts<N> {
    /// Encode the scene's constants for engine `E` and evaluate the camera
    /// basis with `engine` (the only part computed rather than encoded).
    pub fn build<E: Engine<N = N>>(
        scene: &Scene,
        engine: &mut E,
        dither_threshold_fault: bool,
    ) -> Result<Self, SceneError> {
        let m = &scene.march;
        let s = &scene.shading;
        let h = m.normal_h;
        let hk = |a: f64, b: f64, c: f64| enc3::<E>("march.normal_h", [a * h, b * h, c * h]);
        let camera = enc3::<E>("camera.position", scene.camera.position)?;
        let look_at = enc3::<E>("camera.look_at", scene.camera.look_at)?;
        let up = enc3::<E>("camera.up", scene.camera.up)?;
        let rows = camera_rows(engine, camera, look_at, up)?;
        Ok(Consts {
            zero: exact::<E>(0.0),
            one: exact::<E>(1.0),
            half: exact::<E>(0.5),
            precision: enc::<E>("march.precision", m.precision)?,
            shadow_offset: enc::<E>("march.precision", 2.0 * m.precision)?,
            max_distance: enc::<E>("march.max_distance", m.max_distance)?,
            view_steps: m.view_steps,
            shadow_steps: m.shadow_steps,
            normal_k: [
                hk(1.0, -1.0, -1.0)?,
                hk(-1.0, -1.0, 1.0)?,
                hk(-1.0, 1.0, -1.0)?,
                hk(1.0, 1.0, 1.0)?,
            ],
            sphere_centre: enc3::<E>("sphere.centre", scene.sphere.centre)?,
            sphere_radius: enc::<E>("sphere.radius", scene.sphere.radius)?,
            sphere_colour: enc::<E>("sphere.colour", scene.sphere.colour)?,
            torus_centre: enc3::<E>("torus.centre", scene.torus.centre)?,
            ring_radius: enc::<E>("torus.ring_radius", scene.torus.ring_radius)?,
            tube_radius: enc::<E>("torus.tube_radius", scene.torus.tube_radius)?,
            torus_colour: enc::<E>("torus.colour", scene.torus.colour)?,
            floor_offset: enc::<E>("floor.height", -scene.floor.height)?,
            floor_colour: enc::<E>("floor.colour", scene.floor.colour)?,
            floor_checker: enc::<E>("floor.checker", scene.floor.checker)?,
            light: enc3::<E>("shading.light", s.light)?,
            camera,
            rows,
            diffuse_k: enc::<E>("shading.diffuse_k", s.diffuse_k)?,
            diffuse_i: enc::<E>("shading.diffuse_i", s.diffuse_i)?,
            specular_k: enc::<E>("shading.specular_k", s.specular_k)?,
            specular_i: enc::<E>("shading.specular_i", s.specular_i)?,
            ambient_factor: enc::<E>("shading.ambient", s.ambient)?,
            diffuse_ki: enc::<E>("shading.diffuse_k", s.diffuse_k * s.diffuse_i)?,
            specular_ki: enc::<E>("shading.specular_k", s.specular_k * s.specular_i)?,
            ambient: enc::<E>("shading.ambient", s.ambient * s.background)?,
            background: enc::<E>("shading.background", s.background)?,
            half_width: exact::<E>(256.0),
            half_height: exact::<E>(128.0),
            pixel_scale: exact::<E>(256.0),
            view_z: exact::<E>(-1.0),
            bayer: BAYER.map(|b| exact::<E>(f64::from(b) / 64.0)),
            bayer_centred: BAYER.map(|b| exact::<E>((f64::from(b) - 32.0) / 64.0)),
            dither_threshold_fault,
        })
    }
}

/// The camera matrix rows: forward = normalize(cam - lookAt), right =
/// normalize(cross(up, forward)), up' = cross(forward, right); r1 =
/// (right.x, up'.x, forward.x) and so on.
fn camera_rows<E: Engine>(
    e: &mut E,
    cam: V3<E::N>,
    look_at: V3<E::N>,
    up: V3<E::N>,
) -> Result<[V3<E::N>; 3], SceneError> {
    let r = e.frame(
        || "camera".into(),
        |e| {
            let f = vec3::sub(e, cam, look_at)?;
            let f = vec3::normalize(e, f)?;
            let r = vec3::cross(e, up, f)?;
            let r = vec3::normalize(e, r)?;
            let u = vec3::cross(e, f, r)?;
            Ok([
                V3::new(r.x, u.x, f.x),
                V3::new(r.y, u.y, f.y),
                V3::new(r.z, u.z, f.z),
            ])
        },
    );
    outcome(r)
        .value()
        .ok_or_else(|| SceneError::Camera(format!("{:?}", outcome(r).kind())))
}
