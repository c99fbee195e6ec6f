//! The contact in space: the planar contact and the paper's torsional case
//! are its special cases (bit for bit in `exact` precision); momentum,
//! angular momentum about the contact point, energy and rotation invariants
//! on random scenes; refusals of what the model cannot answer.

// Component loops over x, y, z read several vectors at once.
#![allow(clippy::needless_range_loop)]

use crate::common::{Rng, rotation};
use restitution::impact::{Arithmetic, solve_in};
use restitution::{
    BodiesImpact, ImpactError, Input, Lamina, Law, Outputs, PlanarContact, Precision, Regime, RigidBody,
    SpatialContact, SpatialImpact, SpatialOutcome, TorsionalImpact, TorsionalRegime, Twist, solve,
};

fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a == 0.0 && b == 0.0)
}

fn random_law(rng: &mut Rng) -> Law {
    let e = if rng.chance(0.2) {
        rng.pick(&[0.0, 1.0, 0.5])
    } else {
        rng.unit()
    };
    match rng.next_u64() % 6 {
        0 => Law::Frictionless { restitution: e },
        5 => Law::KineticFriction {
            value: e,
            approach_friction: rng.pick(&[0.0, 0.1, 0.3, 1.0, 10.0]),
            rebound_impulse_ratio: if rng.chance(0.5) { 0.0 } else { rng.range(0.0, 1.0) },
        },
        1 => Law::ImpulseRatio {
            restitution: e,
            impulse_ratio: rng.range(0.0, 1.0),
        },
        4 => Law::KineticRestitution {
            value: e,
            approach_impulse_ratio: if rng.chance(0.2) { 0.0 } else { rng.range(0.0, 1.0) },
            rebound_impulse_ratio: if rng.chance(0.3) { 0.0 } else { rng.range(0.0, 1.0) },
        },
        2 => Law::Friction {
            restitution: e,
            friction: rng.pick(&[0.0, 0.1, 0.3, 1.0, 10.0]),
        },
        _ => Law::TangentialRestitution {
            restitution: e,
            friction: rng.pick(&[0.1, 0.3, 1.0, 10.0]),
            tangential_restitution: rng.range(-1.0, 1.0),
        },
    }
}

/// `R diag(moments) Rᵀ` as `[xx, yy, zz, xy, xz, yz]`.
fn tensor(r: &[[f64; 3]; 3], moments: [f64; 3]) -> [f64; 6] {
    let entry = |i: usize, j: usize| (0..3).map(|k| r[i][k] * moments[k] * r[j][k]).sum::<f64>();
    [
        entry(0, 0),
        entry(1, 1),
        entry(2, 2),
        entry(0, 1),
        entry(0, 2),
        entry(1, 2),
    ]
}

