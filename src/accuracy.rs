//! What the `fast` precision promises of every number it answers, and the
//! scales that promise is measured against.
//!
//! Every `fast` output `h` of an exact value `x` obeys
//! `|h − x| ≤ 2⁻³² · max(|x|, S)` ([`PROMISED_RELATIVE_ERROR`]), where `S` is
//! the scale of the output's unit in the impact ([`ErrorScales`], computed
//! from the inputs alone, so a sweep's row is its point's single solve
//! whatever outputs are asked for). Where the f64 evaluation's error bound
//! cannot show that, the impact is answered by the exact stages instead,
//! whose outputs are correctly rounded.

use crate::error::Output;

/// The error every `fast` output is within, relative to the larger of its
/// exact value's magnitude and its unit's scale ([`ErrorScales`]): `2⁻³²`,
/// about `2.3·10⁻¹⁰`. (The f64 evaluation's own error is typically a few
/// ulps; the promise is what its static bound can guarantee for every
/// impact without sending most spatial impacts to the exact stages.)
pub const PROMISED_RELATIVE_ERROR: f64 = 1.0 / (1u64 << 32) as f64;

/// The magnitudes of one impact that the promised error of each unit is
/// measured against (all from the inputs; `docs/accuracy.md` gives each
/// case's definitions). A zero scale makes the promise relative to the
/// output itself; an infinite one makes no promise.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorScales {
    /// Of a dimensionless output (a ratio, a restitution): 1.
    pub dimensionless: f64,
    /// `S_v` (m/s): the largest initial velocity component and spin times
    /// lever arm (`|ω| |r|`, the distance from a centre of mass to the contact).
    pub velocity: f64,
    /// `S_ω` (rad/s): the largest initial spin component, and `S_v / |r|` of
    /// each body with a non-zero lever arm.
    pub angular_velocity: f64,
    /// `S_J` (N·s): `m_min S_v`, `m_min` the smallest mass.
    pub impulse: f64,
    /// `S_M` (N·m·s): `S_J` times the largest lever arm or pitch radius.
    pub angular_impulse: f64,
    /// `S_T` (J): `m_min S_v²`.
    pub energy: f64,
}

impl ErrorScales {
    /// Infinite scales: no promise, so the f64 evaluation answers its value
    /// whatever its bound (the measurement mode `Arithmetic::Unpromised`).
    pub const UNPROMISED: ErrorScales = ErrorScales {
        dimensionless: f64::INFINITY,
        velocity: f64::INFINITY,
        angular_velocity: f64::INFINITY,
        impulse: f64::INFINITY,
        angular_impulse: f64::INFINITY,
        energy: f64::INFINITY,
    };

    /// The scale `output` is measured against.
    pub fn of_output(&self, output: Output) -> f64 {
        self.by_kind()[output.scale_kind() as usize]
    }

    /// The scales by [`ScaleKind`].
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn by_kind(&self) -> [f64; 6] {
        [
            self.dimensionless,
            self.velocity,
            self.angular_velocity,
            self.impulse,
            self.angular_impulse,
            self.energy,
        ]
    }
}

/// Gathers an impact's bodies into its [`ErrorScales`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScalesOf {
    velocity: f64,
    spin: f64,
    min_mass: f64,
    min_arm: f64,
    max_arm: f64,
}

impl ScalesOf {
    pub(crate) fn new() -> Self {
        ScalesOf {
            velocity: 0.0,
            spin: 0.0,
            min_mass: f64::INFINITY,
            min_arm: f64::INFINITY,
            max_arm: 0.0,
        }
    }

    /// A body of `mass` with these velocity and spin components, its lever
    /// arm `arm` from its centre of mass to the contact (for the torsional
    /// case, the pitch radius).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn body(mut self, mass: f64, velocity: &[f64], spin: &[f64], arm: f64) -> Self {
        let spin = spin.iter().fold(0.0f64, |s, w| s.max(w.abs()));
        let velocity = velocity.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        self.velocity = self.velocity.max(velocity).max(spin * arm);
        self.spin = self.spin.max(spin);
        self.min_mass = self.min_mass.min(mass);
        if arm > 0.0 {
            self.min_arm = self.min_arm.min(arm);
        }
        self.max_arm = self.max_arm.max(arm);
        self
    }

    /// A lever arm of a couple that is no body's (a pitch radius): it
    /// scales angular impulses only.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn lever(mut self, arm: f64) -> Self {
        self.max_arm = self.max_arm.max(arm);
        self
    }

    /// The scales: `S_v`; `S_ω` the largest spin and `S_v` over the shortest
    /// non-zero arm; `S_J = m_min S_v`; `S_M = S_J` times the longest arm;
    /// `S_T = S_J S_v`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn scales(self) -> ErrorScales {
        let impulse = self.min_mass * self.velocity;
        ErrorScales {
            dimensionless: 1.0,
            velocity: self.velocity,
            angular_velocity: if self.min_arm < f64::INFINITY {
                self.spin.max(self.velocity / self.min_arm)
            } else {
                self.spin
            },
            impulse,
            angular_impulse: impulse * self.max_arm,
            energy: impulse * self.velocity,
        }
    }
}

/// The unit class of an output, as an index of [`ErrorScales::by_kind`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ScaleKind {
    Dimensionless = 0,
    Velocity = 1,
    AngularVelocity = 2,
    Impulse = 3,
    AngularImpulse = 4,
    Energy = 5,
}

/// `a == b` for strings, in a constant.
const fn same(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The class of a unit of [`crate::quantity`]'s table (a name's empty unit
/// counts as dimensionless: it is never rounded).
const fn kind_of_unit(unit: &str) -> ScaleKind {
    if same(unit, "m/s") {
        ScaleKind::Velocity
    } else if same(unit, "rad/s") {
        ScaleKind::AngularVelocity
    } else if same(unit, "N·s") {
        ScaleKind::Impulse
    } else if same(unit, "N·m·s") {
        ScaleKind::AngularImpulse
    } else if same(unit, "J") {
        ScaleKind::Energy
    } else if same(unit, "1") || same(unit, "") {
        ScaleKind::Dimensionless
    } else {
        panic!("an output unit with no error scale")
    }
}

/// Each output's class, by its position in [`Output::ALL`], from the
/// quantity table's units (a unit without a class fails the build).
const KINDS: [ScaleKind; Output::ALL.len()] = {
    let mut kinds = [ScaleKind::Dimensionless; Output::ALL.len()];
    let mut i = 0;
    while i < kinds.len() {
        kinds[i] = kind_of_unit(Output::ALL[i].unit());
        i += 1;
    }
    kinds
};

impl Output {
    /// The unit class the output's promised error is measured in.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) const fn scale_kind(self) -> ScaleKind {
        KINDS[self as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_output_has_the_scale_of_its_unit() {
        let scales = ErrorScales {
            dimensionless: 13.0,
            velocity: 2.0,
            angular_velocity: 3.0,
            impulse: 5.0,
            angular_impulse: 7.0,
            energy: 11.0,
        };
        for &output in Output::ALL {
            let expected = match output.unit() {
                "m/s" => 2.0,
                "rad/s" => 3.0,
                "N·s" => 5.0,
                "N·m·s" => 7.0,
                "J" => 11.0,
                _ => 13.0,
            };
            assert_eq!(scales.of_output(output), expected, "{output:?}");
        }
    }
}
