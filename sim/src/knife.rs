//! Knives: the edge's shape in the knife frame, the blade's section, the F/T sensor mount.
//!
//! Knife frame (DESIGN §2): origin at the heel end of the edge, z along the
//! edge towards the tip, y up, x normal to the blade. The edge lies in the
//! knife's yz-plane and is stored as a polyline of (z, y) points ordered from
//! heel to tip; every query is by arc length s ∈ [0, length].

use nalgebra::{Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::blade::BladeSection;
use crate::invalid_setting::InvalidSetting;
use crate::physical_range::{
    EDGE_LENGTH, KNIFE_COORDINATE, MAX_EDGE_POINTS, MIN_EDGE_CHORD, WIRE_RADIUS, check_count,
};

/// Shape of the edge, as written in a knife config (`edge = { kind = … }`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(
    tag = "kind",
    rename_all = "kebab-case",
    deny_unknown_fields,
    expecting = "a table with kind = \"straight\", \"chef\", \"polyline\" or \"wire\""
)]
pub enum EdgeShape {
    /// A straight horizontal edge.
    Straight {
        /// Edge length, m.
        length: f64,
    },
    /// A chef's-knife edge: flat from the heel for `flat_length`, then rising
    /// as a parabola y = tip_rise·((z − flat_length)/(length − flat_length))²
    /// to the tip at z = `length`.
    Chef {
        /// Extent of the edge along the knife's z axis, m (default knife 0.2).
        length: f64,
        /// Length of the flat part next to the heel, m (default knife 0.06).
        flat_length: f64,
        /// Height of the tip above the flat part, m (default knife 0.035).
        tip_rise: f64,
    },
    /// Any edge given as a polyline of [z, y] points in the knife frame, m,
    /// heel first; z must increase strictly.
    Polyline {
        /// The points, heel to tip, m.
        points: Vec<[f64; 2]>,
    },
    /// A taut wire of radius `radius` (seed 001), straight along z.
    Wire {
        /// Wire length between the clamps, m.
        length: f64,
        /// Wire radius R, m (seed 001: about 150 µm).
        radius: f64,
    },
}

/// Number of chords a [`EdgeShape::Chef`] profile is sampled with.
pub const CHEF_CHORDS: usize = 200;

/// Position of the F/T sensor in the knife frame (the handle mount). Its axes
/// are parallel to the knife frame's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SensorMount {
    /// Sensor origin [x, y, z] in the knife frame, m (default [0, 0.03, −0.03]:
    /// 3 cm above the edge and 3 cm behind the heel, inside the handle);
    /// exactly three numbers, each in [−1, 1] m.
    pub position: [f64; 3],
}

impl Default for SensorMount {
    fn default() -> Self {
        Self {
            position: [0.0, 0.03, -0.03],
        }
    }
}

/// A knife as written in config: edge shape, blade section and sensor mount.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnifeSettings {
    /// Shape of the edge.
    pub edge: EdgeShape,
    /// Blade section normal to the edge (ignored for a wire, whose section is
    /// its circle).
    #[serde(default)]
    pub blade: BladeSection,
    /// F/T sensor mount.
    #[serde(default)]
    pub sensor: SensorMount,
}

/// The named knife presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum KnifePreset {
    /// Straight 0.2 m edge, default blade (seed 000 §V.A uses the straight part
    /// of a kitchen knife near the handle).
    Straight,
    /// Chef's knife: 0.2 m edge, 0.06 m flat, tip 0.035 m above the flat.
    Chef,
    /// Wire of radius 150 µm and length 0.1 m (seed 001).
    Wire,
}

impl KnifePreset {
    /// Every preset.
    pub const ALL: [KnifePreset; 3] = [KnifePreset::Straight, KnifePreset::Chef, KnifePreset::Wire];

    /// The preset's config name.
    pub fn name(self) -> &'static str {
        match self {
            KnifePreset::Straight => "straight",
            KnifePreset::Chef => "chef",
            KnifePreset::Wire => "wire",
        }
    }

    /// Looks a preset up by name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The knife settings of this preset.
    pub fn settings(self) -> KnifeSettings {
        let edge = match self {
            KnifePreset::Straight => EdgeShape::Straight { length: 0.2 },
            KnifePreset::Chef => EdgeShape::Chef {
                length: 0.2,
                flat_length: 0.06,
                tip_rise: 0.035,
            },
            KnifePreset::Wire => EdgeShape::Wire {
                length: 0.1,
                radius: 150e-6,
            },
        };
        KnifeSettings {
            edge,
            blade: BladeSection::default(),
            sensor: SensorMount::default(),
        }
    }
}

