//! The validation datasets (`tests/data/`, each copied from its published source
//! with their provenance headers) and the model's predictions for them, shared
//! by `tests/validation.rs` (bounds) and `examples/validation_report.rs`
//! (tables and plots in `docs/validation.md`).
//!
//! Every dataset is a sphere on a rigid plane: `I = 2/5 m R²`, contact at
//! `d_c = 0`, `d_d = R` (so `1 + λ = 1 + d_d²/k² = 3.5`), in the planar model
//! with the bilinear tangential law (Eqs 20–27): `e_t = 0` is Coulomb friction
//! alone, and a fitted `e_t` the tangential-restitution model. The model's
//! values come from the sweep engine (`restitution::sweep`), one zipped sweep
//! over the initial velocities per curve.

use super::rotation::{Rotation, rotate};
use std::collections::BTreeMap;

use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{
    BarrierImpact, Contact, Input, Law, Output, PlanarVelocity, Precision, RigidBody, SpatialContact,
    SpatialImpact,
};

/// Where the data files are.
pub const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data");

/// How a dataset's abscissa sets the initial velocities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// Incidence angle θ in degrees from the normal at speed `speed`, no spin:
    /// `v_n = −|v| cos θ`, `v_t = |v| sin θ`.
    Incidence { speed: f64 },
    /// `x = v_t / (μ |v_n|)` at `|v_n| = normal_speed`, no spin.
    TangentialOverFriction { normal_speed: f64 },
    /// `x = 3.5 μ (1 + e) |v_n| / |v_ct|` (`f / μ_c` for a sphere), `v_t = 0`,
    /// spin alone giving `v_ct > 0`.
    CriticalOverSlip { normal_speed: f64 },
    /// `x = v_ct / |v_n|`, `v_t = 0`, spin alone giving `v_ct > 0`.
    SlipOverNormal { normal_speed: f64 },
}

/// A plotted quantity and how it is formed from the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Quantity {
    /// `atan(V_t / V_n)` in degrees.
    ReboundAngleCentroid,
    /// `atan(V_ct / V_n)` in degrees.
    ReboundAngleContactPoint,
    /// `V_t / v_t` (what these sources call a "tangential coefficient of restitution"; not `e_t`).
    CentroidRatio,
    /// `|Ω|` in rad/s.
    SpinMagnitude,
    /// `V_ct / (μ V_n)`.
    RecoilOverFriction,
    /// `R |Ω| / (μ |v_n|)`.
    SpinOverFriction,
    /// `β = −V_ct / v_ct` (Walton's sign: −1 no change, 0 rolling, 1 full reversal).
    Beta,
    /// `V_ct / V_n`.
    RecoilOverRebound,
}

impl Quantity {
    /// The name used in tables and file names.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::ReboundAngleCentroid => "rebound_angle_centroid",
            Quantity::ReboundAngleContactPoint => "rebound_angle_contact_point",
            Quantity::CentroidRatio => "tangential_cor_centroid",
            Quantity::SpinMagnitude => "spin_magnitude",
            Quantity::RecoilOverFriction => "norm_recoil_Vct_over_mu_Vn",
            Quantity::SpinOverFriction => "norm_spin_R_Omega_over_mu_vn",
            Quantity::Beta => "beta",
            Quantity::RecoilOverRebound => "tan_recoil_Vct_over_Vn",
        }
    }

    /// The axis label.
    pub fn label(self) -> &'static str {
        match self {
            Quantity::ReboundAngleCentroid => "rebound angle atan(V_t/V_n) (deg)",
            Quantity::ReboundAngleContactPoint => "rebound angle atan(V_ct/V_n) (deg)",
            Quantity::CentroidRatio => "V_t / v_t",
            Quantity::SpinMagnitude => "|Ω| (rad/s)",
            Quantity::RecoilOverFriction => "V_ct / (μ V_n)",
            Quantity::SpinOverFriction => "R |Ω| / (μ |v_n|)",
            Quantity::Beta => "β = −V_ct / v_ct",
            Quantity::RecoilOverRebound => "V_ct / V_n",
        }
    }

    /// Whether the data's sign is an axis convention of the source (only the
    /// magnitude is compared).
    fn magnitude_only(self) -> bool {
        matches!(self, Quantity::SpinMagnitude | Quantity::SpinOverFriction)
    }
}

