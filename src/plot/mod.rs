//! Plots of runs and of the model, as SVG or PNG chosen by the file extension.

pub mod comparison;
pub mod control_trace;
pub mod cut_curves;
pub mod legend;
pub mod surrogate_fit;
pub mod toughness_ratio;
pub mod typeface;
pub mod wire_slab;

use std::path::Path;

use crate::error::{ConfigError, RunError};
use shearcut_sim::InvalidSetting;

/// Image formats a plot can be written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// Scalable vector graphics (`.svg`).
    Svg,
    /// Portable network graphics (`.png`).
    Png,
}

impl ImageFormat {
    /// The format named by `path`'s extension; anything else is a config error.
    pub fn from_path(path: &Path) -> Result<Self, ConfigError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => Ok(ImageFormat::Svg),
            Some("png") => Ok(ImageFormat::Png),
            _ => Err(ConfigError::Argument(InvalidSetting::new(
                "--plot",
                path.display(),
                "must be a file name ending in .svg or .png (a name before the extension)",
            ))),
        }
    }
}

/// Draws with `$draw(&root)` on an SVG or PNG backend for `$path` in the
/// built-in typeface ([`typeface`]), then presents, under a temporary name
/// renamed into place
/// ([`publish`](crate::result_file::publish)); evaluates to
/// `Result<(), RunError>`.
#[macro_export]
macro_rules! render_plot {
    ($path:expr, $size:expr, $draw:expr) => {{
        use plotters::prelude::*;
        let path: &std::path::Path = $path;
        let fmt = $crate::plot::ImageFormat::from_path(path)?;
        $crate::plot::typeface::register();
        $crate::result_file::publish(path, |partial| {
            let res: Result<(), String> = match fmt {
                $crate::plot::ImageFormat::Svg => {
                    let root = SVGBackend::new(partial, $size).into_drawing_area();
                    ($draw)(&root)
                        .map_err(|e| e.to_string())
                        .and_then(|_| root.present().map_err(|e| e.to_string()))
                }
                $crate::plot::ImageFormat::Png => {
                    let root = BitMapBackend::new(partial, $size).into_drawing_area();
                    ($draw)(&root)
                        .map_err(|e| e.to_string())
                        .and_then(|_| root.present().map_err(|e| e.to_string()))
                }
            };
            res.map_err(|e| $crate::error::RunError::write(path, e))
        })
    }};
}

/// Creates the parent directory of `path` if needed.
pub fn ensure_parent(path: &Path) -> Result<(), RunError> {
    if let Some(dir) = path.parent()
        && !dir.as_os_str().is_empty()
    {
        std::fs::create_dir_all(dir).map_err(|e| RunError::write(dir, e))?;
    }
    Ok(())
}

/// A palette of distinguishable line colours for curves.
pub const CURVE_COLORS: [plotters::style::RGBColor; 6] = [
    plotters::style::RGBColor(0, 0, 0),
    plotters::style::RGBColor(214, 39, 40),
    plotters::style::RGBColor(31, 119, 180),
    plotters::style::RGBColor(44, 160, 44),
    plotters::style::RGBColor(148, 103, 189),
    plotters::style::RGBColor(255, 127, 14),
];
