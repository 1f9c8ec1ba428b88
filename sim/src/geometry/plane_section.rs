//! Plane sections of closed meshes: the 2D cross sections of seed 000 §III–IV.

use std::collections::HashMap;

use nalgebra::{Vector2, Vector3};

use super::polygon::Polygon;
use super::triangle_mesh::TriangleMesh;

/// A cutting plane with 2D coordinates on it.
///
/// The plane passes through `origin` and is spanned by the unit vectors
/// `u_axis` (across the cut: world x) and `v_axis` (up within the plane). A
/// section normal to a knife segment with unit normal n (in the yz-plane,
/// pointing into the material) has `v_axis = −n`; with `origin` on the board
/// (y = 0) the board is the line v = 0 of the section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionPlane {
    /// A point on the plane, the origin of its coordinates, m.
    pub origin: Vector3<f64>,
    /// Unit vector of the u coordinate.
    pub u_axis: Vector3<f64>,
    /// Unit vector of the v coordinate, orthogonal to `u_axis`.
    pub v_axis: Vector3<f64>,
}

impl SectionPlane {
    /// The plane normal to a knife segment: through the board point below `q`
    /// along the segment's `up` direction (unit, in the yz-plane, y > 0), with
    /// u along world x.
    ///
    /// `q` lies on the knife plane x = 0; the origin is where the line from q
    /// along −up meets the board.
    pub fn normal_to_segment(q: Vector3<f64>, up: Vector3<f64>) -> Self {
        let up = up.normalize();
        let origin = q - up * (q.y / up.y);
        Self {
            origin,
            u_axis: Vector3::x(),
            v_axis: up,
        }
    }

    /// The plane's unit normal u × v.
    pub fn normal(&self) -> Vector3<f64> {
        self.u_axis.cross(&self.v_axis)
    }

    /// Section coordinates (u, v) of a world point (projected onto the plane).
    pub fn to_plane(&self, p: &Vector3<f64>) -> Vector2<f64> {
        let d = p - self.origin;
        Vector2::new(d.dot(&self.u_axis), d.dot(&self.v_axis))
    }

    /// World point of section coordinates (u, v).
    pub fn to_world(&self, uv: &Vector2<f64>) -> Vector3<f64> {
        self.origin + self.u_axis * uv.x + self.v_axis * uv.y
    }

    /// Every closed loop in which the plane cuts `mesh`, counter-clockwise.
    ///
    /// Vertices exactly on the plane count as being on its positive side, so
    /// each crossing is found once per mesh edge and loops close exactly.
    pub fn loops(&self, mesh: &TriangleMesh) -> Vec<Polygon> {
        let n = self.normal();
        let dist: Vec<f64> = mesh
            .vertices()
            .iter()
            .map(|p| (p - self.origin).dot(&n))
            .collect();
        let side = |i: usize| dist[i] >= 0.0;
        // Crossing point id per mesh edge, and segments between crossing ids.
        let mut point_of_edge: HashMap<(usize, usize), usize> = HashMap::new();
        let mut points: Vec<Vector2<f64>> = Vec::new();
        let mut next: HashMap<usize, Vec<usize>> = HashMap::new();
        for tri in mesh.triangles() {
            let mut ids = [0usize; 2];
            let mut k = 0;
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                if side(a) == side(b) {
                    continue;
                }
                let key = (a.min(b), a.max(b));
                let id = *point_of_edge.entry(key).or_insert_with(|| {
                    let (pa, pb) = (mesh.vertices()[key.0], mesh.vertices()[key.1]);
                    let (da, db) = (dist[key.0], dist[key.1]);
                    let t = da / (da - db);
                    points.push(self.to_plane(&(pa + (pb - pa) * t)));
                    points.len() - 1
                });
                if k < 2 {
                    ids[k] = id;
                }
                k += 1;
            }
            if k == 2 {
                next.entry(ids[0]).or_default().push(ids[1]);
                next.entry(ids[1]).or_default().push(ids[0]);
            }
        }
        // Chain the segments into loops (every crossing point has two neighbours
        // on a closed mesh).
        let mut used = vec![false; points.len()];
        let mut loops = Vec::new();
        for start in 0..points.len() {
            if used[start] {
                continue;
            }
            let mut chain = vec![start];
            used[start] = true;
            let mut prev = usize::MAX;
            let mut cur = start;
            while let Some(&nxt) = next
                .get(&cur)
                .and_then(|nb| nb.iter().find(|&&x| x != prev && !used[x]))
            {
                used[nxt] = true;
                chain.push(nxt);
                prev = cur;
                cur = nxt;
            }
            if chain.len() >= 3 {
                loops.push(Polygon::new(chain.into_iter().map(|i| points[i]).collect()));
            }
        }
        loops
    }

    /// The section of `mesh`: its largest loop, or None if the plane misses it.
    pub fn section(&self, mesh: &TriangleMesh) -> Option<Polygon> {
        self.loops(mesh)
            .into_iter()
            .max_by(|a, b| a.area().total_cmp(&b.area()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cuboid() -> TriangleMesh {
        TriangleMesh::cuboid(
            Vector3::new(-0.015, 0.0, 0.02),
            Vector3::new(0.015, 0.025, 0.05),
        )
    }

    #[test]
    fn vertical_section_of_a_cuboid_is_its_rectangle() {
        let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, 0.03), Vector3::y());
        let p = plane.section(&cuboid()).unwrap();
        assert!((p.area() - 0.03 * 0.025).abs() < 1e-15);
        let (lo, hi) = p.bounds();
        assert!((lo - Vector2::new(-0.015, 0.0)).norm() < 1e-15);
        assert!((hi - Vector2::new(0.015, 0.025)).norm() < 1e-15);
    }

    #[test]
    fn tilted_section_is_stretched_by_one_over_cos() {
        // A segment tilted by 20°: its section through the cuboid's middle is
        // 0.025/cos 20° tall (it cuts top and bottom faces).
        let tilt: f64 = 20f64.to_radians();
        let up = Vector3::new(0.0, tilt.cos(), tilt.sin());
        let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.0125, 0.035), up);
        let p = plane.section(&cuboid()).unwrap();
        let (lo, hi) = p.bounds();
        assert!((hi.y - lo.y - 0.025 / tilt.cos()).abs() < 1e-12);
        assert!(lo.y.abs() < 1e-12, "board at v = 0");
        assert!(p.asymmetry() < 1e-12);
    }

    #[test]
    fn plane_missing_the_object_has_no_section() {
        let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, 0.3), Vector3::y());
        assert!(plane.section(&cuboid()).is_none());
    }
}
