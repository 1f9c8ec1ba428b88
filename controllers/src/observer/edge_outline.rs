//! The knife edge against the object's outline in the knife plane: how far
//! the edge is above the object, and how much of it lies inside.

use shearcut_sim::geometry::{Polygon, TriangleMesh};
use shearcut_sim::knife_plane::knife_plane_silhouette;
use shearcut_sim::{InvalidSetting, KnifeEdge};

/// Points the edge is sampled at, heel to tip (the edge's own vertices are
/// not needed: between samples the gap to the outline is interpolated
/// linearly, and a chef's edge 0.2 m long sampled every 0.5 mm deviates from
/// its chords by under 0.1 µm).
const EDGE_SAMPLES: usize = 401;

/// Columns the outline's top and bottom are tabulated at over its extent
/// along z (every 0.1 mm over a 0.2 m object). A corner of the outline
/// (a cuboid's top edge) is rounded over one column.
const OUTLINE_COLUMNS: usize = 2001;

/// Equal shares of the contact length [`EdgeOutline::contact_inclination`]
/// reports a mean slope for.
pub const INCLINATION_BINS: usize = 4;

/// How the edge in contact is inclined ([`EdgeOutline::contact_inclination`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactInclination {
    /// The edge's slope dy/dz at its deepest point in the object (knife
    /// frame; positive rising towards the tip): the rate at which the edge's
    /// depth grows per unit of the knife's travel towards its tip.
    pub deepest: f64,
    /// Mean slope over each equal share of the contact length, heel to tip.
    pub bins: [f64; INCLINATION_BINS],
}

/// The knife edge against the object's outline in the knife plane (world z,
/// y; what a vision system reports as `knife_plane_silhouette` of the
/// object): for a knife frame origin at (z, y) (world, m), the edge's
/// clearance above the outline and the length of edge inside it.
///
/// The outline is reduced to its top and bottom over each z (a vertical line
/// through it is taken to cross it once: true of the cuboid, the half potato
/// and the eggplant lying across the knife). An edge point is inside when
/// it lies between them.
///
/// The edge's depth in the object ([`depth`](Self::depth)) is its deepest
/// penetration below the outline's top: the largest `top(z) − y` over the
/// edge's points. Pressing straight down, it is the knife's travel since the
/// edge touched, whatever the edge's shape; when the knife slides along a
/// curved edge, a higher or lower part of the edge comes over the object and
/// the depth follows it. Under a straight horizontal edge it is the edge's
/// depth below the outline's highest point, the depth
/// [`DepthProfile`](crate::mpc::DepthProfile) is indexed by.
///
/// # Cost
/// Construction tabulates the edge at 401 points and the outline at 2001
/// columns (allocates). Each query walks the
/// edge samples once with a table look-up per sample: a fixed cost per tick,
/// no allocation.
#[derive(Clone, PartialEq)]
pub struct EdgeOutline {
    /// Edge samples (z, y) in the knife frame, heel to tip, m.
    edge: Vec<[f64; 2]>,
    /// z of the outline's first column, m.
    z_start: f64,
    /// Column spacing along z, m.
    z_step: f64,
    /// Top of the outline at each column, m.
    top: Vec<f64>,
    /// Bottom of the outline at each column, m.
    bottom: Vec<f64>,
}

impl std::fmt::Debug for EdgeOutline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let end = self.z_start + self.z_step * (self.top.len() - 1) as f64;
        f.debug_struct("EdgeOutline")
            .field("edge_samples", &self.edge.len())
            .field("z", &[self.z_start, end])
            .field("top", &self.top())
            .finish_non_exhaustive()
    }
}

