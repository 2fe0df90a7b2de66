//! Image geometry and the ordered-dither matrix (spec section 6).

/// Image width in pixels (the Hack screen).
pub const WIDTH: usize = 512;
/// Image height in pixels.
pub const HEIGHT: usize = 256;

/// The standard 8x8 Bayer matrix, row by row.
pub const BAYER: [u8; 64] = [
    0, 48, 12, 60, 3, 51, 15, 63, //
    32, 16, 44, 28, 35, 19, 47, 31, //
    8, 56, 4, 52, 11, 59, 7, 55, //
    40, 24, 36, 20, 43, 27, 39, 23, //
    2, 50, 14, 62, 1, 49, 13, 61, //
    34, 18, 46, 30, 33, 17, 45, 29, //
    10, 58, 6, 54, 9, 57, 5, 53, //
    42, 26, 38, 22, 41, 25, 37, 21,
];

/// The Bayer entry for pixel (x, y): `B[(y mod 8) * 8 + (x mod 8)]`.
pub const fn bayer(x: usize, y: usize) -> u8 {
    BAYER[(y % 8) * 8 + (x % 8)]
}
