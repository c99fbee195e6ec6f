//! Torsional restitution (section 4, Eqs 28–31): the bilinear model of the
//! spin `ω_n` about the contact normal.
//!
//! The normal impact is that of the body's centre (`V_n = −e v_n`,
//! `P_n = m (1 + e) |v_n|`). Low spin, `|ω_n| ≤ ω_s`: `Ω_n = −e_z ω_n` (Eq 28).
//! High spin: rotational sliding continues through separation and Eq 29 gives
//! `Ω_n = (1 − e_z) ω_n − sgn(ω_n) μ_z ρ_p m (1 + e) |v_n| / I_n` (Eq 30, with the
//! friction impulse opposing the spin and `ρ_D` read as `ρ_p`). The branches
//! meet at `ω_s = μ_z ρ_p m (1 + e) |v_n| / I_n` (Eq 31). As in the paper, the
//! restitution moment `−e_z I_n ω_n` of Eq 29 acts outside the friction cap.

use crate::error::{ImpactError, Input, Output, Result, finite, finite_output, in_range, positive};

/// A torsional impact request.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionalImpact {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Moment of inertia about the normal axis `I_n > 0`.
    pub normal_inertia: f64,
    /// Initial normal velocity `v_n < 0`.
    pub normal_velocity: f64,
    /// Initial spin about the normal `ω_n`.
    pub spin: f64,
    /// Kinematic coefficient of restitution `e ∈ [0, 1]`.
    pub restitution: f64,
    /// Torsional coefficient of restitution `e_z ∈ [0, 1]`.
    pub torsional_restitution: f64,
    /// Torsional friction coefficient `μ_z ≥ 0` (a magnitude).
    pub torsional_friction: f64,
    /// Pitch radius `ρ_p > 0` of the torsional friction impulse.
    pub pitch_radius: f64,
}

/// Which branch of the torsional model applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TorsionalRegime {
    /// `|ω_n| ≤ ω_s`: `Ω_n = −e_z ω_n` (Eq 28).
    Restitution,
    /// `|ω_n| > ω_s`: rotational sliding through separation (Eq 30).
    Sliding,
}

impl TorsionalRegime {
    /// The regime's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            TorsionalRegime::Restitution => "restitution",
            TorsionalRegime::Sliding => "sliding",
        }
    }
}

/// Rotational kinetic energy about the normal axis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RotationalEnergy {
    /// `½ I_n ω_n²`.
    pub initial: f64,
    /// `½ I_n Ω_n²`.
    pub r#final: f64,
    /// `½ I_n (ω_n − Ω_n)(ω_n + Ω_n) ≥ 0`.
    pub loss: f64,
}

/// The outcome of a torsional impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionalOutcome {
    /// Final normal velocity `V_n = −e v_n`.
    pub final_normal_velocity: f64,
    /// Final spin `Ω_n`.
    pub final_spin: f64,
    /// Normal impulse `P_n = m (1 + e) |v_n|`.
    pub normal_impulse: f64,
    /// Torsional impulse `M_n = I_n (Ω_n − ω_n)` (Eq 29).
    pub torsional_impulse: f64,
    /// The branch used.
    pub regime: TorsionalRegime,
    /// The switch spin magnitude `ω_s` of Eq 31 (`≥ 0`).
    pub switch_spin: f64,
    /// Rotational energies, when asked for.
    pub energy: Option<RotationalEnergy>,
}

/// Solves a torsional impact. `energy` chooses whether energies are computed.
/// The validated inputs of a torsional impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Validated {
    pub m: f64,
    pub i_n: f64,
    pub vn: f64,
    pub w: f64,
    pub e: f64,
    pub ez: f64,
    pub mu_z: f64,
    pub rho: f64,
}

impl TorsionalImpact {
    /// Checks every input's range and that the body approaches (`v_n < 0`).
    pub(crate) fn validate(&self) -> Result<Validated> {
        let m = positive(Input::Mass, self.mass)?;
        let i_n = positive(Input::NormalInertia, self.normal_inertia)?;
        let vn = finite(Input::NormalVelocity, self.normal_velocity)?;
        let w = finite(Input::Spin, self.spin)?;
        let e = in_range(Input::Restitution, self.restitution, 0.0, 1.0)?;
        let ez = in_range(Input::TorsionalRestitution, self.torsional_restitution, 0.0, 1.0)?;
        let mu_z = in_range(
            Input::TorsionalFriction,
            self.torsional_friction,
            0.0,
            f64::INFINITY,
        )?;
        let rho = positive(Input::PitchRadius, self.pitch_radius)?;
        if vn >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: vn,
            });
        }
        Ok(Validated {
            m,
            i_n,
            vn,
            w,
            e,
            ez,
            mu_z,
            rho,
        })
    }
}

/// Solves a torsional impact. `energy` chooses whether energies are computed.
pub fn solve(impact: &TorsionalImpact, energy: bool) -> Result<TorsionalOutcome> {
    let Validated {
        m,
        i_n,
        vn,
        w,
        e,
        ez,
        mu_z,
        rho,
    } = impact.validate()?;
    let qn = (1.0 + e) * -vn;
    let switch_spin = finite_output(Output::SwitchSpin, mu_z * rho * qn * (m / i_n))?;
    let magnitude = w.abs();
    let sign = if w < 0.0 { -1.0 } else { 1.0 };
    // `spin_change` = ω_n − Ω_n and `spin_sum` = ω_n + Ω_n, each from its branch formula.
    let (regime, final_spin, spin_change, spin_sum) = if magnitude <= switch_spin {
        (
            TorsionalRegime::Restitution,
            -ez * w,
            (1.0 + ez) * w,
            (1.0 - ez) * w,
        )
    } else {
        let change = ez.mul_add(magnitude, switch_spin);
        let remaining = (1.0 - ez).mul_add(magnitude, -switch_spin);
        let sum = (2.0 - ez).mul_add(magnitude, -switch_spin);
        (
            TorsionalRegime::Sliding,
            sign * remaining,
            sign * change,
            sign * sum,
        )
    };
    let final_spin = finite_output(Output::FinalSpin, final_spin)?;
    let torsional_impulse = finite_output(Output::TorsionalImpulse, -i_n * spin_change)?;
    let energy = if energy {
        Some(RotationalEnergy {
            initial: finite_output(Output::InitialEnergy, 0.5 * i_n * w * w)?,
            r#final: finite_output(Output::FinalEnergy, 0.5 * i_n * final_spin * final_spin)?,
            loss: finite_output(Output::EnergyLoss, 0.5 * i_n * spin_change * spin_sum)?,
        })
    } else {
        None
    };
    Ok(TorsionalOutcome {
        final_normal_velocity: finite_output(Output::FinalNormalVelocity, -e * vn)?,
        final_spin,
        normal_impulse: finite_output(Output::NormalImpulse, m * qn)?,
        torsional_impulse,
        regime,
        switch_spin,
        energy,
    })
}