impl KnifeSettings {
    /// Checks every field; the error names the key (e.g. `edge.length`).
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        self.edge.validate().map_err(|e| e.prefixed("edge"))?;
        // A wire's section is its circle (`Knife::new`), not this blade;
        // the table is checked all the same, so that no value it holds is
        // out of range unseen.
        self.blade.validate().map_err(|e| e.prefixed("blade"))?;
        KNIFE_COORDINATE.check_each("sensor.position", &self.sensor.position)
    }
}

impl EdgeShape {
    /// Checks the shape's fields; keys are relative to the edge table.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        match self {
            EdgeShape::Straight { length } => EDGE_LENGTH.check("length", *length),
            EdgeShape::Chef {
                length,
                flat_length,
                tip_rise,
            } => {
                EDGE_LENGTH.check("length", *length)?;
                if !(flat_length.is_finite() && *flat_length >= 0.0 && flat_length < length) {
                    return Err(InvalidSetting::new(
                        "flat_length",
                        flat_length,
                        format!("must be in [0, length = {length})"),
                    ));
                }
                EDGE_LENGTH
                    .at_least(MIN_EDGE_CHORD)
                    .check("tip_rise", *tip_rise)
            }
            EdgeShape::Polyline { points } => {
                check_count("points", points.len() as u64, 2, MAX_EDGE_POINTS).map_err(|e| {
                    InvalidSetting {
                        value: format!("{} point(s)", points.len()),
                        ..e
                    }
                })?;
                for (i, p) in points.iter().enumerate() {
                    KNIFE_COORDINATE.check_each(&format!("points[{i}]"), p)?;
                }
                for (i, w) in points.windows(2).enumerate() {
                    if w[1][0] - w[0][0] < MIN_EDGE_CHORD {
                        return Err(InvalidSetting::new(
                            format!("points[{}]", i + 1),
                            format!("{:?}", w[1]),
                            format!(
                                "z must increase from heel to tip by at least {MIN_EDGE_CHORD} m a point"
                            ),
                        ));
                    }
                }
                EDGE_LENGTH.check(
                    "points (z extent)",
                    points[points.len() - 1][0] - points[0][0],
                )
            }
            EdgeShape::Wire { length, radius } => {
                EDGE_LENGTH.check("length", *length)?;
                WIRE_RADIUS.check("radius", *radius)
            }
        }
    }
}

/// A knife ready for geometry queries.
#[derive(Debug, Clone, PartialEq)]
pub struct Knife {
    edge: KnifeEdge,
    blade: BladeSection,
    sensor: SensorMount,
    wire_radius: Option<f64>,
}

impl Knife {
    /// Builds a knife from validated settings.
    pub fn new(settings: &KnifeSettings) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        let (points, blade, wire_radius) = match &settings.edge {
            EdgeShape::Straight { length } => {
                (vec![[0.0, 0.0], [*length, 0.0]], settings.blade, None)
            }
            EdgeShape::Chef {
                length,
                flat_length,
                tip_rise,
            } => {
                let mut pts = vec![[0.0, 0.0]];
                let curved = length - flat_length;
                if *flat_length > 0.0 {
                    pts.push([*flat_length, 0.0]);
                }
                for k in 1..=CHEF_CHORDS {
                    let u = k as f64 / CHEF_CHORDS as f64;
                    pts.push([flat_length + u * curved, tip_rise * u * u]);
                }
                (pts, settings.blade, None)
            }
            EdgeShape::Polyline { points } => (points.clone(), settings.blade, None),
            EdgeShape::Wire { length, radius } => {
                // The wire's circle seen as a wedge: a flat of width R at the
                // bottom (the chord where a soft solid wraps the wire), faces at
                // 45°, full width 2R. An approximation for the section model.
                let blade = BladeSection {
                    thickness: 2.0 * radius,
                    bevel_angle: std::f64::consts::FRAC_PI_4,
                    edge_width: *radius,
                };
                (vec![[0.0, 0.0], [*length, 0.0]], blade, Some(*radius))
            }
        };
        Ok(Self {
            edge: KnifeEdge::from_points(points),
            blade,
            sensor: settings.sensor,
            wire_radius,
        })
    }

    /// The edge geometry.
    pub fn edge(&self) -> &KnifeEdge {
        &self.edge
    }

    /// The blade's section normal to the edge.
    pub fn blade(&self) -> &BladeSection {
        &self.blade
    }

    /// The F/T sensor origin in the knife frame, m.
    pub fn sensor_position(&self) -> Vector3<f64> {
        Vector3::from(self.sensor.position)
    }

    /// The wire radius, m, if this knife is a wire.
    pub fn wire_radius(&self) -> Option<f64> {
        self.wire_radius
    }
}

