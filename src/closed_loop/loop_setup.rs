//! What every closed loop of a scenario is built from: the cut task a
//! controller is given, the plant, the controller, and the labels of the
//! samples, in one place so that the in-process loop and the two processes
//! of the iceoryx2 loop build the same ones (their runs must be
//! bit-identical).

use std::sync::Arc;

use shearcut_controllers::controller::{
    ConstantSlice, Controller, CutTask, ForceFeedback, ForceFeedbackGains, MotionLimits,
};
use shearcut_controllers::mpc::{DepthProfile, Mpc, SurrogateModel};
use shearcut_controllers::observer::EdgeOutline;
use shearcut_plant::{Plant, PlantError, PlantSettings, PlantSpec};
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::{InvalidSetting, Knife};

use super::LoopCut;
use crate::controller_choice::ControllerChoice;
use crate::error::{ConfigError, RunError};
use crate::object_profile::surrogate_profile;
use crate::run_replica::RunReplica;
use crate::scenario::{Scenario, check_planner_keeps_the_clock};
use crate::surrogates::surrogate_for;

/// Margin on the arm's acceleration and jerk limits for the controllers'
/// plans (their finite-difference checks see rounding).
const ARM_MARGIN: f64 = 0.9;

fn invalid(scenario: &Scenario, setting: InvalidSetting) -> RunError {
    RunError::Config(ConfigError::Invalid {
        path: scenario.name.clone(),
        setting,
    })
}

/// The cut task of a scenario for its first z₀: target depth (motion.depth
/// or 0.8 × the object's height), the knife's edge against the object's
/// outline in the knife plane (the object's silhouette there, as vision
/// would give it on a real cell), servo period, blade budget and limits.
///
/// # Errors
/// The object does not cross the knife plane x = 0.
pub fn cut_task(
    s: &Scenario,
    knife: &Knife,
    mesh: &TriangleMesh,
) -> Result<CutTask, InvalidSetting> {
    let (lo, hi) = mesh.bounds();
    let z0 = s.motion.loop_z0();
    // The knife slides towards its tip, so the object moves towards the
    // heel: the room there, z0 past the heel, is the default.
    let (heel, _) = edge_ends(knife);
    let budget = s.controller.blade_budget.unwrap_or((z0 - heel).max(0.0));
    let outline = EdgeOutline::of_object(knife.edge(), mesh)?;
    let arm = &s.control_loop.arm_limits;
    Ok(CutTask {
        target_depth: s.motion.depth.unwrap_or(0.8 * (hi.y - lo.y)),
        outline: Arc::new(outline),
        overtravel: s.controller.overtravel,
        period: 1.0 / s.control_loop.rate_hz,
        blade_budget: budget,
        limits: MotionLimits::within_arm(
            s.controller.max_normal_speed.min(arm.velocity),
            s.controller.max_tangential_speed.min(arm.velocity),
            arm.acceleration,
            arm.jerk,
            ARM_MARGIN,
        ),
    })
}

/// The knife frame's z of the edge's heel and tip, m.
fn edge_ends(knife: &Knife) -> (f64, f64) {
    knife
        .edge()
        .vertices()
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.x), b.max(p.x))
        })
}

/// Checks that the object stays on the knife's edge over the cut: the
/// knife slides towards its tip ([`Plant::direction_at`]), so the object,
/// its near face at knife-frame z = `z0` ([`Plant::start_position`]) and L
/// long along the edge, moves towards the heel by up to the task's blade
/// budget B; z0 ∈ [heel + B, tip − L] keeps it between heel and tip
/// throughout (heel at z = 0 on every preset). A part beyond the tip would
/// go uncut, and the run would report the work of the rest as the cut's.
/// The error's key is `z0`, its value z0, m.
pub fn check_on_edge(
    knife: &Knife,
    mesh: &TriangleMesh,
    task: &CutTask,
    z0: f64,
) -> Result<(), InvalidSetting> {
    let (lo, hi) = mesh.bounds();
    let length = hi.z - lo.z;
    let (heel, tip) = edge_ends(knife);
    let budget = task.blade_budget;
    let (first, last) = (heel + budget, tip - length);
    if (first..=last).contains(&z0) {
        return Ok(());
    }
    let (length_mm, edge_mm, budget_mm) = (1e3 * length, 1e3 * (tip - heel), 1e3 * budget);
    let allowed = if first <= last {
        format!(
            "must be in [{first:.4}, {last:.4}] m: the object ({length_mm:.1} mm along the edge) stays on the {edge_mm:.0} mm edge over a {budget_mm:.1} mm stroke towards the heel"
        )
    } else {
        // No z0 fits this budget: both bounds, so that following the
        // message leads to a place.
        format!(
            "must be at most {last:.4} m, with a blade budget of at most {:.4} m: the object ({length_mm:.1} mm along the edge) and a {budget_mm:.1} mm stroke towards the heel need more than the {edge_mm:.0} mm edge",
            last - heel
        )
    };
    Err(InvalidSetting::new("z0", z0, allowed))
}

