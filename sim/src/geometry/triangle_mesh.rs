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
    /// Two closed shells face opposite ways and one lies outside the other:
    /// a shell that nothing encloses is the outside of a piece, so it must
    /// face the way the largest shell faces (a shell facing the other way
    /// is a cavity, and lies within another).
    #[error(
        "mesh is not consistently wound: the closed shell through {} faces the other way from the largest shell and lies outside every other shell (reverse that shell's faces, e.g. Blender's Recalculate Outside)",
        Point(.vertex)
    )]
    InsideOutShell {
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
        if let Some(v) = inside_out_shell(&vertices, &triangles) {
            return Err(MeshError::InsideOutShell { vertex: at(v) });
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

/// The first vertex of the first closed shell (by its first vertex) that
/// faces the other way from the shell enclosing the largest volume while its
/// bounding box meets no other shell's, if any. Nothing can enclose such a
/// shell, so it is the outside of a piece and must face as the largest
/// (which nothing encloses either) does. Shells whose boxes meet are left
/// alone: one may be a cavity of the other, which faces the other way.
fn inside_out_shell(vertices: &[Vector3<f64>], triangles: &[[usize; 3]]) -> Option<usize> {
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
    }
    let mut shells: HashMap<usize, Shell> = HashMap::new();
    for t in triangles {
        let shell = shells.entry(root(&mut parent, t[0])).or_insert(Shell {
            first: t[0],
            signed_volume: 0.0,
            lo: vertices[t[0]],
            hi: vertices[t[0]],
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
    let shells: Vec<Shell> = shells.into_values().collect();
    // Ties by the first vertex: the same shell from run to run.
    let largest = shells.iter().max_by(|a, b| {
        (a.signed_volume.abs().total_cmp(&b.signed_volume.abs())).then(b.first.cmp(&a.first))
    })?;
    let meet = |a: &Shell, b: &Shell| (0..3).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k]);
    shells
        .iter()
        .filter(|s| s.signed_volume * largest.signed_volume < 0.0)
        .filter(|s| {
            !shells
                .iter()
                .any(|other| other.first != s.first && meet(s, other))
        })
        .map(|s| s.first)
        .min()
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
        let two = |second: TriangleMesh, reversed: bool| {
            let mut vertices = unit.vertices().to_vec();
            let mut triangles = unit.triangles().to_vec();
            let n = vertices.len();
            vertices.extend_from_slice(second.vertices());
            triangles.extend(second.triangles().iter().map(|&[a, b, c]| {
                if reversed {
                    [a + n, c + n, b + n]
                } else {
                    [a + n, b + n, c + n]
                }
            }));
            TriangleMesh::new(vertices, triangles)
        };
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
