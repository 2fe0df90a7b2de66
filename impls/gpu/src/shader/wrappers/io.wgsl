
// ---- The harness's wrapper around the shader above (docs/shaders.md). ----
// Names starting with `harness_` are the wrapper's; a shader must not declare them.

struct HarnessParams {
    count: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<storage, read> harness_in: array<u32>;
@group(0) @binding(1) var<storage, read_write> harness_out: array<u32>;
@group(0) @binding(2) var<uniform> harness_params: HarnessParams;

// The loop guard counts every loop iteration of the shader here and breaks
// every loop once the count passes the limit; the answer is then a hang.
var<private> harness_iterations: u32 = 0u;
var<private> harness_runaway: bool = false;

fn harness_status() -> u32 {
    if (harness_runaway) {
        return 2u;
    }
    return bitcast<u32>(HARNESS_USER_STATUS);
}
