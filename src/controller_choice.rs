//! Which controller a closed-loop run uses: `mpc`, `press`, `slice:XI`, `force:N`.

use std::fmt;
use std::str::FromStr;

use shearcut_sim::InvalidSetting;

/// A controller named on the command line or in `[controller] kind`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ControllerChoice {
    /// The model-predictive controller.
    Mpc,
    /// Pressing: ξ = 0 at the configured speed.
    Press,
    /// Slicing at a constant slice-push ratio ξ ≥ 0.
    Slice(f64),
    /// A PI loop holding the vertical force at a setpoint, N > 0.
    Force(f64),
}

/// What the string forms allow, for error messages.
const ALLOWED: &str =
    "one of mpc, press, slice:XI (XI in [0, 20], e.g. slice:0.75), force:N (N > 0, e.g. force:20)";

impl ControllerChoice {
    /// The slice-push ratio the controller starts with (the plant builds its
    /// first sections for it): ξ for slicing, 0 for pressing and force control,
    /// and the MPC's nominal `mpc_start` ratio.
    pub fn nominal_slice_push_ratio(&self, mpc_start: f64) -> f64 {
        match self {
            Self::Mpc => mpc_start,
            Self::Press | Self::Force(_) => 0.0,
            Self::Slice(xi) => *xi,
        }
    }
}

impl FromStr for ControllerChoice {
    type Err = InvalidSetting;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || InvalidSetting::new("controller", s, ALLOWED);
        let number = |text: &str| text.trim().parse::<f64>().ok().filter(|x| x.is_finite());
        match s.trim() {
            "mpc" => Ok(Self::Mpc),
            "press" => Ok(Self::Press),
            other => {
                if let Some(xi) = other.strip_prefix("slice:") {
                    number(xi)
                        .filter(|x| *x >= 0.0)
                        .map(Self::Slice)
                        .ok_or_else(bad)
                } else if let Some(n) = other.strip_prefix("force:") {
                    number(n)
                        .filter(|x| *x > 0.0)
                        .map(Self::Force)
                        .ok_or_else(bad)
                } else {
                    Err(bad())
                }
            }
        }
    }
}

impl fmt::Display for ControllerChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Mpc => write!(f, "mpc"),
            Self::Press => write!(f, "press"),
            Self::Slice(xi) => write!(f, "slice:{xi}"),
            Self::Force(n) => write!(f, "force:{n}"),
        }
    }
}

impl TryFrom<String> for ControllerChoice {
    type Error = InvalidSetting;

    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl From<ControllerChoice> for String {
    fn from(c: ControllerChoice) -> Self {
        c.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::ControllerChoice;

    #[test]
    fn parses_and_prints_every_form() {
        for (text, choice) in [
            ("mpc", ControllerChoice::Mpc),
            ("press", ControllerChoice::Press),
            ("slice:0.75", ControllerChoice::Slice(0.75)),
            ("force:20", ControllerChoice::Force(20.0)),
        ] {
            assert_eq!(text.parse::<ControllerChoice>().unwrap(), choice);
            assert_eq!(choice.to_string(), text);
        }
    }

    #[test]
    fn refuses_bad_forms_naming_the_value() {
        for text in [
            "",
            "slice",
            "slice:-1",
            "slice:nan",
            "force:0",
            "force:x",
            "pid",
        ] {
            let e = text.parse::<ControllerChoice>().unwrap_err();
            assert_eq!(e.key, "controller");
            assert_eq!(e.value, text);
        }
    }
}