/// The ratio the MPC's first plan starts from: what spreads the blade
/// budget evenly over the depth, at most 1.
pub fn mpc_start(task: &CutTask) -> f64 {
    (task.blade_budget / task.target_depth).min(1.0)
}

/// The ratio the MPC is going to cut along: the mean ratio of its first
/// plan from the intact object ([`Mpc::planned_ratio_from_rest`]). The plant builds its first
/// sections for it before the loop starts, so that a real-time loop finds
/// them ready (its results do not depend on it: the sections are placed
/// where the edge arrives). `start_z` is the knife frame origin's world z
/// at the start, m ([`Plant::start_position`]).
pub fn mpc_cutting_ratio(
    s: &Scenario,
    task: &CutTask,
    profile: &DepthProfile,
    start_z: f64,
) -> Result<f64, RunError> {
    let surrogate = surrogate_for(s).map_err(|e| invalid(s, e))?;
    Mpc::planned_ratio_from_rest(
        task,
        &s.controller.mpc,
        SurrogateModel::new(surrogate),
        profile.clone(),
        mpc_start(task),
        start_z,
    )
    .map_err(|e| invalid(s, e.prefixed("controller")))
}

/// The scenario's MPC for `task`, seeing the object as `profile`, on the
/// scenario's surrogate.
fn make_mpc(
    s: &Scenario,
    task: &CutTask,
    profile: DepthProfile,
) -> Result<Mpc<SurrogateModel>, RunError> {
    let surrogate = surrogate_for(s).map_err(|e| invalid(s, e))?;
    Mpc::new(
        task,
        &s.controller.mpc,
        SurrogateModel::new(surrogate),
        profile,
        mpc_start(task),
    )
    .map_err(|e| invalid(s, e.prefixed("controller")))
}

/// The object as `s`'s MPC sees it ([`surrogate_profile`]; built once per
/// setup: finding the equivalent rectangle runs the section model), with
/// the contact under the knife's own edge at its start pose when
/// `[controller.mpc] edge_contact` is set ([`DepthProfile::under_edge`]). Logs a
/// warning when that section lies beyond the sizes the surrogate was fitted
/// on (`FitRange::covers_section`): the MPC's model then extrapolates.
pub fn mpc_profile(
    s: &Scenario,
    task: &CutTask,
    mesh: &TriangleMesh,
) -> Result<DepthProfile, RunError> {
    let surrogate = surrogate_for(s).map_err(|e| invalid(s, e))?;
    let mut profile =
        surrogate_profile(s, &surrogate, mesh, task.target_depth).map_err(|e| invalid(s, e))?;
    if s.controller.mpc.edge_contact {
        let knife = Knife::new(&s.knife).map_err(|e| invalid(s, e.prefixed("knife")))?;
        let z0 = s.motion.loop_z0();
        let start_z = Plant::start_position(&knife, mesh, z0, s.plant.start_gap).z;
        profile = profile
            .under_edge(&task.outline, start_z)
            .map_err(|e| invalid(s, e.prefixed("controller.mpc.edge_contact")))?;
    }
    let range = &surrogate.range;
    // Once per process (`compare` sets up every replica).
    static WARNED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    if !range.covers_section(profile.height(), profile.half_width())
        && !WARNED.swap(true, std::sync::atomic::Ordering::Relaxed)
    {
        let name = s
            .controller
            .surrogate
            .clone()
            .unwrap_or_else(|| format!("{}-{}", surrogate.material_name, surrogate.knife_name));
        tracing::warn!(
            "the MPC's section ({:.1} mm high, {:.1} mm half width) lies beyond the sizes its \
             surrogate {name} was fitted on ({:.0}-{:.0} mm high, {:.0}-{:.0} mm half width): \
             it extrapolates (`shearcut fit --extra-sizes` fits one over other sizes; \
             docs/surrogates.md)",
            1e3 * profile.height(),
            1e3 * profile.half_width(),
            1e3 * range.height[0],
            1e3 * range.height[1],
            1e3 * range.half_width[0],
            1e3 * range.half_width[1],
        );
    }
    Ok(profile)
}

