// A WGSL shader with an entry point of its own, which the harness's wrapper
// would never call: refused (docs/shaders.md, "Do not declare entry points").
fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {
    return coord.x / resolution.x;
}

@compute @workgroup_size(1)
fn main() {}
