//! The recommended setting of a scenario group under each named weighting,
//! and its settings block, ready to paste into a scenario file.
//!
//! Only settings whose every run completed compete. The best is the least
//! [`Weighting::score`] of the setting's means against the group's best
//! means; a tie goes to the setting listed first.

use crate::tune::job_list::SettingRecord;
use crate::tune::objective::Objective;
use crate::tune::robust_stats::SettingStats;
use crate::tune::weighting::Weighting;

/// The best setting of a group under one weighting.
#[derive(Debug, Clone, PartialEq)]
pub struct Recommendation<'a> {
    /// The weighting's name.
    pub weighting: String,
    /// The setting's statistics.
    pub stats: &'a SettingStats,
    /// Its score (1 for a weighting of one objective at the group's best).
    pub score: f64,
}

/// The group's best mean of each objective over its competing settings.
pub fn best_means(group: &[&SettingStats]) -> [f64; 4] {
    std::array::from_fn(|i| {
        group
            .iter()
            .filter(|s| s.all_completed())
            .map(|s| s.mean[i])
            .fold(f64::INFINITY, f64::min)
    })
}

/// The best setting of `group` (one scenario's settings) under each of
/// `weightings`; none if no setting completed every run.
pub fn recommend<'a>(
    group: &[&'a SettingStats],
    weightings: &std::collections::BTreeMap<String, Weighting>,
) -> Vec<Recommendation<'a>> {
    let best = best_means(group);
    weightings
        .iter()
        .filter_map(|(name, w)| {
            group
                .iter()
                .filter(|s| s.all_completed())
                .map(|s| (*s, w.score(&s.mean, &best)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(stats, score)| Recommendation {
                    weighting: name.clone(),
                    stats,
                    score,
                })
        })
        .collect()
}

/// The settings block of a recommendation: a comment saying what it is
/// best at, then the scenario's whole `[controller]` table (with
/// `[controller.mpc]`) under the setting.
pub fn settings_block(scenario: &str, r: &Recommendation, setting: &SettingRecord) -> String {
    let s = r.stats;
    let mut text = format!(
        "# Recommended by `shearcut tune` for {scenario} under the weighting \"{}\" (score {:.4}):\n\
         # setting {} ({}{}), mean over {} runs: ",
        r.weighting,
        r.score,
        s.setting,
        setting.controller,
        if setting.overrides.is_empty() {
            String::new()
        } else {
            format!("; {}", setting.overrides.join(", "))
        },
        s.runs,
    );
    let parts: Vec<String> = Objective::ALL
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let (label, k) = o.label();
            format!("{label} {:.4}", s.mean[i] * k)
        })
        .collect();
    text += &parts.join(", ");
    text += "\n";
    text += &setting.controller_toml;
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tune::weighting::default_weightings;

    fn stats(setting: usize, mean: [f64; 4], completed: usize) -> SettingStats {
        SettingStats {
            scenario: 0,
            setting,
            controller: "mpc".into(),
            runs: 2,
            completed,
            mean,
            worst: mean,
            spread: [0.0; 4],
        }
    }

    #[test]
    fn each_weighting_picks_its_end_of_the_front() {
        let a = stats(0, [1.0, 2.0, 10.0, 1.0], 2);
        let b = stats(1, [2.0, 1.0, 10.0, 1.0], 2);
        // Least of everything, but one run stopped short: out.
        let c = stats(2, [0.5, 0.5, 5.0, 0.5], 1);
        let group = [&a, &b, &c];
        let r = recommend(&group, &default_weightings());
        let pick = |name: &str| {
            r.iter()
                .find(|x| x.weighting == name)
                .unwrap()
                .stats
                .setting
        };
        assert_eq!(pick("least-work"), 0);
        assert_eq!(pick("least-deformation"), 1);
        // Equal scores (1+2+1+1 each): the first listed.
        assert_eq!(pick("balanced"), 0);
        assert_eq!(best_means(&group), [1.0, 1.0, 10.0, 1.0]);
    }
}