/// The controller a choice names, for a scenario's task and object; the
/// MPC's from `profile` (the object as it sees it, [`mpc_profile`];
/// built here if `None`).
pub fn make_controller(
    s: &Scenario,
    choice: ControllerChoice,
    task: &CutTask,
    mesh: &TriangleMesh,
    profile: Option<&DepthProfile>,
) -> Result<Box<dyn Controller>, RunError> {
    let c = &s.controller;
    let made: Result<Box<dyn Controller>, InvalidSetting> = match choice {
        ControllerChoice::Press => {
            ConstantSlice::press(task, c.speed).map(|x| Box::new(x) as Box<dyn Controller>)
        }
        ControllerChoice::Slice(xi) => {
            ConstantSlice::new(task, xi, c.speed).map(|x| Box::new(x) as Box<dyn Controller>)
        }
        ControllerChoice::Force(n) => {
            let gains = c
                .force_gains
                .unwrap_or_else(|| ForceFeedbackGains::for_setpoint(n, c.speed));
            ForceFeedback::new(task, n, gains, 0.0, c.speed)
                .map(|x| Box::new(x) as Box<dyn Controller>)
        }
        ControllerChoice::Mpc => {
            let profile = match profile {
                Some(p) => p.clone(),
                None => mpc_profile(s, task, mesh)?,
            };
            return Ok(Box::new(make_mpc(s, task, profile)?));
        }
    };
    made.map_err(|e| invalid(s, e.prefixed("controller")))
}

/// Builds the plant for a cut planned at slice-push ratio `xi` (its first
/// sections are built for that direction; they are placed where the edge
/// really arrives, see [`Plant`]) and the scenario's first z₀, its edge
/// segmented within `reach` of the object along z (the controller's blade
/// budget; `[plant] reach` if larger), the knife starting `start_gap` above
/// the object (m; `[plant] start_gap` unless a replica raises it).
pub fn make_plant(
    s: &Scenario,
    knife: &Knife,
    mesh: &TriangleMesh,
    xi: f64,
    reach: f64,
    start_gap: f64,
) -> Result<Plant, RunError> {
    let settings = placed_settings(s, reach, start_gap);
    let spec = plant_spec(s, knife, mesh, xi, &settings);
    Plant::new(spec, s.seed).map_err(|e| plant_refused(s, xi, spec.z0, e))
}

/// Checks what [`make_plant`] checks before it builds a section
/// ([`Plant::check`]): cheap, for `shearcut check`.
pub fn check_plant(
    s: &Scenario,
    knife: &Knife,
    mesh: &TriangleMesh,
    xi: f64,
    reach: f64,
    start_gap: f64,
) -> Result<(), RunError> {
    let settings = placed_settings(s, reach, start_gap);
    let spec = plant_spec(s, knife, mesh, xi, &settings);
    Plant::check(spec).map_err(|e| plant_refused(s, xi, spec.z0, e))
}

/// The scenario's plant settings with `reach` (the larger of the two) and
/// `start_gap`.
fn placed_settings(s: &Scenario, reach: f64, start_gap: f64) -> PlantSettings {
    PlantSettings {
        reach: s.plant.reach.max(reach),
        start_gap,
        ..s.plant
    }
}

/// The loop's plant: the scenario's material, sections and arm limits, its
/// first z₀, the direction planned for the slice-push ratio `xi`, and
/// `settings`.
fn plant_spec<'a>(
    s: &'a Scenario,
    knife: &'a Knife,
    mesh: &'a TriangleMesh,
    xi: f64,
    settings: &'a PlantSettings,
) -> PlantSpec<'a> {
    PlantSpec {
        material: &s.material,
        knife,
        object: mesh,
        z0: s.motion.loop_z0(),
        direction: Plant::direction_at(xi),
        settings,
        section: &s.section,
        arm_limits: &s.control_loop.arm_limits,
    }
}

fn plant_refused(s: &Scenario, xi: f64, z0: f64, e: PlantError) -> RunError {
    invalid(
        s,
        InvalidSetting::new("motion", format!("xi = {xi}, z0 = {z0}"), e.to_string()),
    )
}

/// What every closed loop of a scenario is built from, in one place so that
/// the in-process loop and the two processes of the iceoryx2 loop build the
/// same plant, controller and labels (their runs must be bit-identical).
#[derive(Debug, Clone)]
pub struct LoopSetup {
    /// The knife.
    pub knife: Knife,
    /// The object.
    pub mesh: TriangleMesh,
    /// The cut the controller is given.
    pub task: CutTask,
    /// The controller's nominal slice-push ratio: the plant builds its first
    /// sections for it and the samples carry it as `xi`.
    pub xi: f64,
    /// The object as the MPC sees it ([`mpc_profile`]; the MPC only).
    pub profile: Option<DepthProfile>,
    /// Height of the edge's lowest point over the object above the
    /// object's top at the start, m (`[plant] start_gap`, raised by a
    /// replica; [`Plant::start_position`]).
    pub start_gap: f64,
}

