// Bindings shared by every kernel: a flat array of input words, a flat array
// of output words, and the number of items in this batch. Each kernel reads
// a fixed number of words per item and writes a fixed number of words per
// item (the strides are fixed on the Rust side, in kernel.rs).

struct Params {
    count: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<storage, read> inp: array<u32>;
@group(0) @binding(1) var<storage, read_write> outp: array<u32>;
@group(0) @binding(2) var<uniform> params: Params;

// Items per workgroup; must equal WORKGROUP_SIZE in kernel.rs.
const WG: u32 = 64u;
