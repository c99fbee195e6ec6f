//! The named quantities of the service: every input an impact reads and every
//! output it answers, each declared once with its symbol in the paper, its
//! name in words and its path in the case's request or outcome (a JSON pointer
//! on the wire, a column name in a sweep).
//!
//! The lists are macro-generated tables rather than hand-written `match`es in
//! several places, so that adding a quantity is one line here; which case
//! reads or answers a quantity, and how, is said once per case in
//! [`crate::impact`].

use std::fmt;

/// Declares a field-less enum whose variants each carry a symbol, a name and a path.
macro_rules! quantities {
    (
        $(#[$meta:meta])*
        pub enum $enum:ident {
            $($(#[doc = $doc:literal])* $variant:ident => ($symbol:literal, $name:literal, $path:literal),)*
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
        }
    };
}

quantities! {
    /// A named input of an impact request.
    pub enum Input {
        /// Mass `m`.
        Mass => ("m", "mass", "/body/mass"),
        /// Centroidal moment of inertia `I = m k²`.
        Inertia => ("I", "moment of inertia", "/body/inertia"),
        /// Tangential offset `d_c` of the centre of mass from the contact point.
        TangentialOffset => ("d_c", "tangential offset", "/contact/tangential_offset"),
        /// Normal offset `d_d` of the centre of mass from the contact point.
        NormalOffset => ("d_d", "normal offset", "/contact/normal_offset"),
        /// Initial normal velocity of the centre of mass `v_n`.
        NormalVelocity => ("v_n", "normal velocity", "/velocity/normal"),
        /// Initial tangential velocity of the centre of mass `v_t`.
        TangentialVelocity => ("v_t", "tangential velocity", "/velocity/tangential"),
        /// Initial angular velocity `ω`.
        AngularVelocity => ("ω", "angular velocity", "/velocity/angular"),
        /// Kinematic coefficient of restitution `e`.
        Restitution => ("e", "coefficient of restitution", "/restitution"),
        /// Coulomb friction coefficient `f`.
        Friction => ("f", "friction coefficient", "/friction"),
        /// Prescribed impulse ratio `μ`.
        ImpulseRatio => ("μ", "impulse ratio", "/impulse_ratio"),
        /// Tangential coefficient of restitution `e_t`.
        TangentialRestitution => ("e_t", "tangential coefficient of restitution", "/tangential_restitution"),
        /// Kinetic coefficient of restitution `R`.
        KineticRestitution => ("R", "kinetic coefficient of restitution", "/kinetic_restitution/value"),
        /// Approach-phase impulse ratio `μ_A`.
        ApproachImpulseRatio => ("μ_A", "approach impulse ratio", "/kinetic_restitution/approach_impulse_ratio"),
        /// Rebound-phase impulse ratio `μ_R`.
        ReboundImpulseRatio => ("μ_R", "rebound impulse ratio", "/kinetic_restitution/rebound_impulse_ratio"),
        /// Moment of inertia about the normal axis `I_n`.
        NormalInertia => ("I_n", "moment of inertia about the normal", "/body/normal_inertia"),
        /// Initial spin about the normal axis `ω_n`.
        Spin => ("ω_n", "spin about the normal", "/velocity/spin"),
        /// Torsional coefficient of restitution `e_z`.
        TorsionalRestitution => ("e_z", "torsional coefficient of restitution", "/torsion/restitution"),
        /// Torsional friction coefficient `μ_z`.
        TorsionalFriction => ("μ_z", "torsional friction coefficient", "/torsion/friction"),
        /// Pitch radius `ρ_p` of the torsional friction impulse.
        PitchRadius => ("ρ_p", "pitch radius", "/torsion/pitch_radius"),
        /// Mass of body A.
        MassA => ("m_A", "mass of body A", "/bodies/0/mass"),
        /// Moment of inertia of body A about its mass centre.
        InertiaA => ("I_A", "moment of inertia of body A", "/bodies/0/inertia"),
        /// x of body A's mass centre.
        PositionAX => ("x_A", "x of body A", "/bodies/0/position/x"),
        /// y of body A's mass centre.
        PositionAY => ("y_A", "y of body A", "/bodies/0/position/y"),
        /// Initial x velocity of body A.
        VelocityAX => ("v_Ax", "x velocity of body A", "/bodies/0/velocity/x"),
        /// Initial y velocity of body A.
        VelocityAY => ("v_Ay", "y velocity of body A", "/bodies/0/velocity/y"),
        /// Initial angular velocity of body A.
        AngularVelocityA => ("ω_A", "angular velocity of body A", "/bodies/0/angular_velocity"),
        /// Mass of body B.
        MassB => ("m_B", "mass of body B", "/bodies/1/mass"),
        /// Moment of inertia of body B about its mass centre.
        InertiaB => ("I_B", "moment of inertia of body B", "/bodies/1/inertia"),
        /// x of body B's mass centre.
        PositionBX => ("x_B", "x of body B", "/bodies/1/position/x"),
        /// y of body B's mass centre.
        PositionBY => ("y_B", "y of body B", "/bodies/1/position/y"),
        /// Initial x velocity of body B.
        VelocityBX => ("v_Bx", "x velocity of body B", "/bodies/1/velocity/x"),
        /// Initial y velocity of body B.
        VelocityBY => ("v_By", "y velocity of body B", "/bodies/1/velocity/y"),
        /// Initial angular velocity of body B.
        AngularVelocityB => ("ω_B", "angular velocity of body B", "/bodies/1/angular_velocity"),
        /// x of the contact point.
        ContactX => ("x_C", "x of the contact point", "/contact/point/x"),
        /// y of the contact point.
        ContactY => ("y_C", "y of the contact point", "/contact/point/y"),
        /// x of the contact normal (from B into A).
        NormalX => ("n_x", "x of the contact normal", "/contact/normal/x"),
        /// y of the contact normal.
        NormalY => ("n_y", "y of the contact normal", "/contact/normal/y"),
        /// Body A's velocity as a whole (the approach a refusal names).
        VelocityA => ("v_A", "velocity of body A", "/bodies/0/velocity"),
        /// The contact normal as a whole.
        Normal => ("n", "contact normal", "/contact/normal"),
        /// Inertia tensor entry `I_xx` of body A.
        InertiaAXX => ("I_Axx", "inertia tensor entry xx of body A", "/bodies/0/inertia/xx"),
        /// Inertia tensor entry `I_yy` of body A.
        InertiaAYY => ("I_Ayy", "inertia tensor entry yy of body A", "/bodies/0/inertia/yy"),
        /// Inertia tensor entry `I_zz` of body A.
        InertiaAZZ => ("I_Azz", "inertia tensor entry zz of body A", "/bodies/0/inertia/zz"),
        /// Inertia tensor entry `I_xy` of body A.
        InertiaAXY => ("I_Axy", "inertia tensor entry xy of body A", "/bodies/0/inertia/xy"),
        /// Inertia tensor entry `I_xz` of body A.
        InertiaAXZ => ("I_Axz", "inertia tensor entry xz of body A", "/bodies/0/inertia/xz"),
        /// Inertia tensor entry `I_yz` of body A.
        InertiaAYZ => ("I_Ayz", "inertia tensor entry yz of body A", "/bodies/0/inertia/yz"),
        /// z of body A's mass centre.
        PositionAZ => ("z_A", "z of body A", "/bodies/0/position/z"),
        /// Initial z velocity of body A.
        VelocityAZ => ("v_Az", "z velocity of body A", "/bodies/0/velocity/z"),
        /// Initial x angular velocity of body A (space).
        AngularVelocityAX => ("ω_Ax", "x angular velocity of body A", "/bodies/0/angular_velocity/x"),
        /// Initial y angular velocity of body A (space).
        AngularVelocityAY => ("ω_Ay", "y angular velocity of body A", "/bodies/0/angular_velocity/y"),
        /// Initial z angular velocity of body A (space).
        AngularVelocityAZ => ("ω_Az", "z angular velocity of body A", "/bodies/0/angular_velocity/z"),
        /// Inertia tensor entry `I_xx` of body B.
        InertiaBXX => ("I_Bxx", "inertia tensor entry xx of body B", "/bodies/1/inertia/xx"),
        /// Inertia tensor entry `I_yy` of body B.
        InertiaBYY => ("I_Byy", "inertia tensor entry yy of body B", "/bodies/1/inertia/yy"),
        /// Inertia tensor entry `I_zz` of body B.
        InertiaBZZ => ("I_Bzz", "inertia tensor entry zz of body B", "/bodies/1/inertia/zz"),
        /// Inertia tensor entry `I_xy` of body B.
        InertiaBXY => ("I_Bxy", "inertia tensor entry xy of body B", "/bodies/1/inertia/xy"),
        /// Inertia tensor entry `I_xz` of body B.
        InertiaBXZ => ("I_Bxz", "inertia tensor entry xz of body B", "/bodies/1/inertia/xz"),
        /// Inertia tensor entry `I_yz` of body B.
        InertiaBYZ => ("I_Byz", "inertia tensor entry yz of body B", "/bodies/1/inertia/yz"),
        /// z of body B's mass centre.
        PositionBZ => ("z_B", "z of body B", "/bodies/1/position/z"),
        /// Initial z velocity of body B.
        VelocityBZ => ("v_Bz", "z velocity of body B", "/bodies/1/velocity/z"),
        /// Initial x angular velocity of body B (space).
        AngularVelocityBX => ("ω_Bx", "x angular velocity of body B", "/bodies/1/angular_velocity/x"),
        /// Initial y angular velocity of body B (space).
        AngularVelocityBY => ("ω_By", "y angular velocity of body B", "/bodies/1/angular_velocity/y"),
        /// Initial z angular velocity of body B (space).
        AngularVelocityBZ => ("ω_Bz", "z angular velocity of body B", "/bodies/1/angular_velocity/z"),
        /// z of the contact point.
        ContactZ => ("z_C", "z of the contact point", "/contact/point/z"),
        /// z of the contact normal.
        NormalZ => ("n_z", "z of the contact normal", "/contact/normal/z"),
        /// The twist law as a whole (space).
        Torsion => ("twist", "twist law", "/torsion"),
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
        FinalNormalVelocity => ("V_n", "final normal velocity", "/final_velocity/normal"),
        /// Final tangential velocity `V_t`.
        FinalTangentialVelocity => ("V_t", "final tangential velocity", "/final_velocity/tangential"),
        /// Final angular velocity `Ω`.
        FinalAngularVelocity => ("Ω", "final angular velocity", "/final_velocity/angular"),
        /// Final spin about the normal `Ω_n`.
        FinalSpin => ("Ω_n", "final spin about the normal", "/final_velocity/spin"),
        /// Initial normal contact-point velocity `v_cn`.
        InitialNormalContactVelocity => ("v_cn", "initial normal contact velocity", "/contact_velocity/initial/normal"),
        /// Initial tangential contact-point velocity `v_ct`.
        InitialTangentialContactVelocity => ("v_ct", "initial tangential contact velocity", "/contact_velocity/initial/tangential"),
        /// Final normal contact-point velocity `V_cn`.
        FinalNormalContactVelocity => ("V_cn", "final normal contact velocity", "/contact_velocity/final/normal"),
        /// Final tangential contact-point velocity `V_ct`.
        FinalTangentialContactVelocity => ("V_ct", "final tangential contact velocity", "/contact_velocity/final/tangential"),
        /// Normal impulse `P_n`.
        NormalImpulse => ("P_n", "normal impulse", "/impulse/normal"),
        /// Tangential impulse `P_t`.
        TangentialImpulse => ("P_t", "tangential impulse", "/impulse/tangential"),
        /// Torsional impulse `M_n`.
        TorsionalImpulse => ("M_n", "torsional impulse", "/impulse/torsional"),
        /// Applied impulse ratio `μ`.
        ImpulseRatio => ("μ", "impulse ratio", "/impulse_ratio"),
        /// Critical impulse ratio `μ_c`.
        CriticalImpulseRatio => ("μ_c", "critical impulse ratio", "/critical_impulse_ratio"),
        /// Kinematic coefficient of restitution `e`.
        Restitution => ("e", "coefficient of restitution", "/restitution"),
        /// Kinetic coefficient of restitution `R`.
        KineticRestitution => ("R", "kinetic coefficient of restitution", "/kinetic_restitution"),
        /// The regime (which branch of the law answered).
        Regime => ("regime", "regime", "/regime"),
        /// Spin at the switch between the torsional branches (Eq 31).
        SwitchSpin => ("ω_switch", "switch spin", "/switch_spin"),
        /// Initial kinetic energy.
        InitialEnergy => ("T_i", "initial kinetic energy", "/energy/initial"),
        /// Final kinetic energy.
        FinalEnergy => ("T_f", "final kinetic energy", "/energy/final"),
        /// Kinetic energy loss `T_L`.
        EnergyLoss => ("T_L", "energy loss", "/energy/loss"),
        /// Maximum energy loss `T_M`.
        MaxEnergyLoss => ("T_M", "maximum energy loss", "/energy/max_loss"),
        /// Normalised energy loss `T_L* = T_L / T_M`.
        NormalizedEnergyLoss => ("T_L*", "normalized energy loss", "/energy/normalized_loss"),
        /// World x of the impulse on A.
        ImpulseX => ("P_x", "x impulse", "/impulse/x"),
        /// World y of the impulse on A.
        ImpulseY => ("P_y", "y impulse", "/impulse/y"),
        /// Final x velocity of body A.
        FinalVelocityAX => ("V_Ax", "final x velocity of body A", "/bodies/0/velocity/x"),
        /// Final y velocity of body A.
        FinalVelocityAY => ("V_Ay", "final y velocity of body A", "/bodies/0/velocity/y"),
        /// Final angular velocity of body A.
        FinalAngularVelocityA => ("Ω_A", "final angular velocity of body A", "/bodies/0/angular_velocity"),
        /// x velocity change of body A.
        VelocityChangeAX => ("ΔV_Ax", "x velocity change of body A", "/bodies/0/velocity_change/x"),
        /// y velocity change of body A.
        VelocityChangeAY => ("ΔV_Ay", "y velocity change of body A", "/bodies/0/velocity_change/y"),
        /// Delta-V of body A, `|ΔV_A|`.
        DeltaVA => ("|ΔV_A|", "delta-V of body A", "/bodies/0/delta_v"),
        /// Angular velocity change of body A.
        AngularVelocityChangeA => ("ΔΩ_A", "angular velocity change of body A", "/bodies/0/angular_velocity_change"),
        /// Final x velocity of body B.
        FinalVelocityBX => ("V_Bx", "final x velocity of body B", "/bodies/1/velocity/x"),
        /// Final y velocity of body B.
        FinalVelocityBY => ("V_By", "final y velocity of body B", "/bodies/1/velocity/y"),
        /// Final angular velocity of body B.
        FinalAngularVelocityB => ("Ω_B", "final angular velocity of body B", "/bodies/1/angular_velocity"),
        /// x velocity change of body B.
        VelocityChangeBX => ("ΔV_Bx", "x velocity change of body B", "/bodies/1/velocity_change/x"),
        /// y velocity change of body B.
        VelocityChangeBY => ("ΔV_By", "y velocity change of body B", "/bodies/1/velocity_change/y"),
        /// Delta-V of body B, `|ΔV_B|`.
        DeltaVB => ("|ΔV_B|", "delta-V of body B", "/bodies/1/delta_v"),
        /// Angular velocity change of body B.
        AngularVelocityChangeB => ("ΔΩ_B", "angular velocity change of body B", "/bodies/1/angular_velocity_change"),
        /// Final z velocity of body A (space).
        FinalVelocityAZ => ("V_Az", "final z velocity of body A", "/bodies/0/velocity/z"),
        /// Final x angular velocity of body A (space).
        FinalAngularVelocityAX => ("Ω_Ax", "final x angular velocity of body A", "/bodies/0/angular_velocity/x"),
        /// Final y angular velocity of body A (space).
        FinalAngularVelocityAY => ("Ω_Ay", "final y angular velocity of body A", "/bodies/0/angular_velocity/y"),
        /// Final z angular velocity of body A (space).
        FinalAngularVelocityAZ => ("Ω_Az", "final z angular velocity of body A", "/bodies/0/angular_velocity/z"),
        /// Z velocity change of body A (space).
        VelocityChangeAZ => ("ΔV_Az", "z velocity change of body A", "/bodies/0/velocity_change/z"),
        /// X angular velocity change of body A (space).
        AngularVelocityChangeAX => ("ΔΩ_Ax", "x angular velocity change of body A", "/bodies/0/angular_velocity_change/x"),
        /// Y angular velocity change of body A (space).
        AngularVelocityChangeAY => ("ΔΩ_Ay", "y angular velocity change of body A", "/bodies/0/angular_velocity_change/y"),
        /// Z angular velocity change of body A (space).
        AngularVelocityChangeAZ => ("ΔΩ_Az", "z angular velocity change of body A", "/bodies/0/angular_velocity_change/z"),
        /// Final z velocity of body B (space).
        FinalVelocityBZ => ("V_Bz", "final z velocity of body B", "/bodies/1/velocity/z"),
        /// Final x angular velocity of body B (space).
        FinalAngularVelocityBX => ("Ω_Bx", "final x angular velocity of body B", "/bodies/1/angular_velocity/x"),
        /// Final y angular velocity of body B (space).
        FinalAngularVelocityBY => ("Ω_By", "final y angular velocity of body B", "/bodies/1/angular_velocity/y"),
        /// Final z angular velocity of body B (space).
        FinalAngularVelocityBZ => ("Ω_Bz", "final z angular velocity of body B", "/bodies/1/angular_velocity/z"),
        /// Z velocity change of body B (space).
        VelocityChangeBZ => ("ΔV_Bz", "z velocity change of body B", "/bodies/1/velocity_change/z"),
        /// X angular velocity change of body B (space).
        AngularVelocityChangeBX => ("ΔΩ_Bx", "x angular velocity change of body B", "/bodies/1/angular_velocity_change/x"),
        /// Y angular velocity change of body B (space).
        AngularVelocityChangeBY => ("ΔΩ_By", "y angular velocity change of body B", "/bodies/1/angular_velocity_change/y"),
        /// Z angular velocity change of body B (space).
        AngularVelocityChangeBZ => ("ΔΩ_Bz", "z angular velocity change of body B", "/bodies/1/angular_velocity_change/z"),
        /// Initial tangential contact velocity x (space).
        InitialTangentialContactVelocityX => ("u_tx", "initial tangential contact velocity x", "/contact_velocity/initial/tangential/x"),
        /// Initial tangential contact velocity y (space).
        InitialTangentialContactVelocityY => ("u_ty", "initial tangential contact velocity y", "/contact_velocity/initial/tangential/y"),
        /// Initial tangential contact velocity z (space).
        InitialTangentialContactVelocityZ => ("u_tz", "initial tangential contact velocity z", "/contact_velocity/initial/tangential/z"),
        /// Initial relative spin about the normal (space).
        InitialContactSpin => ("s", "initial relative spin about the normal", "/contact_velocity/initial/spin"),
        /// Final tangential contact velocity x (space).
        FinalTangentialContactVelocityX => ("U_tx", "final tangential contact velocity x", "/contact_velocity/final/tangential/x"),
        /// Final tangential contact velocity y (space).
        FinalTangentialContactVelocityY => ("U_ty", "final tangential contact velocity y", "/contact_velocity/final/tangential/y"),
        /// Final tangential contact velocity z (space).
        FinalTangentialContactVelocityZ => ("U_tz", "final tangential contact velocity z", "/contact_velocity/final/tangential/z"),
        /// Final relative spin about the normal (space).
        FinalContactSpin => ("S", "final relative spin about the normal", "/contact_velocity/final/spin"),
        /// Tangential impulse x (space).
        TangentialImpulseX => ("P_tx", "tangential impulse x", "/impulse/tangential/x"),
        /// Tangential impulse y (space).
        TangentialImpulseY => ("P_ty", "tangential impulse y", "/impulse/tangential/y"),
        /// Tangential impulse z (space).
        TangentialImpulseZ => ("P_tz", "tangential impulse z", "/impulse/tangential/z"),
        /// Z impulse (space).
        ImpulseZ => ("P_z", "z impulse", "/impulse/z"),
        /// Torsional regime (space).
        TorsionalRegime => ("torsional_regime", "torsional regime", "/torsional_regime"),
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
}
