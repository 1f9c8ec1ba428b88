//! Closed triangle meshes of objects.

use std::collections::HashMap;

use nalgebra::Vector3;

use crate::physical_range::number_text;

/// Why a mesh cannot be used as a solid object.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("cannot read mesh `{path}`: {message}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// The file is not a valid OBJ or STL (truncated, malformed).
    #[error("mesh `{path}` is malformed: {message}")]
    Malformed {
        /// The file.
        path: String,
        /// What the parser said.
        message: String,
    },
    /// The file extension is neither .obj nor .stl.
    #[error("mesh `{path}`: unknown format (expected a .obj or .stl file)")]
    UnknownFormat {
        /// The file.
        path: String,
    },
    /// No triangles.
    #[error("mesh has no triangles")]
    Empty,
    /// A coordinate is NaN or infinite.
    #[error("mesh vertex {} has a non-finite coordinate", Point(.position))]
    NonFinite {
        /// The vertex's coordinates as given, m.
        position: [f64; 3],
    },
    /// A triangle refers to a vertex that does not exist (indices count
    /// from 0, as in [`TriangleMesh::new`]'s arguments).
    #[error(
        "mesh triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices"
    )]
    BadIndex {
        /// Index of the triangle.
        triangle: usize,
        /// The index it holds.
        vertex: usize,
        /// Number of vertices.
        count: usize,
    },
    /// The surface is not closed: an edge belongs to other than two triangles.
    #[error(
        "mesh is not closed: the edge from {} to {} belongs to {count} triangle(s), a closed surface needs exactly 2",
        Point(.a),
        Point(.b)
    )]
    NotClosed {
        /// One end of the edge, m.
        a: [f64; 3],
        /// The other end, m.
        b: [f64; 3],
        /// How many triangles share it.
        count: usize,
    },
    /// The two triangles that share an edge run along it the same way: one
    /// side of the edge (a face or a region of faces) is wound backwards,
    /// so the surface has no consistent outside.
    #[error(
        "mesh is not consistently wound: both triangles on the edge run from {} to {} (faces on one side of it are reversed; reorient the faces consistently, e.g. Blender's Recalculate Outside)",
        Point(.from),
        Point(.to)
    )]
    InconsistentWinding {
        /// Where both triangles' edge starts, m.
        from: [f64; 3],
        /// Where it ends, m.
        to: [f64; 3],
    },
    /// A closed shell that lies in no piece's material faces the other way
    /// from the largest shell: a shell there is the outside of a piece (in
    /// free space or in a cavity), and faces as the largest one does.
    #[error(
        "mesh is not consistently wound: the closed shell through {} faces the other way from the largest shell and lies in no piece's material, so it is the outside of a piece (reverse that shell's faces, e.g. Blender's Recalculate Outside)",
        Point(.vertex)
    )]
    InsideOutShell {
        /// A vertex of that shell, m.
        vertex: [f64; 3],
    },
    /// A closed shell that lies within a piece's material faces the way the
    /// largest shell faces: a shell there is a cavity's wall, which faces
    /// the other way (into the cavity's material-free inside).
    #[error(
        "mesh is not consistently wound: the closed shell through {} lies within a piece's material, so it is a cavity's wall, and faces the same way as the largest shell where a cavity faces the other way (reverse that shell's faces, e.g. Blender's Recalculate Outside)",
        Point(.vertex)
    )]
    InsideOutCavity {
        /// A vertex of that shell, m.
        vertex: [f64; 3],
    },
    /// The enclosed volume is zero (flat or degenerate mesh).
    #[error("mesh encloses no volume")]
    NoVolume,
}

/// A closed, consistently usable triangle surface bounding a solid, in world
/// coordinates (m). Built only through [`TriangleMesh::new`], which checks it.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    vertices: Vec<Vector3<f64>>,
    triangles: Vec<[usize; 3]>,
}

