//! The named quantities of the service: every input an impact reads and every
//! output it answers, each declared once with its symbol in the paper, its
//! name in words, its path in the case's request or outcome (a JSON pointer
//! on the wire, a column name in a sweep) and its SI unit (`1` for a
//! dimensionless number; none for a name or a law).
//!
//! The lists are macro-generated tables rather than hand-written `match`es in
//! several places, so that adding a quantity is one line here; which case
//! reads or answers a quantity, and how, is said once per case in
//! [`crate::impact`].

use std::fmt;

/// Declares a field-less enum whose variants each carry a symbol, a name, a path and a unit.
macro_rules! quantities {
    (
        $(#[$meta:meta])*
        pub enum $enum:ident {
            $($(#[doc = $doc:literal])* $variant:ident => ($symbol:literal, $name:literal, $path:literal, $unit:literal),)*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $enum {
            $($(#[doc = $doc])* $variant,)*
        }

        impl $enum {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$enum] = &[$($enum::$variant,)*];

            /// The paper's symbol (or a short name).
            pub fn symbol(self) -> &'static str {
                match self {
                    $($enum::$variant => $symbol,)*
                }
            }

            /// A plain-words name.
            pub fn name(self) -> &'static str {
                match self {
                    $($enum::$variant => $name,)*
                }
            }

            /// Where the quantity sits in a request or outcome (a JSON pointer).
            pub fn path(self) -> &'static str {
                match self {
                    $($enum::$variant => $path,)*
                }
            }

            /// The SI unit (`m/s`, `rad/s`, `kg`, `kg·m²`, `m`, `N·s`,
            /// `N·m·s`, `J`), [`DIMENSIONLESS`] for a pure number, empty for
            /// a name or a law.
            pub const fn unit(self) -> &'static str {
                match self {
                    $($enum::$variant => $unit,)*
                }
            }

            /// An axis label: the name, the symbol (`_` before a subscript, as
            /// [`crate::plot`] writes it) and the unit in parentheses, e.g.
            /// `tangential velocity v_t (m/s)`, `friction coefficient f (dimensionless)`.
            pub fn label(self) -> String {
                let unit = match self.unit() {
                    "" => String::new(),
                    DIMENSIONLESS => " (dimensionless)".to_owned(),
                    unit => format!(" ({unit})"),
                };
                format!("{} {}{unit}", self.name(), self.symbol())
            }
        }
    };
}

/// The unit of a dimensionless number.
pub const DIMENSIONLESS: &str = "1";

