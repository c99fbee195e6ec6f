//! Axes and ticks: the data's extent, tick candidates on linear and
//! logarithmic axes, and the choice among them.

use super::*;

/// The range of the finite values (positive ones on a log scale), padded.
pub(super) fn extent(values: impl Iterator<Item = f64>, scale: Scale) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (scale == Scale::Linear || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    match scale {
        Scale::Linear if !lo.is_finite() => (0.0, 1.0),
        Scale::Linear => {
            let pad = if hi > lo {
                (hi - lo) * 0.05
            } else {
                if lo == 0.0 { 0.05 } else { lo.abs() * 0.05 }
            };
            (lo - pad, hi + pad)
        }
        Scale::Log if !lo.is_finite() => (1.0, 10.0),
        Scale::Log => {
            let (a, b) = (lo.log10(), hi.log10());
            let pad = if b > a { (b - a) * 0.04 } else { 0.5 };
            (10f64.powf(a - pad), 10f64.powf(b + pad))
        }
    }
}

/// One axis: its values' range mapped onto a pixel range.
#[derive(Debug, Clone, Copy)]
pub(super) struct Axis {
    pub(super) scale: Scale,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// Pixel of `lo`.
    pub(super) from: f64,
    /// Pixel of `hi`.
    pub(super) to: f64,
}

impl Axis {
    pub(super) fn t(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
        }
    }

    pub(super) fn at(&self, v: f64) -> f64 {
        self.from + self.t(v) * (self.to - self.from)
    }

    pub(super) fn shows(&self, v: f64) -> bool {
        v.is_finite() && (self.scale == Scale::Linear || v > 0.0)
    }
}

/// An axis's ticks: labelled ones with grid lines, unlabelled minor ones.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Ticks {
    pub(super) major: Vec<(f64, String)>,
    pub(super) minor: Vec<f64>,
    /// A factor every label shares (`×10^{n}`), said once after the axis name.
    pub(super) factor: Option<String>,
}

/// The decimals that write `step` exactly.
pub(super) fn decimals(step: f64) -> usize {
    (0..=15)
        .find(|&d| {
            let scaled = step * 10f64.powi(d as i32);
            (scaled - scaled.round()).abs() <= 1e-6 * scaled.abs().max(1.0)
        })
        .unwrap_or(15)
}

/// A number as a tick label: `decimals` decimals, a true minus, no negative zero.
pub(super) fn fixed(value: f64, decimals: usize) -> String {
    let s = format!("{value:.decimals$}");
    let zero = s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.');
    if zero {
        s.trim_start_matches('-').to_owned()
    } else {
        s.replace('-', "−")
    }
}

pub(super) fn power_of_ten(k: i32) -> String {
    format!("10^{{{}}}", k.to_string().replace('-', "−"))
}

/// Candidate linear tick sets for `[lo, hi]`, densest first.
pub(super) fn linear_candidates(lo: f64, hi: f64) -> Vec<Ticks> {
    let span = hi - lo;
    if span.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !span.is_finite() {
        return vec![Ticks::default()];
    }
    let magnitude = lo.abs().max(hi.abs());
    let exponent = magnitude.log10().floor() as i32;
    let factored = !(1e-3..1e5).contains(&magnitude);
    let scale = if factored { 10f64.powi(exponent) } else { 1.0 };
    let k0 = (span / 30.0).log10().floor() as i32;
    let mut candidates = Vec::new();
    for k in k0..=k0 + 3 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let step = m * 10f64.powi(k);
            let first = (lo / step).ceil() as i64;
            let last = (hi / step).floor() as i64;
            if last - first > 40 || last < first + 1 {
                continue;
            }
            let d = decimals(step / scale);
            let major = (first..=last)
                .map(|i| {
                    let v = i as f64 * step;
                    (v, fixed(v / scale, d))
                })
                .collect();
            candidates.push(Ticks {
                major,
                minor: Vec::new(),
                factor: factored.then(|| format!("×{}", power_of_ten(exponent))),
            });
        }
    }
    if candidates.is_empty() {
        let d = decimals(span / scale).min(6);
        candidates.push(Ticks {
            major: vec![(lo, fixed(lo / scale, d)), (hi, fixed(hi / scale, d))],
            minor: Vec::new(),
            factor: factored.then(|| format!("×{}", power_of_ten(exponent))),
        });
    }
    candidates
}

