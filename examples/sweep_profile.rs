//! A fixed workload for profilers: 1,000,000 points of the oblique sweep with
//! every output on one thread (the case of `benches/sweep.rs`).
//!
//! ```text
//! CARGO_PROFILE_RELEASE_DEBUG=true cargo build --release --example sweep_profile
//! valgrind --tool=callgrind --callgrind-out-file=callgrind.out target/release/examples/sweep_profile
//! callgrind_annotate --inclusive=yes callgrind.out | head -40
//! ```
//!
//! `RESTITUTION_KERNELS=portable` runs the portable copy of the solver instead
//! of the x86-64-v3 one (`restitution::kernels`), as the binary does (and as
//! callgrind needs: valgrind 3.19 stops at an AVX instruction of the other).
//! `sweep_profile one` sweeps the final tangential contact velocity alone
//! (the bench's `one_output`), `sweep_profile fixed` the same over the
//! friction coefficient in `[0, 1]` (the scene built once: the bench's
//! `one_output_fixed_scene`); a second argument `unfiltered` takes every
//! decision on the f64 value as it is (`Arithmetic::Unfiltered`: what the
//! filter of `fast` costs).

use restitution::impact::Arithmetic;
use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{BarrierImpact, Contact, Input, Law, Output, PlanarVelocity};

fn main() {
    if std::env::var("RESTITUTION_KERNELS").as_deref() == Ok("portable") {
        restitution::kernels::force_portable();
    }
    eprintln!("kernels: {}", restitution::kernels::selected().as_str());
    let base = BarrierImpact::rigid(
        1.0,
        0.00125,
        Contact {
            tangential_offset: 0.01,
            normal_offset: 0.05,
        },
        PlanarVelocity {
            normal: -1.0,
            tangential: 0.0,
            angular: 2.0,
        },
        Law::Friction {
            restitution: 0.93,
            friction: 0.123,
        },
    );
    let args: Vec<String> = std::env::args().skip(1).collect();
    let velocity = (Input::TangentialVelocity, -5.0, 5.0);
    let (columns, (param, start, stop)) = match args.first().map(String::as_str) {
        Some("one") => (vec![Output::FinalTangentialContactVelocity], velocity),
        Some("fixed") => (
            vec![Output::FinalTangentialContactVelocity],
            (Input::Friction, 0.0, 1.0),
        ),
        None | Some("three") => (
            vec![
                Output::FinalTangentialContactVelocity,
                Output::CriticalImpulseRatio,
                Output::NormalizedEnergyLoss,
            ],
            velocity,
        ),
        Some(other) => panic!("workload: one, fixed or three, not {other}"),
    };
    let arithmetic = match args.get(1).map(String::as_str) {
        None | Some("fast") => Arithmetic::Fast,
        Some("unfiltered") => Arithmetic::Unfiltered,
        Some(other) => panic!("arithmetic: fast or unfiltered, not {other}"),
    };
    let case = CaseSweep::in_arithmetic(&base, &[param], columns, arithmetic).expect("an input of the law");
    let axes = vec![Axis {
        param,
        values: AxisValues::Linspace {
            start,
            stop,
            count: 1_000_000,
        },
    }];
    let sweep = Sweep::new(case, base, axes, Combine::Product, u64::MAX).expect("a valid sweep");
    let mut sum = 0.0;
    sweep.for_each_in(0..sweep.points(), |row| {
        if let Ok([Cell::Number(x), ..]) = row.outcome {
            sum += x;
        }
    });
    println!("{sum}");
}
