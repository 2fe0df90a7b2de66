//! The scene's parameters as a serde struct. `Scene::default()` is the seed
//! scene of the spec; a JSON file may override any subset of the fields
//! (`harness render --scene FILE`). Unknown fields are rejected by name.

use serde::{Deserialize, Serialize};
use std::path::Path;

/// A scene file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file is not a readable regular UTF-8 file of bounded size.
    #[error("scene file: {0}")]
    Input(#[from] common::input::InputError),
    /// The JSON is malformed or a field has the wrong type or name (serde's
    /// message names the field and the line).
    #[error("malformed scene file {path}: {source}")]
    Parse {
        path: String,
        source: serde_json::Error,
    },
    /// A field's value cannot be used by an implementation (the value as
    /// [`common::shown`] shows it: `1e300`, never 301 digits).
    #[error("scene field `{field}` = {}: {reason}", common::shown(*.value))]
    Field {
        field: String,
        value: f64,
        reason: &'static str,
    },
    /// The file is not a JSON object (`[]`, a number, ...).
    #[error("scene file {path}: a scene is a JSON object of fields")]
    NotAnObject { path: String },
    /// The object sets no field: almost surely not the file meant (the
    /// seed scene needs no file).
    #[error("scene file {path}: the object sets no field (leave out --scene for the seed scene)")]
    Empty { path: String },
    /// An error of the file's fields ([`Scene::check`]), with the file
    /// named.
    #[error("scene file {path}: {error}")]
    InFile {
        path: String,
        error: Box<SceneError>,
    },
    /// Evaluating the camera basis (done once per image) trapped.
    #[error("the camera basis cannot be computed: {0}")]
    Camera(String),
}

/// A sphere.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sphere {
    pub centre: [f64; 3],
    pub radius: f64,
    /// Its colour (the shade factor).
    pub colour: f64,
}

/// A torus whose axis is the y axis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Torus {
    pub centre: [f64; 3],
    /// Distance from the centre to the middle of the tube.
    pub ring_radius: f64,
    pub tube_radius: f64,
    pub colour: f64,
}

/// The checkered floor, a plane `y = height`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Floor {
    pub height: f64,
    /// Colour of the even squares.
    pub colour: f64,
    /// Added to the colour of the odd squares.
    pub checker: f64,
}

/// Ray-marching constants.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct March {
    /// A ray hits when the distance falls below this.
    pub precision: f64,
    /// A ray misses when its depth exceeds this.
    pub max_distance: f64,
    pub view_steps: u32,
    pub shadow_steps: u32,
    /// The offset `h` of the normal estimate.
    pub normal_h: f64,
}

/// Light and shading factors (a pixel in shadow is quartered). Float316 uses the truncated products
/// `diffuse_k * diffuse_i` (0.63), `specular_k * specular_i` (0.35) and
/// `ambient * background` (0.167); the float formulation multiplies them
/// in its own order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Shading {
    pub light: [f64; 3],
    pub diffuse_k: f64,
    pub diffuse_i: f64,
    pub specular_k: f64,
    pub specular_i: f64,
    pub ambient: f64,
    /// Shade of a ray that hits nothing.
    pub background: f64,
}

/// The camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    pub position: [f64; 3],
    pub look_at: [f64; 3],
    pub up: [f64; 3],
}

/// Every parameter of the scene. The default is the seed scene.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    pub camera: Camera,
    pub sphere: Sphere,
    pub torus: Torus,
    pub floor: Floor,
    pub march: March,
    pub shading: Shading,
}

impl Default for Sphere {
    fn default() -> Self {
        Sphere {
            centre: [-1.5, 0.0, 0.0],
            radius: 1.0,
            colour: 0.7,
        }
    }
}

impl Default for Torus {
    fn default() -> Self {
        Torus {
            centre: [1.5, 0.0, 0.0],
            ring_radius: 1.0,
            tube_radius: 0.25,
            colour: 0.7,
        }
    }
}

impl Default for Floor {
    fn default() -> Self {
        Floor {
            height: -1.0,
            colour: 1.0,
            checker: 0.7,
        }
    }
}

