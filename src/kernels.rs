//! Which compiled copy of the hot code runs: the portable one (baseline
//! x86-64, or whatever the target is), or, on an x86-64 CPU with AVX2, FMA and
//! the rest of x86-64-v3 (Haswell, Zen and later), a copy compiled for those
//! instructions. The choice is made once, at the first use, from what the CPU
//! reports; [`force_portable`] overrides it (the binary's `--kernels portable`,
//! `RESTITUTION_KERNELS=portable`).
//!
//! Answers are the same bits either way: Rust never contracts `a·b + c` into a
//! fused multiply-add by itself, and the model's explicit `mul_add` is
//! correctly rounded on both paths (one instruction on x86-64-v3; a call into
//! compiler-builtins' software fma on the portable path, which is what makes
//! that path slower). `tests/kernels.rs` runs both and compares the bytes.
//!
//! `run` is the only door: it wraps a closure whose body is inlined into
//! the x86-64-v3 copy. Target features do not pass to a function that is
//! called rather than inlined: such a function is compiled once, for the
//! baseline, where every `mul_add` is a call into the software fma. So the
//! model's functions are `#[inline(always)]` (a plain `#[inline]` is a hint
//! that large functions and closures called twice do not get), closures
//! that would be called more than once are functions or are marked
//! `#[inline(always)]` too, and where the model calls itself (a spatial
//! branch that needs another branch's solution) the cycle passes through
//! `run` again, whose copy is then the one out-of-line function. The
//! stages of the exact evaluation pass through `run` too. A
//! profile of a release build that shows `fma` or a model function beside
//! `kernels::v3` has a function left out (measured: 2.3× on a spatial solve
//! with twist, 2.2× on two laminae in world axes).
//!
//! A debug build (the tests' build, unoptimised) compiles the portable copy
//! alone and reports it ([`V3_COMPILED`]): unoptimised, the second copy ran
//! no faster (the tests' held-out fit, 152.3 s with it against 136.9 s
//! without) and made the library and its unit tests take about half as
//! long again to build (docs/performance.md, "The CI's run time"). The two
//! copies are compared with the release binary (`tests/kernels.rs` with
//! `RESTITUTION_BINARY`, as `.ci/run` runs it).
//!
//! For the same reason the forced inlining is written
//! `#[cfg_attr(not(debug_assertions), inline(always))]`: it exists for the
//! copies, and a debug build has one. Unoptimised, the whole model inlined
//! into each entry made frames of about a megabyte and bought nothing. Left
//! out of the test build, the crate's targets built in 105 s instead of
//! 165–213 s, and the library's and suite's tests ran in 298 s instead of
//! 412 s (547 s of CPU against 687 s; the held-out fit 66 s against 158 s).
#![allow(unsafe_code)]

use std::sync::atomic::{AtomicU8, Ordering};

/// A compiled copy of the hot code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernels {
    /// Compiled for the build's target (baseline x86-64 unless told otherwise).
    Portable,
    /// Compiled for x86-64-v3 (AVX2, FMA, BMI1/2, LZCNT, MOVBE, F16C).
    X86_64V3,
}

impl Kernels {
    /// The name the binary's `--kernels` option and its log use.
    pub fn as_str(self) -> &'static str {
        match self {
            Kernels::Portable => "portable",
            Kernels::X86_64V3 => "x86-64-v3",
        }
    }
}

/// Whether this build compiles the x86-64-v3 copy: on x86-64, in an
/// optimised build (module documentation).
pub const V3_COMPILED: bool = cfg!(all(target_arch = "x86_64", not(debug_assertions)));

const UNDECIDED: u8 = 0;
const PORTABLE: u8 = 1;
const V3: u8 = 2;

static SELECTED: AtomicU8 = AtomicU8::new(UNDECIDED);

/// The copy that runs: x86-64-v3 where the CPU has it, unless
/// [`force_portable`] was called.
#[inline]
pub fn selected() -> Kernels {
    match SELECTED.load(Ordering::Relaxed) {
        PORTABLE => Kernels::Portable,
        V3 => Kernels::X86_64V3,
        _ => detect(),
    }
}

#[cold]
fn detect() -> Kernels {
    let kernels = if V3_COMPILED && cpu_has_v3() {
        Kernels::X86_64V3
    } else {
        Kernels::Portable
    };
    let code = if kernels == Kernels::X86_64V3 {
        V3
    } else {
        PORTABLE
    };
    // A concurrent force_portable wins.
    match SELECTED.compare_exchange(UNDECIDED, code, Ordering::Relaxed, Ordering::Relaxed) {
        Ok(_) => kernels,
        Err(_) => selected(),
    }
}

/// Runs the portable copy from now on, whatever the CPU has (for comparison
/// and for a CPU whose feature report is not trusted).
pub fn force_portable() {
    SELECTED.store(PORTABLE, Ordering::Relaxed);
}

/// Whether the CPU has every x86-64-v3 feature the fast copy is compiled for
/// (whether or not this build compiles that copy: [`V3_COMPILED`]).
pub fn cpu_has_v3() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("fma")
            && std::arch::is_x86_feature_detected!("bmi1")
            && std::arch::is_x86_feature_detected!("bmi2")
            && std::arch::is_x86_feature_detected!("lzcnt")
            && std::arch::is_x86_feature_detected!("movbe")
            && std::arch::is_x86_feature_detected!("f16c")
            && std::arch::is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Runs `work` in the selected copy. Either way `work` gets a function (and
/// a stack frame) of its own: the stages of the exact evaluation, each run
/// through here, do not pile their frames into one.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn run<R>(work: impl FnOnce() -> R) -> R {
    #[cfg(all(target_arch = "x86_64", not(debug_assertions)))]
    if selected() == Kernels::X86_64V3 {
        // SAFETY: `selected()` is `X86_64V3` only when `cpu_has_v3()` found
        // every feature `v3` is compiled with on this CPU.
        return unsafe { v3(work) };
    }
    portable(work)
}

/// `work` compiled for the build's target.
#[inline(never)]
fn portable<R>(work: impl FnOnce() -> R) -> R {
    work()
}

/// `work` compiled for x86-64-v3; its callees are inlined into it where they
/// are `#[inline]` (a function compiled for fewer features may be inlined
/// into one compiled for more).
#[cfg(all(target_arch = "x86_64", not(debug_assertions)))]
#[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,movbe,f16c,popcnt")]
fn v3<R>(work: impl FnOnce() -> R) -> R {
    work()
}