impl TriangleMesh {
    /// A mesh from vertices and triangles, after checking that it is a closed
    /// surface (every edge shared by exactly two triangles, after merging
    /// vertices that coincide to 1e-9 of the mesh size) wound consistently
    /// (the two triangles on an edge run along it in opposite directions:
    /// each closed shell faces all inwards or all outwards), finite, and
    /// encloses a volume.
    pub fn new(vertices: Vec<Vector3<f64>>, triangles: Vec<[usize; 3]>) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(p) = vertices.iter().find(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(MeshError::NonFinite {
                position: (*p).into(),
            });
        }
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v >= vertices.len()) {
                return Err(MeshError::BadIndex {
                    triangle: t,
                    vertex: v,
                    count: vertices.len(),
                });
            }
        }
        let (vertices, triangles) = weld(vertices, triangles);
        // Per undirected edge: how many triangles run along it from its lower
        // to its higher vertex index, and how many the other way.
        let mut edges: HashMap<(usize, usize), [usize; 2]> = HashMap::new();
        for tri in &triangles {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                edges.entry((a.min(b), a.max(b))).or_default()[usize::from(a > b)] += 1;
            }
        }
        // The first bad edge by vertex index, so that the error is the same
        // from run to run.
        let first_edge = |bad: fn(&[usize; 2]) -> bool| {
            edges
                .iter()
                .filter(|(_, counts)| bad(counts))
                .min_by_key(|(edge, _)| **edge)
                .map(|(&edge, &counts)| (edge, counts))
        };
        let at = |i: usize| -> [f64; 3] { vertices[i].into() };
        if let Some(((a, b), [up, down])) = first_edge(|[u, d]| u + d != 2) {
            return Err(MeshError::NotClosed {
                a: at(a),
                b: at(b),
                count: up + down,
            });
        }
        if let Some(((a, b), [up, _])) = first_edge(|[u, d]| u != d) {
            // Both run from the lower index to the higher one, or both back.
            let (from, to) = if up == 2 { (a, b) } else { (b, a) };
            return Err(MeshError::InconsistentWinding {
                from: at(from),
                to: at(to),
            });
        }
        if let Some((v, within)) = inside_out_shell(&vertices, &triangles) {
            return Err(if within {
                MeshError::InsideOutCavity { vertex: at(v) }
            } else {
                MeshError::InsideOutShell { vertex: at(v) }
            });
        }
        let mesh = Self {
            vertices,
            triangles,
        };
        if mesh.volume().abs() <= 1e-12 * mesh.size().powi(3) {
            return Err(MeshError::NoVolume);
        }
        Ok(mesh)
    }

    /// The vertices, m.
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The triangles as vertex indices.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// (min, max) corners of the bounding box, m.
    pub fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for p in &self.vertices {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }

    /// Length of the bounding box diagonal, m.
    pub fn size(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (hi - lo).norm()
    }

    /// Enclosed volume by the divergence theorem, m³ (absolute value: a
    /// consistently wound mesh may face inwards or outwards).
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let (a, b, c) = (
                    self.vertices[t[0]],
                    self.vertices[t[1]],
                    self.vertices[t[2]],
                );
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum::<f64>()
            .abs()
    }

    /// A closed box mesh [x0, x1] × [y0, y1] × [z0, z1].
    pub fn cuboid(min: Vector3<f64>, max: Vector3<f64>) -> Self {
        let c = |i: usize| {
            Vector3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        };
        let vertices = (0..8).map(c).collect();
        let triangles = vec![
            [0, 2, 1],
            [1, 2, 3], // z = min
            [4, 5, 6],
            [5, 7, 6], // z = max
            [0, 1, 4],
            [1, 5, 4], // y = min
            [2, 6, 3],
            [3, 6, 7], // y = max
            [0, 4, 2],
            [2, 4, 6], // x = min
            [1, 3, 5],
            [3, 7, 5], // x = max
        ];
        Self::new(vertices, triangles).expect("a box is closed")
    }
}

/// A point in an error message: its coordinates in metres as the file
/// wrote them. OBJ and STL coordinates are read as f32, so a coordinate
/// that is an f32 is printed as the shortest f32 (0.05, not
/// 0.05000000074505806); any other as [`number_text`] prints it.
struct Point<'a>(&'a [f64; 3]);

impl std::fmt::Display for Point<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let text = |c: f64| {
            let single = c as f32;
            if f64::from(single) == c {
                single.to_string()
            } else {
                number_text(c)
            }
        };
        let [x, y, z] = self.0.map(text);
        write!(f, "({x}, {y}, {z}) m")
    }
}

