//! The Pareto front of a scenario group: the settings no other setting
//! beats on every objective at once (work, maximum deformation, peak
//! vertical force, time; each setting by its mean over its runs).

/// Whether `a` dominates `b`: no worse on every objective and better on
/// one (all objectives to be made small).
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| x <= y) && a.iter().zip(b).any(|(x, y)| x < y)
}

/// Which of `points` lie on the front: those no other point dominates.
/// Equal points are all on it.
pub fn front(points: &[&[f64]]) -> Vec<bool> {
    points
        .iter()
        .map(|p| !points.iter().any(|q| dominates(q, p)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_keeps_the_trade_offs_and_drops_the_dominated() {
        let pts: [&[f64]; 5] = [
            &[1.0, 4.0],
            &[2.0, 2.0],
            &[4.0, 1.0],
            &[3.0, 3.0], // beaten by (2, 2)
            &[2.0, 2.0], // equal to a front point: on it too
        ];
        assert_eq!(front(&pts), [true, true, true, false, true]);
        assert!(!dominates(&[1.0, 1.0], &[1.0, 1.0]));
        assert!(dominates(&[1.0, 1.0], &[1.0, 1.5]));
    }
}