impl EdgeOutline {
    /// The edge `edge` against `outline` (knife plane: x = world z, y = world
    /// y, as `shearcut_sim::knife_plane::knife_plane_silhouette` gives it).
    pub fn new(edge: &KnifeEdge, outline: &Polygon) -> Self {
        let len = edge.length();
        let samples = (0..EDGE_SAMPLES)
            .map(|i| {
                let p = edge.point_at(len * i as f64 / (EDGE_SAMPLES - 1) as f64);
                [p.x, p.y]
            })
            .collect();
        let (lo, hi) = outline.bounds();
        let z_step = (hi.x - lo.x) / (OUTLINE_COLUMNS - 1) as f64;
        let (mut top, mut bottom) = (
            Vec::with_capacity(OUTLINE_COLUMNS),
            Vec::with_capacity(OUTLINE_COLUMNS),
        );
        for i in 0..OUTLINE_COLUMNS {
            // The end columns sit on the outline's extremes; nudge them in
            // so that a vertical side counts with its full height.
            let z = (lo.x + z_step * i as f64).clamp(lo.x + 1e-9 * z_step, hi.x - 1e-9 * z_step);
            let (b, t) = vertical_extent(outline, z).unwrap_or((0.0, 0.0));
            top.push(t);
            bottom.push(b);
        }
        Self {
            edge: samples,
            z_start: lo.x,
            z_step,
            top,
            bottom,
        }
    }

    /// The edge `edge` against the outline of `mesh` (world frame) in the
    /// knife plane x = 0, its exact silhouette there (what a vision system
    /// measures on a real cell).
    ///
    /// # Errors
    /// The mesh does not cross the knife plane.
    pub fn of_object(edge: &KnifeEdge, mesh: &TriangleMesh) -> Result<Self, InvalidSetting> {
        let silhouette = knife_plane_silhouette(mesh).ok_or_else(|| {
            InvalidSetting::new("object", "mesh", "does not cross the knife plane x = 0")
        })?;
        Ok(Self::new(edge, &silhouette))
    }

    /// Height of the outline's top over world z = `z`, m, or None beside it.
    pub fn top_at(&self, z: f64) -> Option<f64> {
        self.column(z)
            .map(|(i, t)| lerp(self.top[i], self.top[i + 1], t))
    }

