// A shader that ends, but slowly: 10000 dependent steps per pixel, which a
// whole image on lavapipe takes seconds for.
fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {
    var h = u32(coord.x);
    for (var i = 0u; i < 10000u; i++) {
        h = (h * 1664525u + 1013904223u) ^ (h >> 13u);
    }
    return f32(h & 1023u) / 1024.0;
}