/// One measured (or reference) point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub x: f64,
    pub value: f64,
}

/// A series of a dataset: one source (digitization, material, code) of one quantity.
#[derive(Debug, Clone)]
pub struct Series {
    pub source: String,
    pub quantity: Quantity,
    pub points: Vec<Point>,
}

/// A dataset: the impact it describes and its series.
#[derive(Debug, Clone)]
pub struct Dataset {
    /// Short name, used in file names.
    pub key: &'static str,
    /// Title for tables and plots.
    pub title: &'static str,
    /// The data file in [`DATA_DIR`].
    pub file: &'static str,
    pub radius: f64,
    pub restitution: f64,
    pub friction: f64,
    /// How the abscissa sets the velocities, and its label, per quantity.
    pub drives: Vec<(Quantity, Drive, &'static str)>,
    /// The quantity `e_t` is fitted to.
    pub fitted: Quantity,
    pub series: Vec<Series>,
}

/// Reads the rows `(source, quantity, x, value)` of a data file whose first
/// four columns are those, keeping the sources and quantities `keep` maps.
fn read(file: &str, keep: impl Fn(&str, &str) -> Option<(String, Quantity)>) -> Result<Vec<Series>, String> {
    let path = format!("{DATA_DIR}/{file}");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?;
    let mut series: BTreeMap<(String, Quantity), Vec<Point>> = BTreeMap::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() < 4 {
            return Err(format!("{path}: short row {line:?}"));
        }
        let Some(key) = keep(fields[0], fields[1]) else {
            continue;
        };
        let number = |s: &str| s.trim().parse::<f64>().map_err(|e| format!("{path}: {s:?}: {e}"));
        let mut value = number(fields[3])?;
        if key.1.magnitude_only() {
            value = value.abs();
        }
        series.entry(key).or_default().push(Point {
            x: number(fields[2])?,
            value,
        });
    }
    Ok(series
        .into_iter()
        .map(|((source, quantity), points)| Series {
            source,
            quantity,
            points,
        })
        .collect())
}

/// The same drive and abscissa for every quantity of `series`.
fn every(series: &[Series], drive: Drive, label: &'static str) -> Vec<(Quantity, Drive, &'static str)> {
    let mut q: Vec<Quantity> = series.iter().map(|s| s.quantity).collect();
    q.sort();
    q.dedup();
    q.into_iter().map(|q| (q, drive, label)).collect()
}

/// Kharaz, Gorham & Salman (2001): the experiment, three digitizations.
pub fn kharaz() -> Result<Dataset, String> {
    let file = "kharaz2001_al2o3_on_glass_experiment.csv";
    let series = read(file, |source, quantity| {
        let q = match quantity {
            "rebound_angle_centroid" => Quantity::ReboundAngleCentroid,
            "rebound_angle_contact_point" => Quantity::ReboundAngleContactPoint,
            "tangential_cor_centroid" => Quantity::CentroidRatio,
            "spin_magnitude" => Quantity::SpinMagnitude,
            _ => return None,
        };
        Some((source.to_owned(), q))
    })?;
    Ok(kharaz_impact(
        "kharaz2001",
        "Kharaz et al. (2001), Al₂O₃ spheres on glass (experiment)",
        file,
        series,
    ))
}