    /// Height of the outline's highest point, m.
    pub fn top(&self) -> f64 {
        self.top.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    /// The edge's clearance above the outline with the knife frame origin at
    /// world (`z`, `y`), m: the least height of an edge point above the
    /// outline's top over its z, among the edge points over the outline
    /// (negative once the edge is inside). +∞ when no edge point is over the
    /// outline.
    pub fn clearance(&self, z: f64, y: f64) -> f64 {
        let mut least = f64::INFINITY;
        for p in &self.edge {
            if let Some(top) = self.top_at(z + p[0]) {
                least = least.min(y + p[1] - top);
            }
        }
        least
    }

    /// The edge's depth in the object with the knife frame origin at world
    /// (`z`, `y`), m: its deepest penetration below the outline's top, the
    /// largest `top(z_i) − y_i` over the edge points over the outline
    /// ([`penetration`](Self::penetration) of the
    /// [`clearance`](Self::clearance)); 0 while the edge is above the
    /// outline or beside it.
    pub fn depth(&self, z: f64, y: f64) -> f64 {
        Self::penetration(self.clearance(z, y))
    }

    /// The sections' mean depth with the knife frame origin at world (`z`,
    /// `y`) and each section cut to the edge, m: below the outline's
    /// highest point, the mean over the edge's length along z over the
    /// outline of the lower of the edge and the outline's top (a section the
    /// edge has not reached stands at its top). What a plant reports as its
    /// crack front's depth when the crack is at the edge; under a straight
    /// horizontal edge below the whole top it is the edge's
    /// [`depth`](Self::depth). None when no edge is over the outline.
    pub fn mean_cut_depth(&self, z: f64, y: f64) -> Option<f64> {
        let summit = self.top();
        let height = |p: &[f64; 2]| self.top_at(z + p[0]).map(|t| t.min(y + p[1]));
        let (mut area, mut span) = (0.0, 0.0);
        for pair in self.edge.windows(2) {
            let dz = (pair[1][0] - pair[0][0]).abs();
            let (over, mean) = match (height(&pair[0]), height(&pair[1])) {
                (Some(a), Some(b)) => (dz, 0.5 * (a + b)),
                // The chord leaves the outline's extent: the part over it,
                // at the height of its end over it.
                (Some(a), None) | (None, Some(a)) => {
                    (dz * self.fraction_over(z + pair[0][0], z + pair[1][0]), a)
                }
                (None, None) => continue,
            };
            area += over * (summit - mean);
            span += over;
        }
        (span > 0.0).then(|| area / span)
    }

    /// The depth of an edge whose [`clearance`](Self::clearance) is
    /// `clearance` (m): `−clearance`, 0 above the outline or beside it.
    pub fn penetration(clearance: f64) -> f64 {
        (-clearance).max(0.0)
    }

    /// The knife frame origin's height at which the edge, with the origin at
    /// world z = `z`, just meets the outline (its clearance is 0), m; None
    /// when no edge point is over the outline. A touch-off at that z finds
    /// it.
    pub fn touch_height(&self, z: f64) -> Option<f64> {
        // The clearance is y plus a function of z alone.
        let c = self.clearance(z, 0.0);
        c.is_finite().then_some(-c)
    }

    /// Length of edge inside the outline with the knife frame origin at
    /// world (`z`, `y`), m. Between two samples the edge is a chord; where
    /// one end is inside and the other not, the inside part is found by
    /// linear interpolation of the signed distance to the outline.
    pub fn contact_length(&self, z: f64, y: f64) -> f64 {
        let mut length = 0.0;
        self.for_each_chord_inside(z, y, |inside, _| length += inside);
        length
    }

    /// How the edge in contact with the knife frame origin at world (`z`,
    /// `y`) is inclined: the edge's slope dy/dz (knife frame, rising towards
    /// the tip when positive) at its deepest point, and the mean slope over
    /// each of [`INCLINATION_BINS`] equal shares of the contact length, heel
    /// to tip. Zero slopes where nothing is in contact. A knife moving
    /// towards its tip (world +z) at tangential speed v_t and down at v_n
    /// moves an edge point of slope κ into the material at v_n + κ·v_t and
    /// along itself at v_t − κ·v_n (per √(1 + κ²)): the local slice-push
    /// ratio (seed 000 §IV, Fig. 4(a)) is (ξ − κ)/(1 + κξ) for ξ = v_t/v_n.
    pub fn contact_inclination(&self, z: f64, y: f64) -> ContactInclination {
        let total = self.contact_length(z, y);
        let mut bins = [0.0; INCLINATION_BINS];
        if total > 0.0 {
            let share = total / INCLINATION_BINS as f64;
            let (mut bin, mut along) = (0, 0.0);
            self.for_each_chord_inside(z, y, |inside, slope| {
                // Split the chord's inside length over the bins it spans.
                let mut left = inside;
                loop {
                    let last = bin + 1 == INCLINATION_BINS;
                    let part = if last {
                        left
                    } else {
                        left.min((bin + 1) as f64 * share - along).max(0.0)
                    };
                    bins[bin] += part * slope;
                    along += part;
                    left -= part;
                    if left <= 0.0 || last {
                        break;
                    }
                    bin += 1;
                }
            });
            for b in &mut bins {
                *b /= share;
            }
        }
        let mut deepest = (f64::NEG_INFINITY, 0.0);
        for (i, p) in self.edge.iter().enumerate() {
            if let Some(top) = self.top_at(z + p[0]) {
                let depth = top - (y + p[1]);
                if depth > deepest.0 {
                    let (a, b) = (
                        self.edge[i.saturating_sub(1)],
                        self.edge[(i + 1).min(self.edge.len() - 1)],
                    );
                    deepest = (depth, chord_slope(a, b));
                }
            }
        }
        ContactInclination {
            deepest: if deepest.0 > 0.0 { deepest.1 } else { 0.0 },
            bins,
        }
    }

    /// Calls `f(length inside, slope)` for each chord between edge samples
    /// with a part inside the outline, heel to tip (see
    /// [`contact_length`](Self::contact_length)).
    fn for_each_chord_inside<F: FnMut(f64, f64)>(&self, z: f64, y: f64, mut f: F) {
        let mut previous: Option<([f64; 2], f64)> = None;
        for p in &self.edge {
            let depth = self.depth_inside(z + p[0], y + p[1]);
            if let Some((q, d)) = previous {
                let chord = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
                let fraction = if d.is_finite() == depth.is_finite() {
                    inside_fraction(d, depth)
                } else if d.max(depth) > 0.0 {
                    // One end inside, the other beside the outline: the
                    // chord leaves it through a side, at the end of the
                    // outline's extent along z.
                    self.fraction_over(z + q[0], z + p[0])
                } else {
                    0.0
                };
                if fraction > 0.0 {
                    f(chord * fraction, chord_slope(q, *p));
                }
            }
            previous = Some((*p, depth));
        }
    }

    /// The fraction of the span [`a`, `b`] of z (either order) over the
    /// outline's extent.
    fn fraction_over(&self, a: f64, b: f64) -> f64 {
        let (low, high) = (a.min(b), a.max(b));
        let end = self.z_start + self.z_step * (self.top.len() - 1) as f64;
        let over = high.min(end) - low.max(self.z_start);
        if high > low {
            (over / (high - low)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// How far inside the outline the point (`z`, `y`) lies (world, m): the
    /// smaller of its depth below the top and its height above the bottom;
    /// negative outside, −∞ beside the outline.
    fn depth_inside(&self, z: f64, y: f64) -> f64 {
        match self.column(z) {
            Some((i, t)) => {
                let top = lerp(self.top[i], self.top[i + 1], t);
                let bottom = lerp(self.bottom[i], self.bottom[i + 1], t);
                (top - y).min(y - bottom)
            }
            None => f64::NEG_INFINITY,
        }
    }

    /// The column left of `z` and the fraction towards the next, or None
    /// beside the outline.
    fn column(&self, z: f64) -> Option<(usize, f64)> {
        let x = (z - self.z_start) / self.z_step;
        let last = (self.top.len() - 1) as f64;
        if !(x >= 0.0 && x <= last) {
            return None;
        }
        let i = (x.floor() as usize).min(self.top.len() - 2);
        Some((i, x - i as f64))
    }
}

/// Slope dy/dz of the chord from `a` to `b` ((z, y) points), 0 for a
/// vertical or empty one.
fn chord_slope(a: [f64; 2], b: [f64; 2]) -> f64 {
    let dz = b[0] - a[0];
    if dz.abs() > 0.0 {
        (b[1] - a[1]) / dz
    } else {
        0.0
    }
}

/// Linear interpolation between `a` and `b` at fraction `t`.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// The fraction of a chord inside the outline whose ends lie `a` and `b`
/// inside it (negative: outside), the signed distance taken linear along the
/// chord.
fn inside_fraction(a: f64, b: f64) -> f64 {
    match (a > 0.0, b > 0.0) {
        (true, true) => 1.0,
        (false, false) => 0.0,
        (true, false) => a / (a - b),
        (false, true) => b / (b - a),
    }
}

/// The lowest and highest points where the vertical line z = `z` crosses the
/// outline's boundary, or None if it misses.
fn vertical_extent(outline: &Polygon, z: f64) -> Option<(f64, f64)> {
    let n = outline.points.len();
    let mut extent: Option<(f64, f64)> = None;
    for i in 0..n {
        let (a, b) = (outline.points[i], outline.points[(i + 1) % n]);
        let (lo, hi) = if a.x <= b.x { (a, b) } else { (b, a) };
        if z < lo.x || z > hi.x {
            continue;
        }
        let (y_low, y_high) = if hi.x - lo.x > 0.0 {
            let y = lo.y + (z - lo.x) / (hi.x - lo.x) * (hi.y - lo.y);
            (y, y)
        } else {
            (lo.y.min(hi.y), lo.y.max(hi.y))
        };
        extent = Some(extent.map_or((y_low, y_high), |(b, t)| (b.min(y_low), t.max(y_high))));
    }
    extent
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;
    use shearcut_sim::{Knife, KnifePreset};

    fn straight() -> Knife {
        Knife::new(&KnifePreset::Straight.settings()).unwrap()
    }

    /// A 30 mm long (z from 0.02), 25 mm high block in the knife plane.
    fn block() -> Polygon {
        Polygon::new(vec![
            Vector2::new(0.02, 0.0),
            Vector2::new(0.05, 0.0),
            Vector2::new(0.05, 0.025),
            Vector2::new(0.02, 0.025),
        ])
    }

    #[test]
    fn a_straight_edge_over_a_block() {
        let knife = straight();
        let o = EdgeOutline::new(knife.edge(), &block());
        // Knife origin at z = 0: the edge (along +z from the origin, at the
        // origin's height) spans the block's 30 mm.
        assert!((o.clearance(0.0, 0.026) - 0.001).abs() < 1e-12);
        assert_eq!(o.contact_length(0.0, 0.026), 0.0);
        // Inside: the whole 30 mm along the block, to the column table's
        // resolution (one column of 15 µm at each side).
        let l = o.contact_length(0.0, 0.02);
        assert!((l - 0.03).abs() < 2.0 * 15e-6, "{l}");
        assert!((o.clearance(0.0, 0.02) + 0.005).abs() < 1e-12);
        // Beside the block: no clearance to speak of.
        assert_eq!(o.clearance(0.5, 0.02), f64::INFINITY);
        assert_eq!(o.top(), 0.025);
    }

    #[test]
    fn the_inclination_of_a_chefs_edge_over_a_block() {
        // The chef's edge: flat to 60 mm from the heel, then the parabola
        // y = 0.035·((z − 0.06)/0.14)², slope 0.5·(z − 0.06)/0.14.
        let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        let o = EdgeOutline::new(knife.edge(), &block());
        let slope = |z: f64| 0.5 * ((z - 0.06) / 0.14).max(0.0);
        // The block (z 0.02–0.05) under the flat part: no inclination.
        let flat = o.contact_inclination(0.0, 0.02);
        assert_eq!(flat.deepest, 0.0);
        assert!(flat.bins.iter().all(|b| b.abs() < 1e-12), "{flat:?}");
        // The block under 100–130 mm of the edge (origin at z = −0.08), the
        // edge's lowest point over it 4 mm below its top: the contact runs
        // from the heel side of the block to where the parabola leaves the
        // top, and each quarter's mean slope is the parabola's over it; the
        // deepest point is at the block's heel-side end.
        let y = 0.025 - 0.004 - 0.035 * (0.04f64 / 0.14).powi(2);
        let i = o.contact_inclination(-0.08, y);
        let l = o.contact_length(-0.08, y);
        assert!((i.deepest - slope(0.1)).abs() < 3e-3, "{i:?}");
        let z_end = 0.06 + 0.14 * ((0.035f64 * (0.04f64 / 0.14).powi(2) + 0.004) / 0.035).sqrt();
        assert!(
            (l - (z_end - 0.1)).abs() < 5e-4,
            "{l} against {}",
            z_end - 0.1
        );
        for (k, b) in i.bins.iter().enumerate() {
            let mid = 0.1 + (k as f64 + 0.5) * (z_end - 0.1) / 4.0;
            assert!(
                (b - slope(mid)).abs() < 5e-3,
                "bin {k}: {b} against {}",
                slope(mid)
            );
        }
        assert!(i.bins.windows(2).all(|w| w[1] > w[0]), "{i:?}");
    }

    #[test]
    fn a_straight_edge_half_over_a_block_counts_half() {
        let knife = straight();
        let len = knife.edge().length();
        let o = EdgeOutline::new(knife.edge(), &block());
        // The edge's tip 15 mm into the block.
        let l = o.contact_length(0.035 - len, 0.01);
        assert!((l - 0.015).abs() < 2.0 * 15e-6, "{l}");
    }

    #[test]
    fn a_tilted_chord_is_cut_where_it_leaves_the_outline() {
        // A triangle outline, apex up at (0.1, 0.02), base 0.08..0.12:
        // a horizontal edge at height h has the chord 0.04·(1 − h/0.02)
        // inside it.
        let tri = Polygon::new(vec![
            Vector2::new(0.08, 0.0),
            Vector2::new(0.12, 0.0),
            Vector2::new(0.1, 0.02),
        ]);
        let knife = straight();
        let o = EdgeOutline::new(knife.edge(), &tri);
        for h in [0.001, 0.01, 0.019] {
            let l = o.contact_length(0.0, h);
            let expect = 0.04 * (1.0 - h / 0.02);
            // Column table: 20 µm columns, the sides' slope 1: ±2 columns.
            assert!((l - expect).abs() < 4e-5, "h {h}: {l} vs {expect}");
        }
        assert!((o.clearance(0.0, 0.021) - 0.001).abs() < 2e-5);
    }

    /// A parabolic dome y = H − a(w − c)² (world z = w) standing on the
    /// board, sampled every 0.1 mm.
    fn dome(height: f64, half_length: f64, centre: f64) -> Polygon {
        let a = height / (half_length * half_length);
        let n = 900;
        let mut points: Vec<Vector2<f64>> = (0..=n)
            .map(|i| {
                let w = centre - half_length + 2.0 * half_length * i as f64 / n as f64;
                Vector2::new(w, (height - a * (w - centre).powi(2)).max(0.0))
            })
            .collect();
        points.reverse();
        Polygon::new(points)
    }

    /// The chef's curved edge, e(s) = k·(s − s_f)² past its flat s_f,
    /// sliding over the dome H − a(w − c)²: with the knife origin at
    /// (Z, y), the penetration at w is H − a(w − c)² − y − k(w − Z − s_f)²,
    /// largest at w* = (a·c + k·(Z + s_f))/(a + k), where it is
    /// H − y − a·k/(a + k)·(c − Z − s_f)² (when c − Z > s_f, so that w*
    /// lies over the curve and the flat's deepest point, at its end, is
    /// shallower). Sliding 20 mm at a constant height changes it by
    /// millimetres; the geometric depth follows.
    #[test]
    fn a_curved_edge_sliding_over_a_dome_has_the_analytic_depth() {
        let chef = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        let (h, half, c) = (0.035, 0.045, 0.15);
        let o = EdgeOutline::new(chef.edge(), &dome(h, half, c));
        let (k, s_f) = (0.035 / 0.14f64.powi(2), 0.06);
        let a = h / (half * half);
        let touch = |z: f64| h - a * k / (a + k) * (c - z - s_f).powi(2);
        // Tolerance: the edge is sampled every 0.5 mm, so the deepest
        // sample is within (a + k)·(0.25 mm)² = 1.2 µm of the deepest point;
        // the edge's chords (0.7 mm) and the dome's (0.1 mm) and columns
        // (0.045 mm) each sag under 0.1 µm.
        let tol = 1.5e-6;
        let y = 0.02;
        let mut last = f64::NEG_INFINITY;
        for z in [0.03, 0.04, 0.05, 0.06, 0.07, 0.08] {
            let expect = touch(z) - y;
            let d = o.depth(z, y);
            assert!((d - expect).abs() < tol, "z {z}: {d} vs {expect}");
            let t = o.touch_height(z).unwrap();
            assert!((t - touch(z)).abs() < tol, "z {z}: touch {t}");
            // The knife moving along +z brings the lower edge, nearer the
            // heel, over the dome: deeper at the same height.
            assert!(d > last, "z {z}: {d} after {last}");
            last = d;
        }
        // 50 mm of slide moves the depth by 5.7 mm at a constant height.
        let slid = o.depth(0.08, y) - o.depth(0.03, y);
        assert!((slid - (touch(0.08) - touch(0.03))).abs() < 2.0 * tol);
        assert!(slid > 5.5e-3, "{slid}");
        // Pressing straight down, the depth is the travel since the touch.
        for travel in [0.0, 1e-3, 0.01, 0.03] {
            let d = o.depth(0.05, touch(0.05) - travel);
            assert!((d - travel).abs() < tol, "travel {travel}: {d}");
        }
        // Above the dome and beside it: no depth.
        assert_eq!(o.depth(0.05, touch(0.05) + 1e-4), 0.0);
        assert_eq!(o.depth(1.0, 0.0), 0.0);
        assert_eq!(o.touch_height(1.0), None);
    }

    #[test]
    fn the_sections_mean_depth_under_a_straight_and_a_rising_edge() {
        // A straight edge below the whole block: every section at the edge.
        let o = EdgeOutline::new(straight().edge(), &block());
        let d = o.mean_cut_depth(0.0, 0.01).unwrap();
        assert!((d - 0.015).abs() < 1e-12, "{d}");
        // Above part of a triangle's slopes, the untouched sections stand at
        // their tops: apex 20 mm at z = 0.1, base 0.08–0.12, the edge 10 mm
        // down covers the middle half at the edge's height (mean depth 10
        // mm) and the outer halves at the slopes' (mean 15 mm): 12.5 mm.
        let tri = Polygon::new(vec![
            Vector2::new(0.08, 0.0),
            Vector2::new(0.12, 0.0),
            Vector2::new(0.1, 0.02),
        ]);
        let o = EdgeOutline::new(straight().edge(), &tri);
        let d = o.mean_cut_depth(0.0, 0.01).unwrap();
        assert!((d - 0.0125).abs() < 2e-5, "{d}");
        assert_eq!(o.mean_cut_depth(1.0, 0.0), None);
        // The chef's rise over the block (100–130 mm of the edge, origin at
        // z = −0.08), the edge 2 mm below the top at the heel-side end: the
        // mean depth is 2 mm less the parabola's mean rise over the block,
        // so sliding the block towards the flat heel deepens the mean.
        let chef = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        let o = EdgeOutline::new(chef.edge(), &block());
        let rise = |s: f64| 0.035 * ((s - 0.06) / 0.14).max(0.0).powi(2);
        let y = 0.025 - 0.002 - rise(0.1);
        // Mean of max(0, 2 mm − (rise(s) − rise(0.1))) over s in 0.1–0.13.
        let n = 3000;
        let expect = (0..n)
            .map(|i| {
                let s = 0.1 + 0.03 * (i as f64 + 0.5) / n as f64;
                (0.002 - (rise(s) - rise(0.1))).max(0.0)
            })
            .sum::<f64>()
            / n as f64;
        // Tolerance: the part of a 0.5 mm chord over the block's heel-side
        // face is taken at its inside end's height, off by up to its slope
        // (0.14) times its length over the 30 mm (0.6 µm on the mean at the
        // worst alignment of the samples); trapezoids over the samples of a
        // parabola (curvature 3.6/m), the kink where the edge leaves the top
        // and the corners rounded over one 15 µm column add under 0.1 µm.
        let d = o.mean_cut_depth(-0.08, y).unwrap();
        assert!((d - expect).abs() < 1e-6, "{d} against {expect}");
        assert!(d < 0.002 - 1e-4, "{d}");
        assert!(o.mean_cut_depth(-0.07, y).unwrap() > d + 1e-4);
    }
}
