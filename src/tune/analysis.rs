//! The analysis of a complete sweep, per scenario group: robust statistics
//! and the Pareto front (`front.csv`, `front-<scenario>.svg/.png`), each
//! setting's effect (`effects.csv`, `effects-<scenario>.svg/.png`), the
//! recommended setting under each weighting
//! (`recommended/<scenario>-<weighting>.toml`), with a best-constant grid
//! the MPC against the best constant per variant (`best-constant.csv`,
//! [`best_constant_pairing`]) and against each point of the grid held over
//! the variants (`constant-grid.csv`, [`uniform_constant`]), and a summary
//! (`summary.md`, also printed).

use std::path::Path;

use crate::error::RunError;
use crate::render_plot;
use crate::result_file::{write_table, write_text};
use crate::tune::best_constant_pairing;
use crate::tune::effect_plot::draw_effects;
use crate::tune::front_plot::draw_front;
use crate::tune::job_list::JobCatalog;
use crate::tune::job_outcome::JobRow;
use crate::tune::objective::Objective;
use crate::tune::pareto_front::front;
use crate::tune::recommendation::{recommend, settings_block};
use crate::tune::robust_stats::{SettingStats, setting_stats};
use crate::tune::setting_effect::{EffectLevel, effects};
use crate::tune::uniform_constant;

/// How far a controller's front reaches along deformation: the maximum
/// deformation at its least-work end over that at its least-deformation
/// end.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontSpan {
    /// The controller family (`mpc`, `slice`, `press`, `force`).
    pub family: String,
    /// The least-work setting on the family's front.
    pub least_work: usize,
    /// The least-deformation setting on it.
    pub least_deformation: usize,
    /// Mean maximum deformation at the least-work end over that at the
    /// least-deformation end (≥ 1).
    pub ratio: f64,
}

/// Which of `group` lie on its front (settings that did not complete every
/// run are not on it).
pub fn front_of(group: &[&SettingStats]) -> Vec<bool> {
    let eligible: Vec<&SettingStats> = group
        .iter()
        .copied()
        .filter(|s| s.all_completed())
        .collect();
    let points: Vec<&[f64]> = eligible.iter().map(|s| s.mean.as_slice()).collect();
    let flags = front(&points);
    group
        .iter()
        .map(|s| {
            eligible
                .iter()
                .position(|e| std::ptr::eq(*e, *s))
                .is_some_and(|i| flags[i])
        })
        .collect()
}

/// The front span of each controller family with two or more completed
/// settings in `group`.
pub fn front_spans(group: &[&SettingStats]) -> Vec<FrontSpan> {
    let family = |s: &SettingStats| s.controller.split(':').next().unwrap_or("").to_string();
    let mut families: Vec<String> = group.iter().map(|s| family(s)).collect();
    families.dedup();
    families.sort();
    families.dedup();
    families
        .into_iter()
        .filter_map(|f| {
            let members: Vec<&SettingStats> = group
                .iter()
                .copied()
                .filter(|s| family(s) == f && s.all_completed())
                .collect();
            if members.len() < 2 {
                return None;
            }
            let on: Vec<&SettingStats> = members
                .iter()
                .zip(front_of(&members))
                .filter(|(_, on)| *on)
                .map(|(s, _)| *s)
                .collect();
            let by = |i: usize| {
                move |a: &&&SettingStats, b: &&&SettingStats| a.mean[i].total_cmp(&b.mean[i])
            };
            let least_work = on.iter().min_by(by(0))?;
            let least_deformation = on.iter().min_by(by(1))?;
            Some(FrontSpan {
                family: f,
                least_work: least_work.setting,
                least_deformation: least_deformation.setting,
                ratio: least_work.mean[1] / least_deformation.mean[1],
            })
        })
        .collect()
}

