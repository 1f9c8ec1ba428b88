//! Scenario TOML: any text is parsed, resolved and validated, or refused
//! with one line; never a panic, never a runaway.
#![no_main]

#[path = "input_surface.rs"]
mod input_surface;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    input_surface::scenario_toml(data);
});