quantities! {
    /// A named input of an impact request.
    pub enum Input {
        /// Mass `m`.
        Mass => ("m", "mass", "/body/mass", "kg"),
        /// Centroidal moment of inertia `I = m k²`.
        Inertia => ("I", "moment of inertia", "/body/inertia", "kg·m²"),
        /// Tangential offset `d_c` of the centre of mass from the contact point.
        TangentialOffset => ("d_c", "tangential offset", "/contact/tangential_offset", "m"),
        /// Normal offset `d_d` of the centre of mass from the contact point.
        NormalOffset => ("d_d", "normal offset", "/contact/normal_offset", "m"),
        /// Initial normal velocity of the centre of mass `v_n`.
        NormalVelocity => ("v_n", "normal velocity", "/velocity/normal", "m/s"),
        /// Initial tangential velocity of the centre of mass `v_t`.
        TangentialVelocity => ("v_t", "tangential velocity", "/velocity/tangential", "m/s"),
        /// Initial angular velocity `ω`.
        AngularVelocity => ("ω", "angular velocity", "/velocity/angular", "rad/s"),
        /// Kinematic coefficient of restitution `e`.
        Restitution => ("e", "coefficient of restitution", "/restitution", "1"),
        /// Coulomb friction coefficient `f`.
        Friction => ("f", "friction coefficient", "/friction", "1"),
        /// Prescribed impulse ratio `μ`.
        ImpulseRatio => ("μ", "impulse ratio", "/impulse_ratio", "1"),
        /// Tangential coefficient of restitution `e_t`.
        TangentialRestitution => ("e_t", "tangential coefficient of restitution", "/tangential_restitution", "1"),
        /// Kinetic coefficient of restitution `R`.
        KineticRestitution => ("R", "kinetic coefficient of restitution", "/kinetic_restitution/value", "1"),
        /// Approach-phase impulse ratio `μ_A`.
        ApproachImpulseRatio => ("μ_A", "approach impulse ratio", "/kinetic_restitution/approach_impulse_ratio", "1"),
        /// Approach-phase Coulomb friction coefficient `f_A` (in space).
        ApproachFriction => ("f_A", "approach friction coefficient", "/kinetic_restitution/approach_friction", "1"),
        /// Rebound-phase impulse ratio `μ_R`.
        ReboundImpulseRatio => ("μ_R", "rebound impulse ratio", "/kinetic_restitution/rebound_impulse_ratio", "1"),
        /// Moment of inertia about the normal axis `I_n`.
        NormalInertia => ("I_n", "moment of inertia about the normal", "/body/normal_inertia", "kg·m²"),
        /// Initial spin about the normal axis `ω_n`.
        Spin => ("ω_n", "spin about the normal", "/velocity/spin", "rad/s"),
        /// Torsional coefficient of restitution `e_z`.
        TorsionalRestitution => ("e_z", "torsional coefficient of restitution", "/torsion/restitution", "1"),
        /// Torsional friction coefficient `μ_z`.
        TorsionalFriction => ("μ_z", "torsional friction coefficient", "/torsion/friction", "1"),
        /// Pitch radius `ρ_p` of the torsional friction impulse.
        PitchRadius => ("ρ_p", "pitch radius", "/torsion/pitch_radius", "m"),
        /// Mass of body A.
        MassA => ("m_A", "mass of body A", "/bodies/0/mass", "kg"),
        /// Moment of inertia of body A about its mass centre.
        InertiaA => ("I_A", "moment of inertia of body A", "/bodies/0/inertia", "kg·m²"),
        /// x of body A's mass centre.
        PositionAX => ("x_A", "x of body A", "/bodies/0/position/x", "m"),
        /// y of body A's mass centre.
        PositionAY => ("y_A", "y of body A", "/bodies/0/position/y", "m"),
        /// Initial x velocity of body A.
        VelocityAX => ("v_Ax", "x velocity of body A", "/bodies/0/velocity/x", "m/s"),
        /// Initial y velocity of body A.
        VelocityAY => ("v_Ay", "y velocity of body A", "/bodies/0/velocity/y", "m/s"),
        /// Initial angular velocity of body A.
        AngularVelocityA => ("ω_A", "angular velocity of body A", "/bodies/0/angular_velocity", "rad/s"),
        /// Mass of body B.
        MassB => ("m_B", "mass of body B", "/bodies/1/mass", "kg"),
        /// Moment of inertia of body B about its mass centre.
        InertiaB => ("I_B", "moment of inertia of body B", "/bodies/1/inertia", "kg·m²"),
        /// x of body B's mass centre.
        PositionBX => ("x_B", "x of body B", "/bodies/1/position/x", "m"),
        /// y of body B's mass centre.
        PositionBY => ("y_B", "y of body B", "/bodies/1/position/y", "m"),
        /// Initial x velocity of body B.
        VelocityBX => ("v_Bx", "x velocity of body B", "/bodies/1/velocity/x", "m/s"),
        /// Initial y velocity of body B.
        VelocityBY => ("v_By", "y velocity of body B", "/bodies/1/velocity/y", "m/s"),
        /// Initial angular velocity of body B.
        AngularVelocityB => ("ω_B", "angular velocity of body B", "/bodies/1/angular_velocity", "rad/s"),
        /// x of the contact point.
        ContactX => ("x_C", "x of the contact point", "/contact/point/x", "m"),
        /// y of the contact point.
        ContactY => ("y_C", "y of the contact point", "/contact/point/y", "m"),
        /// x of the contact normal (from B into A).
        NormalX => ("n_x", "x of the contact normal", "/contact/normal/x", "1"),
        /// y of the contact normal.
        NormalY => ("n_y", "y of the contact normal", "/contact/normal/y", "1"),
        /// Body A's velocity as a whole (the approach a refusal names).
        VelocityA => ("v_A", "velocity of body A", "/bodies/0/velocity", "m/s"),
        /// The contact normal as a whole.
        Normal => ("n", "contact normal", "/contact/normal", "1"),
        /// Inertia tensor entry `I_xx` of body A.
        InertiaAXX => ("I_Axx", "inertia tensor entry xx of body A", "/bodies/0/inertia/xx", "kg·m²"),
        /// Inertia tensor entry `I_yy` of body A.
        InertiaAYY => ("I_Ayy", "inertia tensor entry yy of body A", "/bodies/0/inertia/yy", "kg·m²"),
        /// Inertia tensor entry `I_zz` of body A.
        InertiaAZZ => ("I_Azz", "inertia tensor entry zz of body A", "/bodies/0/inertia/zz", "kg·m²"),
        /// Inertia tensor entry `I_xy` of body A.
        InertiaAXY => ("I_Axy", "inertia tensor entry xy of body A", "/bodies/0/inertia/xy", "kg·m²"),
        /// Inertia tensor entry `I_xz` of body A.
        InertiaAXZ => ("I_Axz", "inertia tensor entry xz of body A", "/bodies/0/inertia/xz", "kg·m²"),
        /// Inertia tensor entry `I_yz` of body A.
        InertiaAYZ => ("I_Ayz", "inertia tensor entry yz of body A", "/bodies/0/inertia/yz", "kg·m²"),
        /// z of body A's mass centre.
        PositionAZ => ("z_A", "z of body A", "/bodies/0/position/z", "m"),
        /// Initial z velocity of body A.
        VelocityAZ => ("v_Az", "z velocity of body A", "/bodies/0/velocity/z", "m/s"),
        /// Initial x angular velocity of body A (space).
        AngularVelocityAX => ("ω_Ax", "x angular velocity of body A", "/bodies/0/angular_velocity/x", "rad/s"),
        /// Initial y angular velocity of body A (space).
        AngularVelocityAY => ("ω_Ay", "y angular velocity of body A", "/bodies/0/angular_velocity/y", "rad/s"),
        /// Initial z angular velocity of body A (space).
        AngularVelocityAZ => ("ω_Az", "z angular velocity of body A", "/bodies/0/angular_velocity/z", "rad/s"),
        /// Inertia tensor entry `I_xx` of body B.
        InertiaBXX => ("I_Bxx", "inertia tensor entry xx of body B", "/bodies/1/inertia/xx", "kg·m²"),
        /// Inertia tensor entry `I_yy` of body B.
        InertiaBYY => ("I_Byy", "inertia tensor entry yy of body B", "/bodies/1/inertia/yy", "kg·m²"),
        /// Inertia tensor entry `I_zz` of body B.
        InertiaBZZ => ("I_Bzz", "inertia tensor entry zz of body B", "/bodies/1/inertia/zz", "kg·m²"),
        /// Inertia tensor entry `I_xy` of body B.
        InertiaBXY => ("I_Bxy", "inertia tensor entry xy of body B", "/bodies/1/inertia/xy", "kg·m²"),
        /// Inertia tensor entry `I_xz` of body B.
        InertiaBXZ => ("I_Bxz", "inertia tensor entry xz of body B", "/bodies/1/inertia/xz", "kg·m²"),
        /// Inertia tensor entry `I_yz` of body B.
        InertiaBYZ => ("I_Byz", "inertia tensor entry yz of body B", "/bodies/1/inertia/yz", "kg·m²"),
        /// z of body B's mass centre.
        PositionBZ => ("z_B", "z of body B", "/bodies/1/position/z", "m"),
        /// Initial z velocity of body B.
        VelocityBZ => ("v_Bz", "z velocity of body B", "/bodies/1/velocity/z", "m/s"),
        /// Initial x angular velocity of body B (space).
        AngularVelocityBX => ("ω_Bx", "x angular velocity of body B", "/bodies/1/angular_velocity/x", "rad/s"),
        /// Initial y angular velocity of body B (space).
        AngularVelocityBY => ("ω_By", "y angular velocity of body B", "/bodies/1/angular_velocity/y", "rad/s"),
        /// Initial z angular velocity of body B (space).
        AngularVelocityBZ => ("ω_Bz", "z angular velocity of body B", "/bodies/1/angular_velocity/z", "rad/s"),
        /// z of the contact point.
        ContactZ => ("z_C", "z of the contact point", "/contact/point/z", "m"),
        /// z of the contact normal.
        NormalZ => ("n_z", "z of the contact normal", "/contact/normal/z", "1"),
        /// The twist law as a whole (space).
        Torsion => ("twist", "twist law", "/torsion", ""),
    }
}

