//! Log-log line charts drawn side by side into one PNG.
//!
//! plotters draws into an RGB buffer; the PNG is written by voxtrace's own
//! encoder, so the report needs no second image stack. Text needs a TrueType
//! font, read at run time (the repository ships none).

use std::path::{Path, PathBuf};

use plotters::coord::combinators::BindKeyPoints;
use plotters::element::ComposedElement;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// One line of a chart.
pub struct Series {
    /// Legend text.
    pub name: String,
    /// `(x, y)` points, both positive (the axes are logarithmic).
    pub points: Vec<(f64, f64)>,
    /// Index into [`COLORS`]: series of one kind share a color.
    pub color: usize,
    /// How the line is drawn.
    pub line: Line,
}

/// Line styles, to tell apart series of one color.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Line {
    /// Solid, thick.
    Thick,
    /// Solid, thin.
    Thin,
    /// Dashed: reference figures from elsewhere.
    Dashed,
}

/// The colors of the series, chosen to stay apart for color-blind readers
/// (Okabe and Ito's palette).
pub const COLORS: [RGBColor; 4] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
];

/// One panel: a title, axis labels and its series.
pub struct Chart {
    /// Caption above the panel.
    pub title: String,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// Label of the vertical axis.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
    /// The corner for the legend, where the lines are not.
    pub legend: SeriesLabelPosition,
}

/// Places where common systems keep a sans-serif TrueType font.
const FONT_CANDIDATES: [&str; 5] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/Library/Fonts/Arial.ttf",
];

/// Loads `explicit`, or the first font of [`FONT_CANDIDATES`] that exists,
/// and registers it as plotters' sans-serif. Call once per process.
pub fn load_font(explicit: Option<&Path>) -> Result<(), String> {
    let path: PathBuf = match explicit {
        Some(path) => path.to_path_buf(),
        None => FONT_CANDIDATES
            .iter()
            .map(PathBuf::from)
            .find(|p| p.is_file())
            .ok_or("no TrueType font found for the plot's text; pass --font PATH.ttf")?,
    };
    let bytes =
        std::fs::read(&path).map_err(|e| format!("cannot read --font {}: {e}", path.display()))?;
    // plotters keeps fonts for the whole process.
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
        .map_err(|_| format!("{} is not a TrueType/OpenType font", path.display()))
}

/// Panel size in pixels.
const PANEL: (u32, u32) = (800, 560);

/// Draws `charts` left to right into the PNG at `path`.
pub fn draw(path: &Path, charts: &[Chart]) -> Result<(), String> {
    let width = PANEL.0 * charts.len() as u32;
    let height = PANEL.1;
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let panels = root.split_evenly((1, charts.len()));
        for (chart, area) in charts.iter().zip(&panels) {
            draw_chart(area, chart)?;
        }
        root.present().map_err(plot_error)?;
    }
    let pixels: Vec<u32> = rgb
        .chunks_exact(3)
        .map(|c| voxtrace::pack(voxtrace::glam::U8Vec3::new(c[0], c[1], c[2])))
        .collect();
    // Whole or not at all: a failed run keeps the previous plot.
    voxtrace_cli::atomic::write_atomic(path, |out| {
        voxtrace::encode_png(out, width, height, &pixels).map_err(|e| e.to_string())
    })
    .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn plot_error<E: std::fmt::Display>(e: E) -> String {
    format!("cannot draw the plot: {e}")
}

/// The x axis' labelled values: every x of the data when there are few
/// (so each measured size has its label), but none closer to the one
/// before it than a sixteenth of the axis (labels side by side would run
/// into one: "76.0087.173"); else 1, 2 and 5 times the powers of ten
/// inside `range`.
fn x_ticks(values: impl Iterator<Item = f64>, range: &std::ops::Range<f64>) -> Vec<f64> {
    let mut xs: Vec<f64> = values.filter(|v| *v > 0.0 && v.is_finite()).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    if !xs.is_empty() && xs.len() <= 12 {
        // On the log axis, a sixteenth of its width in decades.
        let gap = (range.end.log10() - range.start.max(f64::MIN_POSITIVE).log10()) / 16.0;
        let mut kept: Vec<f64> = Vec::with_capacity(xs.len());
        for x in xs {
            if kept
                .last()
                .is_none_or(|&last| x.log10() - last.log10() >= gap)
            {
                kept.push(x);
            }
        }
        return kept;
    }
    let mut ticks = Vec::new();
    let mut decade = 10f64.powf(range.start.max(f64::MIN_POSITIVE).log10().floor());
    while decade <= range.end && ticks.len() < 64 {
        for m in [1.0, 2.0, 5.0] {
            let t = m * decade;
            if range.contains(&t) {
                ticks.push(t);
            }
        }
        decade *= 10.0;
    }
    ticks
}

