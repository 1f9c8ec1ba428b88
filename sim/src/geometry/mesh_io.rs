//! Reading and writing object meshes: Wavefront OBJ (via `tobj`) and STL
//! (ASCII or binary, via `stl_io`). Coordinates are metres in the world frame.

use std::fs::File;
use std::io::{BufReader, Write};
use std::path::Path;

use nalgebra::Vector3;

use super::triangle_mesh::{MeshError, TriangleMesh};

/// Reads a closed mesh from an `.obj` or `.stl` file and checks it.
pub fn read_mesh(path: &Path) -> Result<TriangleMesh, MeshError> {
    let name = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (vertices, triangles) = match ext.as_deref() {
        Some("obj") => read_obj(path, &name)?,
        Some("stl") => read_stl(path, &name)?,
        _ => return Err(MeshError::UnknownFormat { path: name }),
    };
    TriangleMesh::new(vertices, triangles)
}

type Soup = (Vec<Vector3<f64>>, Vec<[usize; 3]>);

fn read_obj(path: &Path, name: &str) -> Result<Soup, MeshError> {
    if let Err(e) = std::fs::metadata(path) {
        return Err(MeshError::Read {
            path: name.to_string(),
            message: e.to_string(),
        });
    }
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &opts).map_err(|e| MeshError::Malformed {
        path: name.to_string(),
        message: e.to_string(),
    })?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for m in models {
        let base = vertices.len();
        let pos = &m.mesh.positions;
        if pos.len() % 3 != 0 || m.mesh.indices.len() % 3 != 0 {
            return Err(MeshError::Malformed {
                path: name.to_string(),
                message: "positions or faces are not whole triples".into(),
            });
        }
        vertices.extend(
            pos.chunks_exact(3)
                .map(|c| Vector3::new(c[0] as f64, c[1] as f64, c[2] as f64)),
        );
        triangles.extend(m.mesh.indices.chunks_exact(3).map(|c| {
            [
                base + c[0] as usize,
                base + c[1] as usize,
                base + c[2] as usize,
            ]
        }));
    }
    Ok((vertices, triangles))
}

fn read_stl(path: &Path, name: &str) -> Result<Soup, MeshError> {
    let file = File::open(path).map_err(|e| MeshError::Read {
        path: name.to_string(),
        message: e.to_string(),
    })?;
    let mut reader = BufReader::new(file);
    let mesh = stl_io::read_stl(&mut reader).map_err(|e| MeshError::Malformed {
        path: name.to_string(),
        message: e.to_string(),
    })?;
    let vertices = mesh
        .vertices
        .iter()
        .map(|v| Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64))
        .collect();
    let triangles = mesh.faces.iter().map(|f| f.vertices).collect();
    Ok((vertices, triangles))
}

/// Writes `mesh` as a Wavefront OBJ file (full f64 precision).
pub fn write_obj(path: &Path, mesh: &TriangleMesh) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(File::create(path)?);
    writeln!(w, "# shearcut object mesh, metres")?;
    for v in mesh.vertices() {
        writeln!(w, "v {:e} {:e} {:e}", v.x, v.y, v.z)?;
    }
    for t in mesh.triangles() {
        writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
    }
    w.flush()
}

/// Writes `mesh` as a binary STL file (f32 coordinates, as the format stores).
pub fn write_stl(path: &Path, mesh: &TriangleMesh) -> std::io::Result<()> {
    let v = mesh.vertices();
    let tris: Vec<stl_io::Triangle> = mesh
        .triangles()
        .iter()
        .map(|t| {
            let (a, b, c) = (v[t[0]], v[t[1]], v[t[2]]);
            let n = (b - a)
                .cross(&(c - a))
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::zeros);
            let p = |x: Vector3<f64>| stl_io::Vertex::new([x.x as f32, x.y as f32, x.z as f32]);
            stl_io::Triangle {
                normal: stl_io::Normal::new([n.x as f32, n.y as f32, n.z as f32]),
                vertices: [p(a), p(b), p(c)],
            }
        })
        .collect();
    let mut w = std::io::BufWriter::new(File::create(path)?);
    stl_io::write_stl(&mut w, tris.iter())?;
    w.flush()
}