fn matrix(t: &[f64; 6]) -> [[f64; 3]; 3] {
    let [xx, yy, zz, xy, xz, yz] = *t;
    [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
}

fn random_body(rng: &mut Rng) -> RigidBody {
    let m = rng.log_uniform(-2.0, 3.0);
    let k = [0; 3].map(|_| rng.log_uniform(-1.5, 0.5));
    // Principal moments of a solid: each at most the sum of the other two.
    let mut moments = [
        m * (k[1] * k[1] + k[2] * k[2]),
        m * (k[0] * k[0] + k[2] * k[2]),
        m * (k[0] * k[0] + k[1] * k[1]),
    ];
    if rng.chance(0.2) {
        moments = [moments[0]; 3];
    }
    let r = rotation::random(|| rng.range(-1.0, 1.0));
    RigidBody {
        mass: m,
        inertia: tensor(&r, moments),
        position: [0; 3].map(|_| rng.range(-2.0, 2.0)),
        velocity: [0; 3].map(|_| rng.range(-20.0, 20.0)),
        angular_velocity: [0; 3].map(|_| rng.range(-10.0, 10.0)),
    }
}

fn random_twist(rng: &mut Rng) -> Option<Twist> {
    rng.chance(0.4).then(|| Twist {
        restitution: rng.unit(),
        friction: rng.pick(&[0.0, 0.05, 0.3, 2.0]),
        pitch_radius: rng.log_uniform(-2.0, 0.0),
    })
}

fn random_scene(rng: &mut Rng, two: bool) -> SpatialImpact {
    let a = random_body(rng);
    let b = two.then(|| random_body(rng));
    let r = rotation::random(|| rng.range(-1.0, 1.0));
    let size = rng.log_uniform(-1.0, 1.0);
    SpatialImpact {
        a,
        b,
        contact: SpatialContact {
            point: [0; 3].map(|_| rng.range(-1.0, 1.0)),
            normal: rotation::rotate(&r, [size, 0.0, 0.0]),
        },
        law: random_law(rng),
        torsion: random_twist(rng),
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn size(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn close(a: f64, b: f64, scale: f64, what: &str, context: &dyn std::fmt::Debug) {
    assert!(
        (a - b).abs() <= 1e-9 * scale.max(1e-300),
        "{what}: {a:e} vs {b:e} (scale {scale:e}) in {context:?}"
    );
}

#[test]
fn planar_motion_in_space_is_the_planar_answer_bit_for_bit_in_exact_precision() {
    let mut rng = Rng::new(0x5_9a7e);
    let (mut answered, mut refused, mut kinetic, mut kept_branch) = (0, 0, 0, 0);
    // Coulomb approaches answered, sticking and sliding.
    let mut coulomb = [0; 2];
    for _ in 0..1800 {
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
        let a = lamina(&mut rng);
        let b = rng.chance(0.7).then(|| lamina(&mut rng));
        let angle = rng.range(0.0, std::f64::consts::TAU);
        let contact = PlanarContact {
            point: [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)],
            normal: [angle.cos() * rng.log_uniform(-1.0, 1.0), angle.sin()],
        };
        let law = random_law(&mut rng);
        let mut plane = BodiesImpact { a, b, contact, law };
        // The planar ratios are signed along t̂; in space they oppose the
        // slip (both phases of the kinetic law along the one direction).
        if matches!(law, Law::ImpulseRatio { .. } | Law::KineticRestitution { .. }) {
            let Ok(probe) = solve(&plane, Outputs::MINIMAL, Precision::Exact) else {
                continue;
            };
            let slip = probe.contact_velocity.initial.tangential;
            if slip == 0.0 {
                continue;
            }
            plane.law = match law {
                Law::ImpulseRatio {
                    restitution,
                    impulse_ratio,
                } => Law::ImpulseRatio {
                    restitution,
                    impulse_ratio: -impulse_ratio * slip.signum(),
                },
                Law::KineticRestitution {
                    value,
                    approach_impulse_ratio,
                    rebound_impulse_ratio,
                } => Law::KineticRestitution {
                    value,
                    approach_impulse_ratio: -approach_impulse_ratio * slip.signum(),
                    rebound_impulse_ratio: -rebound_impulse_ratio * slip.signum(),
                },
                other => other,
            };
        }
        let lift = |l: &Lamina, rng: &mut Rng| RigidBody {
            mass: l.mass,
            // Moments about x and y of a rigid body (each principal moment at
            // most the sum of the other two): the motion stays in the plane.
            inertia: [
                l.inertia * rng.range(0.5, 1.5),
                l.inertia * rng.range(0.5, 1.5),
                l.inertia,
                0.0,
                0.0,
                0.0,
            ],
            position: [l.position[0], l.position[1], 0.0],
            velocity: [l.velocity[0], l.velocity[1], 0.0],
            angular_velocity: [0.0, 0.0, l.angular_velocity],
        };
        let space = SpatialImpact {
            a: lift(&a, &mut rng),
            b: b.map(|b| lift(&b, &mut rng)),
            contact: SpatialContact {
                point: [contact.point[0], contact.point[1], 0.0],
                normal: [contact.normal[0], contact.normal[1], 0.0],
            },
            law,
            torsion: None,
        };
        match (
            solve(&plane, Outputs::ALL, Precision::Exact),
            solve(&space, Outputs::ALL, Precision::Exact),
        ) {
            (Ok(p), Ok(s)) => {
                answered += 1;
                kinetic += matches!(law, Law::KineticRestitution { .. }) as usize;
                if matches!(law, Law::KineticFriction { .. }) {
                    coulomb[(p.regime == Regime::Sliding) as usize] += 1;
                }
                let mut pairs = vec![
                    (
                        "u_n",
                        p.contact_velocity.initial.normal,
                        s.contact_velocity.initial.normal,
                    ),
                    (
                        "U_n",
                        p.contact_velocity.r#final.normal,
                        s.contact_velocity.r#final.normal,
                    ),
                    ("P_n", p.impulse.normal, s.impulse.normal),
                    ("P_x", p.impulse.x, s.impulse.x),
                    ("P_y", p.impulse.y, s.impulse.y),
                    ("P_z", 0.0, s.impulse.z),
                    ("|μ|", p.impulse_ratio.abs(), s.impulse_ratio),
                    ("e", p.restitution, s.restitution),
                    ("T_i", p.energy.unwrap().initial, s.energy.unwrap().initial),
                    ("T_f", p.energy.unwrap().r#final, s.energy.unwrap().r#final),
                    ("T_L", p.energy.unwrap().loss, s.energy.unwrap().loss),
                    ("T_M", p.energy.unwrap().max_loss, s.energy.unwrap().max_loss),
                    (
                        "T_L*",
                        p.energy.unwrap().normalized_loss,
                        s.energy.unwrap().normalized_loss,
                    ),
                ];
                if let (Some(pc), Some(sc)) = (p.critical_impulse_ratio, s.critical_impulse_ratio) {
                    pairs.push(("|μ_c|", pc.abs(), sc));
                }
                for k in 0..p.body_count {
                    let (pb, sb) = (&p.bodies[k], &s.bodies[k]);
                    pairs.extend([
                        ("V_x", pb.velocity[0], sb.velocity[0]),
                        ("V_y", pb.velocity[1], sb.velocity[1]),
                        ("V_z", 0.0, sb.velocity[2]),
                        ("Ω_z", pb.angular_velocity, sb.angular_velocity[2]),
                        ("Ω_x", 0.0, sb.angular_velocity[0]),
                        ("ΔV_x", pb.velocity_change[0], sb.velocity_change[0]),
                        ("ΔV_y", pb.velocity_change[1], sb.velocity_change[1]),
                        ("|ΔV|", pb.delta_v, sb.delta_v),
                        ("ΔΩ_z", pb.angular_velocity_change, sb.angular_velocity_change[2]),
                    ]);
                }
                for (name, a, b) in pairs {
                    assert!(same_bits(a, b), "{name}: {a:e} vs {b:e} for {plane:?}");
                }
                assert_eq!(p.regime, s.regime, "{plane:?}");
            }
            (Err(p), Err(s)) => {
                refused += 1;
                // One reading of the law: the same refusal, at the same member.
                assert_eq!(
                    (p.slug(), p.input()),
                    (s.slug(), s.input()),
                    "{plane:?}: {p} vs {s}"
                );
                kept_branch += (p.input() == Some(Input::TangentialRestitution)) as usize;
            }
            (p, s) => panic!("{plane:?}: planar {p:?}, space {s:?}"),
        }
    }
    assert!(
        answered > 500 && refused > 100 && kinetic > 50 && kept_branch > 0 && coulomb.iter().all(|&n| n > 20),
        "answered {answered} ({kinetic} kinetic, {coulomb:?} Coulomb approaches sticking and sliding), \
         refused {refused} ({kept_branch} by the restitution branch)"
    );
}

#[test]
fn a_sphere_spinning_on_its_normal_is_the_torsional_case_bit_for_bit_in_exact_precision() {
    let mut rng = Rng::new(0x70_5105);
    let mut regimes = [0; 2];
    for i in 0..600 {
        let m = rng.log_uniform(-2.0, 2.0);
        let radius = rng.log_uniform(-2.0, 0.0);
        let moment = rng.log_uniform(-1.0, 0.0) * m * radius * radius;
        let vn = -rng.log_uniform(-1.0, 1.5);
        let spin = rng.range(-200.0, 200.0);
        let e = rng.unit();
        let twist = Twist {
            restitution: rng.unit(),
            friction: rng.pick(&[0.0, 0.1, 0.5]),
            pitch_radius: rng.log_uniform(-3.0, -1.0),
        };
        // The normal along a signed axis, of any length.
        let axis = i % 3;
        let sense = if i % 2 == 0 { 1.0 } else { -1.0 };
        let mut normal = [0.0; 3];
        normal[axis] = sense * rng.pick(&[1.0, 2.0, 0.375]);
        let along = |x: f64| {
            let mut v = [0.0; 3];
            v[axis] = sense * x;
            v
        };
        let sphere = RigidBody {
            mass: m,
            inertia: [moment, moment, moment, 0.0, 0.0, 0.0],
            position: along(radius),
            velocity: along(vn),
            angular_velocity: along(spin),
        };
        let space = SpatialImpact {
            a: sphere,
            b: None,
            contact: SpatialContact {
                point: [0.0; 3],
                normal,
            },
            law: if i % 4 == 0 {
                Law::Friction {
                    restitution: e,
                    friction: 0.4,
                }
            } else {
                Law::Frictionless { restitution: e }
            },
            torsion: Some(twist),
        };
        let torsional = TorsionalImpact {
            mass: m,
            normal_inertia: moment,
            normal_velocity: vn,
            spin,
            restitution: e,
            torsional_restitution: twist.restitution,
            torsional_friction: twist.friction,
            pitch_radius: twist.pitch_radius,
        };
        let t = solve(&torsional, Outputs::ALL, Precision::Exact).unwrap();
        let s = solve(&space, Outputs::ALL, Precision::Exact).unwrap();
        let pairs = [
            ("Ω_n", t.final_spin, s.contact_velocity.r#final.spin),
            (
                "Ω_n of A",
                t.final_spin,
                sense * s.bodies[0].angular_velocity[axis],
            ),
            ("M_n", t.torsional_impulse, s.impulse.torsional),
            ("P_n", t.normal_impulse, s.impulse.normal),
            ("V_n", t.final_normal_velocity, sense * s.bodies[0].velocity[axis]),
        ];
        for (name, a, b) in pairs {
            assert!(same_bits(a, b), "{name}: {a:e} vs {b:e} for {space:?}");
        }
        let regime = s.torsional_regime.unwrap();
        assert_eq!(t.regime, regime, "{space:?}");
        regimes[(regime == TorsionalRegime::Sliding) as usize] += 1;
        // The rotational energy the couple removes is the torsional case's loss.
        let te = t.energy.unwrap();
        let planar_loss = 0.5 * m * vn * vn * (1.0 - e * e);
        close(
            s.energy.unwrap().loss,
            te.loss + planar_loss,
            te.initial + 0.5 * m * vn * vn,
            "T_L",
            &space,
        );
    }
    assert!(regimes[0] > 50 && regimes[1] > 50, "{regimes:?}");
}

/// Checks the invariants of one answer in f64 (relative to the scene's own scales).
fn check_invariants(i: &SpatialImpact, o: &SpatialOutcome) {
    let n = i.contact.normal;
    let nhat = n.map(|x| x / size(n));
    let p = [o.impulse.x, o.impulse.y, o.impulse.z];
    let couple = nhat.map(|x| x * o.impulse.torsional);
    let bodies: Vec<RigidBody> = std::iter::once(i.a).chain(i.b).collect();
    let scale_p = size(p) + o.impulse.normal;
    for (k, b) in bodies.iter().enumerate() {
        let sign = if k == 0 { 1.0 } else { -1.0 };
        let out = &o.bodies[k];
        // Linear momentum: m ΔV = ±P.
        for c in 0..3 {
            close(b.mass * out.velocity_change[c], sign * p[c], scale_p, "m ΔV", i);
            close(
                out.velocity[c],
                b.velocity[c] + out.velocity_change[c],
                size(b.velocity) + size(out.velocity),
                "V",
                i,
            );
        }
        // Angular momentum about the contact point: I Δω = ±(r × P + M n̂).
        let r = [0, 1, 2].map(|c| i.contact.point[c] - b.position[c]);
        let moment = cross(r, p);
        let m = matrix(&b.inertia);
        let turned = [0, 1, 2].map(|c| dot(m[c], out.angular_velocity_change));
        let scale = size(r) * scale_p
            + o.impulse.torsional.abs()
            + [0, 1, 2]
                .iter()
                .map(|&c| dot(m[c].map(f64::abs), out.angular_velocity_change.map(f64::abs)))
                .sum::<f64>();
        for c in 0..3 {
            close(turned[c], sign * (moment[c] + couple[c]), scale, "I Δω", i);
        }
        close(out.delta_v, size(out.velocity_change), out.delta_v, "|ΔV|", i);
    }
    // P_n > 0, the normal law, the split of P.
    assert!(o.impulse.normal > 0.0, "{i:?}");
    let cv = &o.contact_velocity;
    close(
        cv.r#final.normal,
        -o.restitution * cv.initial.normal,
        cv.initial.normal.abs(),
        "U_n",
        i,
    );
    close(o.impulse.normal, dot(p, nhat), scale_p, "P_n", i);
    for c in 0..3 {
        close(
            o.impulse.tangential[c],
            p[c] - o.impulse.normal * nhat[c],
            scale_p,
            "P_t",
            i,
        );
    }
    close(
        o.impulse_ratio,
        size(o.impulse.tangential) / o.impulse.normal,
        o.impulse_ratio.max(1.0),
        "μ",
        i,
    );
    // Energy: never created, never more than T_M.
    let e = o.energy.unwrap();
    assert!(
        e.loss >= 0.0 && e.normalized_loss >= 0.0 && e.normalized_loss <= 1.0,
        "{e:?} {i:?}"
    );
    close(e.r#final, e.initial - e.loss, e.initial, "T_f", i);
    // The regimes keep their own conditions.
    let slip = size(cv.r#final.tangential);
    let slip_scale = size(cv.initial.tangential) + cv.initial.normal.abs();
    match (o.regime, i.law) {
        (Regime::Sticking, Law::Friction { friction, .. }) => {
            close(slip, 0.0, slip_scale, "U_t (sticking)", i);
            assert!(o.impulse_ratio <= friction * (1.0 + 1e-9) + 1e-12, "{i:?}");
        }
        (Regime::Sliding, Law::Friction { friction, .. } | Law::TangentialRestitution { friction, .. }) => {
            if size(o.impulse.tangential) > 0.0 {
                close(o.impulse_ratio, friction, friction, "μ (sliding)", i);
            }
            if let Some(mu_c) = o
                .critical_impulse_ratio
                .filter(|_| matches!(i.law, Law::Friction { .. }))
            {
                assert!(
                    mu_c >= friction * (1.0 - 1e-9),
                    "μ_c {mu_c} < f {friction}: {i:?}"
                );
            }
        }
        (
            Regime::Restitution,
            Law::TangentialRestitution {
                tangential_restitution,
                ..
            },
        ) => {
            for c in 0..3 {
                close(
                    cv.r#final.tangential[c],
                    -tangential_restitution * cv.initial.tangential[c],
                    slip_scale,
                    "U_t",
                    i,
                );
            }
        }
        (
            Regime::Prescribed,
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            },
        ) => {
            // Both phases along one direction against the slip; A-16's e.
            if size(o.impulse.tangential) > 0.0 {
                let mu = (approach_impulse_ratio + value * rebound_impulse_ratio) / (1.0 + value);
                close(o.impulse_ratio, mu, mu, "μ (kinetic)", i);
                let along = dot(o.impulse.tangential, cv.initial.tangential);
                assert!(
                    along <= 1e-12 * size(o.impulse.tangential) * size(cv.initial.tangential),
                    "P_t with the slip: {i:?}"
                );
            }
            if value == 0.0 {
                assert_eq!(o.restitution, 0.0, "{i:?}");
            }
        }
        (
            Regime::Sticking | Regime::Sliding,
            Law::KineticFriction {
                value,
                approach_friction,
                rebound_impulse_ratio,
            },
        ) => {
            // The approach's tangential impulse within f_A times its normal
            // one (P_n^A = P_n/(1 + R)), the rebound's μ_R times R of it.
            let cap = (approach_friction + value * rebound_impulse_ratio) / (1.0 + value);
            assert!(o.impulse_ratio <= cap * (1.0 + 1e-9) + 1e-12, "{i:?}");
            if o.regime == Regime::Sliding && size(o.impulse.tangential) > 0.0 {
                close(o.impulse_ratio, cap, cap, "μ (Coulomb approach, sliding)", i);
            }
        }
        _ => {}
    }
    if let (Some(t), Some(regime)) = (i.torsion, o.torsional_regime) {
        let s = cv.initial.spin;
        if regime == TorsionalRegime::Restitution {
            close(
                cv.r#final.spin,
                -t.restitution * s,
                s.abs() + cv.r#final.spin.abs(),
                "S",
                i,
            );
        }
    }
}

#[test]
fn answers_in_space_conserve_momentum_and_angular_momentum_and_never_create_energy() {
    let mut rng = Rng::new(0x3d_5eed);
    let (mut answered, mut refused) = (0, 0);
    let mut regimes = std::collections::HashMap::new();
    let mut regimes_by_law: std::collections::HashMap<&str, std::collections::HashSet<Regime>> =
        std::collections::HashMap::new();
    for k in 0..4000 {
        let scene = random_scene(&mut rng, k % 3 != 0);
        let fast = solve_in(&scene, Outputs::ALL, Arithmetic::Fast).0;
        let exact = solve_in(&scene, Outputs::ALL, Arithmetic::Exact).0;
        match (fast, exact) {
            (Ok(f), Ok(x)) => {
                answered += 1;
                check_invariants(&scene, &f);
                check_invariants(&scene, &x);
                *regimes.entry((f.regime, f.torsional_regime)).or_insert(0) += 1;
                regimes_by_law
                    .entry(scene.law.describe())
                    .or_default()
                    .insert(f.regime);
                // The two precisions agree to the fast bound (relative to the
                // scale of each group of outputs).
                let scale = size([f.impulse.x, f.impulse.y, f.impulse.z]) + f.impulse.normal;
                close(f.impulse.x, x.impulse.x, scale, "P_x fast", &scene);
                close(f.impulse.normal, x.impulse.normal, scale, "P_n fast", &scene);
                assert_eq!(f.regime, x.regime, "{scene:?}");
            }
            (Err(f), Err(x)) => {
                refused += 1;
                assert_eq!(f.slug(), x.slug(), "{scene:?}");
            }
            (f, x) => panic!("{scene:?}: fast {f:?}, exact {x:?}"),
        }
    }
    assert!(answered > 1500, "answered {answered}, refused {refused}");
    let coulomb_approach = regimes_by_law.get("two-phase kinetic restitution with a Coulomb approach");
    assert!(
        coulomb_approach.is_some_and(|r| r.contains(&Regime::Sticking) && r.contains(&Regime::Sliding)),
        "{regimes_by_law:?}"
    );
    for regime in [
        Regime::Sticking,
        Regime::Sliding,
        Regime::Restitution,
        Regime::Frictionless,
        Regime::Prescribed,
    ] {
        assert!(
            regimes.keys().any(|(r, _)| *r == regime),
            "{regime:?} never seen: {regimes:?}"
        );
    }
    for twist in [TorsionalRegime::Restitution, TorsionalRegime::Sliding] {
        assert!(
            regimes.keys().any(|(_, t)| *t == Some(twist)),
            "{twist:?} never seen: {regimes:?}"
        );
    }
}

#[test]
fn a_rotated_scene_gives_the_rotated_answer() {
    let mut rng = Rng::new(0x0020_7a7e);
    let mut checked = 0;
    for k in 0..1500 {
        let scene = random_scene(&mut rng, k % 2 == 0);
        let Ok(o) = solve(&scene, Outputs::ALL, Precision::Exact) else {
            continue;
        };
        let r = rotation::random(|| rng.range(-1.0, 1.0));
        let turn = |b: &RigidBody| {
            let m = matrix(&b.inertia);
            // R I Rᵀ.
            let ri = [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| r[i][k] * m[k][j]).sum::<f64>()));
            let entry = |i: usize, j: usize| (0..3).map(|k| ri[i][k] * r[j][k]).sum::<f64>();
            RigidBody {
                inertia: [
                    entry(0, 0),
                    entry(1, 1),
                    entry(2, 2),
                    entry(0, 1),
                    entry(0, 2),
                    entry(1, 2),
                ],
                position: rotation::rotate(&r, b.position),
                velocity: rotation::rotate(&r, b.velocity),
                angular_velocity: rotation::rotate(&r, b.angular_velocity),
                ..*b
            }
        };
        let rotated = SpatialImpact {
            a: turn(&scene.a),
            b: scene.b.as_ref().map(turn),
            contact: SpatialContact {
                point: rotation::rotate(&r, scene.contact.point),
                normal: rotation::rotate(&r, scene.contact.normal),
            },
            ..scene
        };
        let Ok(q) = solve(&rotated, Outputs::ALL, Precision::Exact) else {
            continue;
        };
        // A decision within the rotation's roundings of a switch may flip.
        if q.regime != o.regime || q.torsional_regime != o.torsional_regime {
            continue;
        }
        checked += 1;
        let p = rotation::rotate(&r, [o.impulse.x, o.impulse.y, o.impulse.z]);
        let scale = o.impulse.normal + size(p);
        for (c, got) in [q.impulse.x, q.impulse.y, q.impulse.z].into_iter().enumerate() {
            assert!(
                (got - p[c]).abs() <= 1e-8 * scale,
                "P: {got} vs {} in {scene:?}",
                p[c]
            );
        }
        assert!(
            (q.impulse.normal - o.impulse.normal).abs() <= 1e-8 * scale,
            "{scene:?}"
        );
        assert!(
            (q.impulse.torsional - o.impulse.torsional).abs()
                <= 1e-8 * (o.impulse.torsional.abs() + 1e-6 * scale),
            "{scene:?}"
        );
        let e = (q.energy.unwrap(), o.energy.unwrap());
        assert!((e.0.loss - e.1.loss).abs() <= 1e-8 * e.1.initial, "{scene:?}");
        for k in 0..o.body_count {
            let v = rotation::rotate(&r, o.bodies[k].velocity);
            let w = rotation::rotate(&r, o.bodies[k].angular_velocity);
            let sv = size(v) + size(scene.a.velocity);
            let sw = size(w) + size(o.bodies[k].angular_velocity_change) + 1e-6;
            for c in 0..3 {
                assert!((q.bodies[k].velocity[c] - v[c]).abs() <= 1e-8 * sv, "{scene:?}");
                assert!(
                    (q.bodies[k].angular_velocity[c] - w[c]).abs() <= 1e-7 * sw,
                    "{scene:?}"
                );
            }
        }
    }
    assert!(checked > 500, "checked {checked}");
}

fn ball() -> SpatialImpact {
    SpatialImpact {
        a: RigidBody {
            mass: 0.057,
            inertia: [3.5e-5, 3.5e-5, 3.5e-5, 0.0, 0.0, 0.0],
            position: [0.0, 0.0, 0.033],
            velocity: [20.0, 0.0, -10.0],
            angular_velocity: [0.0, -300.0, 0.0],
        },
        b: None,
        contact: SpatialContact {
            point: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        law: Law::Friction {
            restitution: 0.8,
            friction: 0.6,
        },
        torsion: None,
    }
}

fn refusal(i: &SpatialImpact) -> ImpactError {
    let fast = solve(i, Outputs::ALL, Precision::Fast).unwrap_err();
    let exact = solve(i, Outputs::ALL, Precision::Exact).unwrap_err();
    assert_eq!(fast, exact, "{i:?}");
    fast
}

#[test]
fn what_space_cannot_answer_is_refused_naming_the_input() {
    let mut i = ball();
    // An indefinite tensor: the second leading minor is negative.
    i.a.inertia = [1.0, 1.0, 1.0, 2.0, 0.0, 0.0];
    let e = refusal(&i);
    assert!(
        matches!(
            e,
            ImpactError::NotPositiveDefinite {
                input: restitution::Input::InertiaA,
                order: 2,
                ..
            }
        ),
        "{e:?}"
    );
    // Singular: det = 0 exactly (rows 1 and 2 equal), every f64 minor test near zero.
    i.a.inertia = [1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    assert!(matches!(
        refusal(&i),
        ImpactError::NotPositiveDefinite { order: 2, .. }
    ));
    i.a.inertia = [2.0, 2.0, 2.0, 1.0, 1.0, -1.0];
    // det = 2(4−1) − 1(2+1) + 1(−1−2) = 0
    assert!(
        matches!(refusal(&i), ImpactError::NotPositiveDefinite { order: 3, .. }),
        "{:?}",
        refusal(&i)
    );
    // Positive definite by one ulp: accepted.
    i.a.inertia = [2.0, 2.0, 2.0f64.next_up(), 1.0, 1.0, -1.0];
    let accepted = solve(&i, Outputs::ALL, Precision::Fast);
    assert!(
        !matches!(accepted, Err(ImpactError::NotPositiveDefinite { .. })),
        "{accepted:?}"
    );
    // Principal moments that break the triangle inequality (no rigid body has
    // them), diagonal and rotated; a lamina's `I_z = I_x + I_y` in decimal and
    // a breach within the relative tolerance 1e-9 are accepted.
    for (tensor, rigid) in [
        ([1.0, 1.0, 5.0, 0.0, 0.0, 0.0], false),
        ([3.0, 3.0, 1.0, 2.0, 0.0, 0.0], false),
        ([1.0, 1.0, 2.0 + 1e-8, 0.0, 0.0, 0.0], false),
        ([1.0, 1.0, 2.0 + 1e-9, 0.0, 0.0, 0.0], true),
        ([0.1, 0.2, 0.3, 0.0, 0.0, 0.0], true),
    ] {
        let mut i = ball();
        i.a.inertia = tensor;
        let answer = solve(&i, Outputs::ALL, Precision::Fast);
        let broken = matches!(
            answer,
            Err(ImpactError::NotRigidInertia {
                input: restitution::Input::InertiaA,
                ..
            })
        );
        assert_eq!(broken, !rigid, "{tensor:?}: {answer:?}");
        if broken {
            assert_eq!(refusal(&i), answer.unwrap_err());
        }
    }
    let mut i = ball();
    i.b = Some(RigidBody {
        inertia: [f64::NAN, 1.0, 1.0, 0.0, 0.0, 0.0],
        ..i.a
    });
    assert_eq!(
        refusal(&i),
        ImpactError::NotFinite {
            input: restitution::Input::InertiaBXX
        }
    );
    let mut i = ball();
    i.contact.normal = [0.0; 3];
    assert_eq!(
        refusal(&i),
        ImpactError::ZeroVector {
            input: restitution::Input::Normal
        }
    );
    let mut i = ball();
    i.a.velocity[2] = 10.0;
    assert!(matches!(refusal(&i), ImpactError::NotApproaching { .. }));
    let mut i = ball();
    i.law = Law::ImpulseRatio {
        restitution: 0.5,
        impulse_ratio: -0.1,
    };
    assert!(matches!(
        refusal(&i),
        ImpactError::OutOfRange {
            input: restitution::Input::ImpulseRatio,
            ..
        }
    ));
    // The kinetic law's ratios are magnitudes in space; it takes no twist law.
    i.law = Law::KineticRestitution {
        value: 0.5,
        approach_impulse_ratio: 0.1,
        rebound_impulse_ratio: -0.1,
    };
    assert!(matches!(
        refusal(&i),
        ImpactError::OutOfRange {
            input: restitution::Input::ReboundImpulseRatio,
            ..
        }
    ));
    i.law = Law::KineticRestitution {
        value: 0.5,
        approach_impulse_ratio: 0.1,
        rebound_impulse_ratio: 0.1,
    };
    i.torsion = Some(Twist {
        restitution: 0.5,
        friction: 0.1,
        pitch_radius: 0.01,
    });
    assert!(matches!(
        refusal(&i),
        ImpactError::Unavailable {
            input: restitution::Input::Torsion,
            ..
        }
    ));
    // A prescribed ratio with no slip and a sticking impulse with no tangential part.
    let mut i = ball();
    i.a.velocity = [0.0, 0.0, -10.0];
    i.a.angular_velocity = [0.0; 3];
    i.law = Law::ImpulseRatio {
        restitution: 0.5,
        impulse_ratio: 0.3,
    };
    assert_eq!(
        refusal(&i),
        ImpactError::NoSlipDirection {
            input: restitution::Input::ImpulseRatio
        }
    );
    // The kinetic law likewise, at the first phase that needs a direction.
    for (mu_a, mu_r, input) in [
        (0.3, 0.0, restitution::Input::ApproachImpulseRatio),
        (0.0, 0.3, restitution::Input::ReboundImpulseRatio),
    ] {
        i.law = Law::KineticRestitution {
            value: 0.5,
            approach_impulse_ratio: mu_a,
            rebound_impulse_ratio: mu_r,
        };
        assert_eq!(refusal(&i), ImpactError::NoSlipDirection { input });
    }
    i.law = Law::ImpulseRatio {
        restitution: 0.5,
        impulse_ratio: 0.0,
    };
    let o = solve(&i, Outputs::ALL, Precision::Exact).unwrap();
    assert_eq!(o.regime, Regime::Prescribed);
    i.torsion = Some(Twist {
        restitution: 2.0,
        friction: 0.1,
        pitch_radius: 0.01,
    });
    assert!(matches!(
        refusal(&i),
        ImpactError::OutOfRange {
            input: restitution::Input::TorsionalRestitution,
            ..
        }
    ));
}

/// `POST /v1/impacts/spatial` with `kinetic_restitution`: the two-phase law
/// with a prescribed approach ratio or Coulomb friction in the approach, in
/// both precisions, and each refusal at its member.
#[tokio::test]
async fn the_spatial_endpoint_takes_the_two_phase_law_and_refuses_at_its_members() {
    use crate::common::server::spawn_app;
    use reqwest::StatusCode;
    use restitution::http::ServiceConfig;
    use serde_json::{Value, json};
    let app = spawn_app(ServiceConfig::default()).await;
    let tennis = |kinetic: Value| {
        let mut r = crate::common::examples::example("spatial_tennis_topspin.json");
        let o = r.as_object_mut().unwrap();
        o.remove("restitution");
        o.remove("friction");
        o.insert("kinetic_restitution".into(), kinetic);
        r
    };
    let problem = |status: StatusCode, headers: &reqwest::header::HeaderMap, body: &Value, pointer: &str| {
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
        assert_eq!(headers["content-type"], "application/problem+json", "{body}");
        assert_eq!(body["pointer"], pointer, "{body}");
        assert!(body["detail"].as_str().is_some_and(|d| !d.is_empty()), "{body}");
    };
    for precision in ["fast", "exact"] {
        // A ball on its normal: r ∥ n, so D_R = D_A and the equivalent e is R.
        let mut r =
            tennis(json!({"value": 0.75, "approach_impulse_ratio": 0.3, "rebound_impulse_ratio": 0.1}));
        r["precision"] = json!(precision);
        let (status, _, o) = app.post("/v1/impacts/spatial", &r).await;
        assert_eq!(status, StatusCode::OK, "{o}");
        assert_eq!(o["regime"], "prescribed", "{o}");
        assert_eq!(o["restitution"], 0.75, "{o}");
        assert_eq!(o["bodies"][0]["velocity"]["z"], 7.5, "{o}");
        let mu = o["impulse_ratio"].as_f64().unwrap();
        assert!((mu - (0.3 + 0.75 * 0.1) / 1.75).abs() < 1e-15, "{o}");
        // The contact point slips forward (+x) under topspin: P_t points back.
        assert!(o["impulse"]["tangential"]["x"].as_f64().unwrap() < 0.0, "{o}");
        // Coulomb in the approach, a frictionless rebound (a time-stepping
        // engine's contact): the friction is capped by the approach's impulse.
        let mut r = tennis(json!({"value": 0.75, "approach_friction": 0.2, "rebound_impulse_ratio": 0.0}));
        r["precision"] = json!(precision);
        let (status, _, o) = app.post("/v1/impacts/spatial", &r).await;
        assert_eq!(status, StatusCode::OK, "{o}");
        assert_eq!(o["regime"], "sliding", "{o}");
        assert_eq!(o["bodies"][0]["velocity"]["z"], 7.5, "{o}");
        let mu = o["impulse_ratio"].as_f64().unwrap();
        assert!((mu - 0.2 / 1.75).abs() < 1e-15, "{o}");
        let mut r = tennis(json!({"value": 0.75, "approach_friction": 10.0, "rebound_impulse_ratio": 0.0}));
        r["precision"] = json!(precision);
        let (status, _, o) = app.post("/v1/impacts/spatial", &r).await;
        assert_eq!(status, StatusCode::OK, "{o}");
        assert_eq!(o["regime"], "sticking", "{o}");
    }
    let cases = [
        (
            json!({"value": 0.5, "approach_impulse_ratio": 0.1, "approach_friction": 0.1, "rebound_impulse_ratio": 0.0}),
            "/kinetic_restitution/approach_friction",
        ),
        (
            json!({"value": 0.5, "rebound_impulse_ratio": 0.0}),
            "/kinetic_restitution/approach_impulse_ratio",
        ),
        (
            json!({"value": 0.5, "approach_impulse_ratio": 0.1, "rebound_impulse_ratio": -0.1}),
            "/kinetic_restitution/rebound_impulse_ratio",
        ),
        (
            json!({"value": 1.5, "approach_impulse_ratio": 0.1, "rebound_impulse_ratio": 0.1}),
            "/kinetic_restitution/value",
        ),
        (
            json!({"value": 0.5, "approach_friction": -1.0, "rebound_impulse_ratio": 0.1}),
            "/kinetic_restitution/approach_friction",
        ),
    ];
    for (kinetic, pointer) in cases {
        let (status, headers, body) = app.post("/v1/impacts/spatial", &tennis(kinetic)).await;
        problem(status, &headers, &body, pointer);
    }
    let law = json!({"value": 0.5, "approach_impulse_ratio": 0.1, "rebound_impulse_ratio": 0.1});
    let mut r = tennis(law.clone());
    r["torsion"] = json!({"restitution": 0.3, "friction": 0.2, "pitch_radius": 0.01});
    let (status, headers, body) = app.post("/v1/impacts/spatial", &r).await;
    problem(status, &headers, &body, "/torsion");
    assert_eq!(body["type"], "urn:restitution:problem:law-unavailable", "{body}");
    let mut r = tennis(law.clone());
    r["restitution"] = json!(0.5);
    let (status, headers, body) = app.post("/v1/impacts/spatial", &r).await;
    problem(status, &headers, &body, "/restitution");
    // Straight down without spin: no slip and no tangential sticking impulse.
    let mut r = tennis(law);
    r["bodies"][0]["velocity"] = json!({"x": 0.0, "y": 0.0, "z": -10.0});
    r["bodies"][0]["angular_velocity"] = json!({"x": 0.0, "y": 0.0, "z": 0.0});
    let (status, headers, body) = app.post("/v1/impacts/spatial", &r).await;
    problem(
        status,
        &headers,
        &body,
        "/kinetic_restitution/approach_impulse_ratio",
    );
    assert_eq!(
        body["type"], "urn:restitution:problem:no-slip-direction",
        "{body}"
    );
    // The plane has the Coulomb approach phase too (the same law as in space).
    let mut planar = crate::common::examples::example("planar_car_to_car.json");
    let o = planar.as_object_mut().unwrap();
    o.remove("restitution");
    o.remove("friction");
    o.insert(
        "kinetic_restitution".into(),
        json!({"value": 0.2, "approach_friction": 0.6, "rebound_impulse_ratio": 0.0}),
    );
    let (status, _, body) = app.post("/v1/impacts/planar", &planar).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["kinetic_restitution"], 0.2, "{body}");
    assert!(
        matches!(body["regime"].as_str(), Some("sticking" | "sliding")),
        "{body}"
    );
}

/// A sphere on a level plane (the normal along a coordinate axis, of any
/// length): the slip's and the impulse's components along the normal are
/// exact zeros, which the exact stages decide without falling through to
/// fractions, so `exact` costs a few times `fast`, not a hundred. Each
/// answer with generic coefficients settles before the last stage, except
/// where the law itself makes an exact zero (a sticking contact's final
/// slip), and its structural zeros are `+0` in both precisions. A sliding
/// answer's root is taken in the compensated stage.
#[test]
fn a_sphere_on_a_level_plane_settles_before_the_fractions_stage() {
    use restitution::impact::Stage;
    let mut rng = Rng::new(0x5be7e);
    let mut stages = std::collections::BTreeMap::new();
    for k in 0..600 {
        let radius = rng.range(0.01, 0.2);
        let mass = rng.range(0.01, 5.0);
        let i = 2.0 / 3.0 * mass * radius * radius;
        let axis = k % 3;
        let mut normal = [0.0; 3];
        normal[axis] = rng.pick(&[1.0, 2.0, 3.0, 0.7]);
        let mut position = [0.0; 3];
        position[axis] = radius;
        // An approach along the axis, slip and spin in any direction.
        let mut velocity = [
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
        ];
        velocity[axis] = -rng.range(0.5, 20.0);
        let e = rng.range(0.05, 0.95);
        let c = rng.range(0.05, 1.5);
        let law = match k % 6 {
            0 => Law::Frictionless { restitution: e },
            1 => Law::Friction {
                restitution: e,
                friction: c,
            },
            2 => Law::TangentialRestitution {
                restitution: e,
                friction: c,
                tangential_restitution: rng.range(-0.9, 0.9),
            },
            3 => Law::ImpulseRatio {
                restitution: e,
                impulse_ratio: rng.range(0.05, 0.9),
            },
            4 => Law::KineticRestitution {
                value: e,
                approach_impulse_ratio: rng.range(0.05, 0.9),
                rebound_impulse_ratio: rng.range(0.05, 0.9),
            },
            _ => Law::KineticFriction {
                value: e,
                approach_friction: c,
                rebound_impulse_ratio: rng.range(0.05, 0.9),
            },
        };
        let scene = SpatialImpact {
            a: RigidBody {
                mass,
                inertia: [i, i, i, 0.0, 0.0, 0.0],
                position,
                velocity,
                angular_velocity: [
                    rng.range(-300.0, 300.0),
                    rng.range(-300.0, 300.0),
                    rng.range(-300.0, 300.0),
                ],
            },
            b: None,
            contact: SpatialContact {
                point: [0.0; 3],
                normal,
            },
            law,
            torsion: rng.chance(0.3).then(|| Twist {
                restitution: rng.range(0.05, 0.95),
                friction: rng.range(0.05, 1.0),
                pitch_radius: 0.1 * radius,
            }),
        };
        let (fast, _) = solve_in(&scene, Outputs::ALL, Arithmetic::Fast);
        let (exact, stage) = solve_in(&scene, Outputs::ALL, Arithmetic::Exact);
        match (fast, exact) {
            (Ok(f), Ok(x)) => {
                let sticks = f.regime == Regime::Sticking;
                assert!(sticks || stage != Stage::Rational, "{scene:?}");
                *stages.entry((sticks, format!("{stage:?}"))).or_insert(0) += 1;
                for o in [&f, &x] {
                    let zeros = [
                        o.contact_velocity.initial.tangential[axis],
                        o.contact_velocity.r#final.tangential[axis],
                        o.impulse.tangential[axis],
                    ];
                    for z in zeros {
                        assert_eq!(z.to_bits(), 0.0f64.to_bits(), "{scene:?}: {zeros:?}");
                    }
                }
            }
            (Err(f), Err(x)) => assert_eq!(f.slug(), x.slug(), "{scene:?}"),
            (f, x) => panic!("{scene:?}: fast {f:?}, exact {x:?}"),
        }
    }
    eprintln!("(sticks, stage): count {stages:?}");
    // Both stages before the fractions answer some; sticking scenes are there.
    let settled = |name: &str| stages.iter().any(|((_, s), n)| s == name && *n > 0);
    assert!(settled("Compensated") && settled("DoubleDouble"), "{stages:?}");
    assert!(stages.keys().any(|(sticks, _)| *sticks), "{stages:?}");
    // The compensated stage takes the slip's root: nearly every answer that
    // does not stick settles there (without the root, most went on to
    // double-double).
    let moving = |stage: Option<&str>| -> usize {
        stages
            .iter()
            .filter(|((sticks, s), _)| !sticks && stage.is_none_or(|name| s == name))
            .map(|(_, n)| n)
            .sum()
    };
    assert!(moving(Some("Compensated")) * 10 >= moving(None) * 9, "{stages:?}");
}
