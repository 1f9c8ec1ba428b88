//! Every observer of a cut, fed one arm reading per tick.

use serde::{Deserialize, Serialize};
use shearcut_sim::arm::ArmReading;
use shearcut_sim::geometry::Polygon;
use shearcut_sim::{InvalidSetting, Knife};

use super::contact_length::ContactLength;
use super::cut_done::{CutDone, CutTarget};
use super::edge_depth::EdgeDepth;
use super::edge_outline::EdgeOutline;
use super::first_fracture::{FirstFracture, FractureDetector, FractureSettings};
use super::touch::{Touch, TouchDetector, TouchSettings};
use super::wrench_tare::{WrenchTare, WrenchTareSettings};

/// Settings of [`CutObserver`]: one table per observer.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CutObserverSettings {
    /// The sensor's tare in free air.
    pub tare: WrenchTareSettings,
    /// The touch.
    pub touch: TouchSettings,
    /// The first fracture.
    pub fracture: FractureSettings,
}

impl CutObserverSettings {
    /// Checks every table, naming the key (e.g. `touch.sigmas`).
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        self.tare.validate().map_err(|e| e.prefixed("tare"))?;
        self.touch.validate().map_err(|e| e.prefixed("touch"))?;
        self.fracture.validate().map_err(|e| e.prefixed("fracture"))
    }
}

/// What the observers make of the readings so far.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CutEstimate {
    /// The normal force fy less the sensor's bias, N (the object's
    /// resistance to the knife pressing down).
    pub normal_force: f64,
    /// The sensor's noise level on fy, N ([`WrenchTare::sigma`]).
    pub force_noise: f64,
    /// The edge's clearance above the object's outline as given, m (+∞ with
    /// no edge over it; negative inside).
    pub clearance: f64,
    /// The touch, once detected.
    pub touch: Option<Touch>,
    /// The first fracture, once detected.
    pub fracture: Option<FirstFracture>,
    /// The edge's depth below the touch point, m.
    pub edge_depth: f64,
    /// Length of edge in contact, m.
    pub contact_length: f64,
    /// Whether the cut has reached its target.
    pub done: bool,
}

/// Every observer of a cut from what an arm reports ([`ArmReading`]) and
/// what the lab knows before the cut (the knife, the object's outline in
/// the knife plane, the target), in the order each needs the others:
/// [`WrenchTare`] in free air (the edge's clearance from [`EdgeOutline`]),
/// then [`TouchDetector`] on the tared force once the edge is within the
/// tare's clearance, [`FractureDetector`] after the touch, [`EdgeDepth`]
/// and [`ContactLength`] from the touch, and [`CutDone`].
///
/// Deterministic (the same readings give bit-identical estimates), no
/// clock of its own (time is the readings'). [`CutObserver::new`]
/// allocates the outline's tables; [`CutObserver::observe`] allocates
/// nothing, at a fixed cost per reading.
#[derive(Debug, Clone, PartialEq)]
pub struct CutObserver {
    contact: ContactLength,
    tare: WrenchTare,
    touch: TouchDetector,
    fracture: FractureDetector,
    depth: EdgeDepth,
    done: CutDone,
    estimate: CutEstimate,
}

impl CutObserver {
    /// Observers for `knife` cutting the object whose outline in the knife
    /// plane is `outline` (world z, y, as
    /// `shearcut_sim::knife_plane::knife_plane_silhouette` gives it), to `target`.
    ///
    /// # Errors
    /// A setting or the target is out of range.
    pub fn new(
        knife: &Knife,
        outline: &Polygon,
        target: CutTarget,
        settings: &CutObserverSettings,
    ) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        Ok(Self {
            contact: ContactLength::new(EdgeOutline::new(knife.edge(), outline)),
            tare: WrenchTare::new(settings.tare)?,
            touch: TouchDetector::new(settings.touch)?,
            fracture: FractureDetector::new(settings.fracture)?,
            depth: EdgeDepth::default(),
            done: CutDone::new(target, knife.edge())?,
            estimate: CutEstimate::default(),
        })
    }

    /// Takes one tick's reading and returns the estimate after it.
    pub fn observe(&mut self, reading: &ArmReading) -> CutEstimate {
        let p = &reading.position;
        let clearance = self.contact.outline().clearance(p.z, p.y);
        self.tare.observe(&reading.wrench, clearance);
        let force = self.tare.tared(&reading.wrench)[1];
        let sigma = self.tare.sigma()[1];
        let was_touched = self.estimate.touch.is_some();
        let touch = if self.tare.frozen() {
            self.touch.observe(reading.time, p, force, sigma)
        } else {
            None
        };
        // The fracture detector starts on the reading after the touch's
        // detection, from the force then.
        let fracture = if was_touched {
            self.fracture.observe(reading.time, p, force, sigma)
        } else {
            None
        };
        let edge_depth = self.depth.observe(p.y, touch.as_ref());
        self.estimate = CutEstimate {
            normal_force: force,
            force_noise: sigma,
            clearance,
            touch,
            fracture,
            edge_depth,
            contact_length: self.contact.observe(p, touch.as_ref()),
            done: self.done.observe(reading.time, p.y, edge_depth),
        };
        self.estimate
    }

    /// The estimate after the last reading.
    pub fn estimate(&self) -> CutEstimate {
        self.estimate
    }

    /// The sensor's tare.
    pub fn tare(&self) -> &WrenchTare {
        &self.tare
    }

    /// The contact-length observer (with the outline's offset found at the
    /// touch).
    pub fn contact(&self) -> &ContactLength {
        &self.contact
    }

    /// The cut-done test.
    pub fn cut_done(&self) -> &CutDone {
        &self.done
    }
}
