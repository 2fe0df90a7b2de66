//! SVG charts drawn with `plotters`: the colour bars that go with heat maps
//! and cost maps, and the speed-against-error plot.

use crate::images::{Palette, Scale};
use crate::model::SpeedPoint;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Width of a colour bar, pixels (matches the 512-pixel images).
const BAR_WIDTH: u32 = 512;
/// Steps of colour drawn across a colour bar.
const BAR_STEPS: usize = 128;

/// A number in short engineering form: `3.2e-4`, `0.25`, `1.3k`.
pub fn short_number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".to_string()
    } else if a >= 1e6 {
        format!("{:.1}M", v / 1e6)
    } else if a >= 1e3 {
        format!("{:.1}k", v / 1e3)
    } else if a >= 0.01 {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.1e}")
    }
}

fn to_anyhow<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing SVG: {e}")
}

/// A horizontal colour bar for `scale` and `palette`, titled `title`
/// (which should name the unit and, for log scales, the colour of zero).
pub fn colour_bar(title: &str, scale: Scale, palette: Palette) -> anyhow::Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (BAR_WIDTH, 84)).into_drawing_area();
        root.fill(&WHITE).map_err(to_anyhow)?;
        // The chart runs over positions 0..1 of the scale; ticks are placed
        // at round values of the scale itself.
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 17))
            .margin_left(20)
            .margin_right(28)
            .build_cartesian_2d(0.0..1.0, -0.6..1.0)
            .map_err(to_anyhow)?;
        chart
            .draw_series((0..BAR_STEPS).map(|i| {
                let (t0, t1) = (
                    i as f64 / BAR_STEPS as f64,
                    (i + 1) as f64 / BAR_STEPS as f64,
                );
                let [r, g, b] = palette.rgb((t0 + t1) / 2.0);
                Rectangle::new([(t0, 0.0), (t1, 1.0)], RGBColor(r, g, b).filled())
            }))
            .map_err(to_anyhow)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(0.0, 0.0), (1.0, 1.0)],
                BLACK.stroke_width(1),
            )))
            .map_err(to_anyhow)?;
        let label = ("sans-serif", 15)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Top));
        for v in ticks(scale) {
            let Some(t) = scale.position(v) else { continue };
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(t, 0.0), (t, -0.15)],
                    BLACK,
                )))
                .map_err(to_anyhow)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    short_number(v),
                    (t, -0.2),
                    label.clone(),
                )))
                .map_err(to_anyhow)?;
        }
        root.present().map_err(to_anyhow)?;
    }
    Ok(svg)
}

/// Round values to label on a colour bar: the decades of a log scale (or
/// its ends when it spans less than two), five steps of a linear one.
fn ticks(scale: Scale) -> Vec<f64> {
    let (lo, hi) = scale.bounds();
    match scale {
        Scale::Linear { .. } => (0..5).map(|i| lo + (hi - lo) * i as f64 / 4.0).collect(),
        Scale::Log { .. } => {
            let decades: Vec<f64> = (lo.log10().ceil() as i32..=hi.log10().floor() as i32)
                .map(|k| 10f64.powi(k))
                .collect();
            if decades.len() >= 2 {
                decades
            } else {
                vec![lo, hi]
            }
        }
    }
}

/// Colours of the plot's series.
const MEAN_COLOUR: RGBColor = RGBColor(31, 119, 180);
const MAX_COLOUR: RGBColor = RGBColor(214, 39, 40);
const FLIP_COLOUR: RGBColor = RGBColor(44, 160, 44);