impl Default for March {
    fn default() -> Self {
        March {
            precision: 0.01,
            max_distance: 12.0,
            view_steps: 64,
            shadow_steps: 32,
            normal_h: 0.005,
        }
    }
}

impl Default for Shading {
    fn default() -> Self {
        Shading {
            light: [2.0, 5.0, -1.0],
            diffuse_k: 0.9,
            diffuse_i: 0.7,
            specular_k: 0.7,
            specular_i: 0.5,
            ambient: 0.2,
            background: 0.835,
        }
    }
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            position: [0.0, 1.5, 4.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
        }
    }
}

impl Scene {
    /// Read a scene from a JSON file; fields left out keep the seed scene's
    /// values. Every error names the file (and the field, where one is at
    /// fault).
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let shown = path.display().to_string();
        let text = common::input::read_text(path)?;
        if !text.trim_start().starts_with('{') {
            return Err(SceneError::NotAnObject { path: shown });
        }
        // The JSON itself first, so that a syntax error (a NaN, a file cut
        // short) is reported at its line, not as the first field the
        // parameters do not know.
        let value: serde_json::Value =
            serde_json::from_str(&text).map_err(|source| SceneError::Parse {
                path: shown.clone(),
                source,
            })?;
        if value.as_object().is_some_and(|o| o.is_empty()) {
            return Err(SceneError::Empty { path: shown });
        }
        // Parsed again from the text, so that a field's error has its line.
        let scene: Scene = serde_json::from_str(&text).map_err(|source| SceneError::Parse {
            path: shown.clone(),
            source,
        })?;
        scene.check().map_err(|error| SceneError::InFile {
            path: shown,
            error: Box::new(error),
        })?;
        Ok(scene)
    }

    /// The limits every run relies on: march steps in 1..=[`MAX_STEPS`] (a
    /// render is bounded), a camera with a direction and an up vector that
    /// is not parallel to it (else the image is silently black).
    pub fn check(&self) -> Result<(), SceneError> {
        let m = &self.march;
        for (field, steps) in [
            ("march.view_steps", m.view_steps),
            ("march.shadow_steps", m.shadow_steps),
        ] {
            if !(1..=MAX_STEPS).contains(&steps) {
                return Err(SceneError::Field {
                    field: field.into(),
                    value: f64::from(steps),
                    reason: "must lie in 1..=1024",
                });
            }
        }
        let c = &self.camera;
        let f: Vec<f64> = (0..3).map(|i| c.position[i] - c.look_at[i]).collect();
        if f.iter().all(|&x| x == 0.0) {
            return Err(SceneError::Field {
                field: "camera.look_at".into(),
                value: c.look_at[0],
                reason: "equals camera.position: the camera has no direction",
            });
        }
        let u = c.up;
        let cross = [
            u[1] * f[2] - u[2] * f[1],
            u[2] * f[0] - u[0] * f[2],
            u[0] * f[1] - u[1] * f[0],
        ];
        if cross.iter().all(|&x| x == 0.0) {
            return Err(SceneError::Field {
                field: "camera.up".into(),
                value: u[1],
                reason: "is zero or parallel to the viewing direction",
            });
        }
        Ok(())
    }
}

/// The most steps a march may take.
pub const MAX_STEPS: u32 = 1024;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partial_file_keeps_the_seed_values() {
        let s: Scene = serde_json::from_str(r#"{"torus": {"tube_radius": 0.5}}"#).unwrap();
        assert_eq!(s.torus.tube_radius, 0.5);
        assert_eq!(s.torus.ring_radius, 1.0);
        assert_eq!(s.camera, Camera::default());
    }

    #[test]
    fn unknown_and_mistyped_fields_are_named() {
        let err = serde_json::from_str::<Scene>(r#"{"torus": {"tube": 0.5}}"#).unwrap_err();
        assert!(err.to_string().contains("unknown field `tube`"), "{err}");
        let err = serde_json::from_str::<Scene>(r#"{"march": {"view_steps": -3}}"#).unwrap_err();
        assert!(err.to_string().contains("-3"), "{err}");
    }

    #[test]
    fn round_trips_through_json() {
        let s = Scene::default();
        let text = serde_json::to_string_pretty(&s).unwrap();
        assert_eq!(serde_json::from_str::<Scene>(&text).unwrap(), s);
    }
}