/// The edge as a polyline in the knife's yz-plane, parametrised by arc length.
#[derive(Debug, Clone, PartialEq)]
pub struct KnifeEdge {
    /// Vertices (z, y), heel to tip.
    points: Vec<Vector2<f64>>,
    /// Arc length at each vertex; `arc[0] = 0`.
    arc: Vec<f64>,
}

impl KnifeEdge {
    /// An edge through `points` ([z, y], heel first; at least two, distinct).
    fn from_points(points: Vec<[f64; 2]>) -> Self {
        let points: Vec<Vector2<f64>> = points
            .into_iter()
            .map(|[z, y]| Vector2::new(z, y))
            .collect();
        let mut arc = Vec::with_capacity(points.len());
        let mut s = 0.0;
        arc.push(0.0);
        for w in points.windows(2) {
            s += (w[1] - w[0]).norm();
            arc.push(s);
        }
        Self { points, arc }
    }

    /// Total arc length of the edge, m.
    pub fn length(&self) -> f64 {
        *self.arc.last().expect("an edge has at least two points")
    }

    /// The vertices (z, y) of the polyline, heel to tip, m.
    pub fn vertices(&self) -> &[Vector2<f64>] {
        &self.points
    }

    /// Index of the chord containing arc length `s` (clamped to the edge) and
    /// the fraction along it.
    fn locate(&self, s: f64) -> (usize, f64) {
        let s = s.clamp(0.0, self.length());
        let i = match self.arc.partition_point(|&a| a <= s) {
            0 => 0,
            k => (k - 1).min(self.points.len() - 2),
        };
        let len = self.arc[i + 1] - self.arc[i];
        (i, ((s - self.arc[i]) / len).clamp(0.0, 1.0))
    }

    /// Point (z, y) at arc length `s`, m (clamped to the edge's ends).
    pub fn point_at(&self, s: f64) -> Vector2<f64> {
        let (i, u) = self.locate(s);
        self.points[i] + (self.points[i + 1] - self.points[i]) * u
    }

    /// Unit tangent (dz, dy) at arc length `s`, pointing towards the tip (the
    /// chord's direction; at a vertex, the chord after it).
    pub fn tangent_at(&self, s: f64) -> Vector2<f64> {
        let (i, _) = self.locate(s);
        (self.points[i + 1] - self.points[i]).normalize()
    }

    /// Unit normal at arc length `s` in the knife's yz-plane, pointing away
    /// from the blade (−y on a flat edge): the direction in which the edge
    /// presses into the material.
    pub fn normal_at(&self, s: f64) -> Vector2<f64> {
        let t = self.tangent_at(s);
        Vector2::new(t.y, -t.x)
    }

    /// The edge's lowest point: (arc length, point). On a flat stretch the
    /// heel-most point of it.
    pub fn lowest_point(&self) -> (f64, Vector2<f64>) {
        let mut best = 0;
        for (i, p) in self.points.iter().enumerate() {
            if p.y < self.points[best].y {
                best = i;
            }
        }
        (self.arc[best], self.points[best])
    }