/// The speed-against-error plot: on the left, mean (circle) and max
/// (triangle) shade error against `ref-f64`, on the right dithered pixel
/// flips, both against microseconds per pixel (log). Points without error
/// figures (the oracle itself) are left out; an error of zero is drawn on
/// the bottom edge. `None` when no point can be drawn.
pub fn speed_error(points: &[SpeedPoint]) -> anyhow::Result<Option<String>> {
    let pts: Vec<&SpeedPoint> = points
        .iter()
        .filter(|p| p.time_per_pixel_s > 0.0 && p.mean_shade_error.is_some())
        .collect();
    if pts.is_empty() {
        return Ok(None);
    }
    let us = |p: &SpeedPoint| p.time_per_pixel_s * 1e6;
    let (xlo, xhi) = padded_log_range(pts.iter().map(|p| us(p)));
    let errors = pts
        .iter()
        .flat_map(|p| [p.mean_shade_error, p.max_shade_error])
        .flatten();
    let (ylo, yhi) = padded_log_range(errors.filter(|e| *e > 0.0));
    let on_axis = |e: f64| e.max(ylo);
    let max_flips = pts.iter().map(|p| p.pixel_flips).max().unwrap_or(0) as f64;
    let label_style = ("sans-serif", 15).into_font().color(&BLACK);

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 440)).into_drawing_area();
        root.fill(&WHITE).map_err(to_anyhow)?;
        let (left, right) = root.split_horizontally(520);

        let mut chart = ChartBuilder::on(&left)
            .caption("Shade error against ref-f64", ("sans-serif", 19))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d((xlo..xhi).log_scale(), (ylo..yhi).log_scale())
            .map_err(to_anyhow)?;
        chart
            .configure_mesh()
            .x_desc("µs per pixel (log)")
            .y_desc("|shade - ref-f64| (log)")
            .x_label_formatter(&|v| short_number(*v))
            .y_label_formatter(&|v| short_number(*v))
            .draw()
            .map_err(to_anyhow)?;
        chart
            .draw_series(pts.iter().filter_map(|p| {
                let (mean, max) = (p.mean_shade_error?, p.max_shade_error?);
                Some(PathElement::new(
                    vec![(us(p), on_axis(mean)), (us(p), on_axis(max))],
                    BLACK.mix(0.3),
                ))
            }))
            .map_err(to_anyhow)?;
        chart
            .draw_series(pts.iter().filter_map(|p| {
                Some(Circle::new(
                    (us(p), on_axis(p.mean_shade_error?)),
                    5,
                    MEAN_COLOUR.filled(),
                ))
            }))
            .map_err(to_anyhow)?
            .label("mean")
            .legend(|(x, y)| Circle::new((x, y), 5, MEAN_COLOUR.filled()));
        chart
            .draw_series(pts.iter().filter_map(|p| {
                Some(TriangleMarker::new(
                    (us(p), on_axis(p.max_shade_error?)),
                    6,
                    MAX_COLOUR.filled(),
                ))
            }))
            .map_err(to_anyhow)?
            .label("max")
            .legend(|(x, y)| TriangleMarker::new((x, y), 6, MAX_COLOUR.filled()));
        chart
            .draw_series(pts.iter().filter_map(|p| {
                Some(Text::new(
                    format!(" {}", p.label),
                    (us(p), on_axis(p.max_shade_error?)),
                    label_style.clone(),
                ))
            }))
            .map_err(to_anyhow)?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(to_anyhow)?;

        let mut flips = ChartBuilder::on(&right)
            .caption("Dithered pixels differing from ref-f64", ("sans-serif", 19))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d((xlo..xhi).log_scale(), 0.0..(max_flips * 1.15).max(1.0))
            .map_err(to_anyhow)?;
        flips
            .configure_mesh()
            .x_desc("µs per pixel (log)")
            .y_desc("pixel flips")
            .x_label_formatter(&|v| short_number(*v))
            .y_label_formatter(&|v| short_number(*v))
            .draw()
            .map_err(to_anyhow)?;
        flips
            .draw_series(
                pts.iter()
                    .map(|p| Circle::new((us(p), p.pixel_flips as f64), 5, FLIP_COLOUR.filled())),
            )
            .map_err(to_anyhow)?;
        flips
            .draw_series(pts.iter().map(|p| {
                Text::new(
                    format!(" {}", p.label),
                    (us(p), p.pixel_flips as f64),
                    label_style.clone(),
                )
            }))
            .map_err(to_anyhow)?;
        root.present().map_err(to_anyhow)?;
    }
    Ok(Some(svg))
}