impl fmt::Display for Input {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.name(), self.symbol())
    }
}

quantities! {
    /// A named output of an impact outcome.
    pub enum Output {
        /// Final normal velocity `V_n`.
        FinalNormalVelocity => ("V_n", "final normal velocity", "/final_velocity/normal", "m/s"),
        /// Final tangential velocity `V_t`.
        FinalTangentialVelocity => ("V_t", "final tangential velocity", "/final_velocity/tangential", "m/s"),
        /// Final angular velocity `Ω`.
        FinalAngularVelocity => ("Ω", "final angular velocity", "/final_velocity/angular", "rad/s"),
        /// Final spin about the normal `Ω_n`.
        FinalSpin => ("Ω_n", "final spin about the normal", "/final_velocity/spin", "rad/s"),
        /// Initial normal contact-point velocity `v_cn`.
        InitialNormalContactVelocity => ("v_cn", "initial normal contact velocity", "/contact_velocity/initial/normal", "m/s"),
        /// Initial tangential contact-point velocity `v_ct`.
        InitialTangentialContactVelocity => ("v_ct", "initial tangential contact velocity", "/contact_velocity/initial/tangential", "m/s"),
        /// Final normal contact-point velocity `V_cn`.
        FinalNormalContactVelocity => ("V_cn", "final normal contact velocity", "/contact_velocity/final/normal", "m/s"),
        /// Final tangential contact-point velocity `V_ct`.
        FinalTangentialContactVelocity => ("V_ct", "final tangential contact velocity", "/contact_velocity/final/tangential", "m/s"),
        /// Normal impulse `P_n`.
        NormalImpulse => ("P_n", "normal impulse", "/impulse/normal", "N·s"),
        /// Tangential impulse `P_t`.
        TangentialImpulse => ("P_t", "tangential impulse", "/impulse/tangential", "N·s"),
        /// Torsional impulse `M_n`.
        TorsionalImpulse => ("M_n", "torsional impulse", "/impulse/torsional", "N·m·s"),
        /// Applied impulse ratio `μ`.
        ImpulseRatio => ("μ", "impulse ratio", "/impulse_ratio", "1"),
        /// Critical impulse ratio `μ_c`.
        CriticalImpulseRatio => ("μ_c", "critical impulse ratio", "/critical_impulse_ratio", "1"),
        /// Kinematic coefficient of restitution `e`.
        Restitution => ("e", "coefficient of restitution", "/restitution", "1"),
        /// Kinetic coefficient of restitution `R`.
        KineticRestitution => ("R", "kinetic coefficient of restitution", "/kinetic_restitution", "1"),
        /// The regime (which branch of the law answered).
        Regime => ("regime", "regime", "/regime", ""),
        /// Spin at the switch between the torsional branches (Eq 31).
        SwitchSpin => ("ω_switch", "switch spin", "/switch_spin", "rad/s"),
        /// Initial kinetic energy.
        InitialEnergy => ("T_i", "initial kinetic energy", "/energy/initial", "J"),
        /// Final kinetic energy.
        FinalEnergy => ("T_f", "final kinetic energy", "/energy/final", "J"),
        /// Kinetic energy loss `T_L`.
        EnergyLoss => ("T_L", "energy loss", "/energy/loss", "J"),
        /// Maximum energy loss `T_M`.
        MaxEnergyLoss => ("T_M", "maximum energy loss", "/energy/max_loss", "J"),
        /// Normalised energy loss `T_L* = T_L / T_M`.
        NormalizedEnergyLoss => ("T_L*", "normalized energy loss", "/energy/normalized_loss", "1"),
        /// World x of the impulse on A.
        ImpulseX => ("P_x", "x impulse", "/impulse/x", "N·s"),
        /// World y of the impulse on A.
        ImpulseY => ("P_y", "y impulse", "/impulse/y", "N·s"),
        /// Final x velocity of body A.
        FinalVelocityAX => ("V_Ax", "final x velocity of body A", "/bodies/0/velocity/x", "m/s"),
        /// Final y velocity of body A.
        FinalVelocityAY => ("V_Ay", "final y velocity of body A", "/bodies/0/velocity/y", "m/s"),
        /// Final angular velocity of body A.
        FinalAngularVelocityA => ("Ω_A", "final angular velocity of body A", "/bodies/0/angular_velocity", "rad/s"),
        /// x velocity change of body A.
        VelocityChangeAX => ("ΔV_Ax", "x velocity change of body A", "/bodies/0/velocity_change/x", "m/s"),
        /// y velocity change of body A.
        VelocityChangeAY => ("ΔV_Ay", "y velocity change of body A", "/bodies/0/velocity_change/y", "m/s"),
        /// Delta-V of body A, `|ΔV_A|`.
        DeltaVA => ("|ΔV_A|", "delta-V of body A", "/bodies/0/delta_v", "m/s"),
        /// Angular velocity change of body A.
        AngularVelocityChangeA => ("ΔΩ_A", "angular velocity change of body A", "/bodies/0/angular_velocity_change", "rad/s"),
        /// Final x velocity of body B.
        FinalVelocityBX => ("V_Bx", "final x velocity of body B", "/bodies/1/velocity/x", "m/s"),
        /// Final y velocity of body B.
        FinalVelocityBY => ("V_By", "final y velocity of body B", "/bodies/1/velocity/y", "m/s"),
        /// Final angular velocity of body B.
        FinalAngularVelocityB => ("Ω_B", "final angular velocity of body B", "/bodies/1/angular_velocity", "rad/s"),
        /// x velocity change of body B.
        VelocityChangeBX => ("ΔV_Bx", "x velocity change of body B", "/bodies/1/velocity_change/x", "m/s"),
        /// y velocity change of body B.
        VelocityChangeBY => ("ΔV_By", "y velocity change of body B", "/bodies/1/velocity_change/y", "m/s"),
        /// Delta-V of body B, `|ΔV_B|`.
        DeltaVB => ("|ΔV_B|", "delta-V of body B", "/bodies/1/delta_v", "m/s"),
        /// Angular velocity change of body B.
        AngularVelocityChangeB => ("ΔΩ_B", "angular velocity change of body B", "/bodies/1/angular_velocity_change", "rad/s"),
        /// Final z velocity of body A (space).
        FinalVelocityAZ => ("V_Az", "final z velocity of body A", "/bodies/0/velocity/z", "m/s"),
        /// Final x angular velocity of body A (space).
        FinalAngularVelocityAX => ("Ω_Ax", "final x angular velocity of body A", "/bodies/0/angular_velocity/x", "rad/s"),
        /// Final y angular velocity of body A (space).
        FinalAngularVelocityAY => ("Ω_Ay", "final y angular velocity of body A", "/bodies/0/angular_velocity/y", "rad/s"),
        /// Final z angular velocity of body A (space).
        FinalAngularVelocityAZ => ("Ω_Az", "final z angular velocity of body A", "/bodies/0/angular_velocity/z", "rad/s"),
        /// Z velocity change of body A (space).
        VelocityChangeAZ => ("ΔV_Az", "z velocity change of body A", "/bodies/0/velocity_change/z", "m/s"),
        /// X angular velocity change of body A (space).
        AngularVelocityChangeAX => ("ΔΩ_Ax", "x angular velocity change of body A", "/bodies/0/angular_velocity_change/x", "rad/s"),
        /// Y angular velocity change of body A (space).
        AngularVelocityChangeAY => ("ΔΩ_Ay", "y angular velocity change of body A", "/bodies/0/angular_velocity_change/y", "rad/s"),
        /// Z angular velocity change of body A (space).
        AngularVelocityChangeAZ => ("ΔΩ_Az", "z angular velocity change of body A", "/bodies/0/angular_velocity_change/z", "rad/s"),
        /// Final z velocity of body B (space).
        FinalVelocityBZ => ("V_Bz", "final z velocity of body B", "/bodies/1/velocity/z", "m/s"),
        /// Final x angular velocity of body B (space).
        FinalAngularVelocityBX => ("Ω_Bx", "final x angular velocity of body B", "/bodies/1/angular_velocity/x", "rad/s"),
        /// Final y angular velocity of body B (space).
        FinalAngularVelocityBY => ("Ω_By", "final y angular velocity of body B", "/bodies/1/angular_velocity/y", "rad/s"),
        /// Final z angular velocity of body B (space).
        FinalAngularVelocityBZ => ("Ω_Bz", "final z angular velocity of body B", "/bodies/1/angular_velocity/z", "rad/s"),
        /// Z velocity change of body B (space).
        VelocityChangeBZ => ("ΔV_Bz", "z velocity change of body B", "/bodies/1/velocity_change/z", "m/s"),
        /// X angular velocity change of body B (space).
        AngularVelocityChangeBX => ("ΔΩ_Bx", "x angular velocity change of body B", "/bodies/1/angular_velocity_change/x", "rad/s"),
        /// Y angular velocity change of body B (space).
        AngularVelocityChangeBY => ("ΔΩ_By", "y angular velocity change of body B", "/bodies/1/angular_velocity_change/y", "rad/s"),
        /// Z angular velocity change of body B (space).
        AngularVelocityChangeBZ => ("ΔΩ_Bz", "z angular velocity change of body B", "/bodies/1/angular_velocity_change/z", "rad/s"),
        /// Initial tangential contact velocity x (space).
        InitialTangentialContactVelocityX => ("u_tx", "initial tangential contact velocity x", "/contact_velocity/initial/tangential/x", "m/s"),
        /// Initial tangential contact velocity y (space).
        InitialTangentialContactVelocityY => ("u_ty", "initial tangential contact velocity y", "/contact_velocity/initial/tangential/y", "m/s"),
        /// Initial tangential contact velocity z (space).
        InitialTangentialContactVelocityZ => ("u_tz", "initial tangential contact velocity z", "/contact_velocity/initial/tangential/z", "m/s"),
        /// Initial relative spin about the normal (space).
        InitialContactSpin => ("s", "initial relative spin about the normal", "/contact_velocity/initial/spin", "rad/s"),
        /// Final tangential contact velocity x (space).
        FinalTangentialContactVelocityX => ("U_tx", "final tangential contact velocity x", "/contact_velocity/final/tangential/x", "m/s"),
        /// Final tangential contact velocity y (space).
        FinalTangentialContactVelocityY => ("U_ty", "final tangential contact velocity y", "/contact_velocity/final/tangential/y", "m/s"),
        /// Final tangential contact velocity z (space).
        FinalTangentialContactVelocityZ => ("U_tz", "final tangential contact velocity z", "/contact_velocity/final/tangential/z", "m/s"),
        /// Final relative spin about the normal (space).
        FinalContactSpin => ("S", "final relative spin about the normal", "/contact_velocity/final/spin", "rad/s"),
        /// Tangential impulse x (space).
        TangentialImpulseX => ("P_tx", "tangential impulse x", "/impulse/tangential/x", "N·s"),
        /// Tangential impulse y (space).
        TangentialImpulseY => ("P_ty", "tangential impulse y", "/impulse/tangential/y", "N·s"),
        /// Tangential impulse z (space).
        TangentialImpulseZ => ("P_tz", "tangential impulse z", "/impulse/tangential/z", "N·s"),
        /// Z impulse (space).
        ImpulseZ => ("P_z", "z impulse", "/impulse/z", "N·s"),
        /// Torsional regime (space).
        TorsionalRegime => ("torsional_regime", "torsional regime", "/torsional_regime", ""),
    }
}