    /// The arc of the edge that lies at or below the horizontal line y = `height`
    /// (knife frame), around the lowest point: (s₁, s₂) with s₁ ≤ s₂, or `None`
    /// when the whole edge is above it. This is the arc in contact with a flat
    /// horizontal surface at that height.
    pub fn arc_below(&self, height: f64) -> Option<(f64, f64)> {
        let (s_low, p_low) = self.lowest_point();
        if p_low.y > height {
            return None;
        }
        let k = self.arc.iter().position(|&a| a == s_low).unwrap_or(0);
        // Walk towards the heel.
        let mut s1 = 0.0;
        for i in (0..k).rev() {
            let (a, b) = (self.points[i], self.points[i + 1]);
            if a.y > height {
                let u = (height - b.y) / (a.y - b.y);
                s1 = self.arc[i + 1] - u * (self.arc[i + 1] - self.arc[i]);
                break;
            }
        }
        // Walk towards the tip.
        let mut s2 = self.length();
        for i in k..self.points.len() - 1 {
            let (a, b) = (self.points[i], self.points[i + 1]);
            if b.y > height {
                let u = (height - a.y) / (b.y - a.y);
                s2 = self.arc[i] + u.max(0.0) * (self.arc[i + 1] - self.arc[i]);
                break;
            }
        }
        Some((s1, s2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chef() -> Knife {
        Knife::new(&KnifePreset::Chef.settings()).unwrap()
    }

    #[test]
    fn presets_validate() {
        for p in KnifePreset::ALL {
            Knife::new(&p.settings()).unwrap();
            assert_eq!(KnifePreset::from_name(p.name()), Some(p));
        }
    }

    #[test]
    fn straight_edge_queries() {
        let k = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let e = k.edge();
        assert!((e.length() - 0.2).abs() < 1e-15);
        assert_eq!(e.point_at(0.05), Vector2::new(0.05, 0.0));
        assert_eq!(e.tangent_at(0.1), Vector2::new(1.0, 0.0));
        assert_eq!(e.normal_at(0.1), Vector2::new(0.0, -1.0));
        assert_eq!(e.arc_below(0.0), Some((0.0, 0.2)));
        assert_eq!(e.arc_below(-1e-9), None);
    }

    #[test]
    fn chef_profile_is_flat_then_rises_to_the_tip() {
        let e = chef().edge().clone();
        // Arc length exceeds the 0.2 m extent only by the curve's extra length.
        assert!(e.length() > 0.2 && e.length() < 0.2 + 0.01);
        let tip = e.point_at(e.length());
        assert!((tip - Vector2::new(0.2, 0.035)).norm() < 1e-12);
        let (s_low, p_low) = e.lowest_point();
        assert_eq!((s_low, p_low.y), (0.0, 0.0));
        // Tangent and normal are orthonormal everywhere and the normal points down.
        for k in 0..=50 {
            let s = e.length() * k as f64 / 50.0;
            let (t, n) = (e.tangent_at(s), e.normal_at(s));
            assert!((t.norm() - 1.0).abs() < 1e-12 && t.dot(&n).abs() < 1e-12 && n.y < 0.0);
        }
    }

    #[test]
    fn contact_arc_of_chef_edge_matches_the_parabola() {
        let e = chef().edge().clone();
        // y = 0.035 u², u = (z − 0.06)/0.14: y = 0.01 at z = 0.06 + 0.14·√(0.01/0.035).
        let z_cross = 0.06 + 0.14 * (0.01f64 / 0.035).sqrt();
        let (s1, s2) = e.arc_below(0.01).unwrap();
        assert_eq!(s1, 0.0);
        let p = e.point_at(s2);
        // Chords of 0.7 mm: the chord's crossing is within its sagitta of the curve.
        assert!((p.y - 0.01).abs() < 1e-12);
        assert!((p.x - z_cross).abs() < 1e-4, "{} vs {}", p.x, z_cross);
    }

    #[test]
    fn v_shaped_edge_has_a_two_sided_arc() {
        let s = KnifeSettings {
            edge: EdgeShape::Polyline {
                points: vec![[0.0, 0.02], [0.1, 0.0], [0.2, 0.02]],
            },
            blade: BladeSection::default(),
            sensor: SensorMount::default(),
        };
        let k = Knife::new(&s).unwrap();
        let (s_low, p) = k.edge().lowest_point();
        assert_eq!(p, Vector2::new(0.1, 0.0));
        let (s1, s2) = k.edge().arc_below(0.01).unwrap();
        assert!((k.edge().point_at(s1) - Vector2::new(0.05, 0.01)).norm() < 1e-12);
        assert!((k.edge().point_at(s2) - Vector2::new(0.15, 0.01)).norm() < 1e-12);
        assert!(s1 < s_low && s_low < s2);
    }

    #[test]
    fn bad_polyline_names_the_point() {
        let s = KnifeSettings {
            edge: EdgeShape::Polyline {
                points: vec![[0.0, 0.0], [0.1, 0.0], [0.05, 0.0]],
            },
            blade: BladeSection::default(),
            sensor: SensorMount::default(),
        };
        let e = Knife::new(&s).unwrap_err();
        assert_eq!(e.key, "edge.points[2]");
    }
}
