//! The plots' legend: a boxed list of the series' labels, each beside a
//! short line in its series' colour.

use plotters::chart::{ChartContext, SeriesLabelPosition};
use plotters::coord::CoordTranslate;
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;

/// A series' legend sample: a line `length` pixels long, 2 pixels wide, in
/// `color`, starting at the label's anchor.
pub fn legend_line<C: Color + Copy>(
    color: C,
    length: i32,
) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + length, y)], color.stroke_width(2))
}

/// Draws the chart's series labels in a box at `position`: a white
/// background at 80 % opacity and a black border.
pub fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}