impl LoopSetup {
    /// The setup of `s` under the controller `choice`.
    pub fn new(s: &Scenario, choice: ControllerChoice) -> Result<Self, RunError> {
        Self::on_replica(s, choice, RunReplica::NOMINAL)
    }

    /// The setup of `s` under the controller `choice` for one of its
    /// replicas (the knife starting a few µm higher: [`RunReplica`]).
    pub fn on_replica(
        s: &Scenario,
        choice: ControllerChoice,
        replica: RunReplica,
    ) -> Result<Self, RunError> {
        let knife = Knife::new(&s.knife).map_err(|e| invalid(s, e.prefixed("knife")))?;
        let mesh = s
            .object
            .mesh()
            .map_err(|e| invalid(s, InvalidSetting::new("object", "mesh", e.to_string())))?;
        let task = cut_task(s, &knife, &mesh).map_err(|e| invalid(s, e))?;
        let z0 = s.motion.loop_z0();
        check_on_edge(&knife, &mesh, &task, z0).map_err(|e| invalid(s, e.prefixed("motion")))?;
        if choice == ControllerChoice::Mpc {
            check_planner_keeps_the_clock(&s.control_loop, &s.controller)
                .map_err(|e| invalid(s, e))?;
        }
        let profile = match choice {
            ControllerChoice::Mpc => Some(mpc_profile(s, &task, &mesh)?),
            _ => None,
        };
        let start_gap = replica.start_gap(s.plant.start_gap);
        let xi = match &profile {
            Some(p) => {
                let start_z = Plant::start_position(&knife, &mesh, z0, start_gap).z;
                mpc_cutting_ratio(s, &task, p, start_z)?
            }
            None => choice.nominal_slice_push_ratio(mpc_start(&task)),
        };
        Ok(Self {
            knife,
            mesh,
            task,
            xi,
            profile,
            start_gap,
        })
    }

    /// A fresh plant.
    pub fn plant(&self, s: &Scenario) -> Result<Plant, RunError> {
        make_plant(
            s,
            &self.knife,
            &self.mesh,
            self.xi,
            self.task.blade_budget,
            self.start_gap,
        )
    }

    /// Checks what [`LoopSetup::plant`] checks before it builds a section
    /// ([`check_plant`]).
    pub fn check_plant(&self, s: &Scenario) -> Result<(), RunError> {
        check_plant(
            s,
            &self.knife,
            &self.mesh,
            self.xi,
            self.task.blade_budget,
            self.start_gap,
        )
    }

    /// A fresh controller.
    pub fn controller(
        &self,
        s: &Scenario,
        choice: ControllerChoice,
    ) -> Result<Box<dyn Controller>, RunError> {
        make_controller(s, choice, &self.task, &self.mesh, self.profile.as_ref())
    }

    /// The loop's labels and stop conditions, with the knife's start where
    /// the plant puts it ([`Plant::start_position`]: no plant is built, so
    /// a controller process does not build one of its own).
    pub fn cut(&self, s: &Scenario) -> LoopCut {
        let z0 = s.motion.loop_z0();
        LoopCut {
            xi_label: self.xi,
            z0,
            start: Plant::start_position(&self.knife, &self.mesh, z0, self.start_gap),
            gap: self.start_gap,
            target_depth: self.task.target_depth,
            max_duration: s.controller.max_duration,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The usable edge's ends are inclusive; past either, and with a budget
    /// that leaves no place, the message says what to change.
    #[test]
    fn the_object_must_stay_on_the_edge_over_the_stroke() {
        // A 30 mm cuboid on the straight 200 mm edge, 12 mm of blade.
        let s = Scenario::load("loop-potato-cuboid").unwrap();
        let knife = Knife::new(&s.knife).unwrap();
        let mesh = s.object.mesh().unwrap();
        let task = cut_task(&s, &knife, &mesh).unwrap();
        let on_edge = |task: &CutTask, z0: f64| check_on_edge(&knife, &mesh, task, z0);
        assert!(on_edge(&task, 0.012).is_ok() && on_edge(&task, 0.17).is_ok());
        for z0 in [0.0119, 0.1701] {
            let e = on_edge(&task, z0).unwrap_err().to_string();
            assert!(e.contains("must be in [0.0120, 0.1700] m"), "{e}");
        }
        let long = CutTask {
            blade_budget: 0.2,
            ..task.clone()
        };
        let e = on_edge(&long, 0.1).unwrap_err().to_string();
        assert!(
            e.contains("must be at most 0.1700 m, with a blade budget of at most 0.1700 m"),
            "{e}"
        );
        // Without a budget the room towards the heel, z0, is the budget.
        let mut free = s.clone();
        free.controller.blade_budget = None;
        free.motion.z0 = vec![0.05];
        assert_eq!(cut_task(&free, &knife, &mesh).unwrap().blade_budget, 0.05);
    }
}
