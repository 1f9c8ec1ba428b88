//! Reading and writing object meshes: Wavefront OBJ (via `tobj`) and STL
//! (ASCII or binary, via `stl_io`). Coordinates are metres in the world frame.

use std::fs::File;
use std::io::{Cursor, Write};
use std::path::Path;

use nalgebra::Vector3;

use super::triangle_mesh::{MeshError, TriangleMesh};
use crate::capped_read::read_capped;
use crate::resource_budget::{MESH_FILE_BYTES, MESH_TRIANGLES_BUDGET};

/// The mesh file formats read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (text; polygons are triangulated, materials ignored).
    Obj,
    /// STL, ASCII or binary.
    Stl,
}

impl MeshFormat {
    /// The format named by a path's extension (`.obj`, `.stl`, any case).
    pub fn from_path(path: &Path) -> Option<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("obj") => Some(Self::Obj),
            Some("stl") => Some(Self::Stl),
            _ => None,
        }
    }
}

/// Reads a closed mesh from an `.obj` or `.stl` file and checks it. At
/// most [`MESH_FILE_BYTES`] are read; the file is parsed only as the format
/// its extension names, and no referenced file (an OBJ's material library)
/// is opened.
pub fn read_mesh(path: &Path) -> Result<TriangleMesh, MeshError> {
    let name = path.display().to_string();
    let format = MeshFormat::from_path(path)
        .ok_or_else(|| MeshError::UnknownFormat { path: name.clone() })?;
    let bytes = read_capped(path, MESH_FILE_BYTES).map_err(|e| MeshError::Read {
        path: name.clone(),
        message: e.to_string(),
    })?;
    parse_mesh(&bytes, format, &name)
}

/// Parses a closed mesh from the bytes of a file of `format`; `name` names
/// it in errors. Errors never quote the file's contents. More than
/// [`MESH_TRIANGLES_BUDGET`] triangles are refused.
pub fn parse_mesh(bytes: &[u8], format: MeshFormat, name: &str) -> Result<TriangleMesh, MeshError> {
    let (vertices, triangles) = match format {
        MeshFormat::Obj => parse_obj(bytes, name)?,
        MeshFormat::Stl => parse_stl(bytes, name)?,
    };
    if triangles.len() > MESH_TRIANGLES_BUDGET {
        return Err(MeshError::Malformed {
            path: name.to_string(),
            message: format!(
                "{} triangles, more than the {MESH_TRIANGLES_BUDGET} a mesh may have (docs/reliability.md)",
                triangles.len()
            ),
        });
    }
    TriangleMesh::new(vertices, triangles)
}

type Soup = (Vec<Vector3<f64>>, Vec<[usize; 3]>);

fn parse_obj(bytes: &[u8], name: &str) -> Result<Soup, MeshError> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let mut reader = Cursor::new(bytes);
    // Material libraries are not opened: a mesh file names only its geometry.
    let (models, _) =
        tobj::load_obj_buf(&mut reader, &opts, |_| Err(tobj::LoadError::OpenFileFailed)).map_err(
            |e| MeshError::Malformed {
                path: name.to_string(),
                message: e.to_string(),
            },
        )?;
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

fn parse_stl(bytes: &[u8], name: &str) -> Result<Soup, MeshError> {
    // stl_io's messages quote the offending line: report the format only.
    let mesh = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|_| MeshError::Malformed {
        path: name.to_string(),
        message: "not a valid ASCII or binary STL file (truncated, or text that is not STL)".into(),
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
