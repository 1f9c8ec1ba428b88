//! Trajectory cases: every line of a JSONL file is run or answered with an
//! error line.
#![no_main]

#[path = "input_surface.rs"]
mod input_surface;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    input_surface::trajectory_cases(data);
});
