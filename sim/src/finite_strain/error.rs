//! Errors of the finite-strain slab model.

/// Why a finite-strain slab could not be built or solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum FiniteStrainError {
    /// The mesh is unusable (the text says why).
    #[error("mesh: {0}")]
    Mesh(&'static str),
    /// An element turned inside out at a converged or starting state.
    #[error("an element is inverted (J <= 0)")]
    Inverted,
    /// The sparse factorisation failed (the text names the stage).
    #[error("factorisation failed: {0}")]
    Factorisation(&'static str),
    /// Newton's method did not converge even at the smallest load step.
    #[error("Newton's method did not converge at depth {depth_um} µm")]
    NotConverged {
        /// Wire depth where it failed, µm (rounded).
        depth_um: u32,
    },
}
