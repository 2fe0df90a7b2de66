
// ---- The harness's wrapper around the shader above (docs/shaders.md). ----
// Names starting with `harness_` are the wrapper's; a shader must not declare them.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer HarnessIn { uint harness_in[]; };
layout(std430, set = 0, binding = 1) buffer HarnessOut { uint harness_out[]; };
layout(std140, set = 0, binding = 2) uniform HarnessParams {
    uint harness_count;
    uint harness_pad0;
    uint harness_pad1;
    uint harness_pad2;
};

// The loop guard counts every loop iteration of the shader here and breaks
// every loop once the count passes the limit; the answer is then a hang.
uint harness_iterations = 0u;
bool harness_runaway = false;