/// The range covering `values` padded by a fifth of a decade each side.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return 1.0..10.0;
    }
    let pad = 10f64.powf(0.2);
    lo / pad..hi * pad
}

fn draw_chart(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    chart: &Chart,
) -> Result<(), String> {
    let points = || chart.series.iter().flat_map(|s| s.points.iter());
    let xs = log_range(points().map(|p| p.0));
    let ys = log_range(points().map(|p| p.1));
    let mut context = ChartBuilder::on(area)
        .caption(&chart.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(
            xs.clone()
                .log_scale()
                .with_key_points(x_ticks(points().map(|p| p.0), &xs)),
            ys.log_scale(),
        )
        .map_err(plot_error)?;
    context
        .configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .x_label_formatter(&|v| short_number(*v))
        .y_label_formatter(&|v| short_number(*v))
        .draw()
        .map_err(plot_error)?;
    for series in &chart.series {
        let color = COLORS[series.color % COLORS.len()];
        let style = color.stroke_width(if series.line == Line::Thin { 1 } else { 3 });
        let drawn = if series.line == Line::Dashed {
            context.draw_series(DashedLineSeries::new(
                series.points.iter().copied(),
                8,
                6,
                style,
            ))
        } else {
            context.draw_series(LineSeries::new(series.points.iter().copied(), style))
        };
        let line = series.line;
        drawn
            .map_err(plot_error)?
            .label(&series.name)
            .legend(move |at| legend_mark(line, at, style));
        context
            .draw_series(
                series
                    .points
                    .iter()
                    .map(|&p| Circle::new(p, 4, color.filled())),
            )
            .map_err(plot_error)?;
    }
    context
        .configure_series_labels()
        .position(chart.legend.clone())
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", LEGEND_TEXT))
        .draw()
        .map_err(plot_error)
}

/// The legend's text size in pixels. Not 15: plotters' ab_glyph text drops
/// a full stop at 15 pixels ("study.vox" read "studyvox"), at 16 it draws it.
const LEGEND_TEXT: u32 = 16;

/// A legend's sample of a line: two strokes from one point.
type LegendMark<DB> =
    ComposedElement<(i32, i32), DB, PathElement<(i32, i32)>, PathElement<(i32, i32)>>;

/// The legend's sample of a line, 20 pixels from `at`, drawn as the chart
/// draws it: a dashed line as two dashes, a solid one whole.
fn legend_mark<DB: DrawingBackend>(
    line: Line,
    at: (i32, i32),
    style: ShapeStyle,
) -> LegendMark<DB> {
    let gap = if line == Line::Dashed {
        (8, 13)
    } else {
        (20, 20)
    };
    EmptyElement::at(at)
        + PathElement::new(vec![(0, 0), (gap.0, 0)], style)
        + PathElement::new(vec![(gap.1, 0), (20, 0)], style)
}

/// Axis labels without trailing zeros: 0.5, 20, 1000.
fn short_number(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_measured_size_gets_its_label() {
        let sizes = [50.0, 100.0, 250.0, 500.0, 1000.0];
        let range = log_range(sizes.iter().copied());
        assert_eq!(x_ticks(sizes.iter().copied(), &range), sizes);
        // Many values: 1, 2, 5 per decade inside the range.
        let many: Vec<f64> = (1..40).map(|i| f64::from(i) * 3.0).collect();
        let range = log_range(many.iter().copied());
        let ticks = x_ticks(many.iter().copied(), &range);
        assert!(
            ticks.contains(&10.0) && ticks.contains(&20.0) && ticks.contains(&50.0),
            "{ticks:?}"
        );
        assert!(ticks.iter().all(|t| range.contains(t)));
    }

    #[test]
    fn labels_side_by_side_are_thinned_not_run_together() {
        // The accuracy plot's times: 134 and 147, 606 and 626 sat so close
        // on a log axis from 50 to 10,000 that their labels ran into one.
        let times = [
            52.764, 134.0, 147.0, 248.0, 410.0, 477.0, 606.0, 626.0, 1096.0, 2196.0, 2216.0, 9742.0,
        ];
        let range = log_range(times.iter().copied());
        let ticks = x_ticks(times.iter().copied(), &range);
        let decades = range.end.log10() - range.start.log10();
        for pair in ticks.windows(2) {
            assert!(
                pair[1].log10() - pair[0].log10() >= decades / 16.0,
                "{ticks:?}"
            );
        }
        // The first of each close pair keeps its label, and the rest stay.
        for t in [52.764, 134.0, 248.0, 410.0, 606.0, 1096.0, 2196.0, 9742.0] {
            assert!(ticks.contains(&t), "{t} lost its label: {ticks:?}");
        }
    }

    /// The runs of colored pixels along the middle row of a legend mark
    /// drawn at (5, 5) on white: `(first x, length)` each.
    fn legend_runs(line: Line) -> Vec<(usize, usize)> {
        let (w, h) = (32, 11);
        let mut rgb = vec![255u8; w * h * 3];
        {
            let root =
                BitMapBackend::with_buffer(&mut rgb, (w as u32, h as u32)).into_drawing_area();
            let style = COLORS[0].stroke_width(1);
            root.draw(&legend_mark(line, (5, 5), style)).unwrap();
            root.present().unwrap();
        }
        let row = &rgb[5 * w * 3..6 * w * 3];
        let mut runs: Vec<(usize, usize)> = Vec::new();
        for x in 0..w {
            if row[x * 3..x * 3 + 3] == [255, 255, 255] {
                continue;
            }
            match runs.last_mut() {
                Some((start, len)) if *start + *len == x => *len += 1,
                _ => runs.push((x, 1)),
            }
        }
        runs
    }

    #[test]
    fn the_legend_draws_dashed_lines_dashed_and_solid_ones_whole() {
        let solid = legend_runs(Line::Thick);
        assert_eq!(solid.len(), 1, "{solid:?}");
        assert!(solid[0].1 >= 20, "{solid:?}");
        let dashed = legend_runs(Line::Dashed);
        assert_eq!(dashed.len(), 2, "{dashed:?}");
        assert!(dashed[1].0 >= dashed[0].0 + dashed[0].1 + 3, "{dashed:?}");
    }

    #[test]
    fn a_chart_with_a_dashed_series_draws() {
        if load_font(None).is_err() {
            println!("skipped: no system font for the plot");
            return;
        }
        let points = vec![(50.0, 1.0), (100.0, 3.0), (250.0, 9.0)];
        let chart = Chart {
            title: "t".into(),
            x_label: "size".into(),
            y_label: "ms".into(),
            series: vec![
                Series {
                    name: "ours".into(),
                    points: points.clone(),
                    color: 0,
                    line: Line::Thick,
                },
                Series {
                    name: "paper".into(),
                    points,
                    color: 1,
                    line: Line::Dashed,
                },
            ],
            legend: SeriesLabelPosition::UpperLeft,
        };
        let path = std::env::temp_dir().join(format!("voxtrace-plot-{}.png", std::process::id()));
        draw(&path, &[chart]).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
        let _ = std::fs::copy(&path, std::env::temp_dir().join("voxtrace-plot-last.png"));
        let _ = std::fs::remove_file(&path);
    }

    /// The ink of a chart whose one series is called `name`: the sum of
    /// how dark its pixels are.
    fn chart_ink(name: &str) -> u64 {
        let chart = Chart {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            series: vec![Series {
                name: name.into(),
                points: vec![(1.0, 1.0), (10.0, 5.0)],
                color: 0,
                line: Line::Thick,
            }],
            legend: SeriesLabelPosition::LowerLeft,
        };
        let mut rgb = vec![0u8; PANEL.0 as usize * PANEL.1 as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, PANEL).into_drawing_area();
            root.fill(&WHITE).unwrap();
            draw_chart(&root, &chart).unwrap();
            root.present().unwrap();
        }
        rgb.iter().map(|&c| u64::from(255 - c)).sum()
    }

    #[test]
    fn the_legend_keeps_a_names_full_stop() {
        if let Err(e) = load_font(None) {
            eprintln!("skipping: {e}");
            return;
        }
        // A space is as wide as a full stop in the sans-serif fonts the
        // report looks for, so the two legends differ only by the stop's
        // ink (at 15 pixels plotters drew none: "studyvox").
        let (with, without) = (chart_ink("study.vox"), chart_ink("study vox"));
        assert!(with > without + 2 * 255, "{with} against {without}");
    }
}
