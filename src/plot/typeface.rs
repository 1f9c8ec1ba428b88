//! The plots' typeface, built into the binary: DejaVu Sans 2.37
//! (`assets/fonts/DejaVuSans.ttf`, Bitstream Vera licence in
//! `assets/fonts/LICENSE`), registered with plotters as `sans-serif`, the
//! family every plot names. Text is laid out and rasterised from these bytes
//! (plotters' `ab_glyph` renderer), so a plot needs no system font and
//! renders the same on every machine.

use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

/// DejaVu Sans, as shipped upstream.
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the typeface once per process; [`render_plot!`](crate::render_plot)
/// calls it before drawing. Returns whether `sans-serif` is registered (it
/// is, unless the built-in bytes were not a font).
pub fn register() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| register_font("sans-serif", FontStyle::Normal, DEJAVU_SANS).is_ok())
}

#[cfg(test)]
mod tests {
    use plotters::prelude::*;

    /// The rows of a 12 px "J" drawn at the top left of a white bitmap that
    /// hold ink (any channel below 128).
    fn inked_rows_of_a_j() -> Vec<usize> {
        assert!(super::register());
        let (w, h) = (24usize, 24usize);
        let mut buffer = vec![255u8; w * h * 3];
        {
            let root =
                BitMapBackend::with_buffer(&mut buffer, (w as u32, h as u32)).into_drawing_area();
            root.draw(&Text::new("J", (4, 2), ("sans-serif", 12).into_font()))
                .unwrap();
            root.present().unwrap();
        }
        (0..h)
            .filter(|y| buffer[y * w * 3..(y + 1) * w * 3].iter().any(|&c| c < 128))
            .collect()
    }

    #[test]
    fn a_small_capital_j_is_drawn_whole() {
        // DejaVu Sans's J at 12 px: its cap height (0.73 em of 12 / 1.24 px)
        // and its descender (0.2 em) make about 9 rows of ink from near
        // the text's top (10 here). The system rasteriser (plotters' `ttf`
        // feature) left no pixel darker than mid-grey: a faint comma.
        let rows = inked_rows_of_a_j();
        let (Some(&top), Some(&bottom)) = (rows.first(), rows.last()) else {
            panic!("no ink: the J was not drawn");
        };
        assert!(bottom - top + 1 >= 8, "ink on rows {rows:?}");
        assert!(top <= 2 + 4, "ink starts on row {top}: {rows:?}");
    }
}
