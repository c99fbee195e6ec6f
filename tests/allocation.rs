//! The sweep engine's hot path does not allocate per point: a counting global
//! allocator sees the same few allocations (the range's buffers) for 1,000 and
//! for 100,000 points, in every case.
//!
//! The sweep runs on the calling thread, and only that thread's allocations
//! are counted: the test harness's own threads allocate at times of their
//! own (a run under load saw 13 against 9).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use restitution::sweep::{Axis, AxisValues, CaseSweep, Combine, Sweep, SweepCase};
use restitution::{BarrierImpact, Contact, Input, Law, Output, PlanarVelocity, Precision, TorsionalImpact};

struct Counting;

thread_local! {
    /// This thread's allocations (const-initialised, no destructor: safe to
    /// touch from inside the allocator).
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_for<C: SweepCase>(sweep: &Sweep<C>, points: u64) -> u64 {
    let before = allocations();
    let mut answered = 0u64;
    sweep.for_each_in(0..points, |row| answered += u64::from(row.outcome.is_ok()));
    assert!(answered > 0, "no point answered");
    allocations() - before
}

fn planar(law: Law, param: Input, columns: Vec<Output>) -> Sweep<CaseSweep<BarrierImpact>> {
    let base = BarrierImpact::rigid(
        1.0,
        0.00125,
        Contact {
            tangential_offset: 0.01,
            normal_offset: 0.05,
        },
        PlanarVelocity {
            normal: -1.0,
            tangential: 0.3,
            angular: 2.0,
        },
        law,
    );
    let case = CaseSweep::new(&base, &[param], columns, Precision::Fast).unwrap();
    // Values crossing regimes and invalid points (v_n > 0, f < 0) alike.
    let start = if param == Input::Friction { -0.001 } else { -5.0 };
    let axes = vec![Axis {
        param,
        values: AxisValues::Linspace {
            start,
            stop: 5.0,
            count: 100_000,
        },
    }];
    Sweep::new(case, base, axes, Combine::Product, u64::MAX).unwrap()
}

#[test]
fn no_allocation_per_point() {
    let every = vec![
        Output::FinalTangentialContactVelocity,
        Output::Regime,
        Output::CriticalImpulseRatio,
        Output::NormalizedEnergyLoss,
    ];
    let friction = Law::Friction {
        restitution: 0.93,
        friction: 0.123,
    };
    let sweeps = [
        planar(friction, Input::TangentialVelocity, every.clone()),
        planar(
            Law::TangentialRestitution {
                restitution: 0.93,
                friction: 0.123,
                tangential_restitution: 0.34,
            },
            Input::TangentialVelocity,
            every.clone(),
        ),
        planar(
            Law::KineticRestitution {
                value: 0.9,
                approach_impulse_ratio: -0.05,
                rebound_impulse_ratio: -0.04,
            },
            Input::NormalVelocity,
            every.clone(),
        ),
        planar(
            Law::ImpulseRatio {
                restitution: 0.93,
                impulse_ratio: -0.05,
            },
            Input::AngularVelocity,
            every.clone(),
        ),
        planar(friction, Input::Friction, vec![Output::Regime]),
    ];
    for sweep in &sweeps {
        let small = allocations_for(sweep, 1_000);
        let large = allocations_for(sweep, 100_000);
        assert_eq!(small, large, "allocations grow with the number of points");
        // The odometer's axis lengths and digits, each axis's sampler, the
        // current axis values, the row handed to the visitor, and the
        // block's axis values, digits, outcomes, refusals and cells, and the
        // points where they are evaluated together: eleven buffers per
        // range, whatever its length.
        assert!(large <= 11, "{large} allocations per range");
    }
    let base = TorsionalImpact {
        mass: 0.1,
        normal_inertia: 3.6e-5,
        normal_velocity: -3.0,
        spin: 0.0,
        restitution: 0.8,
        torsional_restitution: 0.2,
        torsional_friction: 0.3,
        pitch_radius: 0.005,
    };
    let torsional = Sweep::new(
        CaseSweep::new(
            &base,
            &[Input::Spin],
            vec![Output::FinalSpin, Output::EnergyLoss],
            Precision::Fast,
        )
        .unwrap(),
        base,
        vec![Axis {
            param: Input::Spin,
            values: AxisValues::Linspace {
                start: -100.0,
                stop: 100.0,
                count: 100_000,
            },
        }],
        Combine::Product,
        u64::MAX,
    )
    .unwrap();
    assert_eq!(
        allocations_for(&torsional, 1_000),
        allocations_for(&torsional, 100_000)
    );
}