/// Candidate logarithmic tick sets for `[lo, hi]`, densest first: `1 2 5`
/// steps written as decimals when the axis spans a few decades, powers of ten
/// (every decade, then every second, third, …) otherwise.
pub(super) fn log_candidates(lo: f64, hi: f64) -> Vec<Ticks> {
    let (a, b) = (lo.log10(), hi.log10());
    let (k0, k1) = (a.floor() as i32, b.ceil() as i32);
    let inside = |v: f64| v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12);
    let decimal = |m: f64, k: i32| fixed(m * 10f64.powi(k), (-k).max(0) as usize);
    let mut candidates = Vec::new();
    if b - a <= 3.0 {
        for mantissas in [&[1.0, 2.0, 5.0][..], &[1.0][..]] {
            let mut ticks = Ticks::default();
            for k in k0..=k1 {
                for m in 1..10 {
                    let v = f64::from(m) * 10f64.powi(k);
                    if !inside(v) {
                        continue;
                    }
                    if mantissas.contains(&f64::from(m)) {
                        ticks.major.push((v, decimal(f64::from(m), k)));
                    } else {
                        ticks.minor.push(v);
                    }
                }
            }
            if ticks.major.len() >= 2 {
                candidates.push(ticks);
            }
        }
    }
    for every in 1..=((k1 - k0).max(1)) {
        let mut ticks = Ticks::default();
        for k in k0..=k1 {
            let v = 10f64.powi(k);
            if inside(v) && k.rem_euclid(every) == 0 {
                ticks.major.push((v, power_of_ten(k)));
            } else if inside(v) {
                ticks.minor.push(v);
            }
            if every == 1 {
                ticks
                    .minor
                    .extend((2..10).map(|m| f64::from(m) * v).filter(|&v| inside(v)));
            }
        }
        if ticks.major.len() >= 2 || every == (k1 - k0).max(1) {
            candidates.push(ticks);
        }
    }
    candidates
}

/// The densest candidate whose labels keep `gap` pixels apart along the axis
/// (`extent` gives a label's size along it) and whose ticks are `spacing`
/// pixels apart at least, else the sparsest.
pub(super) fn choose(
    axis: &Axis,
    candidates: Vec<Ticks>,
    extent: impl Fn(&str) -> f64,
    gap: f64,
    spacing: f64,
) -> Ticks {
    let fits = |t: &Ticks| {
        let mut at: Vec<f64> = t.major.iter().map(|(v, _)| axis.at(*v)).collect();
        at.sort_by(f64::total_cmp);
        if at.windows(2).any(|w| w[1] - w[0] < spacing) {
            return false;
        }
        let mut spans: Vec<(f64, f64)> = t
            .major
            .iter()
            .map(|(v, label)| {
                let p = axis.at(*v);
                let half = extent(label) / 2.0;
                (p - half, p + half)
            })
            .collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        spans.windows(2).all(|w| w[1].0 - w[0].1 >= gap)
    };
    let last = candidates.len().saturating_sub(1);
    candidates
        .into_iter()
        .enumerate()
        .find(|(i, t)| *i == last || fits(t))
        .map(|(_, t)| t)
        .unwrap_or_default()
}

pub(super) fn candidates(scale: Scale, lo: f64, hi: f64) -> Vec<Ticks> {
    match scale {
        Scale::Linear => linear_candidates(lo, hi),
        Scale::Log => log_candidates(lo, hi),
    }
}