/// Kharaz's impact (Chung & Ooi's Test 4 too): 5 mm spheres at 3.9 m/s,
/// `e = 0.98`, `μ = 0.092`, against incidence; `e_t` fitted to `V_t/v_t`.
fn kharaz_impact(key: &'static str, title: &'static str, file: &'static str, series: Vec<Series>) -> Dataset {
    Dataset {
        key,
        title,
        file,
        radius: 0.0025,
        restitution: 0.98,
        friction: 0.092,
        drives: every(
            &series,
            Drive::Incidence { speed: 3.9 },
            "incidence from the normal (deg)",
        ),
        fitted: Quantity::CentroidRatio,
        series,
    }
}

/// Chung & Ooi (2011) Test 4: the same impact as Kharaz's, their DEM reference
/// curves for Al oxide and Al alloy (both `e = 0.98`, `μ = 0.092`).
pub fn chung_ooi_test4() -> Result<Dataset, String> {
    let file = "chung_ooi2011_test4_reference.csv";
    let series = read(file, |material, quantity| {
        let q = match quantity {
            "tangential_cor_centroid" => Quantity::CentroidRatio,
            "spin_signed_kratos_axis" => Quantity::SpinMagnitude,
            "rebound_angle_contact_point" => Quantity::ReboundAngleContactPoint,
            _ => return None,
        };
        Some((material.to_owned(), q))
    })?;
    Ok(kharaz_impact(
        "chung_ooi_test4",
        "Chung & Ooi (2011) Test 4, sphere on a plane at 3.9 m/s (DEM reference)",
        file,
        series,
    ))
}

/// Chung & Ooi (2011) Test 5: constant `|v_n|`, varying `v_t`; the steel DEM
/// curves (`e = 1`, `μ = 0.3`, `|v_n| = 5 m/s`). The polyethylene and FEM
/// curves are not compared: their `e` and `μ` are not in the data.
pub fn chung_ooi_test5() -> Result<Dataset, String> {
    let file = "chung_ooi2011_test5_reference.csv";
    let series = read(file, |series, quantity| {
        if series != "steel_DEM" {
            return None;
        }
        let q = match quantity {
            "norm_recoil_Vct_over_mu_Vn" => Quantity::RecoilOverFriction,
            "norm_spin_R_Omega_over_mu_vn" => Quantity::SpinOverFriction,
            _ => return None,
        };
        Some((series.to_owned(), q))
    })?;
    Ok(Dataset {
        key: "chung_ooi_test5",
        title: "Chung & Ooi (2011) Test 5, steel sphere, varying v_t (DEM reference)",
        file,
        radius: 1e-5,
        restitution: 1.0,
        friction: 0.3,
        drives: every(
            &series,
            Drive::TangentialOverFriction { normal_speed: 5.0 },
            "v_t / (μ |v_n|)",
        ),
        fitted: Quantity::RecoilOverFriction,
        series,
    })
}

/// Chung & Ooi (2011) Test 6: constant `|v_n|`, varying spin; the Al alloy
/// curves (`e = 0.5`, `μ = 0.4`, `R = 0.1 m`, `|v_n| = 0.2 m/s`), and the
/// nylon `β` curve, which needs neither `e` nor `μ` (its axis is `f/μ_c`); the
/// nylon `V_ct/V_n` curve does, and is not compared.
pub fn chung_ooi_test6() -> Result<Dataset, String> {
    let file = "chung_ooi2011_test6_reference.csv";
    let series = read(file, |material, quantity| {
        let q = match (material, quantity) {
            (_, "beta_vs_x") => Quantity::Beta,
            ("Al_alloy", "tan_recoil_vs_tan_incident") => Quantity::RecoilOverRebound,
            _ => return None,
        };
        Some((material.to_owned(), q))
    })?;
    Ok(Dataset {
        key: "chung_ooi_test6",
        title: "Chung & Ooi (2011) Test 6, sphere with spin, v_t = 0 (DEM reference)",
        file,
        radius: 0.1,
        restitution: 0.5,
        friction: 0.4,
        drives: vec![
            (
                Quantity::Beta,
                Drive::CriticalOverSlip { normal_speed: 0.2 },
                "3.5 μ (1 + e) |v_n| / |v_ct|  (f / μ_c)",
            ),
            (
                Quantity::RecoilOverRebound,
                Drive::SlipOverNormal { normal_speed: 0.2 },
                "v_ct / |v_n|",
            ),
        ],
        fitted: Quantity::Beta,
        series,
    })
}

