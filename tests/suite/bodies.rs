//! The general planar contact (two laminae, or one against a barrier, in
//! world axes): the one-body cases are its special case, bit for bit in
//! `exact` precision; momentum, energy and symmetry invariants on random pairs.

use crate::common::Rng;
use crate::common::accuracy::random_inputs;
use crate::common::reference::ulp_of;
use restitution::impact::{Arithmetic, solve_in};
use restitution::{
    BarrierImpact, BarrierOutcome, BodiesImpact, BodiesOutcome, ImpactError, Lamina, Law, Outputs,
    PlanarContact, Precision, solve,
};

/// The four axis-aligned frames `(n̂, t̂ = ẑ × n̂)`, in which mapping a one-body
/// scene to world axes is exact.
const FRAMES: [[f64; 2]; 4] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];

fn random_law(rng: &mut Rng) -> Law {
    let e = if rng.chance(0.2) {
        rng.pick(&[0.0, 1.0, 0.5])
    } else {
        rng.unit()
    };
    match rng.next_u64() % 5 {
        0 => Law::Frictionless { restitution: e },
        1 => Law::ImpulseRatio {
            restitution: e,
            impulse_ratio: rng.range(-1.0, 1.0),
        },
        2 => Law::Friction {
            restitution: e,
            friction: rng.pick(&[0.0, 0.1, 0.3, 1.0, 10.0]),
        },
        3 => Law::TangentialRestitution {
            restitution: e,
            friction: rng.pick(&[0.1, 0.3, 1.0, 10.0]),
            tangential_restitution: rng.range(-1.0, 1.0),
        },
        _ => Law::KineticRestitution {
            value: e,
            approach_impulse_ratio: rng.range(-0.5, 0.5),
            rebound_impulse_ratio: rng.range(-0.5, 0.5),
        },
    }
}

/// A one-body impact and the same impact in world axes with normal `scale · n̂`.
fn mapped(one: &BarrierImpact, frame: [f64; 2], scale: f64) -> BodiesImpact {
    let restitution::BarrierBody::Rigid {
        mass,
        inertia,
        contact,
    } = one.body
    else {
        unreachable!()
    };
    let [c, s] = frame;
    let t = [-s, c];
    let (dc, dd) = (contact.tangential_offset, contact.normal_offset);
    // r = C − G = −(d_c t̂ + d_d n̂), with C at the origin.
    let g = [dc * t[0] + dd * c, dc * t[1] + dd * s];
    let v = one.velocity;
    BodiesImpact {
        a: Lamina {
            mass,
            inertia,
            position: [g[0] + 0.0, g[1] + 0.0],
            velocity: [
                v.normal * c + v.tangential * t[0],
                v.normal * s + v.tangential * t[1],
            ],
            angular_velocity: v.angular,
        },
        b: None,
        contact: PlanarContact {
            point: [0.0, 0.0],
            normal: [scale * c, scale * s],
        },
        law: one.law,
    }
}

/// The world answer read back in the one-body frame.
fn in_frame(o: &BodiesOutcome, frame: [f64; 2]) -> [f64; 3] {
    let [c, s] = frame;
    let v = o.bodies[0].velocity;
    [
        v[0] * c + v[1] * s + 0.0,
        -v[0] * s + v[1] * c + 0.0,
        o.bodies[0].angular_velocity,
    ]
}

fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a == 0.0 && b == 0.0)
}

