//! The wire slab's `simulate` (seed 001) streamed to disk as its angles
//! end: each finished angle's load steps to `series.csv` and its surface
//! σ₁ profile to `surface.csv`, in the order of the angles, each file
//! written in one write per angle. A sweep killed at any moment (SIGKILL
//! included) leaves every angle that ended before the angles still
//! running, in whole rows that parse.

use std::collections::BTreeMap;
use std::path::Path;

use shearcut_sim::finite_strain::IndentationRun;

use crate::csv_stream::CsvStream;
use crate::error::RunError;

/// One row of a finite-strain run's series (`series.csv`).
#[derive(Debug, Clone, Copy, serde::Serialize)]
struct SlabRow {
    angle_deg: f64,
    depth_m: f64,
    travel_m: f64,
    force_normal_n: f64,
    force_tangential_n: f64,
    surface_stress_pa: f64,
    surface_stress_position_m: f64,
    contact_extent_m: f64,
    newton_iterations: usize,
}

/// One angle's rows: its series, and its surface profile as (angle in
/// degrees, position m, σ₁ Pa).
type AngleRows = (Vec<SlabRow>, Vec<(f64, f64, f64)>);

/// `series.csv` and `surface.csv` of a wire-slab sweep, written angle by
/// angle in the angles' order as they end (an angle that ends before one
/// listed earlier waits for it). The files hold the same bytes as the same
/// runs written at the end would ([`crate::result_file::write_csv`]).
#[derive(Debug)]
pub struct AngleStream {
    series: CsvStream,
    surface: CsvStream,
    next: usize,
    waiting: BTreeMap<usize, AngleRows>,
    error: Option<RunError>,
}

impl AngleStream {
    /// Creates both files in `dir` (empty until the first angle ends).
    ///
    /// # Errors
    /// A file cannot be created.
    pub fn create(dir: &Path) -> Result<Self, RunError> {
        Ok(Self {
            series: CsvStream::create(dir.join("series.csv"))?,
            surface: CsvStream::create(dir.join("surface.csv"))?,
            next: 0,
            waiting: BTreeMap::new(),
            error: None,
        })
    }

    /// The run of the angle listed `index`-th has ended: it is written,
    /// with the angles after it that ended, once every angle before it has
    /// been. A failed write is kept for [`AngleStream::finish`].
    pub fn angle_ended(&mut self, index: usize, run: &IndentationRun) {
        let angle_deg = run.angle.to_degrees();
        let series = run
            .states
            .iter()
            .map(|st| SlabRow {
                angle_deg,
                depth_m: st.depth,
                travel_m: st.travel,
                force_normal_n: st.force_normal,
                force_tangential_n: st.force_tangential,
                surface_stress_pa: st.surface_stress,
                surface_stress_position_m: st.surface_stress_position,
                contact_extent_m: st.contact_extent,
                newton_iterations: st.newton_iterations,
            })
            .collect();
        let surface = run
            .surface_profile
            .iter()
            .map(|p| (angle_deg, p.position, p.stress))
            .collect();
        self.waiting.insert(index, (series, surface));
        while let Some(rows) = self.waiting.remove(&self.next) {
            self.write(&rows);
            self.next += 1;
        }
    }

    /// Writes the angles still waiting for one that never ran (a stopped
    /// sweep), in order.
    ///
    /// # Errors
    /// The first write that failed.
    pub fn finish(mut self) -> Result<(), RunError> {
        for rows in std::mem::take(&mut self.waiting).into_values() {
            self.write(&rows);
        }
        self.error.map_or(Ok(()), Err)
    }

    fn write(&mut self, (series, surface): &AngleRows) {
        let written = series
            .iter()
            .try_for_each(|r| self.series.push(r))
            .and_then(|()| self.series.flush())
            .and_then(|()| surface.iter().try_for_each(|r| self.surface.push(r)))
            .and_then(|()| self.surface.flush());
        if let Err(e) = written
            && self.error.is_none()
        {
            self.error = Some(e);
        }
    }
}