/// The second digitization of Chung & Ooi's Test 6 curve for Al alloy (the
/// `sphere_vs_plane_test6` block of the Test 8 file): its distance from the
/// Test 6 file's curve measures the digitization scatter of these figures.
pub fn chung_ooi_test6_second_digitization() -> Result<Series, String> {
    let mut series = read("chung_ooi2011_test8_reference.csv", |case, quantity| {
        (case == "sphere_vs_plane_test6" && quantity == "beta_vs_x")
            .then(|| (case.to_owned(), Quantity::Beta))
    })?;
    series
        .pop()
        .ok_or_else(|| "no sphere_vs_plane_test6 block".to_owned())
}

/// The RMS difference of the two digitizations of Test 6's β curve for Al
/// alloy, as a fraction of the curve's span: the scatter of one digitization of
/// these figures.
pub fn digitization_scatter() -> Result<f64, String> {
    let test6 = chung_ooi_test6()?;
    let first = test6
        .of(Quantity::Beta)
        .find(|s| s.source == "Al_alloy")
        .ok_or("no Al alloy β in Test 6")?;
    let second = chung_ooi_test6_second_digitization()?;
    let mut d = Deviation::default();
    for p in &second.points {
        if let Some(v) = interpolate(&first.points, p.x) {
            d.add(p.value - v);
        }
    }
    if d.count < 15 {
        return Err(format!(
            "the two digitizations overlap at {} points only",
            d.count
        ));
    }
    Ok(d.rms() / span(&first.points))
}

/// The range of the points' values.
pub fn span(points: &[Point]) -> f64 {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.value), hi.max(p.value))
        });
    hi - lo
}

/// Linear interpolation of `series` at `x` (inside its range), the points sorted by `x`.
pub fn interpolate(points: &[Point], x: f64) -> Option<f64> {
    let i = points.windows(2).position(|w| w[0].x <= x && x <= w[1].x)?;
    let (a, b) = (points[i], points[i + 1]);
    Some(if b.x == a.x {
        a.value
    } else {
        a.value + (b.value - a.value) * (x - a.x) / (b.x - a.x)
    })
}

/// The model's value of one quantity, and the regime that produced it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Predicted {
    pub value: f64,
    pub regime: &'static str,
}

impl Dataset {
    /// How `quantity`'s abscissa sets the velocities, and its label.
    /// Every dataset declares one for each of its quantities; a missing one is
    /// a mistake in this file, not in the data.
    pub fn drive(&self, quantity: Quantity) -> (Drive, &'static str) {
        let d = self
            .drives
            .iter()
            .find(|d| d.0 == quantity)
            .unwrap_or_else(|| panic!("{}: no drive for {}", self.key, quantity.name()));
        (d.1, d.2)
    }

    /// The initial velocities at abscissa `x` of `drive`.
    pub fn velocity(&self, drive: Drive, x: f64) -> PlanarVelocity {
        let k = self.friction * (1.0 + self.restitution) * 3.5;
        let spin = |vn: f64, vct: f64| PlanarVelocity {
            normal: -vn,
            tangential: 0.0,
            angular: -vct / self.radius,
        };
        match drive {
            Drive::Incidence { speed } => {
                let theta = x.to_radians();
                PlanarVelocity {
                    normal: -speed * theta.cos(),
                    tangential: speed * theta.sin(),
                    angular: 0.0,
                }
            }
            Drive::TangentialOverFriction { normal_speed } => PlanarVelocity {
                normal: -normal_speed,
                tangential: x * self.friction * normal_speed,
                angular: 0.0,
            },
            Drive::CriticalOverSlip { normal_speed } => spin(normal_speed, k * normal_speed / x),
            Drive::SlipOverNormal { normal_speed } => spin(normal_speed, x * normal_speed),
        }
    }

