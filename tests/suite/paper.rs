//! The paper's own numbers and printed special cases, derived and checked.

use crate::common::plain::oblique::{self, KineticRestitution, TangentialLaw};
use crate::common::plain::tangential;
use crate::common::plain::torsional::{self, TorsionalImpact, TorsionalRegime};
use restitution::{BarrierScene, Body, Contact, Outputs, PlanarVelocity, Regime};

/// A uniform disc of radius ρ: k² = ρ²/2, so λ = ρ²/k² = 2.
fn disc(rho: f64, vn: f64, vt: f64, w: f64) -> BarrierScene {
    let m = 1.0;
    BarrierScene::new(
        Body::new(m, 0.5 * m * rho * rho).unwrap(),
        Contact::central(rho),
        PlanarVelocity {
            normal: vn,
            tangential: vt,
            angular: w,
        },
    )
    .unwrap()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

#[test]
fn disc_follows_eqs_15_to_19_with_a_prescribed_ratio() {
    let (rho, e, mu) = (0.05, 0.93, -0.1);
    let (vn, vt, w) = (-2.0, 1.5, 3.0);
    let scene = disc(rho, vn, vt, w);
    let out = oblique::solve(&scene, e, TangentialLaw::ImpulseRatio(mu), Outputs::ALL).unwrap();
    assert!(close(out.final_velocity.normal, -e * vn, 1e-15)); // Eq 15
    assert!(close(
        out.final_velocity.tangential,
        vt - mu * (1.0 + e) * vn,
        1e-15
    )); // Eq 16
    assert!(close(
        out.final_velocity.angular,
        w + 2.0 * mu * (1.0 + e) * vn / rho,
        1e-15
    )); // Eq 17
    let vct = vt - rho * w;
    let lambda = 2.0;
    let eq18 = vct - mu * (1.0 + e) * vn * (1.0 + lambda);
    assert!(close(out.contact_velocity.r#final.tangential, eq18, 1e-14)); // Eq 18
    let mu_c = out.critical_impulse_ratio.unwrap();
    assert!(close(mu_c, (vct / vn) / ((1.0 + lambda) * (1.0 + e)), 1e-15)); // Eq 14, λ = ρ²/k²
    assert!(close(
        out.contact_velocity.r#final.tangential,
        vct * (1.0 - mu / mu_c),
        1e-14
    )); // Eq 19
}

/// Figure 2: O (no initial slip → no final slip), B (the switch at |μ_c| = f),
/// A (the sliding line's intercept at v_ct = 0 is −f (1 + e)(1 + λ)).
#[test]
fn figure_2_points_o_a_and_b() {
    let (e, f) = (0.93, 0.124);
    let vn = -1.0;
    // O: v_ct = 0 gives V_ct = 0 (sticking with μ_c = 0).
    let o = oblique::solve(
        &disc(0.05, vn, 0.0, 0.0),
        e,
        TangentialLaw::Friction(f),
        Outputs::ALL,
    )
    .unwrap();
    assert_eq!(o.contact_velocity.r#final.tangential, 0.0);
    assert_eq!(o.regime, Regime::Sticking);
    // B: r_B = f (1 + e)(1 + λ); just below it sticks, just above it slides.
    let r_b = f * (1.0 + e) * 3.0;
    let below = oblique::solve(
        &disc(0.05, vn, r_b * 0.999, 0.0),
        e,
        TangentialLaw::Friction(f),
        Outputs::ALL,
    );
    let above = oblique::solve(
        &disc(0.05, vn, r_b * 1.001, 0.0),
        e,
        TangentialLaw::Friction(f),
        Outputs::ALL,
    );
    assert_eq!(below.unwrap().regime, Regime::Sticking);
    assert_eq!(above.unwrap().regime, Regime::Sliding);
    // A: the sliding line V_ct/|v_n| = v_ct/|v_n| − 0.72 at the Maw values (μ = −0.124 for v_t > 0).
    for x in [1.0, 2.0, 4.0] {
        let out = oblique::solve(
            &disc(0.05, vn, x, 0.0),
            e,
            TangentialLaw::Friction(f),
            Outputs::ALL,
        )
        .unwrap();
        assert_eq!(out.regime, Regime::Sliding);
        assert_eq!(out.impulse_ratio, -f);
        let intercept = out.contact_velocity.r#final.tangential - x;
        assert!(close(intercept, -0.72, 3e-3), "intercept {intercept}");
    }
}

/// Maw et al.'s steel disc: the intercept −0.72 at e = 0.93 identifies
/// μ = 0.72 / ((1 + e)(1 + λ)) = 0.124, and the restitution line has slope −e_t.
#[test]
fn maw_steel_disc_identifies_mu_and_e_t() {
    let e: f64 = 0.93;
    let mu = 0.72 / ((1.0 + e) * 3.0);
    assert!((mu - 0.124).abs() < 5e-4, "μ = {mu}");
    let (f, et) = (0.123, 0.34);
    // Restitution branch: V_ct = −e_t v_ct for small slip (Eq 20).
    for x in [0.05, 0.1, 0.2] {
        let out = tangential::solve(&disc(0.05, -1.0, x, 0.0), e, f, et, Outputs::ALL).unwrap();
        assert_eq!(out.regime, Regime::Restitution);
        assert!(close(out.contact_velocity.r#final.tangential, -et * x, 1e-15));
        // Eq 24: e_t = μ/μ_c − 1.
        let mu_c = out.critical_impulse_ratio.unwrap();
        assert!(close(out.impulse_ratio / mu_c - 1.0, et, 1e-12));
    }
    // Sliding branch beyond the switch f = (1 + e_t)|μ_c| (Eq 26 with its ranges swapped back).
    let switch = f * (1.0 + e) * 3.0 / (1.0 + et);
    let out = tangential::solve(&disc(0.05, -1.0, switch * 1.5, 0.0), e, f, et, Outputs::ALL).unwrap();
    assert_eq!(out.regime, Regime::Sliding);
    let mu_c = out.critical_impulse_ratio.unwrap();
    let eq26 = switch * 1.5 * (1.0 - f / mu_c.abs());
    assert!(close(out.contact_velocity.r#final.tangential, eq26, 1e-14));
    // The two branches meet at the switch.
    let at = tangential::solve(&disc(0.05, -1.0, switch, 0.0), e, f, et, Outputs::ALL).unwrap();
    assert!(close(at.contact_velocity.r#final.tangential, -et * switch, 1e-14));
}

/// Eq 27: with ω = 0 on a disc in the restitution regime, the loss as a
/// fraction of the initial energy is (1 − e²) sin²α + (1 − e_t²) cos²α / (1 + λ).
#[test]
fn eq_27_energy_loss_without_initial_spin() {
    let (e, et, f) = (0.8, 0.4, 10.0);
    for alpha_deg in [20.0f64, 45.0, 70.0] {
        let a = alpha_deg.to_radians();
        let scene = disc(0.1, -a.sin(), a.cos(), 0.0);
        let out = tangential::solve(&scene, e, f, et, Outputs::ALL).unwrap();
        assert_eq!(out.regime, Regime::Restitution);
        let energy = out.energy.unwrap();
        let expected = (1.0 - e * e) * a.sin().powi(2) + (1.0 - et * et) * a.cos().powi(2) / 3.0;
        assert!(
            close(energy.loss / energy.initial, expected, 1e-14),
            "α = {alpha_deg}"
        );
    }
}

/// Eq 11: R = e when μ_A = μ_R, when d_c = 0, or when d_d = 0; otherwise
/// R = e D(μ_A) / D(μ_R).
#[test]
fn eq_11_kinetic_and_kinematic_restitution() {
    let scene_with = |dc: f64, dd: f64| {
        BarrierScene::new(
            Body::new(2.0, 0.3).unwrap(),
            Contact {
                tangential_offset: dc,
                normal_offset: dd,
            },
            PlanarVelocity {
                normal: -1.0,
                tangential: 0.3,
                angular: 0.2,
            },
        )
        .unwrap()
    };
    let solve = |scene: &BarrierScene, mu_a: f64, mu_r: f64| {
        let k = KineticRestitution {
            value: 0.6,
            approach_impulse_ratio: mu_a,
            rebound_impulse_ratio: mu_r,
        };
        oblique::solve_kinetic(scene, k, Outputs::ALL).unwrap()
    };
    let general = scene_with(0.2, 0.5);
    assert!(close(solve(&general, 0.1, 0.1).restitution, 0.6, 1e-15));
    assert!(close(
        solve(&scene_with(0.0, 0.5), 0.1, -0.2).restitution,
        0.6,
        1e-15
    ));
    assert!(close(
        solve(&scene_with(0.2, 0.0), 0.1, -0.2).restitution,
        0.6,
        1e-15
    ));
    let out = solve(&general, 0.1, -0.2);
    let expected_e = 0.6 * general.d(-0.2) / general.d(0.1);
    assert!(close(out.restitution, expected_e, 1e-14));
    assert_ne!(out.restitution, 0.6);
    assert_eq!(out.kinetic_restitution, 0.6);
}

fn ball(spin: f64) -> TorsionalImpact {
    TorsionalImpact {
        mass: 0.6,
        normal_inertia: 0.4 * 0.6 * 0.12 * 0.12,
        normal_velocity: -3.0,
        spin,
        restitution: 0.7,
        torsional_restitution: 0.2,
        torsional_friction: 0.3,
        pitch_radius: 0.01,
    }
}

/// Eqs 28–31: slopes −e_z and 1 − e_z, meeting at the switch of Eq 31.
#[test]
fn torsional_branches_meet_at_eq_31() {
    let b = ball(0.0);
    let switch =
        b.torsional_friction * b.pitch_radius * b.mass * (1.0 + b.restitution) * 3.0 / b.normal_inertia;
    let low = torsional::solve(&ball(0.5 * switch), true).unwrap();
    assert_eq!(low.regime, TorsionalRegime::Restitution);
    assert!(close(low.final_spin, -0.2 * 0.5 * switch, 1e-15));
    assert!(close(low.switch_spin, switch, 1e-15));
    let high1 = torsional::solve(&ball(2.0 * switch), true).unwrap();
    let high2 = torsional::solve(&ball(3.0 * switch), true).unwrap();
    assert_eq!(high1.regime, TorsionalRegime::Sliding);
    assert!(close(
        (high2.final_spin - high1.final_spin) / switch,
        1.0 - 0.2,
        1e-12
    ));
    let at = torsional::solve(&ball(switch), true).unwrap();
    let beyond = torsional::solve(&ball(switch * (1.0 + 1e-12)), true).unwrap();
    assert!(close(at.final_spin, beyond.final_spin, 1e-9));
    // The friction moment opposes the spin in both directions (the printed Eq 30 would speed it up).
    let negative = torsional::solve(&ball(-2.0 * switch), true).unwrap();
    assert_eq!(negative.final_spin, -high1.final_spin);
    assert!(high1.final_spin.abs() < 2.0 * switch);
    assert!(high1.energy.unwrap().loss > 0.0);
}