#[test]
fn one_body_against_a_barrier_is_the_oblique_answer_bit_for_bit_in_exact_precision() {
    let mut rng = Rng::new(0x005e_edb0_d1e5);
    let (mut answered, mut refused) = (0, 0);
    for i in 0..3000 {
        let inp = random_inputs(&mut rng);
        let law = random_law(&mut rng);
        let one = BarrierImpact {
            body: restitution::BarrierBody::Rigid {
                mass: inp.m,
                inertia: inp.inertia,
                contact: restitution::Contact {
                    tangential_offset: inp.dc,
                    normal_offset: inp.dd,
                },
            },
            velocity: restitution::PlanarVelocity {
                normal: inp.vn,
                tangential: inp.vt,
                angular: inp.w,
            },
            law,
        };
        let frame = FRAMES[i % 4];
        let scale = rng.pick(&[1.0, 2.5, 0.125, 3.0]);
        let world = mapped(&one, frame, scale);
        let expected: Result<BarrierOutcome, ImpactError> = solve(&one, Outputs::ALL, Precision::Exact);
        let got = solve(&world, Outputs::ALL, Precision::Exact);
        match (expected, got) {
            (Ok(e), Ok(g)) => {
                answered += 1;
                let v = in_frame(&g, frame);
                let pairs = [
                    ("V_n", e.final_velocity.normal, v[0]),
                    ("V_t", e.final_velocity.tangential, v[1]),
                    ("Ω", e.final_velocity.angular, v[2]),
                    (
                        "v_cn",
                        e.contact_velocity.initial.normal,
                        g.contact_velocity.initial.normal,
                    ),
                    (
                        "v_ct",
                        e.contact_velocity.initial.tangential,
                        g.contact_velocity.initial.tangential,
                    ),
                    (
                        "V_cn",
                        e.contact_velocity.r#final.normal,
                        g.contact_velocity.r#final.normal,
                    ),
                    (
                        "V_ct",
                        e.contact_velocity.r#final.tangential,
                        g.contact_velocity.r#final.tangential,
                    ),
                    ("P_n", e.impulse.normal, g.impulse.normal),
                    ("P_t", e.impulse.tangential, g.impulse.tangential),
                    ("μ", e.impulse_ratio, g.impulse_ratio),
                    (
                        "μ_c",
                        e.critical_impulse_ratio.unwrap(),
                        g.critical_impulse_ratio.unwrap(),
                    ),
                    ("e", e.restitution, g.restitution),
                    ("R", e.kinetic_restitution, g.kinetic_restitution),
                    ("T_i", e.energy.unwrap().initial, g.energy.unwrap().initial),
                    ("T_f", e.energy.unwrap().r#final, g.energy.unwrap().r#final),
                    ("T_L", e.energy.unwrap().loss, g.energy.unwrap().loss),
                    ("T_M", e.energy.unwrap().max_loss, g.energy.unwrap().max_loss),
                    (
                        "T_L*",
                        e.energy.unwrap().normalized_loss,
                        g.energy.unwrap().normalized_loss,
                    ),
                ];
                for (name, a, b) in pairs {
                    // V_n/V_t in world axes are the one-body values with the
                    // frame's exact signs; the rest are frame-free.
                    assert!(same_bits(a, b), "{name}: {a:e} vs {b:e} for {one:?} in {world:?}");
                }
                assert_eq!(e.regime, g.regime, "{one:?}");
            }
            (Err(e), Err(g)) => {
                refused += 1;
                assert_eq!(e.slug(), g.slug(), "{one:?}: {e} vs {g}");
            }
            (e, g) => panic!("{one:?}: one body {e:?}, world axes {g:?}"),
        }
    }
    assert!(
        answered > 2000 && refused > 0,
        "answered {answered}, refused {refused}"
    );
}

/// A random pair in contact: positions, sizes and speeds over a few decades.
fn random_pair(rng: &mut Rng) -> BodiesImpact {
    let lamina = |rng: &mut Rng| {
        let m = rng.log_uniform(-2.0, 3.0);
        let k = rng.log_uniform(-2.0, 1.0);
        Lamina {
            mass: m,
            inertia: m * k * k,
            position: [rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)],
            velocity: [rng.range(-20.0, 20.0), rng.range(-20.0, 20.0)],
            angular_velocity: rng.range(-5.0, 5.0),
        }
    };
    let a = lamina(rng);
    let b = lamina(rng);
    let angle = rng.range(0.0, std::f64::consts::TAU);
    BodiesImpact {
        a,
        b: Some(b),
        contact: PlanarContact {
            point: [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)],
            normal: [angle.cos() * rng.log_uniform(-1.0, 1.0), angle.sin()],
        },
        law: random_law(rng),
    }
}