    /// The bilinear law with this dataset's `e` and `f` and tangential
    /// restitution `et` (`0`: Coulomb friction alone).
    pub fn law(&self, et: f64) -> Law {
        Law::TangentialRestitution {
            restitution: self.restitution,
            friction: self.friction,
            tangential_restitution: et,
        }
    }

    /// The planar impact the model curves evaluate at initial velocities
    /// `velocity`: the sphere of unit mass, `I = 2/5 m R²`, `d_c = 0`, `d_d = R`.
    pub fn planar(&self, velocity: PlanarVelocity, et: f64) -> BarrierImpact {
        let mass = 1.0;
        BarrierImpact::rigid(
            mass,
            0.4 * mass * self.radius * self.radius,
            Contact::central(self.radius),
            velocity,
            self.law(et),
        )
    }

    /// The same impact in space ([`sphere_in_space`]): the planar `t` along
    /// world x, `n` along z, so `ω` (turning `n` toward `t`) is about y.
    pub fn spatial(&self, velocity: PlanarVelocity, et: f64, rotation: Option<&Rotation>) -> SpatialImpact {
        sphere_in_space(
            self.radius,
            self.law(et),
            [velocity.tangential, 0.0, velocity.normal],
            [0.0, velocity.angular, 0.0],
            rotation,
        )
    }

    /// The model's `quantity` at each abscissa in `xs`, with tangential
    /// restitution `et` (`0`: Coulomb friction alone), computed by one zipped
    /// sweep over the initial velocities. `None` where the model has no answer
    /// or the quantity is undefined (`V_t / v_t` at normal incidence).
    pub fn predict(&self, quantity: Quantity, et: f64, xs: &[f64]) -> Vec<Option<Predicted>> {
        let base = self.planar(PlanarVelocity::default(), et);
        let inputs = [
            Input::NormalVelocity,
            Input::TangentialVelocity,
            Input::AngularVelocity,
        ];
        let drive = self.drive(quantity).0;
        let velocities: Vec<PlanarVelocity> = xs.iter().map(|&x| self.velocity(drive, x)).collect();
        let component = |input: Input, v: &PlanarVelocity| match input {
            Input::NormalVelocity => v.normal,
            Input::TangentialVelocity => v.tangential,
            _ => v.angular,
        };
        let axes = inputs
            .iter()
            .map(|&param| Axis {
                param,
                values: AxisValues::List(velocities.iter().map(|v| component(param, v)).collect()),
            })
            .collect();
        let columns = vec![
            Output::FinalNormalVelocity,
            Output::FinalTangentialVelocity,
            Output::FinalAngularVelocity,
            Output::FinalTangentialContactVelocity,
            Output::Regime,
        ];
        let case = CaseSweep::new(&base, &inputs, columns, Precision::Fast)
            .expect("a rigid body reads its velocities");
        let mut out = vec![None; xs.len()];
        let Ok(sweep) = Sweep::new(case, base, axes, Combine::Zip, u64::MAX) else {
            return out;
        };
        sweep.for_each_in(0..sweep.points(), |row| {
            let Ok(cells) = row.outcome else { return };
            let number = |i: usize| match cells[i] {
                Cell::Number(v) => v,
                Cell::Text(_) => f64::NAN,
            };
            let regime = match cells[4] {
                Cell::Text(name) => name,
                Cell::Number(_) => "",
            };
            let v = velocities[row.index as usize];
            let last = PlanarVelocity {
                normal: number(0),
                tangential: number(1),
                angular: number(2),
            };
            let value = self.value(quantity, &v, &last, number(3));
            if value.is_finite() {
                out[row.index as usize] = Some(Predicted { value, regime });
            }
        });
        out
    }

