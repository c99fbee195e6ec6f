//! The HTTP service (axum) over the solver.