/// Momentum of the pair about the origin, and of each body about the contact point.
fn moments(i: &BodiesImpact, o: Option<&BodiesOutcome>) -> ([f64; 2], [f64; 2]) {
    let [cx, cy] = i.contact.point;
    let bodies = [i.a, i.b.unwrap()];
    let mut linear = [0.0; 2];
    let mut angular = [0.0; 2];
    for (k, l) in bodies.iter().enumerate() {
        let (v, w) = match o {
            Some(o) => (o.bodies[k].velocity, o.bodies[k].angular_velocity),
            None => (l.velocity, l.angular_velocity),
        };
        linear[0] += l.mass * v[0];
        linear[1] += l.mass * v[1];
        let g = [l.position[0] - cx, l.position[1] - cy];
        angular[k] = l.inertia * w + l.mass * (g[0] * v[1] - g[1] * v[0]);
    }
    (linear, angular)
}

#[test]
fn two_bodies_conserve_momentum_and_angular_momentum_about_the_contact_and_never_create_energy() {
    let mut rng = Rng::new(0x007a_1e55);
    let mut answered = 0;
    for _ in 0..4000 {
        let impact = random_pair(&mut rng);
        let exact = solve(&impact, Outputs::ALL, Precision::Exact);
        let fast = solve(&impact, Outputs::ALL, Precision::Fast);
        let (o, f) = match (exact, fast) {
            (Ok(o), Ok(f)) => (o, f),
            (Err(e), Err(f)) => {
                assert_eq!(e.slug(), f.slug(), "{impact:?}");
                continue;
            }
            (e, f) => {
                // A decision on a knife edge may differ between the modes only
                // where the fast sign is within its rounding error.
                panic!("{impact:?}: exact {e:?}, fast {f:?}")
            }
        };
        answered += 1;
        let (p0, l0) = moments(&impact, None);
        let (p1, l1) = moments(&impact, Some(&o));
        let scale_p: f64 = [impact.a, impact.b.unwrap()]
            .iter()
            .map(|l| l.mass * l.velocity[0].hypot(l.velocity[1]))
            .sum::<f64>()
            + o.impulse.x.hypot(o.impulse.y);
        for k in 0..2 {
            assert!(
                (p1[k] - p0[k]).abs() <= 64.0 * ulp_of(scale_p),
                "linear {k}: {p0:?} → {p1:?} for {impact:?}"
            );
            let l = [impact.a, impact.b.unwrap()][k];
            let lever =
                (l.position[0] - impact.contact.point[0]).hypot(l.position[1] - impact.contact.point[1]);
            let scale_l = l.inertia * (l.angular_velocity.abs() + o.bodies[k].angular_velocity.abs())
                + l.mass
                    * lever
                    * (l.velocity[0].hypot(l.velocity[1])
                        + o.bodies[k].velocity[0].hypot(o.bodies[k].velocity[1]));
            assert!(
                (l1[k] - l0[k]).abs() <= 64.0 * ulp_of(scale_l),
                "angular {k}: {l0:?} → {l1:?} for {impact:?}"
            );
        }
        let energy = o.energy.unwrap();
        assert!(
            energy.loss >= 0.0 && energy.loss <= energy.max_loss,
            "{energy:?} for {impact:?}"
        );
        assert!((0.0..=1.0).contains(&energy.normalized_loss), "{energy:?}");
        assert!(o.impulse.normal > 0.0, "{o:?}");
        // The law's condition: restitution of the normal contact velocity.
        let u = o.contact_velocity;
        let e = o.restitution;
        assert!(
            (u.r#final.normal + e * u.initial.normal).abs() <= 8.0 * ulp_of(u.initial.normal),
            "U_n = {} for e {e}, u_n {}",
            u.r#final.normal,
            u.initial.normal
        );
        // Fast within a loose relative bound of exact on these well-scaled pairs.
        for (a, b) in [
            (f.bodies[0].velocity[0], o.bodies[0].velocity[0]),
            (f.bodies[1].angular_velocity, o.bodies[1].angular_velocity),
            (f.impulse.normal, o.impulse.normal),
        ] {
            let scale = o.impulse.normal / impact.a.mass.min(impact.b.unwrap().mass) + 100.0;
            assert!(
                (a - b).abs() <= 1e-9 * scale,
                "fast {a} vs exact {b} for {impact:?}"
            );
        }
    }
    assert!(answered > 1200, "answered {answered}");
}

#[test]
fn swapping_the_bodies_and_flipping_the_normal_mirrors_the_answer_exactly() {
    let mut rng = Rng::new(0x5a4b);
    for _ in 0..1000 {
        let impact = random_pair(&mut rng);
        let mut swapped = impact;
        swapped.a = impact.b.unwrap();
        swapped.b = Some(impact.a);
        swapped.contact.normal = [-impact.contact.normal[0], -impact.contact.normal[1]];
        let a = solve(&impact, Outputs::ALL, Precision::Exact);
        let b = solve(&swapped, Outputs::ALL, Precision::Exact);
        match (a, b) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a.bodies[0], b.bodies[1]);
                assert_eq!(a.bodies[1], b.bodies[0]);
                assert_eq!(a.impulse.x, -b.impulse.x);
                assert_eq!(a.impulse.y, -b.impulse.y);
                assert_eq!(a.impulse.normal, b.impulse.normal);
                assert_eq!(a.impulse.tangential, b.impulse.tangential);
                assert_eq!(a.contact_velocity, b.contact_velocity);
                assert_eq!(a.regime, b.regime);
                assert_eq!(a.energy, b.energy);
            }
            (Err(a), Err(b)) => assert_eq!(a.slug(), b.slug()),
            (a, b) => panic!("{impact:?}: {a:?} vs swapped {b:?}"),
        }
    }
}

