//! The general path: the 3×3 linear system of Eqs 1, 2 (or 20) and 3 solved
//! by LU decomposition (nalgebra): a cross-check of the model in tests and a
//! comparator in benchmarks; the service
//! uses the model's closed forms.

use nalgebra::{Matrix3, Vector3};

use restitution::{BarrierScene, PlanarVelocity};

/// The tangential equation closing the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialClosure {
    /// Eq 2: `μ V_n − V_t = μ v_n − v_t`.
    ImpulseRatio(f64),
    /// Eq 20 generalised: `V_t − d_d Ω = V_ct` for a given final `V_ct`.
    ContactVelocity(f64),
}

/// Solves for `(V_n, V_t, Ω)`:
///
/// ```text
/// [ 1     0     d_c ] [V_n]   [ −e (v_n + d_c ω)          ]   (Eq 1)
/// [ μ    −1     0   ] [V_t] = [ μ v_n − v_t               ]   (Eq 2)
/// [ d_c  −d_d  −k²  ] [ Ω ]   [ d_c v_n − d_d v_t − k² ω  ]   (Eq 3 / m)
/// ```
///
/// (the second row becomes `[0, 1, −d_d] = V_ct` for a contact-velocity closure).
/// `None` when the matrix is singular (`D = 0`).
pub fn solve_momentum(
    scene: &BarrierScene,
    restitution: f64,
    closure: TangentialClosure,
) -> Option<PlanarVelocity> {
    let dc = scene.contact().tangential_offset;
    let dd = scene.contact().normal_offset;
    let k2 = scene.body().gyration_squared();
    let v = scene.velocity();
    let vcn = scene.contact_velocity().normal;
    let (row2, rhs2) = match closure {
        TangentialClosure::ImpulseRatio(mu) => ([mu, -1.0, 0.0], mu * v.normal - v.tangential),
        TangentialClosure::ContactVelocity(vct) => ([0.0, 1.0, -dd], vct),
    };
    #[rustfmt::skip]
    let a = Matrix3::new(
        1.0,     0.0, dc,
        row2[0], row2[1], row2[2],
        dc,      -dd, -k2,
    );
    let b = Vector3::new(
        -restitution * vcn,
        rhs2,
        dc * v.normal - dd * v.tangential - k2 * v.angular,
    );
    let x = a.lu().solve(&b)?;
    Some(PlanarVelocity {
        normal: x[0],
        tangential: x[1],
        angular: x[2],
    })
}
