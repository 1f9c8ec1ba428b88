//! OBJ and STL meshes: the first byte picks the format, the rest is the file.
#![no_main]

#[path = "input_surface.rs"]
mod input_surface;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    input_surface::mesh_file(data);
});