/// One configuration of `harness tune`: its estimated cost and what it
/// changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParetoPoint {
    /// Estimated VM instructions per pixel.
    pub per_pixel: f64,
    /// Pixels whose output level differs from the untuned image.
    pub flips: u64,
    /// Largest `|shade - ref-f64|`; `None` when a pixel trapped.
    pub max_error: Option<f64>,
    /// Whether it keeps the search's constraint.
    pub passes: bool,
    /// The configuration the search chose.
    pub chosen: bool,
    /// The untuned configuration.
    pub untuned: bool,
}

const PASS_COLOUR: RGBColor = RGBColor(44, 160, 44);
const FAIL_COLOUR: RGBColor = RGBColor(150, 150, 150);

/// The points of `pts` no other point beats on both `x` and cost (the
/// Pareto front), by increasing `x`.
fn front(pts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = pts.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut out: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if out.last().is_none_or(|l| p.1 < l.1) {
            out.push(p);
        }
    }
    out
}

/// The Pareto plot of a tuning search: estimated VM instructions per pixel
/// against differing pixels (left, log of 1 + flips) and against the largest
/// shade error (right, log), every configuration tried: green where it
/// keeps the constraint, grey where not, the untuned one black, the chosen
/// one red; the line joins the Pareto front. A configuration with a trapped
/// pixel has no error to draw on the right.
pub fn pareto(points: &[ParetoPoint]) -> anyhow::Result<String> {
    let flips: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (1.0 + p.flips as f64, p.per_pixel))
        .collect();
    let errors: Vec<(f64, f64, &ParetoPoint)> = points
        .iter()
        .filter_map(|p| Some((p.max_error?, p.per_pixel, p)))
        .collect();
    let (ylo, yhi) = points
        .iter()
        .map(|p| p.per_pixel)
        .fold((f64::INFINITY, 0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let (ylo, yhi) = if ylo <= yhi {
        let pad = ((yhi - ylo) * 0.08).max(yhi * 0.002).max(1.0);
        (ylo - pad, yhi + pad)
    } else {
        (0.0, 1.0)
    };
    let xflips = (0.8, flips.iter().map(|p| p.0).fold(1.0, f64::max) * 3.0);
    let xerr = padded_log_range(errors.iter().map(|e| e.0));
    let on_axis = |e: f64| e.max(xerr.0);
    let style = |p: &ParetoPoint| -> (RGBColor, u32) {
        if p.chosen {
            (MAX_COLOUR, 7)
        } else if p.untuned {
            (BLACK, 6)
        } else if p.passes {
            (PASS_COLOUR, 4)
        } else {
            (FAIL_COLOUR, 4)
        }
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 440)).into_drawing_area();
        root.fill(&WHITE).map_err(to_anyhow)?;
        let (left, right) = root.split_horizontally(500);
        let panels = [
            (
                left,
                "Cost against differing pixels",
                "1 + pixels whose level differs from the untuned image (log)",
                xflips,
                flips
                    .iter()
                    .zip(points)
                    .map(|(&(x, y), p)| (x, y, p))
                    .collect::<Vec<_>>(),
            ),
            (
                right,
                "Cost against error",
                "largest |shade - ref-f64| (log)",
                xerr,
                errors.iter().map(|&(x, y, p)| (on_axis(x), y, p)).collect(),
            ),
        ];
        for (area, caption, x_desc, (xlo, xhi), pts) in panels {
            let mut chart = ChartBuilder::on(&area)
                .caption(caption, ("sans-serif", 19))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(64)
                .build_cartesian_2d((xlo..xhi).log_scale(), ylo..yhi)
                .map_err(to_anyhow)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc("estimated VM instructions per pixel")
                .x_label_formatter(&|v| short_number(*v))
                .y_label_formatter(&|v| short_number(*v))
                .draw()
                .map_err(to_anyhow)?;
            let line = front(&pts.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>());
            chart
                .draw_series(std::iter::once(PathElement::new(line, BLACK.mix(0.4))))
                .map_err(to_anyhow)?;
            // Chosen and untuned last, on top.
            let mut order: Vec<&(f64, f64, &ParetoPoint)> = pts.iter().collect();
            order.sort_by_key(|p| (p.2.chosen || p.2.untuned, p.2.passes));
            chart
                .draw_series(order.into_iter().map(|&(x, y, p)| {
                    let (colour, size) = style(p);
                    Circle::new((x, y), size, colour.filled())
                }))
                .map_err(to_anyhow)?;
        }
        root.present().map_err(to_anyhow)?;
    }
    Ok(svg)
}

