//! The arithmetics the impact model ([`crate::model`]) is evaluated in, one
//! [`Field`] each:
//!
//! - [`Filtered`] (`filtered.rs`, `fast` precision): plain doubles, fused where
//!   a form asks for it, each with a static error bound that every decision
//!   is checked against (the caller answers in exact arithmetic where one is
//!   too close to call, or a value leaves the f64 range);
//! - `f64`: the same doubles without the bound, deciding as f64 does (tests
//!   of the f64 forms over wide magnitudes, and fits);
//! - [`Compensated`] (`compensated/`): the plain f64 evaluation and its
//!   rounding errors, gathered by error-free transformations, with a static
//!   error bound (answers every typical input in `exact` precision);
//! - [`Bounded`] (`bounded.rs`) double-doubles with a bound tracked operation by
//!   operation, where the compensated stage failed for range reasons
//!   (ill-conditioned quotients, exponents near the ends of the range);
//! - `Bounded<true>`: the same keeping exact sums and products exact (exact
//!   rounding ties and cancelled zeros formed without a quotient);
//! - [`Lanes`] (`lanes.rs`): `fast`'s first field for several points of a
//!   sweep at once, deciding where every lane decides alike, and
//!   [`SharedLanes`] (`filtered/shared.rs`), the same with one static bound
//!   for all lanes (one and two laminae);
//! - [`Surd`]s, `a + b √g` in exact fractions of big integers, which always
//!   decide (every answer holds at most one square root, that of its sliding
//!   direction in space).
//!
//! Each is more decisive and dearer than the last; the order in which `exact`
//! precision tries them is in [`crate::impact`].

/// The [`Field`] methods that read one value, in a field of several points
/// (lanes), which has none: each is `Diverged` (the points are solved one
/// by one), and outputs are read lane by lane ([`Field::lanes_output`]).
macro_rules! no_one_value {
    () => {
        #[cfg_attr(not(debug_assertions), inline(always))]
        fn round(&self) -> Result<f64, Diverged> {
            Err(Diverged)
        }
        #[cfg_attr(not(debug_assertions), inline(always))]
        fn round_output(&self, _: ScaleKind) -> Result<f64, Diverged> {
            Err(Diverged)
        }
        #[cfg_attr(not(debug_assertions), inline(always))]
        fn round_times_sqrt(&self, _: &Self) -> Result<f64, Diverged> {
            Err(Diverged)
        }
        #[cfg_attr(not(debug_assertions), inline(always))]
        fn round_output_times_sqrt(&self, _: &Self, _: ScaleKind) -> Result<f64, Diverged> {
            Err(Diverged)
        }
    };
}

mod bounded;
mod compensated;
mod field;
mod filtered;
mod fraction;
mod lanes;
mod surd;

pub(crate) use bounded::Bounded;
pub(crate) use compensated::{Compensated, Unsettled};
pub(crate) use field::{Field, OutOfRange, Undecided};
pub(crate) use filtered::{Filtered, SharedLanes, Uncertain, measure_against};
pub(crate) use fraction::Fraction;
pub(crate) use lanes::{Lanes, MAX_LANES, measure_lanes_against};
pub(crate) use surd::{Radical, Surd};
