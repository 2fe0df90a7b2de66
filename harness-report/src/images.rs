//! Report images: dithered renders, difference overlays, shade-error heat
//! maps and the Jack program's cost map, as PNG. Colour scales are shared
//! with the colour bars drawn by `plot`, so a legend always matches its image.

use image::{Rgb, RgbImage};
use std::path::Path;

/// A rectangular raster of per-pixel values, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid<T> {
    width: usize,
    height: usize,
    data: Vec<T>,
}

/// A grid whose data does not match its size, or two grids of different sizes.
#[derive(Debug, thiserror::Error)]
pub enum GridError {
    /// `data.len() != width * height`.
    #[error("grid of {width}x{height} needs {} values, got {len}", width * height)]
    Length {
        width: usize,
        height: usize,
        len: usize,
    },
    /// Two grids that should match do not.
    #[error("grid sizes differ: {0}x{1} against {2}x{3}")]
    Mismatch(usize, usize, usize, usize),
}

impl<T> Grid<T> {
    /// A grid from row-major data.
    pub fn new(width: usize, height: usize, data: Vec<T>) -> Result<Self, GridError> {
        if data.len() != width * height {
            return Err(GridError::Length {
                width,
                height,
                len: data.len(),
            });
        }
        Ok(Grid {
            width,
            height,
            data,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row-major values.
    pub fn data(&self) -> &[T] {
        &self.data
    }

    /// The value at (x, y).
    pub fn get(&self, x: usize, y: usize) -> &T {
        &self.data[y * self.width + x]
    }

    /// Fail unless `other` has the same size.
    pub fn same_size<U>(&self, other: &Grid<U>) -> Result<(), GridError> {
        if self.width == other.width && self.height == other.height {
            Ok(())
        } else {
            Err(GridError::Mismatch(
                self.width,
                self.height,
                other.width,
                other.height,
            ))
        }
    }

    /// Row-major positions `(x, y)` where `f(a, b)` holds.
    pub fn positions_where<U>(
        &self,
        other: &Grid<U>,
        f: impl Fn(&T, &U) -> bool,
    ) -> Result<Vec<(usize, usize)>, GridError> {
        self.same_size(other)?;
        Ok(self
            .data
            .iter()
            .zip(&other.data)
            .enumerate()
            .filter(|(_, (a, b))| f(a, b))
            .map(|(i, _)| (i % self.width, i / self.width))
            .collect())
    }
}

/// A colour scale from a number to a colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Palette {
    /// Dark blue to yellow (perceptually uniform), for costs.
    Viridis,
    /// Black, red, yellow, white, for errors.
    Hot,
}

const VIRIDIS: [[u8; 3]; 5] = [
    [68, 1, 84],
    [59, 82, 139],
    [33, 145, 140],
    [94, 201, 98],
    [253, 231, 37],
];
const HOT: [[u8; 3]; 4] = [[20, 0, 0], [200, 20, 0], [255, 200, 0], [255, 255, 230]];

impl Palette {
    /// The colour of `t` in [0, 1] (clamped), interpolated between stops.
    pub fn rgb(self, t: f64) -> [u8; 3] {
        let stops: &[[u8; 3]] = match self {
            Palette::Viridis => &VIRIDIS,
            Palette::Hot => &HOT,
        };
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let pos = t * (stops.len() - 1) as f64;
        let i = (pos.floor() as usize).min(stops.len() - 2);
        let f = pos - i as f64;
        let mix = |k: usize| {
            (stops[i][k] as f64 + (stops[i + 1][k] as f64 - stops[i][k] as f64) * f).round() as u8
        };
        [mix(0), mix(1), mix(2)]
    }
}

/// How values map onto [0, 1] of a palette.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// `lo..hi` linearly.
    Linear { lo: f64, hi: f64 },
    /// `lo..hi` in log10; values at or below zero are off the scale.
    Log { lo: f64, hi: f64 },
}

impl Scale {
    /// A log scale over the positive values, spanning at most `decades`
    /// below the largest; `None` when no value is positive.
    pub fn log_for(values: impl IntoIterator<Item = f64>, decades: f64) -> Option<Scale> {
        let (mut lo, mut hi) = (f64::INFINITY, 0f64);
        for v in values.into_iter().filter(|v| *v > 0.0 && v.is_finite()) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if hi <= 0.0 {
            return None;
        }
        let lo = lo.max(hi / 10f64.powf(decades));
        // A single value still needs a range to draw a colour bar.
        let lo = if lo < hi { lo } else { hi / 10.0 };
        Some(Scale::Log { lo, hi })
    }

    /// Position of `v` in [0, 1] (clamped); `None` when off a log scale.
    pub fn position(self, v: f64) -> Option<f64> {
        match self {
            Scale::Linear { lo, hi } => {
                let span = hi - lo;
                Some(if span > 0.0 {
                    ((v - lo) / span).clamp(0.0, 1.0)
                } else {
                    0.5
                })
            }
            Scale::Log { lo, hi } => {
                if v <= 0.0 || !v.is_finite() {
                    return None;
                }
                Some(((v.log10() - lo.log10()) / (hi.log10() - lo.log10())).clamp(0.0, 1.0))
            }
        }
    }