    /// `quantity` of an impact with initial velocities `v`, final velocities
    /// `last` and final tangential contact-point velocity `vct_f`.
    pub fn value(&self, quantity: Quantity, v: &PlanarVelocity, last: &PlanarVelocity, vct_f: f64) -> f64 {
        let (vn_f, vt_f, w_f) = (last.normal, last.tangential, last.angular);
        let vct = v.tangential - self.radius * v.angular;
        match quantity {
            Quantity::ReboundAngleCentroid => vt_f.atan2(vn_f).to_degrees(),
            Quantity::ReboundAngleContactPoint => vct_f.atan2(vn_f).to_degrees(),
            Quantity::CentroidRatio => vt_f / v.tangential,
            Quantity::SpinMagnitude => w_f.abs(),
            Quantity::RecoilOverFriction => vct_f / (self.friction * vn_f),
            Quantity::SpinOverFriction => self.radius * w_f.abs() / (self.friction * v.normal.abs()),
            Quantity::Beta => -vct_f / vct,
            Quantity::RecoilOverRebound => vct_f / vn_f,
        }
    }

    /// The series of one quantity.
    pub fn of(&self, quantity: Quantity) -> impl Iterator<Item = &Series> {
        self.series.iter().filter(move |s| s.quantity == quantity)
    }

    /// The quantities present, in order.
    pub fn quantities(&self) -> Vec<Quantity> {
        let mut q: Vec<Quantity> = self.series.iter().map(|s| s.quantity).collect();
        q.sort();
        q.dedup();
        q
    }

    /// RMS and maximum `|model − data|` per (quantity, regime), over every
    /// series, for points at abscissa `≥ min_x` (sources pooled).
    pub fn deviations(&self, et: f64, min_x: f64) -> BTreeMap<(Quantity, &'static str), Deviation> {
        let mut table: BTreeMap<(Quantity, &'static str), Deviation> = BTreeMap::new();
        for s in &self.series {
            let points: Vec<&Point> = s.points.iter().filter(|p| p.x >= min_x).collect();
            let xs: Vec<f64> = points.iter().map(|p| p.x).collect();
            for (p, predicted) in points.iter().zip(self.predict(s.quantity, et, &xs)) {
                let Some(m) = predicted else { continue };
                table
                    .entry((s.quantity, m.regime))
                    .or_default()
                    .add(m.value - p.value);
            }
        }
        table
    }

    /// The `e_t ∈ [0, 1]` minimising the sum of squared deviations of the
    /// fitted quantity over points at abscissa `≥ min_x` (golden-section search;
    /// the cost is continuous in `e_t` but need not be unimodal, so it is
    /// bracketed first on a grid of 101 values).
    pub fn fit_et(&self, min_x: f64) -> f64 {
        let points: Vec<Point> = self
            .of(self.fitted)
            .flat_map(|s| s.points.iter().copied())
            .filter(|p| p.x >= min_x)
            .collect();
        let xs: Vec<f64> = points.iter().map(|p| p.x).collect();
        let cost = |et: f64| -> f64 {
            self.predict(self.fitted, et, &xs)
                .iter()
                .zip(&points)
                .filter_map(|(m, p)| m.map(|m| (m.value - p.value).powi(2)))
                .sum()
        };
        let grid = (-100..=100).map(|i| f64::from(i) / 100.0);
        let best = grid.min_by(|a, b| cost(*a).total_cmp(&cost(*b))).unwrap_or(0.0);
        let (mut a, mut b) = ((best - 0.01).max(-1.0), (best + 0.01).min(1.0));
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..40 {
            let c = b - g * (b - a);
            let d = a + g * (b - a);
            if cost(c) < cost(d) {
                b = d;
            } else {
                a = c;
            }
        }
        (a + b) / 2.0
    }
}

/// A solid sphere of radius `radius` and unit mass (`I = 2/5 m R²` as a
/// tensor) against a fixed barrier in space: the centre at the origin, the
/// contact point `R` below it and the normal along `+z`, with initial
/// velocity `velocity` and angular velocity `angular` (world axes), under
/// `law`. With `rotation`, the whole scene (velocities, contact point,
/// normal, tensor `r I rᵀ`) is turned by it, each input rounded; without,
/// the inputs are taken as they are.
pub fn sphere_in_space(
    radius: f64,
    law: Law,
    velocity: [f64; 3],
    angular: [f64; 3],
    rotation: Option<&Rotation>,
) -> SpatialImpact {
    let mass = 1.0;
    let moment = 0.4 * mass * radius * radius;
    let point = [0.0, 0.0, -radius];
    let normal = [0.0, 0.0, 1.0];
    let (velocity, angular, point, normal, inertia) = match rotation {
        None => (
            velocity,
            angular,
            point,
            normal,
            [moment, moment, moment, 0.0, 0.0, 0.0],
        ),
        Some(r) => {
            // r diag(I) rᵀ, entry (i, j) = I Σ_k r_ik r_jk.
            let entry = |i: usize, j: usize| moment * (0..3).map(|k| r[i][k] * r[j][k]).sum::<f64>();
            (
                rotate(r, velocity),
                rotate(r, angular),
                rotate(r, point),
                rotate(r, normal),
                [
                    entry(0, 0),
                    entry(1, 1),
                    entry(2, 2),
                    entry(0, 1),
                    entry(0, 2),
                    entry(1, 2),
                ],
            )
        }
    };
    SpatialImpact {
        a: RigidBody {
            mass,
            inertia,
            position: [0.0; 3],
            velocity,
            angular_velocity: angular,
        },
        b: None,
        contact: SpatialContact { point, normal },
        law,
        torsion: None,
    }
}

/// Accumulated deviations.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Deviation {
    pub sum_squares: f64,
    pub max: f64,
    pub count: usize,
}

