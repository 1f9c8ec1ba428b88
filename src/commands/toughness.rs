//! `shearcut toughness`: the slice-push toughness law of seed 000 §III.B.

use std::path::{Path, PathBuf};

use shearcut_sim::InvalidSetting;
use shearcut_sim::mechanics::{force_ratio, normal_force_ratio, toughness_ratio};
use shearcut_sim::physical_range::{SLICE_PUSH_RATIO, number_text};

use crate::cli::print;
use crate::error::{ConfigError, RunError};
use crate::plot::toughness_ratio::{FIG3_SLICE_PUSH_RATIOS, draw_fig3, fig3_table};
use crate::render_plot;
use crate::result_file::write_table;
use crate::run_dir::claim_output_file;

/// The law evaluated at one (ξ, ν).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToughnessReport {
    /// Slice-push ratio ξ, in [0, 20].
    pub xi: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
    /// r(ξ, ν) = R_c^s / R_c (eq. 6).
    pub toughness_ratio: f64,
    /// F_t / F_n = ξ/(2(1+ν)).
    pub force_ratio: f64,
    /// f_n^s / f_n^p.
    pub normal_force_ratio: f64,
}

/// Validates ν and ξ and evaluates the law.
pub fn evaluate(nu: f64, xi: f64) -> Result<ToughnessReport, ConfigError> {
    if !(nu.is_finite() && nu > 0.0 && nu < 0.5) {
        return Err(ConfigError::Argument(InvalidSetting::new(
            "--nu",
            nu,
            "must be in the open interval (0, 0.5)",
        )));
    }
    SLICE_PUSH_RATIO
        .check("--xi", xi)
        .map_err(ConfigError::Argument)?;
    Ok(ToughnessReport {
        xi,
        nu,
        toughness_ratio: toughness_ratio(xi, nu),
        force_ratio: force_ratio(xi, nu),
        normal_force_ratio: normal_force_ratio(xi, nu),
    })
}

/// Runs the subcommand: prints the law and, with `plot`, draws Fig. 3 and writes its CSV.
pub fn run(nu: f64, xi: f64, plot: Option<&Path>) -> Result<(), RunError> {
    let r = evaluate(nu, xi)?;
    if let Some(path) = plot {
        claim_plot(path)?;
    }
    print(&format!(
        "r(xi={}, nu={}) = {:.4}\nF_t/F_n         = {:.4}\nf_n^s/f_n^p     = {:.4}\n",
        number_text(r.xi),
        number_text(r.nu),
        r.toughness_ratio,
        r.force_ratio,
        r.normal_force_ratio
    ))?;
    if let Some(path) = plot {
        let csv = write_fig3(path)?;
        print(&format!("wrote {} and {}\n", path.display(), csv.display()))?;
    }
    Ok(())
}

/// Checks that `--plot` = `path` names an image this process can write,
/// and that its table beside it (extension `.csv`) can be written too
/// ([`claim_output_file`]), before anything is printed or drawn: the paths
/// are the user's, so one that cannot be created is bad input (exit 2).
fn claim_plot(path: &Path) -> Result<(), RunError> {
    crate::plot::ImageFormat::from_path(path)?;
    claim_output_file("--plot", path)?;
    claim_output_file("--plot (its table)", &path.with_extension("csv"))
}

/// Draws Fig. 3 to `path` (claimed by [`claim_plot`]) and its table to the
/// same path with extension `.csv`.
fn write_fig3(path: &Path) -> Result<PathBuf, RunError> {
    render_plot!(path, (800, 560), draw_fig3)?;
    let csv_path = path.with_extension("csv");
    let mut header = vec!["poisson_ratio".to_string()];
    header.extend(FIG3_SLICE_PUSH_RATIOS.iter().map(|xi| format!("r_xi_{xi}")));
    let rows = fig3_table().into_iter().map(|(nu, r)| {
        let mut row = vec![format!("{nu}")];
        row.extend(r.iter().map(|v| format!("{v}")));
        row
    });
    write_table(&csv_path, header, rows)?;
    Ok(csv_path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_example_prints_0_6224() {
        let r = evaluate(0.4, 0.75).unwrap();
        assert_eq!(format!("{:.4}", r.toughness_ratio), "0.6224");
        assert_eq!(format!("{:.4}", r.force_ratio), "0.2679");
    }

    #[test]
    fn xi_out_of_range_is_refused_before_the_law_turns_nan() {
        let e = evaluate(0.4, 1e300).unwrap_err().to_string();
        assert_eq!(e, "`--xi` = 1e300: must be in [0, 20]");
        let r = evaluate(0.4, 20.0).unwrap();
        assert!(r.toughness_ratio.is_finite() && r.toughness_ratio > 0.0);
    }

    #[test]
    fn nu_out_of_range_is_refused() {
        let e = evaluate(0.7, 0.75).unwrap_err().to_string();
        assert_eq!(e, "`--nu` = 0.7: must be in the open interval (0, 0.5)");
    }
}