    /// The ends of the scale.
    pub fn bounds(self) -> (f64, f64) {
        match self {
            Scale::Linear { lo, hi } | Scale::Log { lo, hi } => (lo, hi),
        }
    }
}

const WHITE: Rgb<u8> = Rgb([255, 255, 255]);
const BLACK: Rgb<u8> = Rgb([0, 0, 0]);
/// Overlay colour where A is white and B black.
pub const A_WHITE_COLOUR: [u8; 3] = [230, 0, 60];
/// Overlay colour where A is black and B white.
pub const B_WHITE_COLOUR: [u8; 3] = [0, 90, 230];

/// The colour of a pixel that trapped (`Sys.error`, hang, out of domain),
/// in renders and overlays alike: a trap is never drawn as black or white.
pub const TRAP_COLOUR: [u8; 3] = [255, 160, 0];

/// The dithered image (`true` = white), trapped pixels in [`TRAP_COLOUR`].
pub fn dithered(bits: &Grid<bool>, traps: Option<&Grid<bool>>) -> RgbImage {
    RgbImage::from_fn(bits.width as u32, bits.height as u32, |x, y| {
        let (x, y) = (x as usize, y as usize);
        if traps.is_some_and(|t| *t.get(x, y)) {
            Rgb(TRAP_COLOUR)
        } else if *bits.get(x, y) {
            WHITE
        } else {
            BLACK
        }
    })
}

/// Paint the pixels marked in `traps` in [`TRAP_COLOUR`].
pub fn mark_traps(img: &mut RgbImage, traps: &Grid<bool>) -> Result<(), GridError> {
    if (img.width() as usize, img.height() as usize) != (traps.width, traps.height) {
        return Err(GridError::Mismatch(
            img.width() as usize,
            img.height() as usize,
            traps.width,
            traps.height,
        ));
    }
    for (i, _) in traps.data.iter().enumerate().filter(|(_, t)| **t) {
        img.put_pixel(
            (i % traps.width) as u32,
            (i / traps.width) as u32,
            Rgb(TRAP_COLOUR),
        );
    }
    Ok(())
}

/// Fade a dithered pixel toward light grey so marks drawn over it stand out.
fn faded(white: bool) -> Rgb<u8> {
    if white {
        Rgb([250, 250, 250])
    } else {
        Rgb([200, 200, 200])
    }
}

/// The difference overlay of two dithered images: A faded, with pixels
/// where A is white and B black in [`A_WHITE_COLOUR`] and the opposite in
/// [`B_WHITE_COLOUR`].
pub fn overlay(a: &Grid<bool>, b: &Grid<bool>) -> Result<RgbImage, GridError> {
    a.same_size(b)?;
    Ok(RgbImage::from_fn(
        a.width as u32,
        a.height as u32,
        |x, y| {
            let (pa, pb) = (
                *a.get(x as usize, y as usize),
                *b.get(x as usize, y as usize),
            );
            match (pa, pb) {
                (true, false) => Rgb(A_WHITE_COLOUR),
                (false, true) => Rgb(B_WHITE_COLOUR),
                _ => faded(pa),
            }
        },
    ))
}

/// Per-pixel absolute difference of two shade grids.
pub fn abs_diff(a: &Grid<f64>, b: &Grid<f64>) -> Result<Grid<f64>, GridError> {
    a.same_size(b)?;
    let data = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(x, y)| (x - y).abs())
        .collect();
    Grid::new(a.width, a.height, data)
}

/// Colour of a pixel with zero error in a heat map: off the log scale.
pub const ZERO_COLOUR: [u8; 3] = [0, 0, 0];

/// A heat map of non-negative values; pixels off the scale (zero error on a
/// log scale) are [`ZERO_COLOUR`].
pub fn heat_map(values: &Grid<f64>, scale: Scale, palette: Palette) -> RgbImage {
    RgbImage::from_fn(
        values.width as u32,
        values.height as u32,
        |x, y| match scale.position(*values.get(x as usize, y as usize)) {
            Some(t) => Rgb(palette.rgb(t)),
            None => Rgb(ZERO_COLOUR),
        },
    )
}