/// Analyses the complete sweep `rows` (every job's, in job order) into
/// `dir`; the summary's text.
pub fn analyse(dir: &Path, catalog: &JobCatalog, rows: &[JobRow]) -> Result<String, RunError> {
    let finished: Vec<_> = catalog.jobs.iter().zip(rows).collect();
    let stats = setting_stats(&finished);
    let mut front_rows: Vec<Vec<String>> = Vec::new();
    let mut front_header = vec![
        "scenario".to_string(),
        "setting".into(),
        "controller".into(),
        "overrides".into(),
        "runs".into(),
        "completed".into(),
        "pareto".into(),
    ];
    for stat in ["mean", "worst", "spread"] {
        front_header.extend(
            Objective::ALL
                .iter()
                .map(|o| format!("{stat}_{}", o.column())),
        );
    }
    let mut effect_rows: Vec<Vec<String>> = Vec::new();
    let mut effect_header = vec![
        "scenario".to_string(),
        "column".into(),
        "controller_family".into(),
        "value".into(),
        "runs".into(),
    ];
    effect_header.extend(
        Objective::ALL
            .iter()
            .map(|o| format!("mean_{}", o.column())),
    );
    let recommended = dir.join("recommended");
    std::fs::create_dir_all(&recommended).map_err(|e| RunError::write(&recommended, e))?;
    let mut summary = format!("# Sweep {}\n", catalog.sweep);
    for (si, name) in catalog.scenarios.iter().enumerate() {
        let group: Vec<&SettingStats> = stats.iter().filter(|s| s.scenario == si).collect();
        let on_front = front_of(&group);
        let settings = &catalog.settings[si];
        for (s, on) in group.iter().zip(&on_front) {
            let f = crate::tune::perturbation::float_cell;
            let mut cells = vec![
                name.clone(),
                s.setting.to_string(),
                s.controller.clone(),
                settings[s.setting].overrides.join("; "),
                s.runs.to_string(),
                s.completed.to_string(),
                on.to_string(),
            ];
            for v in [&s.mean, &s.worst, &s.spread] {
                cells.extend(v.iter().map(|x| f(*x)));
            }
            front_rows.push(cells);
        }
        let levels = effects(catalog, si, &finished);
        for l in &levels {
            let mut cells = vec![
                name.clone(),
                l.column.clone(),
                l.family.clone(),
                l.value.clone(),
                l.runs.to_string(),
            ];
            cells.extend(
                l.mean
                    .iter()
                    .map(|x| crate::tune::perturbation::float_cell(*x)),
            );
            effect_rows.push(cells);
        }
        draw_group_plots(dir, name, &group, &on_front, &levels)?;
        summary += &group_summary(name, &group, &on_front, settings);
        for r in recommend(&group, &catalog.weightings) {
            let path = recommended.join(format!("{name}-{}.toml", r.weighting));
            let block = settings_block(name, &r, &settings[r.stats.setting]);
            write_text(&path, &block)?;
            summary += &format!(
                "| {} | {} | {} | {} | {:.4} | `{}` |\n",
                r.weighting,
                r.stats.setting,
                r.stats.controller,
                settings[r.stats.setting].overrides.join(", "),
                r.score,
                path.strip_prefix(dir).unwrap_or(&path).display()
            );
        }
    }
    let pairs = best_constant_pairing::pairs(catalog, &finished);
    summary += &best_constant_pairing::write_pairs(dir, catalog, &pairs)?;
    let grid_pairs = uniform_constant::grid_point_pairs(catalog, &finished);
    summary += &uniform_constant::write_grid(dir, catalog, &grid_pairs)?;
    write_table(&dir.join("front.csv"), front_header, front_rows)?;
    write_table(&dir.join("effects.csv"), effect_header, effect_rows)?;
    let path = dir.join("summary.md");
    write_text(&path, &summary)?;
    Ok(summary)
}

/// The front and effect plots of one scenario, SVG and PNG.
fn draw_group_plots(
    dir: &Path,
    name: &str,
    group: &[&SettingStats],
    on_front: &[bool],
    levels: &[EffectLevel],
) -> Result<(), RunError> {
    let title = format!("{name}: work against deformation, the Pareto front marked");
    for ext in ["svg", "png"] {
        render_plot!(
            &dir.join(format!("front-{name}.{ext}")),
            (1000, 700),
            |root| { draw_front(root, &title, group, on_front) }
        )?;
    }
    if !levels.is_empty() {
        let title = format!("{name}: each setting's effect (completed runs)");
        let panels = crate::tune::effect_plot::panel_columns(levels).len();
        let height = 380 * panels.div_ceil(3) as u32 + 40;
        for ext in ["svg", "png"] {
            render_plot!(
                &dir.join(format!("effects-{name}.{ext}")),
                (1500, height),
                |root| { draw_effects(root, &title, levels) }
            )?;
        }
    }
    Ok(())
}

/// The summary of one scenario group: its front and front spans, and the
/// head of the recommendations' table (rows follow).
fn group_summary(
    name: &str,
    group: &[&SettingStats],
    on_front: &[bool],
    settings: &[crate::tune::job_list::SettingRecord],
) -> String {
    let mut t = format!(
        "\n## {name}\n\nThe Pareto front (means over each setting's runs; worst case in brackets):\n\n\
         | setting | controller | settings | work (J) | max deformation (mm) | peak Fv (N) | time (s) | runs |\n\
         |---|---|---|---|---|---|---|---|\n"
    );
    for (s, _) in group.iter().zip(on_front).filter(|(_, on)| **on) {
        t += &format!(
            "| {} | {} | {} | {:.4} [{:.4}] | {:.3} [{:.3}] | {:.2} [{:.2}] | {:.3} [{:.3}] | {} |\n",
            s.setting,
            s.controller,
            settings[s.setting].overrides.join(", "),
            s.mean[0],
            s.worst[0],
            s.mean[1] * 1e3,
            s.worst[1] * 1e3,
            s.mean[2],
            s.worst[2],
            s.mean[3],
            s.worst[3],
            s.runs
        );
    }
    let incomplete = group.iter().filter(|s| !s.all_completed()).count();
    if incomplete > 0 {
        t += &format!("\n{incomplete} settings did not complete every run and are left out.\n");
    }
    for span in front_spans(group) {
        if span.least_work == span.least_deformation {
            t += &format!(
                "\n{} settings alone: setting {} has both the least work and the least deformation (no trade-off among them).\n",
                span.family, span.least_work
            );
            continue;
        }
        t += &format!(
            "\n{} settings alone: the front spans {:.2}× in max deformation between its least-work end (setting {}) and its least-deformation end (setting {}).\n",
            span.family, span.ratio, span.least_work, span.least_deformation
        );
    }
    t += "\nRecommended settings:\n\n| weighting | setting | controller | settings | score | block |\n|---|---|---|---|---|---|\n";
    t
}