impl Output {
    /// Whether this output is a name (a regime), not a number.
    pub fn is_name(self) -> bool {
        matches!(self, Output::Regime | Output::TorsionalRegime)
    }

    /// Whether computing this output needs the energies.
    pub fn needs_energy(self) -> bool {
        matches!(
            self,
            Output::InitialEnergy
                | Output::FinalEnergy
                | Output::EnergyLoss
                | Output::MaxEnergyLoss
                | Output::NormalizedEnergyLoss
        )
    }
}

impl fmt::Display for Output {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

/// One output's value: a number, or a name (a regime).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A number.
    Number(f64),
    /// A name.
    Text(&'static str),
}

impl Value {
    /// The number, or `NaN` for a name.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn number(self) -> f64 {
        match self {
            Value::Number(x) => x,
            Value::Text(_) => f64::NAN,
        }
    }
}

impl From<f64> for Value {
    #[inline]
    fn from(x: f64) -> Self {
        Value::Number(x)
    }
}

impl From<&'static str> for Value {
    #[inline]
    fn from(name: &'static str) -> Self {
        Value::Text(name)
    }
}

/// `N` consecutive entries of a declared list from `start`: a part of one
/// declaration (a body's inputs or outputs) as a constant, not a second list.
pub(crate) const fn part<T: Copy, const N: usize>(list: &[T], start: usize) -> [T; N] {
    let mut out = [list[start]; N];
    let mut i = 0;
    while i < N {
        out[i] = list[start + i];
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_json_pointers_and_unique_per_list() {
        for list in [
            Input::ALL.iter().map(|i| i.path()).collect::<Vec<_>>(),
            Output::ALL.iter().map(|o| o.path()).collect(),
        ] {
            for (i, p) in list.iter().enumerate() {
                assert!(p.starts_with('/') && !p.ends_with('/'), "{p}");
                assert!(!list[i + 1..].contains(p), "{p} twice");
            }
        }
    }

    #[test]
    fn every_number_has_an_si_unit_and_names_have_none() {
        const SI: [&str; 9] = [
            DIMENSIONLESS,
            "m/s",
            "rad/s",
            "kg",
            "kg·m²",
            "m",
            "N·s",
            "N·m·s",
            "J",
        ];
        for output in Output::ALL {
            if output.is_name() {
                assert_eq!(output.unit(), "", "{output:?}");
            } else {
                assert!(SI.contains(&output.unit()), "{output:?}: {:?}", output.unit());
            }
        }
        for input in Input::ALL.iter().filter(|&&i| i != Input::Torsion) {
            assert!(SI.contains(&input.unit()), "{input:?}: {:?}", input.unit());
        }
        assert_eq!(Input::Torsion.unit(), "");
        assert_eq!(Input::TangentialVelocity.label(), "tangential velocity v_t (m/s)");
        assert_eq!(Input::Friction.label(), "friction coefficient f (dimensionless)");
        assert_eq!(Output::TorsionalImpulse.label(), "torsional impulse M_n (N·m·s)");
        assert_eq!(Output::Regime.label(), "regime regime");
        assert_eq!(Output::EnergyLoss.unit(), "J");
        assert_eq!(Input::Inertia.unit(), "kg·m²");
    }
}
