//! The wire messages a hostile arm bridge could send (measurements) and a
//! hostile controller could send (commands).
#![no_main]

#[path = "input_surface.rs"]
mod input_surface;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    input_surface::wire_messages(data);
});
