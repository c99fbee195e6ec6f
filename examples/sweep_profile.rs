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
//! of the x86-64-v3 one (`restitution::kernels`), as the binary does.

use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{Contact, Input, Law, Output, PlanarImpact, PlanarVelocity, Precision};

fn main() {
    if std::env::var("RESTITUTION_KERNELS").as_deref() == Ok("portable") {
        restitution::kernels::force_portable();
    }
    eprintln!("kernels: {}", restitution::kernels::selected().as_str());
    let base = PlanarImpact::rigid(
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
    let columns = vec![
        Output::FinalTangentialContactVelocity,
        Output::CriticalImpulseRatio,
        Output::NormalizedEnergyLoss,
    ];
    let case = CaseSweep::new(&base, &[Input::TangentialVelocity], columns, Precision::Fast)
        .expect("a rigid body reads its velocities");
    let axes = vec![Axis {
        param: Input::TangentialVelocity,
        values: AxisValues::Linspace {
            start: -5.0,
            stop: 5.0,
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
