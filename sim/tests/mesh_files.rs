//! Object meshes through OBJ and STL files: round trips keep the sections;
//! truncated, open and unknown files are refused with clear messages.

use nalgebra::Vector3;
use shearcut_sim::geometry::natural_shapes::{Tessellation, half_potato};
use shearcut_sim::geometry::{
    MeshError, SectionPlane, TriangleMesh, read_mesh, write_obj, write_stl,
};

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("shearcut-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn middle_section_area(m: &TriangleMesh) -> f64 {
    let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, 0.045), Vector3::y());
    plane.section(m).unwrap().area()
}

#[test]
fn round_trip_through_obj_and_stl_keeps_sections() {
    let m = half_potato(
        0.09,
        0.06,
        0.035,
        Tessellation {
            rings: 16,
            segments: 32,
        },
    );
    let a0 = middle_section_area(&m);
    let obj = tmp("potato.obj");
    write_obj(&obj, &m).unwrap();
    let from_obj = read_mesh(&obj).unwrap();
    // tobj parses positions as f32: agreement to f32 rounding (relative 1e-7).
    assert_eq!(from_obj.triangles().len(), m.triangles().len());
    assert!((middle_section_area(&from_obj) - a0).abs() < 1e-6 * a0);
    let stl = tmp("potato.stl");
    write_stl(&stl, &m).unwrap();
    let from_stl = read_mesh(&stl).unwrap();
    // STL stores every corner separately; welding restores the shared vertices.
    assert_eq!(from_stl.vertices().len(), m.vertices().len());
    assert!((middle_section_area(&from_stl) - a0).abs() < 1e-6 * a0);
    assert!((from_stl.volume() - m.volume()).abs() < 1e-6 * m.volume());
}

#[test]
fn truncated_stl_is_refused() {
    let m = TriangleMesh::cuboid(Vector3::zeros(), Vector3::repeat(0.03));
    let stl = tmp("box.stl");
    write_stl(&stl, &m).unwrap();
    let bytes = std::fs::read(&stl).unwrap();
    let cut = tmp("box-truncated.stl");
    std::fs::write(&cut, &bytes[..bytes.len() - 30]).unwrap();
    let e = read_mesh(&cut).unwrap_err();
    assert!(matches!(e, MeshError::Malformed { .. }), "{e}");
    assert!(e.to_string().contains("box-truncated.stl"));
}

#[test]
fn open_obj_is_refused_naming_the_edge() {
    let obj = tmp("open.obj");
    // A tetrahedron missing one face.
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n",
    )
    .unwrap();
    let e = read_mesh(&obj).unwrap_err();
    assert!(matches!(e, MeshError::NotClosed { count: 1, .. }), "{e}");
    // The edge is named by where it is: the file's coordinates, not an index.
    assert!(
        e.to_string()
            .contains("the edge from (0, 0, 0) m to (0, 1, 0) m belongs to 1 triangle(s)"),
        "{e}"
    );
}

#[test]
fn malformed_obj_and_unknown_format_are_refused() {
    let obj = tmp("bad.obj");
    std::fs::write(&obj, "v 0 0 zero\nf 1 2 3\n").unwrap();
    assert!(matches!(
        read_mesh(&obj).unwrap_err(),
        MeshError::Malformed { .. }
    ));
    let ply = tmp("x.ply");
    std::fs::write(&ply, "ply\n").unwrap();
    assert!(matches!(
        read_mesh(&ply).unwrap_err(),
        MeshError::UnknownFormat { .. }
    ));
    let missing = read_mesh(std::path::Path::new("/nonexistent/a.obj")).unwrap_err();
    assert!(matches!(missing, MeshError::Read { .. }));
}
