//! Shared by the surrogate tests: sums over a run's settled window.

use shearcut_sim::surrogate::{
    CutState, ScaleFactors, Surrogate, SurrogateOutput, SweepRun, SweepSample,
};

/// Sums over a run's fractured samples at least 2 mm past the onset (the
/// window of the sawtooth the accuracy report averages, `compare_run`) of a
/// section quantity and the surrogate's counterpart at `scale`, as
/// (section, surrogate); `quantity` gives both at a sample.
pub fn settled_window_sums(
    s: &Surrogate,
    run: &SweepRun,
    scale: &ScaleFactors,
    quantity: impl Fn(&SweepSample, &SurrogateOutput) -> (f64, f64),
) -> (f64, f64) {
    let c = run.case;
    let (mut full, mut surrogate) = (0.0, 0.0);
    for x in run
        .samples
        .iter()
        .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
    {
        let state = CutState {
            depth: x.depth,
            height: c.height,
            half_width: c.half_width,
            fractured: true,
            travel_since_fracture: x.travel_since_fracture,
        };
        let (section, model) = quantity(x, &s.evaluate(c.xi, &state, scale));
        full += section;
        surrogate += model;
    }
    (full, surrogate)
}
