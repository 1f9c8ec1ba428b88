//! Shards: a deterministic partition of a sweep's job list over machines.
//!
//! Shard I of N runs the jobs whose index is I modulo N. Dealing the jobs
//! round-robin gives every shard a share of every scenario and setting, so
//! shards take about equally long even when one scenario is slower than
//! the others.
//!
//! The shard comes from `--shard I/N`; without it, from the scheduler's
//! environment: Slurm job arrays (`SLURM_ARRAY_TASK_ID` less
//! `SLURM_ARRAY_TASK_MIN`, of `SLURM_ARRAY_TASK_COUNT`) or Kubernetes
//! indexed jobs (`JOB_COMPLETION_INDEX`, of `SHEARCUT_SHARDS`, which the
//! job's manifest sets to its `completions`: Kubernetes does not tell a
//! pod the count).

use std::fmt;
use std::str::FromStr;

use shearcut_sim::InvalidSetting;

/// One shard of a job list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, 0-based, below `count`.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

/// Most shards accepted.
pub const MAX_SHARDS: usize = 100_000;

impl Shard {
    /// The whole list as one shard.
    pub const WHOLE: Self = Self { index: 0, count: 1 };

    /// A shard, checked: `count` in 1..=[`MAX_SHARDS`], `index` below it.
    pub fn new(index: usize, count: usize, key: &str) -> Result<Self, InvalidSetting> {
        if !(1..=MAX_SHARDS).contains(&count) || index >= count {
            return Err(InvalidSetting::new(
                key,
                format!("{index}/{count}"),
                format!("I/N with N in 1..={MAX_SHARDS} and I in 0..N"),
            ));
        }
        Ok(Self { index, count })
    }

    /// Whether the job at `index` of the list is this shard's.
    pub fn holds(&self, index: usize) -> bool {
        index % self.count == self.index
    }

    /// The shard `--shard` names, else the scheduler's environment (read
    /// through `var`), else the whole list.
    pub fn resolve(
        flag: Option<Shard>,
        var: impl Fn(&str) -> Option<String>,
    ) -> Result<Self, InvalidSetting> {
        if let Some(s) = flag {
            return Ok(s);
        }
        let number = |name: &str| -> Result<Option<usize>, InvalidSetting> {
            match var(name) {
                None => Ok(None),
                Some(text) => text.trim().parse().map(Some).map_err(|_| {
                    InvalidSetting::new(name, format!("{text:?}"), "a whole number >= 0")
                }),
            }
        };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let count = number("SLURM_ARRAY_TASK_COUNT")?.ok_or_else(|| {
                InvalidSetting::new(
                    "SLURM_ARRAY_TASK_COUNT",
                    "unset",
                    "set by Slurm for job arrays (sbatch --array=0-N); or pass --shard I/N",
                )
            })?;
            let index = id.checked_sub(min).ok_or_else(|| {
                InvalidSetting::new(
                    "SLURM_ARRAY_TASK_ID",
                    id,
                    format!(">= SLURM_ARRAY_TASK_MIN ({min})"),
                )
            })?;
            return Self::new(index, count, "SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT");
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let count = number("SHEARCUT_SHARDS")?.ok_or_else(|| {
                InvalidSetting::new(
                    "SHEARCUT_SHARDS",
                    "unset",
                    "set it to the indexed job's completions; or pass --shard I/N",
                )
            })?;
            return Self::new(index, count, "JOB_COMPLETION_INDEX/SHEARCUT_SHARDS");
        }
        if var("SHEARCUT_SHARDS").is_some_and(|t| !t.trim().is_empty()) {
            return Err(InvalidSetting::new(
                "JOB_COMPLETION_INDEX",
                "unset",
                "set by an indexed Kubernetes Job beside SHEARCUT_SHARDS (which alone shards \
                 nothing: the whole sweep would run); or pass --shard I/N",
            ));
        }
        Ok(Self::WHOLE)
    }
}

impl FromStr for Shard {
    type Err = InvalidSetting;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || {
            InvalidSetting::new(
                "--shard",
                s,
                format!("I/N with N in 1..={MAX_SHARDS} and I in 0..N, e.g. 0/4"),
            )
        };
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i = i.trim().parse().map_err(|_| bad())?;
        let n = n.trim().parse().map_err(|_| bad())?;
        Self::new(i, n, "--shard").map_err(|_| bad())
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shards_partition_the_list() {
        let shards: Vec<Shard> = (0..3).map(|i| Shard::new(i, 3, "t").unwrap()).collect();
        for job in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.holds(job)).count(), 1);
        }
        assert!(shards[2].holds(5) && shards[0].holds(6));
    }

    #[test]
    fn the_flag_the_slurm_and_the_kubernetes_forms() {
        assert_eq!(
            "1/4".parse::<Shard>().unwrap(),
            Shard::new(1, 4, "t").unwrap()
        );
        for bad in ["4/4", "1", "a/2", "0/0", "-1/3"] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert_eq!((e.key.as_str(), e.value.as_str()), ("--shard", bad));
        }
        let flag = Shard::new(0, 2, "t").unwrap();
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        assert_eq!(Shard::resolve(Some(flag), env(&slurm)).unwrap(), flag);
        assert_eq!(
            Shard::resolve(None, env(&slurm)).unwrap(),
            Shard { index: 1, count: 3 }
        );
        let k8s = [("JOB_COMPLETION_INDEX", "2"), ("SHEARCUT_SHARDS", "8")];
        assert_eq!(
            Shard::resolve(None, env(&k8s)).unwrap(),
            Shard { index: 2, count: 8 }
        );
        let e = Shard::resolve(None, env(&[("JOB_COMPLETION_INDEX", "2")])).unwrap_err();
        assert_eq!(e.key, "SHEARCUT_SHARDS");
        let e = Shard::resolve(None, env(&[("SHEARCUT_SHARDS", "8")])).unwrap_err();
        assert_eq!(e.key, "JOB_COMPLETION_INDEX");
        assert_eq!(Shard::resolve(None, env(&[])).unwrap(), Shard::WHOLE);
    }
}