/// The first vertex of the first closed shell (by its first vertex) wound
/// the wrong way for where it lies, and whether it lies within a piece's
/// material; None if every shell is wound right. A shell in no piece's
/// material (free space, or a cavity) is the outside of a piece and must
/// face as the shell enclosing the largest volume does (which nothing
/// encloses); a shell within a piece's material is a cavity's wall and
/// must face the other way. Where a shell lies is read from the winding
/// number of its first vertex about the other shells, each counted with
/// the largest shell's orientation: 0 in no material, 1 within one piece's.
/// A shell where that number is neither (pieces that overlap, or shells
/// that touch) is left alone, and so are the shells from the first whose
/// check would bring the bounding-box tests past [`BOX_TEST_BUDGET`] or
/// the triangles' solid angles past [`SOLID_ANGLE_BUDGET`] (over ten
/// thousand shells, or hundreds nested in one another's bounding boxes).
fn inside_out_shell(vertices: &[Vector3<f64>], triangles: &[[usize; 3]]) -> Option<(usize, bool)> {
    // Shells: the vertices joined by triangles (union-find).
    let mut parent: Vec<usize> = (0..vertices.len()).collect();
    let root = |parent: &mut Vec<usize>, mut v: usize| {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    };
    for t in triangles {
        let r = root(&mut parent, t[0]);
        for &v in &t[1..] {
            let other = root(&mut parent, v);
            parent[other] = r;
        }
    }
    struct Shell {
        first: usize,
        signed_volume: f64,
        lo: Vector3<f64>,
        hi: Vector3<f64>,
        triangles: Vec<[usize; 3]>,
    }
    let mut shells: HashMap<usize, Shell> = HashMap::new();
    for t in triangles {
        let shell = shells.entry(root(&mut parent, t[0])).or_insert(Shell {
            first: t[0],
            signed_volume: 0.0,
            lo: vertices[t[0]],
            hi: vertices[t[0]],
            triangles: Vec::new(),
        });
        let [a, b, c] = t.map(|v| vertices[v]);
        shell.signed_volume += a.dot(&b.cross(&c)) / 6.0;
        for &v in t {
            shell.first = shell.first.min(v);
            shell.lo = shell.lo.inf(&vertices[v]);
            shell.hi = shell.hi.sup(&vertices[v]);
        }
    }
    if shells.len() < 2 {
        return None;
    }
    for t in triangles {
        if let Some(shell) = shells.get_mut(&root(&mut parent, t[0])) {
            shell.triangles.push(*t);
        }
    }
    let mut shells: Vec<Shell> = shells.into_values().collect();
    // In the order of their first vertices: the same error from run to run.
    shells.sort_by_key(|s| s.first);
    let largest = shells.iter().max_by(|a, b| {
        (a.signed_volume.abs().total_cmp(&b.signed_volume.abs())).then(b.first.cmp(&a.first))
    })?;
    let outward = largest.signed_volume.signum();
    let (mut box_tests, mut solid_angles) = (BOX_TEST_BUDGET, SOLID_ANGLE_BUDGET);
    for s in &shells {
        // A point outside a closed shell's bounding box winds 0 times
        // about it.
        let p = vertices[s.first];
        box_tests = box_tests.checked_sub(shells.len())?;
        let around: Vec<&Shell> = shells
            .iter()
            .filter(|o| o.first != s.first)
            .filter(|o| (0..3).all(|k| o.lo[k] <= p[k] && p[k] <= o.hi[k]))
            .collect();
        solid_angles = solid_angles.checked_sub(around.iter().map(|o| o.triangles.len()).sum())?;
        let depth: f64 = outward
            * around
                .iter()
                .map(|o| winding_number(vertices, &o.triangles, &p))
                .sum::<f64>();
        let same_way = s.signed_volume * outward > 0.0;
        if depth.abs() < 0.25 && !same_way {
            return Some((s.first, false));
        }
        if (depth - 1.0).abs() < 0.25 && same_way {
            return Some((s.first, true));
        }
    }
    None
}

/// Most bounding-box tests [`inside_out_shell`] makes for one mesh: every
/// shell of 14 000 against every other (under half a second of work).
const BOX_TEST_BUDGET: usize = 200_000_000;

