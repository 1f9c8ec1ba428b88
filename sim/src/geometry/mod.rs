//! Solid geometry of the objects: closed triangle meshes, their plane sections,
//! procedural natural shapes, and mesh files (OBJ, STL).

pub mod mesh_io;
pub mod natural_shapes;
pub mod plane_section;
pub mod polygon;
pub mod triangle_mesh;

pub use mesh_io::{MeshFormat, parse_mesh, read_mesh, write_obj, write_stl};
pub use plane_section::SectionPlane;
pub use polygon::Polygon;
pub use triangle_mesh::{MeshError, TriangleMesh};