#[test]
fn a_very_heavy_second_body_tends_to_the_barrier_answer() {
    let mut rng = Rng::new(0x4ea7);
    for _ in 0..500 {
        let mut impact = random_pair(&mut rng);
        let mut b = impact.b.unwrap();
        b.velocity = [0.0, 0.0];
        b.angular_velocity = 0.0;
        b.mass = 1e30;
        b.inertia = 1e30;
        impact.b = Some(b);
        let barrier = BodiesImpact { b: None, ..impact };
        match (
            solve(&impact, Outputs::ALL, Precision::Exact),
            solve(&barrier, Outputs::ALL, Precision::Exact),
        ) {
            (Ok(heavy), Ok(wall)) => {
                let scale = wall.bodies[0].velocity[0].abs() + wall.bodies[0].velocity[1].abs() + 1.0;
                for k in 0..2 {
                    let d = (heavy.bodies[0].velocity[k] - wall.bodies[0].velocity[k]).abs();
                    assert!(d <= 1e-20 * scale * 1e6, "{heavy:?} vs {wall:?}");
                }
                assert_eq!(heavy.regime, wall.regime);
            }
            (Err(a), Err(b)) => assert_eq!(a.slug(), b.slug()),
            (a, b) => {
                // Only a knife-edge regime decision may differ.
                panic!("heavy {a:?} vs barrier {b:?} for {impact:?}")
            }
        }
    }
}

#[test]
fn the_fast_evaluation_refuses_nothing_the_exact_one_answers_and_is_plain_where_certain() {
    let mut rng = Rng::new(0xfa57);
    let (mut answered, mut plain) = (0, 0);
    for _ in 0..200 {
        let impact = random_pair(&mut rng);
        let (fast, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Fast);
        let (exact, _) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
        if let Ok(exact) = exact {
            answered += 1;
            let fast = fast.unwrap();
            assert_eq!(fast.regime, exact.regime);
            if stage == restitution::impact::Stage::Fast {
                plain += 1;
            } else {
                // Escalated (an output past the promised error): the exact answer.
                assert_eq!(format!("{fast:?}"), format!("{exact:?}"));
            }
        }
    }
    // Random pairs are well conditioned: nearly all stay in f64.
    assert!(
        answered > 50 && plain * 10 >= answered * 9,
        "{plain} of {answered} in f64"
    );
}

