// The evaluation grid and output hash of `surrogate_ratio.rs`'s bit-for-bit
// test.

/// The evaluation grid of the bit-for-bit checks: ξ × states × scales
/// with T = S (ρ = 1), for one surrogate.
fn golden_grid() -> Vec<(f64, CutState, ScaleFactors)> {
    let mut out = Vec::new();
    let xis = [0.0, 0.2, 0.45, 0.75, 1.1, 1.6, 2.4, 3.0];
    let travels = [0.0, 1e-4, 6e-4, 1.5e-3, 3e-3, 5e-3, 8e-3, 1.2e-2, 2e-2];
    let sizes = [(0.03, 0.015), (0.02, 0.025), (0.045, 0.01)];
    let factors = [(1.0, 1.0, 1.0), (0.7, 0.7, 1.3), (1.6, 1.6, 0.5)];
    for &xi in &xis {
        for &(height, half_width) in &sizes {
            for (i, &s) in travels.iter().enumerate() {
                let state = CutState {
                    depth: 1.3e-3 + s + 1e-5 * i as f64,
                    height,
                    half_width,
                    fractured: true,
                    travel_since_fracture: s,
                };
                for &(t, k, f) in &factors {
                    let scale = ScaleFactors {
                        toughness: t,
                        stiffness: k,
                        friction: f,
                    };
                    out.push((xi, state, scale));
                    if i == 0 {
                        let before = CutState {
                            depth: 1e-4,
                            fractured: false,
                            travel_since_fracture: 0.0,
                            ..state
                        };
                        out.push((xi, before, scale));
                    }
                }
            }
        }
    }
    out
}

/// FNV-1a, continued from `h`, over the bits of every format-3 output of
/// `o`, in a fixed order.
fn output_hash(mut h: u64, o: &SurrogateOutput) -> u64 {
    let p = |p: &ScaledParts| [p.by_toughness, p.by_stiffness, p.by_friction_stiffness];
    let mut values = vec![
        o.force_normal,
        o.force_tangential,
        o.work_per_depth,
        o.fracture,
        o.strain,
        o.friction,
        o.deformation,
        o.fracture_onset_depth,
        o.force_normal_slope,
        o.force_tangential_slope,
        o.work_per_depth_slope,
        o.work_per_depth_curvature,
        o.toughness_ratio,
        o.toughness_ratio_slope,
    ];
    values.extend(p(&o.force_normal_parts));
    values.extend(p(&o.force_tangential_parts));
    values.extend(p(&o.work_per_depth_parts));
    for v in values {
        for byte in v.to_bits().to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// The FNV-1a offset basis.
const FNV_START: u64 = 0xcbf2_9ce4_8422_2325;