/// Save an image as PNG.
pub fn save_png(img: &RgbImage, path: &Path) -> anyhow::Result<()> {
    img.save_with_format(path, image::ImageFormat::Png)
        .map_err(|e| anyhow::anyhow!("writing {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(w: usize, h: usize, white: &[(usize, usize)]) -> Grid<bool> {
        let mut data = vec![false; w * h];
        for &(x, y) in white {
            data[y * w + x] = true;
        }
        Grid::new(w, h, data).unwrap()
    }

    #[test]
    fn grid_checks_its_length() {
        assert!(matches!(
            Grid::new(3, 2, vec![0u8; 5]),
            Err(GridError::Length { len: 5, .. })
        ));
        let a = Grid::new(2, 2, vec![1, 2, 3, 4]).unwrap();
        assert_eq!(*a.get(1, 1), 4);
        let b = Grid::new(4, 1, vec![1, 2, 3, 4]).unwrap();
        assert!(a.same_size(&b).is_err());
    }

    #[test]
    fn overlay_marks_exactly_the_differing_pixels() {
        let a = bits(4, 3, &[(0, 0), (1, 0), (2, 2)]);
        let b = bits(4, 3, &[(0, 0), (3, 1), (2, 2)]);
        let img = overlay(&a, &b).unwrap();
        assert_eq!(img.get_pixel(1, 0).0, A_WHITE_COLOUR);
        assert_eq!(img.get_pixel(3, 1).0, B_WHITE_COLOUR);
        let marked = img
            .pixels()
            .filter(|p| p.0 == A_WHITE_COLOUR || p.0 == B_WHITE_COLOUR)
            .count();
        assert_eq!(marked, 2);
        assert_eq!(img.get_pixel(0, 0).0, [250, 250, 250]);
        assert_eq!(img.get_pixel(0, 1).0, [200, 200, 200]);
        assert_eq!(
            a.positions_where(&b, |p, q| p != q).unwrap(),
            vec![(1, 0), (3, 1)]
        );
    }

    #[test]
    fn dithered_is_black_and_white_and_traps_have_their_own_colour() {
        let img = dithered(&bits(3, 1, &[(1, 0), (2, 0)]), None);
        assert_eq!(img.get_pixel(0, 0).0, [0, 0, 0]);
        assert_eq!(img.get_pixel(1, 0).0, [255, 255, 255]);
        let traps = bits(3, 1, &[(2, 0)]);
        let img = dithered(&bits(3, 1, &[(1, 0), (2, 0)]), Some(&traps));
        assert_eq!(img.get_pixel(1, 0).0, [255, 255, 255]);
        assert_eq!(img.get_pixel(2, 0).0, TRAP_COLOUR);
        let mut over = overlay(&bits(3, 1, &[]), &bits(3, 1, &[(0, 0)])).unwrap();
        mark_traps(&mut over, &traps).unwrap();
        assert_eq!(over.get_pixel(0, 0).0, B_WHITE_COLOUR);
        assert_eq!(over.get_pixel(2, 0).0, TRAP_COLOUR);
        assert!(mark_traps(&mut over, &bits(2, 1, &[])).is_err());
    }

    #[test]
    fn palettes_run_from_first_to_last_stop() {
        assert_eq!(Palette::Viridis.rgb(0.0), VIRIDIS[0]);
        assert_eq!(Palette::Viridis.rgb(1.0), VIRIDIS[4]);
        assert_eq!(Palette::Viridis.rgb(7.0), VIRIDIS[4]);
        assert_eq!(Palette::Hot.rgb(0.0), HOT[0]);
        assert_eq!(Palette::Hot.rgb(f64::NAN), HOT[0]);
        // Half-way between the first two stops.
        assert_eq!(Palette::Viridis.rgb(0.125), [64, 42, 112]);
    }

    #[test]
    fn log_scale_leaves_zero_off_the_map() {
        let s = Scale::log_for([0.0, 1e-3, 1e-1], 6.0).unwrap();
        assert_eq!(s.bounds(), (1e-3, 1e-1));
        assert_eq!(s.position(0.0), None);
        assert!((s.position(1e-2).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(s.position(1.0), Some(1.0));
        assert!(Scale::log_for([0.0, 0.0], 6.0).is_none());
        let narrow = Scale::log_for([1e-9, 1.0], 3.0).unwrap();
        assert_eq!(narrow.bounds(), (1e-3, 1.0));
        let single = Scale::log_for([0.5], 3.0).unwrap();
        assert_eq!(single.bounds(), (0.05, 0.5));
    }

    #[test]
    fn heat_map_colours_follow_the_scale() {
        let g = Grid::new(3, 1, vec![0.0, 1e-3, 1e-1]).unwrap();
        let s = Scale::log_for(g.data().iter().copied(), 6.0).unwrap();
        let img = heat_map(&g, s, Palette::Hot);
        assert_eq!(img.get_pixel(0, 0).0, ZERO_COLOUR);
        assert_eq!(img.get_pixel(1, 0).0, HOT[0]);
        assert_eq!(img.get_pixel(2, 0).0, HOT[3]);
        let lin = Scale::Linear { lo: 10.0, hi: 20.0 };
        assert_eq!(lin.position(15.0), Some(0.5));
        assert_eq!(Scale::Linear { lo: 3.0, hi: 3.0 }.position(3.0), Some(0.5));
    }

    #[test]
    fn abs_diff_is_per_pixel() {
        let a = Grid::new(2, 1, vec![0.5, 0.25]).unwrap();
        let b = Grid::new(2, 1, vec![0.25, 0.75]).unwrap();
        assert_eq!(abs_diff(&a, &b).unwrap().data(), &[0.25, 0.5]);
    }
}