impl Deviation {
    pub fn add(&mut self, d: f64) {
        self.sum_squares += d * d;
        self.max = self.max.max(d.abs());
        self.count += 1;
    }

    pub fn rms(&self) -> f64 {
        (self.sum_squares / self.count.max(1) as f64).sqrt()
    }
}

/// Kharaz's `V_t/v_t` points as observations for the coefficient fit
/// (`restitution::fit::tangential`, behind `POST /v1/fits/tangential`), at
/// incidences `≥ min_deg`: initial velocities from the incidence, `V_n = −e v_n`
/// with the experiment's `e` (not measured per point in this file),
/// `V_t = (V_t/v_t) v_t`, and `Ω` from the moment equation about the centre,
/// `I (Ω − ω) = −m R (V_t − v_t)`.
pub fn kharaz_observations(d: &Dataset, min_deg: f64) -> Vec<restitution::fit::Observation> {
    let mass = 1.0;
    let inertia = 0.4 * mass * d.radius * d.radius;
    let Ok(body) = restitution::Body::new(mass, inertia) else {
        return Vec::new();
    };
    d.of(Quantity::CentroidRatio)
        .flat_map(|s| s.points.iter())
        .filter(|p| p.x >= min_deg && p.x > 0.0)
        .map(|p| {
            let initial = d.velocity(d.drive(Quantity::CentroidRatio).0, p.x);
            let vt = p.value * initial.tangential;
            restitution::fit::Observation {
                body,
                contact: Contact::central(d.radius),
                initial,
                r#final: PlanarVelocity {
                    normal: -d.restitution * initial.normal,
                    tangential: vt,
                    angular: initial.angular - mass * d.radius * (vt - initial.tangential) / inertia,
                },
            }
        })
        .collect()
}

/// Every dataset compared.
pub fn datasets() -> Result<Vec<Dataset>, String> {
    Ok(vec![
        kharaz()?,
        chung_ooi_test4()?,
        chung_ooi_test5()?,
        chung_ooi_test6()?,
    ])
}