/// Most triangles whose solid angles [`inside_out_shell`] takes for one
/// mesh (about a third of a second of work); a mesh of the largest size
/// read, 500 000 triangles, in a few shells needs a tenth of it.
const SOLID_ANGLE_BUDGET: usize = 5_000_000;

/// The winding number of the closed surface `triangles` about the point
/// `p` off it: the solid angle its triangles subtend at p over 4π (Van
/// Oosterom and Strackee's formula for each), +1 inside a surface wound
/// outwards (positive signed volume), −1 inside one wound inwards, 0
/// outside.
fn winding_number(vertices: &[Vector3<f64>], triangles: &[[usize; 3]], p: &Vector3<f64>) -> f64 {
    let solid_angle: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| vertices[v] - p);
            let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
            let numerator = a.dot(&b.cross(&c));
            let denominator = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
            2.0 * numerator.atan2(denominator)
        })
        .sum();
    solid_angle / (4.0 * std::f64::consts::PI)
}

/// Merges vertices closer than 1e-9 × the bounding-box diagonal (STL stores
/// each triangle's corners separately), drops triangles that collapse.
fn weld(
    vertices: Vec<Vector3<f64>>,
    triangles: Vec<[usize; 3]>,
) -> (Vec<Vector3<f64>>, Vec<[usize; 3]>) {
    let mut lo = Vector3::repeat(f64::INFINITY);
    let mut hi = Vector3::repeat(f64::NEG_INFINITY);
    for p in &vertices {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let tol = 1e-9 * (hi - lo).norm().max(f64::MIN_POSITIVE);
    let key = |p: &Vector3<f64>| {
        let q = (p - lo) / tol;
        (q.x.round() as i64, q.y.round() as i64, q.z.round() as i64)
    };
    let mut map: HashMap<(i64, i64, i64), usize> = HashMap::new();
    let mut new_vertices = Vec::new();
    let remap: Vec<usize> = vertices
        .iter()
        .map(|p| {
            *map.entry(key(p)).or_insert_with(|| {
                new_vertices.push(*p);
                new_vertices.len() - 1
            })
        })
        .collect();
    let new_triangles = triangles
        .into_iter()
        .map(|t| [remap[t[0]], remap[t[1]], remap[t[2]]])
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    (new_vertices, new_triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_volume() {
        let m = TriangleMesh::cuboid(
            Vector3::new(-0.01, 0.0, 0.0),
            Vector3::new(0.01, 0.03, 0.04),
        );
        assert!((m.volume() - 0.02 * 0.03 * 0.04).abs() < 1e-15);
    }

    #[test]
    fn open_mesh_is_refused() {
        let m = TriangleMesh::cuboid(Vector3::zeros(), Vector3::repeat(1.0));
        let mut tris = m.triangles().to_vec();
        tris.pop();
        let e = TriangleMesh::new(m.vertices().to_vec(), tris).unwrap_err();
        assert!(matches!(e, MeshError::NotClosed { count: 1, .. }), "{e}");
    }

    #[test]
    fn a_reversed_face_is_refused_naming_its_edge() {
        let m = TriangleMesh::cuboid(Vector3::zeros(), Vector3::repeat(1.0));
        let mut tris = m.triangles().to_vec();
        tris[0].swap(1, 2);
        let e = TriangleMesh::new(m.vertices().to_vec(), tris).unwrap_err();
        let MeshError::InconsistentWinding { from, to } = e else {
            panic!("{e}")
        };
        // The floor's triangle [0, 2, 1] reversed is [0, 1, 2]: it runs from
        // corner 0 to corner 1 as the triangle [0, 1, 4] of the face y = min
        // does; (0, 1) is the first of its three edges by index.
        assert_eq!((from, to), ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), "{e}");
        // Every face reversed is a consistent surface, wound inwards.
        let inward: Vec<[usize; 3]> = m.triangles().iter().map(|&[a, b, c]| [a, c, b]).collect();
        let inward = TriangleMesh::new(m.vertices().to_vec(), inward).unwrap();
        assert_eq!(inward.volume(), m.volume());
    }

    /// Two boxes side by side, the second's faces reversed or not, and a box
    /// with a reversed box inside it (a cavity).
    #[test]
    fn a_separate_shell_facing_inwards_is_refused_a_cavity_is_not() {
        let unit = TriangleMesh::cuboid(Vector3::zeros(), Vector3::repeat(1.0));
        let two =
            |second: TriangleMesh, reversed: bool| shells(&[(&unit, false), (&second, reversed)]);
        let beside =
            || TriangleMesh::cuboid(Vector3::new(2.0, 0.0, 0.0), Vector3::new(2.5, 0.5, 0.5));
        let pair = two(beside(), false).unwrap();
        assert!((pair.volume() - 1.125).abs() < 1e-12);
        let e = two(beside(), true).unwrap_err();
        // The second box's first vertex is its corner (2, 0, 0).
        assert_eq!(
            e,
            MeshError::InsideOutShell {
                vertex: [2.0, 0.0, 0.0]
            },
            "{e}"
        );
        let inner = || TriangleMesh::cuboid(Vector3::repeat(0.25), Vector3::repeat(0.75));
        let hollow = two(inner(), true).unwrap();
        assert!((hollow.volume() - (1.0 - 0.125)).abs() < 1e-12);
        // A cavity wound as the outside is refused.
        let e = two(inner(), false).unwrap_err();
        assert_eq!(
            e,
            MeshError::InsideOutCavity {
                vertex: [0.25, 0.25, 0.25]
            },
            "{e}"
        );
    }

    /// Shells joined into one mesh, each wound outwards or (`true`) inwards.
    fn shells(parts: &[(&TriangleMesh, bool)]) -> Result<TriangleMesh, MeshError> {
        let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
        for (m, reversed) in parts {
            let n = vertices.len();
            vertices.extend_from_slice(m.vertices());
            triangles.extend(m.triangles().iter().map(|&[a, b, c]| {
                if *reversed {
                    [a + n, c + n, b + n]
                } else {
                    [a + n, b + n, c + n]
                }
            }));
        }
        TriangleMesh::new(vertices, triangles)
    }

    /// A piece in a cavity is the outside of a piece again; a shell inside
    /// another's bounding box but outside its material is too.
    #[test]
    fn where_a_shell_lies_decides_the_way_it_must_face() {
        let cube =
            |lo: f64, hi: f64| TriangleMesh::cuboid(Vector3::repeat(lo), Vector3::repeat(hi));
        let (outer, cavity, piece) = (cube(0.0, 1.0), cube(0.1, 0.9), cube(0.3, 0.7));
        let nested = shells(&[(&outer, false), (&cavity, true), (&piece, false)]).unwrap();
        let expected = 1.0 - 0.8f64.powi(3) + 0.4f64.powi(3);
        assert!((nested.volume() - expected).abs() < 1e-12);
        let e = shells(&[(&outer, false), (&cavity, true), (&piece, true)]).unwrap_err();
        assert_eq!(e, MeshError::InsideOutShell { vertex: [0.3; 3] }, "{e}");
        // The whole mesh wound inwards is wound consistently.
        shells(&[(&outer, true), (&cavity, false), (&piece, true)]).unwrap();
        // The tetrahedron x, y, z ≥ 0, x + y + z ≤ 1 (wound outwards) and a
        // small box at (0.8, 0.8, 0.8): within the tetrahedron's bounding
        // box, outside its material.
        let tetra = TriangleMesh::new(
            vec![Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z()],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
        .unwrap();
        assert!((tetra.volume() - 1.0 / 6.0).abs() < 1e-15);
        let corner = cube(0.75, 0.85);
        shells(&[(&tetra, false), (&corner, false)]).unwrap();
        let e = shells(&[(&tetra, false), (&corner, true)]).unwrap_err();
        assert_eq!(e, MeshError::InsideOutShell { vertex: [0.75; 3] }, "{e}");
    }

    #[test]
    fn bad_index_and_nan_are_refused() {
        let e = TriangleMesh::new(vec![Vector3::zeros(); 3], vec![[0, 1, 5]]).unwrap_err();
        assert!(matches!(e, MeshError::BadIndex { vertex: 5, .. }));
        let e = TriangleMesh::new(vec![Vector3::new(f64::NAN, 0.0, 0.0); 3], vec![[0, 1, 2]])
            .unwrap_err();
        assert!(matches!(e, MeshError::NonFinite { .. }), "{e}");
        assert!(e.to_string().contains("(NaN, 0, 0)"), "{e}");
    }
}