/// A log-axis range around positive values, with a little room on each side.
fn padded_log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if hi <= 0.0 {
        return (1e-6, 1.0);
    }
    (lo / 2.0, hi * 3.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(label: &str, s: f64, mean: Option<f64>, max: Option<f64>, flips: u64) -> SpeedPoint {
        SpeedPoint {
            label: label.into(),
            time_per_pixel_s: s,
            mean_shade_error: mean,
            max_shade_error: max,
            pixel_flips: flips,
            ..SpeedPoint::default()
        }
    }

    #[test]
    fn the_pareto_plot_draws_every_point_and_its_front() {
        let p = |per_pixel: f64, flips: u64, max_error: Option<f64>| ParetoPoint {
            per_pixel,
            flips,
            max_error,
            passes: flips == 0,
            chosen: per_pixel == 90.0,
            untuned: per_pixel == 100.0,
        };
        let pts = [
            p(100.0, 0, Some(0.01)),
            p(90.0, 0, Some(0.01)),
            p(95.0, 3, Some(0.02)),
            p(80.0, 40, None),
        ];
        let svg = pareto(&pts).unwrap();
        assert!(svg.starts_with("<svg"));
        // Four points on the left, three with an error on the right.
        assert_eq!(svg.matches("<circle").count(), 7);
        assert!(svg.contains("Cost against differing pixels"));
        assert_eq!(
            front(&[(1.0, 100.0), (1.0, 90.0), (4.0, 95.0), (41.0, 80.0)]),
            [(1.0, 90.0), (41.0, 80.0)]
        );
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short_number(0.0), "0");
        assert_eq!(short_number(0.25), "0.25");
        assert_eq!(short_number(1.0), "1");
        assert_eq!(short_number(1500.0), "1.5k");
        assert_eq!(short_number(2.5e6), "2.5M");
        assert_eq!(short_number(0.00032), "3.2e-4");
    }

    #[test]
    fn colour_bars_are_svg_with_their_title_and_ends() {
        let svg = colour_bar(
            "VM instructions per pixel",
            Scale::Linear {
                lo: 1000.0,
                hi: 9000.0,
            },
            Palette::Viridis,
        )
        .unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..60]);
        assert!(svg.contains("VM instructions per pixel"));
        assert!(
            svg.contains("\n1.0k\n") && svg.contains("\n9.0k\n") && svg.contains("\n5.0k\n"),
            "tick labels missing"
        );
        assert!(svg.matches("<rect").count() >= BAR_STEPS);
        let log = colour_bar(
            "shade error",
            Scale::Log { lo: 1e-5, hi: 1e-1 },
            Palette::Hot,
        )
        .unwrap();
        assert!(log.contains("shade error"));
        assert!(
            log.contains("\n1.0e-5\n") && log.contains("\n1.0e-3\n") && log.contains("\n0.1\n"),
            "decade ticks missing"
        );
        assert_eq!(ticks(Scale::Log { lo: 2e-3, hi: 5e-3 }), vec![2e-3, 5e-3]);
        assert!(log.matches("<rect").count() >= BAR_STEPS);
    }

    #[test]
    fn plot_has_one_marker_per_point_and_skips_the_oracle() {
        let points = [
            point("ref-f64", 1e-6, None, None, 0),
            point("ref-f32", 2e-6, Some(1e-7), Some(1e-5), 3),
            point("ref-f316", 5e-6, Some(1e-3), Some(0.2), 613),
            point("jack", 2e-3, Some(0.0), Some(0.2), 613),
        ];
        let svg = speed_error(&points).unwrap().unwrap();
        assert!(svg.contains("ref-f316") && svg.contains("jack") && svg.contains("ref-f32"));
        // Only the two captions name the oracle: it has no error to plot.
        assert_eq!(svg.matches("ref-f64\n").count(), 2);
        // 3 mean circles + 3 flip circles + 1 legend circle.
        assert_eq!(svg.matches("<circle").count(), 7);
        assert!(speed_error(&points[..1]).unwrap().is_none());
    }
}
