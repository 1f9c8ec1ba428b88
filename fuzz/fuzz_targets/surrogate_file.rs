//! Surrogate files: any text is read and validated, or refused.
#![no_main]

#[path = "input_surface.rs"]
mod input_surface;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    input_surface::surrogate_file(data);
});