#[test]
fn a_zero_normal_a_separating_contact_and_bad_bodies_are_refused_with_their_input() {
    let mut rng = Rng::new(1);
    let base = random_pair(&mut rng);
    let mut zero = base;
    zero.contact.normal = [0.0, -0.0];
    let e = solve(&zero, Outputs::ALL, Precision::Fast).unwrap_err();
    assert_eq!(e.input().unwrap().path(), "/contact/normal");
    let mut heavy = base;
    heavy.b.as_mut().unwrap().inertia = -1.0;
    let e = solve(&heavy, Outputs::ALL, Precision::Fast).unwrap_err();
    assert_eq!(e.input().unwrap().path(), "/bodies/1/inertia");
    // Separating: reverse both bodies' velocities of an approaching pair.
    let approaching = (0..100)
        .map(|_| random_pair(&mut rng))
        .find(|i| solve(i, Outputs::ALL, Precision::Exact).is_ok())
        .unwrap();
    let mut separating = approaching;
    for l in std::iter::once(&mut separating.a).chain(separating.b.as_mut()) {
        l.velocity = [-l.velocity[0], -l.velocity[1]];
        l.angular_velocity = -l.angular_velocity;
    }
    let e = solve(&separating, Outputs::ALL, Precision::Exact).unwrap_err();
    assert_eq!(e.input().unwrap().path(), "/bodies/0/velocity");
}

/// An elastic contact whose exact loss is 0, which the f64 evaluation rounds
/// to a small gain: the fast precision confirms refusals exactly, so it is
/// answered (found by the survey of `tests/bodies_reference.rs`).
#[test]
fn an_elastic_contact_with_zero_exact_loss_is_answered_in_fast_precision_too() {
    let lamina = |mass, inertia, velocity, angular_velocity| Lamina {
        mass,
        inertia,
        position: [0.017938629739428967, -0.08798598553630042],
        velocity,
        angular_velocity,
    };
    let impact = BodiesImpact {
        a: lamina(
            60.20917016507488,
            0.8882899289251217,
            [-0.27288632102354077, -0.39792137219484414],
            -3.074062870288868,
        ),
        b: Some(lamina(
            67.18535088614338,
            2.427146316837479,
            [-0.2900082840147605, -0.4731399483198071],
            -0.0,
        )),
        contact: PlanarContact {
            point: [0.0, 0.0],
            normal: [0.035877259478857934, -0.17597197107260085],
        },
        law: Law::TangentialRestitution {
            restitution: 1.0,
            friction: 3.436276980685993,
            tangential_restitution: -1.0,
        },
    };
    let exact = solve(&impact, Outputs::ALL, Precision::Exact).unwrap();
    let fast = solve(&impact, Outputs::ALL, Precision::Fast).unwrap();
    assert_eq!(exact.energy.unwrap().loss, 0.0);
    assert_eq!(fast.regime, exact.regime);
}

/// A refusal decided where the impulse ratio itself is too small to certify
/// (μ ≈ 1.3e-17, sliding at the switch) still names a number in its payload,
/// the exact one's neighbour (it was a NaN), in every precision.
#[test]
fn a_refusal_names_its_impulse_ratio_even_when_it_is_uncertified() {
    let impact = BodiesImpact {
        a: Lamina {
            mass: 3.5,
            inertia: 0.875,
            position: [-1.0, -0.25],
            velocity: [5.0, -4.890218912435025],
            angular_velocity: -0.5,
        },
        b: Some(Lamina {
            mass: 2.0,
            inertia: 3.75,
            position: [1.0, -0.875],
            velocity: [0.5, 3.625],
            angular_velocity: -0.5,
        }),
        contact: PlanarContact {
            point: [0.0, -0.25],
            normal: [-1.0, 0.5],
        },
        law: Law::Friction {
            restitution: 1.0,
            friction: 0.3,
        },
    };
    for arithmetic in [Arithmetic::Fast, Arithmetic::Exact, Arithmetic::Rational] {
        match solve_in(&impact, Outputs::ALL, arithmetic).0 {
            Err(ImpactError::CreatesEnergy { impulse_ratio, .. }) => assert!(
                impulse_ratio.is_finite() && (impulse_ratio - 1.27e-17).abs() < 1e-19,
                "{arithmetic:?}: {impulse_ratio}"
            ),
            other => panic!("{arithmetic:?}: {other:?}"),
        }
    }
}
