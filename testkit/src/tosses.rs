//! Impacts out of trajectories: the ContactNets cube tosses (`tests/data/
//! contactnets_cube_tosses_0-399.csv.gz`, the authors' converted release
//! with its provenance header), their bounces, and the
//! angular-momentum balance of single-corner impacts that checks the
//! extraction and identifies the cube's inertia. Shared by
//! `tests/suite/tosses.rs` and `examples/cube_tosses.rs`; the method and the
//! numbers are in `docs/tosses.md`.
//!
//! Units. The file stores lengths scaled by the half-width
//! [`HALF_WIDTH`]; everything here is SI, world frame (z up, board at
//! `z = 0`). The file's angular velocity is in the body frame and is rotated
//! into the world here: `ω_world = R(q) ω_body`.
//!
//! How the file's velocities were made (ContactNets'
//! `process_dynamics.py`): the orientations were median-filtered (kernel 3)
//! as rotation vectors; `v_k` is the backward difference
//! `(p_k − p_{k−1})/dt` and `ω_k` the body-frame rotation vector of
//! `R_{k−1}ᵀ R_k` over `dt`, each then median-filtered (kernel 3). If the
//! impulse falls in the interval `(j−1, j]`, the backward difference of `j`
//! mixes before and after; the median spreads that to `j−1 … j+1` for `v`,
//! and the orientation filter one sample further for `ω` (`j−2 … j+2`).
//! With `c` the contact sample (a corner's height at a local minimum near
//! the board), `j ∈ {c, c+1}`: the last clean pre-impact sample is `c − 3`
//! and the first clean post-impact sample `c + 4` ([`Detection::measured`]).
//!
//! The impact itself is placed from the clean pre-impact state: carried on
//! in free flight (gravity on G, `ω` constant: the cube is isotropic) until
//! a corner reaches the board. The contact point `r`, the classification and
//! the states (gravity carried to that instant) are taken there, so nothing
//! depends on the filtered samples across the impact.
//!
//! Steps, in [`bounces`]: contacts ([`contacts`]) → skip those within
//! `before + after` samples of another or of a toss's ends → impact time
//! from the pre state → corners within `touching` of the lowest (at the
//! contact sample, and at the impact from the pre and from the post state:
//! the least of the three) give the class → states → keep only those whose
//! contact point approaches before and separates after.

use super::rotation::{Rotation, from_quaternion, rotate};
use std::io::Read;

/// The data file in `tests/data/`.
pub const FILE: &str = "contactnets_cube_tosses_0-399.csv.gz";
/// Its path.
pub const PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/data/contactnets_cube_tosses_0-399.csv.gz"
);
/// The cube's half-width (m): the file's length unit.
pub const HALF_WIDTH: f64 = 0.0524;
/// The sample period (s).
pub const DT: f64 = 1.0 / 148.0;
/// The cube's mass (kg), from the header.
pub const MASS: f64 = 0.37;
/// Gravity (m/s²), the header's `g = 9.81/0.0524` scaled back.
pub const GRAVITY: f64 = 9.81;
/// The header's inertia, in its scaled units: `kg · half-width²` (the
/// authors' simulator has `M = diag(m, m, m, I, I, I)` with lengths in
/// half-widths), identified or assumed by the data's authors for their
/// simulator.
pub const HEADER_INERTIA_SCALED: f64 = 0.2950002913583124;

/// The header's inertia in SI (kg m²).
pub fn header_inertia() -> f64 {
    HEADER_INERTIA_SCALED * HALF_WIDTH * HALF_WIDTH
}

/// A solid uniform cube's `m a²/6 = (2/3) m h²` (kg m²), `a = 2h` the edge.
pub fn solid_cube_inertia() -> f64 {
    2.0 / 3.0 * MASS * HALF_WIDTH * HALF_WIDTH
}

/// An inertia (kg m²) as `I / (m h²)`, the radius of gyration squared in half-widths².
pub fn in_mh2(inertia: f64) -> f64 {
    inertia / (MASS * HALF_WIDTH * HALF_WIDTH)
}

/// One sample of a toss, SI, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The sample's index in its toss.
    pub k: usize,
    /// `k dt` (s).
    pub t: f64,
    /// The centre of mass G (m).
    pub position: [f64; 3],
    /// Unit quaternion, real part first, body to world.
    pub quaternion: [f64; 4],
    /// `R(q)`, body to world.
    pub rotation: Rotation,
    /// Velocity of G (m/s): the file's backward difference, median-filtered.
    pub velocity: [f64; 3],
    /// Angular velocity in the body frame (rad/s), as stored.
    pub omega_body: [f64; 3],
    /// Angular velocity in the world frame (rad/s): `R ω_body`.
    pub omega: [f64; 3],
}

/// The body-frame corners, in half-widths.
pub const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, 1.0, 1.0],
];

impl Sample {
    /// Corner `i` relative to G, world frame (m).
    pub fn corner_offset(&self, i: usize) -> [f64; 3] {
        rotate(&self.rotation, CORNERS[i].map(|c| c * HALF_WIDTH))
    }

    /// The height of corner `i` above the board (m).
    pub fn corner_height(&self, i: usize) -> f64 {
        self.position[2] + self.corner_offset(i)[2]
    }

    /// Corner `i` relative to G after `tau` (s, either sign) of free flight:
    /// turned by `ω tau` (`ω` constant for an isotropic body).
    pub fn corner_offset_at(&self, i: usize, tau: f64) -> [f64; 3] {
        turn(scale(tau, self.omega), self.corner_offset(i))
    }

    /// The height of corner `i` after `tau` of free flight (m); the stored
    /// velocity is half a sample old.
    pub fn corner_height_at(&self, i: usize, tau: f64) -> f64 {
        let vz = self.velocity[2] - GRAVITY * DT / 2.0;
        self.position[2] + vz * tau - GRAVITY * tau * tau / 2.0 + self.corner_offset_at(i, tau)[2]
    }

    /// The lowest corner and its height.
    pub fn lowest(&self) -> (usize, f64) {
        (0..8)
            .map(|i| (i, self.corner_height(i)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("eight corners")
    }
}

/// A toss: its file number and its samples in order.
#[derive(Debug, Clone)]
pub struct Toss {
    pub id: usize,
    pub samples: Vec<Sample>,
}

/// Reads every toss of the data file.
pub fn read() -> Result<Vec<Toss>, String> {
    read_from(PATH)
}

/// Reads the tosses of a gzipped CSV in the data file's format.
pub fn read_from(path: &str) -> Result<Vec<Toss>, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("{path}: {e}"))?;
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::io::BufReader::new(file))
        .read_to_string(&mut text)
        .map_err(|e| format!("{path}: {e}"))?;
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines.next().ok_or_else(|| format!("{path}: no column header"))?;
    let expected = "toss,k,t_s,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
    if header.trim() != expected {
        return Err(format!("{path}: columns {header:?}, expected {expected:?}"));
    }
    let mut tosses: Vec<Toss> = Vec::new();
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != 16 {
            return Err(format!("{path}: row of {} fields: {line:?}", fields.len()));
        }
        let number = |i: usize| {
            fields[i]
                .trim()
                .parse::<f64>()
                .map_err(|e| format!("{path}: {:?}: {e}", fields[i]))
        };
        let index = |i: usize| {
            fields[i]
                .trim()
                .parse::<usize>()
                .map_err(|e| format!("{path}: {:?}: {e}", fields[i]))
        };
        let (id, k) = (index(0)?, index(1)?);
        let position = [number(3)?, number(4)?, number(5)?].map(|x| x * HALF_WIDTH);
        let quaternion = [number(6)?, number(7)?, number(8)?, number(9)?];
        let velocity = [number(10)?, number(11)?, number(12)?].map(|x| x * HALF_WIDTH);
        let omega_body = [number(13)?, number(14)?, number(15)?];
        let rotation = from_quaternion(quaternion);
        let sample = Sample {
            k,
            t: k as f64 * DT,
            position,
            quaternion,
            rotation,
            velocity,
            omega_body,
            omega: rotate(&rotation, omega_body),
        };
        match tosses.last_mut() {
            Some(toss) if toss.id == id => {
                if k != toss.samples.len() {
                    return Err(format!("{path}: toss {id}: sample {k} out of order"));
                }
                toss.samples.push(sample);
            }
            _ => {
                if k != 0 {
                    return Err(format!("{path}: toss {id} starts at sample {k}"));
                }
                tosses.push(Toss {
                    id,
                    samples: vec![sample],
                });
            }
        }
    }
    Ok(tosses)
}

/// How many corners touch at impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// One corner.
    Corner,
    /// Two corners (an edge).
    Edge,
    /// Three or four corners (a face; three corners within the tolerance
    /// can only be three of one face).
    Face,
}

impl Class {
    pub fn name(self) -> &'static str {
        match self {
            Class::Corner => "corner",
            Class::Edge => "edge",
            Class::Face => "face",
        }
    }

    fn of(touching: usize) -> Class {
        match touching {
            1 => Class::Corner,
            2 => Class::Edge,
            _ => Class::Face,
        }
    }
}

/// The detector's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detection {
    /// The board's height in the data (m): see [`board_level`].
    pub board: f64,
    /// A contact is a corner's height at a local minimum (over the samples
    /// either side) within this of the board (m).
    pub contact: f64,
    /// Corners within this height of the lowest corner at the contact sample
    /// touch (m).
    pub touching: f64,
    /// The pre-impact sample is `c − before`, `c` the contact sample.
    pub before: usize,
    /// The post-impact sample is `c + after`.
    pub after: usize,
}

impl Detection {
    /// The defaults with the board level measured from `tosses`:
    /// `contact` 10 mm (the sample nearest an impact has its corner within
    /// half a sample's travel, ≲ 7 mm at the tosses' ≲ 1.5 m/s, of the
    /// board); `touching` 5 mm (about 3° of tilt across an edge of 105 mm,
    /// a third of a sample's rotation at 10 rad/s); `before`/`after` 3/4 (the
    /// module's note).
    pub fn measured(tosses: &[Toss]) -> Detection {
        Detection {
            board: board_level(tosses),
            contact: 0.010,
            touching: 0.005,
            before: 3,
            after: 4,
        }
    }
}

/// The board's height in the data (m): the median over the tosses of the
/// lowest corner's height at the last sample, where the cube rests.
pub fn board_level(tosses: &[Toss]) -> f64 {
    let mut rest: Vec<f64> = tosses
        .iter()
        .filter_map(|t| t.samples.last())
        .map(|s| s.lowest().1)
        .collect();
    rest.sort_by(f64::total_cmp);
    if rest.is_empty() {
        0.0
    } else {
        rest[rest.len() / 2]
    }
}

/// The velocities of the body, world frame, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Velocity of G (m/s).
    pub velocity: [f64; 3],
    /// Angular velocity (rad/s).
    pub omega: [f64; 3],
}

/// A bounce: the states just before and after, referred to the contact sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounce {
    pub toss: usize,
    /// The contact sample `c` (the lowest corner at a local minimum).
    pub contact_sample: usize,
    /// The samples the pre- and post-impact states come from.
    pub pre_sample: usize,
    pub post_sample: usize,
    pub class: Class,
    /// The corners touching at `c`.
    pub corners: Vec<usize>,
    /// The impact's time (s): the pre-impact state carried on in free flight
    /// until its lowest corner reaches the board.
    pub t_impact: f64,
    /// The contact point relative to G at the impact (m, world): the
    /// touching corners' mean, from the pre-impact sample's orientation
    /// turned on by `ω_pre (t_impact − t_pre)` (clean samples only; the
    /// orientations nearer the impact are median-filtered across it).
    pub r: [f64; 3],
    /// The orientation at the impact, body to world: the pre-impact sample's
    /// turned on by `ω_pre (t_impact − t_pre)`.
    pub rotation: Rotation,
    /// The same from the post-impact sample's orientation turned back by
    /// `ω_post (t_post − t_impact)`: `|r − r_after|` measures the error of `r`.
    pub r_after: [f64; 3],
    /// The lowest corner's height above the board at `c` (m).
    pub depth: f64,
    /// The lowest non-touching corner's height above the touching ones (m):
    /// the least over the three views of the impact.
    pub clearance: f64,
    /// The state before, gravity carried forward from the pre sample to the
    /// impact: `v = v_pre + g (t_impact − t_pre + dt/2)` (a backward
    /// difference is the velocity half a sample earlier; `ω` is constant in
    /// free flight for an isotropic body).
    pub pre: State,
    /// The state after, gravity carried back from the post sample to the impact.
    pub post: State,
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
    a.map(|x| s * x)
}

/// `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a · b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `|a|`.
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

const G_VEC: [f64; 3] = [0.0, 0.0, -GRAVITY];

impl Bounce {
    /// The velocity jump the contact alone gave: gravity removed over the
    /// gap between the samples, `Δv − g Δt` (both states are referred to `c`).
    pub fn dv(&self) -> [f64; 3] {
        sub(self.post.velocity, self.pre.velocity)
    }

    /// `Δω` (world).
    pub fn domega(&self) -> [f64; 3] {
        sub(self.post.omega, self.pre.omega)
    }

    /// The contact impulse `m Δv` (N s).
    pub fn impulse(&self) -> [f64; 3] {
        scale(MASS, self.dv())
    }

    /// Its moment about G, `r × m Δv` (N m s): the change of angular
    /// momentum about G whatever the contact law.
    pub fn angular_impulse(&self) -> [f64; 3] {
        cross(self.r, self.impulse())
    }

    /// The contact point's normal velocity before (m/s, < 0 approaching).
    pub fn normal_velocity_pre(&self) -> f64 {
        self.pre.velocity[2] + cross(self.pre.omega, self.r)[2]
    }

    /// The contact point's normal velocity after (m/s, > 0 separating).
    pub fn normal_velocity_post(&self) -> f64 {
        self.post.velocity[2] + cross(self.post.omega, self.r)[2]
    }

    /// The gap between the pre and post samples (s).
    pub fn gap(&self) -> f64 {
        (self.post_sample - self.pre_sample) as f64 * DT
    }
}

/// Why a contact was not taken as a bounce.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Skip {
    /// The pre or post sample falls outside the toss (or on its first two
    /// samples, whose differences repeat, or its last).
    AtEnd,
    /// Another contact within `before + after` samples.
    TooClose,
    /// The contact point does not approach before or separate after (a
    /// resting, rocking or sliding contact).
    NoBounce,
}

impl Skip {
    pub fn name(self) -> &'static str {
        match self {
            Skip::AtEnd => "at a toss's end",
            Skip::TooClose => "another contact too close",
            Skip::NoBounce => "no approach and separation",
        }
    }
}

/// What the detector found in a toss.
#[derive(Debug, Clone, Default)]
pub struct Found {
    pub bounces: Vec<Bounce>,
    /// The contact samples not taken, and why.
    pub skipped: Vec<(usize, Skip)>,
}

/// The contact samples of a toss: samples where some corner's height is at a
/// local minimum (`h(c) < h(c−1)`, `h(c) ≤ h(c+1)`) within `d.contact` of
/// the board. Minima of several corners at the same or neighbouring samples
/// are one contact, at the sample where the lowest corner is lowest.
pub fn contacts(toss: &Toss, d: &Detection) -> Vec<usize> {
    let s = &toss.samples;
    let mut minima: Vec<usize> = Vec::new();
    for c in 1..s.len() {
        let touches = (0..8).any(|i| {
            let h = s[c].corner_height(i);
            h - d.board < d.contact
                && h < s[c - 1].corner_height(i)
                && s.get(c + 1).is_none_or(|n| h <= n.corner_height(i))
        });
        if touches {
            minima.push(c);
        }
    }
    // Merge neighbours into one contact at the lowest sample.
    let mut out: Vec<usize> = Vec::new();
    let mut last: Option<usize> = None;
    for c in minima {
        match (out.last_mut(), last) {
            (Some(prev), Some(l)) if c <= l + 1 => {
                if s[c].lowest().1 < s[*prev].lowest().1 {
                    *prev = c;
                }
            }
            _ => out.push(c),
        }
        last = Some(c);
    }
    out
}

/// `v` turned by the rotation vector `phi` (Rodrigues).
fn turn(phi: [f64; 3], v: [f64; 3]) -> [f64; 3] {
    let angle = norm(phi);
    if angle < 1e-12 {
        return add(v, cross(phi, v));
    }
    let k = scale(1.0 / angle, phi);
    let (sin, cos) = angle.sin_cos();
    add(
        add(scale(cos, v), scale(sin, cross(k, v))),
        scale(dot(k, v) * (1.0 - cos), k),
    )
}

/// The delay after `s` (s, in `[0, horizon]`) at which its free flight brings
/// a corner to `board`, or nearest it.
fn impact_delay(s: &Sample, board: f64, horizon: f64) -> f64 {
    const STEPS: usize = 400;
    let lowest = |tau: f64| {
        (0..8)
            .map(|v| s.corner_height_at(v, tau))
            .fold(f64::INFINITY, f64::min)
    };
    let mut best = (0.0, f64::INFINITY);
    for i in 0..=STEPS {
        let tau = horizon * i as f64 / STEPS as f64;
        let h = lowest(tau) - board;
        if h <= 0.0 {
            return tau;
        }
        if h < best.1 {
            best = (tau, h);
        }
    }
    best.0
}

/// The bounces of a toss.
pub fn bounces(toss: &Toss, d: &Detection) -> Found {
    let mut found = Found::default();
    let all = contacts(toss, d);
    let n = toss.samples.len();
    for (i, &c) in all.iter().enumerate() {
        // The first two samples repeat the first difference; the last has no
        // median neighbour.
        if c < d.before + 2 || c + d.after + 2 > n {
            found.skipped.push((c, Skip::AtEnd));
            continue;
        }
        let (pre_k, post_k) = (c - d.before, c + d.after);
        // Another contact contaminates its samples c' − before + 1 ..= c' + after − 1.
        let isolated = all
            .iter()
            .enumerate()
            .all(|(j, &o)| j == i || o.abs_diff(c) >= d.before + d.after);
        if !isolated {
            found.skipped.push((c, Skip::TooClose));
            continue;
        }
        let at = &toss.samples[c];
        let (pre_s, post_s) = (&toss.samples[pre_k], &toss.samples[post_k]);
        // The impact: the clean pre-impact state carried on in free flight
        // until a corner reaches the board (or comes nearest it).
        let tau = impact_delay(pre_s, d.board, (d.before + 1) as f64 * DT);
        let t_impact = pre_s.t + tau;
        // Each corner's height above the lowest, at the most of three views
        // of the impact: the contact sample, and the pre- and post-impact
        // states carried to the impact.
        let views: [Vec<f64>; 3] = [
            (0..8).map(|v| at.corner_height(v)).collect(),
            (0..8).map(|v| pre_s.corner_height_at(v, tau)).collect(),
            (0..8)
                .map(|v| post_s.corner_height_at(v, t_impact - post_s.t))
                .collect(),
        ];
        let above: Vec<f64> = (0..8)
            .map(|v| {
                views
                    .iter()
                    .map(|h| h[v] - h.iter().copied().fold(f64::INFINITY, f64::min))
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let corners: Vec<usize> = (0..8).filter(|&v| above[v] < d.touching).collect();
        let clearance = (0..8)
            .filter(|v| !corners.contains(v))
            .map(|v| above[v])
            .fold(f64::INFINITY, f64::min);
        let mean = |s: &Sample, tau: f64| {
            scale(
                1.0 / corners.len() as f64,
                corners
                    .iter()
                    .fold([0.0; 3], |acc, &v| add(acc, s.corner_offset_at(v, tau))),
            )
        };
        let r_before = mean(pre_s, tau);
        let r_after = mean(post_s, t_impact - post_s.t);
        let pre = State {
            velocity: add(pre_s.velocity, scale(t_impact - (pre_s.t - DT / 2.0), G_VEC)),
            omega: pre_s.omega,
        };
        let post = State {
            velocity: sub(post_s.velocity, scale((post_s.t - DT / 2.0) - t_impact, G_VEC)),
            omega: post_s.omega,
        };
        let bounce = Bounce {
            toss: toss.id,
            contact_sample: c,
            pre_sample: pre_k,
            post_sample: post_k,
            t_impact,
            class: Class::of(corners.len()),
            corners,
            r: r_before,
            rotation: {
                let columns =
                    [0, 1, 2].map(|j| turn(scale(tau, pre_s.omega), [0, 1, 2].map(|i| pre_s.rotation[i][j])));
                [0, 1, 2].map(|i| [0, 1, 2].map(|j| columns[j][i]))
            },
            r_after,
            depth: at.lowest().1 - d.board,
            clearance,
            pre,
            post,
        };
        if bounce.normal_velocity_pre() >= 0.0 || bounce.normal_velocity_post() <= 0.0 {
            found.skipped.push((c, Skip::NoBounce));
            continue;
        }
        found.bounces.push(bounce);
    }
    found
}

/// The bounces of every toss.
pub fn all_bounces(tosses: &[Toss], d: &Detection) -> Vec<Bounce> {
    tosses.iter().flat_map(|t| bounces(t, d).bounces).collect()
}

/// Pairs of tosses that are one physical toss twice (the source's
/// `process_dynamics.py` turns each toss about z at random; a trajectory
/// processed twice appears twice, turned differently): same length and the
/// same heights. `(kept, repeat)` by file number.
pub fn repeats(tosses: &[Toss]) -> Vec<(usize, usize)> {
    let key = |t: &Toss| {
        let z = |k: usize| {
            t.samples
                .get(k)
                .map_or(0, |s| (s.position[2] * 1e7).round() as i64)
        };
        (t.samples.len(), z(0), z(t.samples.len() / 2))
    };
    let mut first: std::collections::BTreeMap<_, usize> = std::collections::BTreeMap::new();
    let mut out = Vec::new();
    for t in tosses {
        match first.get(&key(t)) {
            Some(&kept) => out.push((kept, t.id)),
            None => {
                first.insert(key(t), t.id);
            }
        }
    }
    out
}

/// The bounces of every distinct toss (each repeat's second copy left out).
pub fn distinct_bounces(tosses: &[Toss], d: &Detection) -> Vec<Bounce> {
    let repeated: Vec<usize> = repeats(tosses).into_iter().map(|(_, r)| r).collect();
    tosses
        .iter()
        .filter(|t| !repeated.contains(&t.id))
        .flat_map(|t| bounces(t, d).bounces)
        .collect()
}

/// The balance `I₀ Δω = r × m Δv` over single-corner impacts, fitted for `I₀`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InertiaFit {
    /// Impacts used.
    pub n: usize,
    /// `I₀` (kg m²), least squares of `r × m Δv` on `Δω` (all three components).
    pub inertia: f64,
    /// Its standard error from the residuals.
    pub standard_error: f64,
    /// The standard deviation of `I₀` over bootstrap resamples of the tosses
    /// (all of a toss's impacts together).
    pub bootstrap_sd: f64,
    /// The 2.5 % and 97.5 % points of the bootstrap.
    pub bootstrap_95: (f64, f64),
    /// `I₀` from the reverse regression (`Δω` on `r × m Δv`): with noise in
    /// both, the two bracket the errors-in-variables bias.
    pub reverse: f64,
}

/// Least squares `L = I₀ Δω`: `(I₀, standard error)`.
fn least_squares(pairs: &[([f64; 3], [f64; 3])]) -> (f64, f64) {
    let sxx: f64 = pairs.iter().map(|(w, _)| dot(*w, *w)).sum();
    let sxy: f64 = pairs.iter().map(|(w, l)| dot(*w, *l)).sum();
    let i0 = sxy / sxx;
    let rss: f64 = pairs
        .iter()
        .map(|(w, l)| norm(sub(*l, scale(i0, *w))).powi(2))
        .sum();
    let dof = (3 * pairs.len()).saturating_sub(1).max(1) as f64;
    (i0, (rss / dof / sxx).sqrt())
}

/// The `(Δω, r × m Δv)` of the single-corner bounces.
pub fn corner_pairs(bounces: &[Bounce]) -> Vec<([f64; 3], [f64; 3])> {
    bounces
        .iter()
        .filter(|b| b.class == Class::Corner)
        .map(|b| (b.domega(), b.angular_impulse()))
        .collect()
}

/// One bounce's `(Δω, r × m Δv)`.
type Pair = ([f64; 3], [f64; 3]);

/// Fits `I₀` over the single-corner bounces (`resamples` bootstrap draws
/// of the tosses, seeded).
pub fn fit_inertia(bounces: &[Bounce], resamples: usize, seed: u64) -> InertiaFit {
    let corners: Vec<&Bounce> = bounces.iter().filter(|b| b.class == Class::Corner).collect();
    let pairs = corner_pairs(bounces);
    let (inertia, standard_error) = least_squares(&pairs);
    let mut groups: std::collections::BTreeMap<usize, Vec<Pair>> = Default::default();
    for b in &corners {
        groups
            .entry(b.toss)
            .or_default()
            .push((b.domega(), b.angular_impulse()));
    }
    let groups: Vec<Vec<_>> = groups.into_values().collect();
    let mut rng = super::Rng::new(seed);
    let mut draws: Vec<f64> = (0..resamples)
        .map(|_| {
            let sample: Vec<_> = (0..groups.len())
                .flat_map(|_| {
                    groups[(rng.next_u64() % groups.len() as u64) as usize]
                        .iter()
                        .copied()
                })
                .collect();
            least_squares(&sample).0
        })
        .collect();
    draws.sort_by(f64::total_cmp);
    let mean = draws.iter().sum::<f64>() / draws.len().max(1) as f64;
    let bootstrap_sd =
        (draws.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (draws.len().max(2) - 1) as f64).sqrt();
    let at = |p: f64| {
        draws
            .get(((draws.len() as f64 - 1.0) * p).round() as usize)
            .copied()
            .unwrap_or(f64::NAN)
    };
    let syy: f64 = pairs.iter().map(|(_, l)| dot(*l, *l)).sum();
    let sxy: f64 = pairs.iter().map(|(w, l)| dot(*w, *l)).sum();
    InertiaFit {
        n: pairs.len(),
        inertia,
        standard_error,
        bootstrap_sd,
        bootstrap_95: (at(0.025), at(0.975)),
        reverse: syy / sxy,
    }
}

/// The balance's relative residual at `inertia`:
/// `sqrt(Σ |I₀ Δω − r × m Δv|² / Σ |r × m Δv|²)` over the single-corner bounces.
pub fn balance_residual(bounces: &[Bounce], inertia: f64) -> f64 {
    let pairs = corner_pairs(bounces);
    let num: f64 = pairs
        .iter()
        .map(|(w, l)| norm(sub(scale(inertia, *w), *l)).powi(2))
        .sum();
    let den: f64 = pairs.iter().map(|(_, l)| dot(*l, *l)).sum();
    (num / den).sqrt()
}

/// The median over single-corner bounces of `|I₀ Δω − r × m Δv| / |r × m Δv|`.
pub fn median_relative_residual(bounces: &[Bounce], inertia: f64) -> f64 {
    let mut rel: Vec<f64> = corner_pairs(bounces)
        .iter()
        .map(|(w, l)| norm(sub(scale(inertia, *w), *l)) / norm(*l))
        .collect();
    rel.sort_by(f64::total_cmp);
    if rel.is_empty() {
        f64::NAN
    } else {
        rel[rel.len() / 2]
    }
}

/// The balance's noise in free flight, where it should vanish. In every toss,
/// windows of the bounces' length (`before + after` samples) whose corners
/// all stay above `clearance` (m) give a `Δω` and a gravity-corrected `m Δv`;
/// with `r` the lowest corner's offset at the window's middle sample,
/// `I₀ Δω − r × m Δv` is the noise of the velocities. Returns the RMS of its
/// magnitude (N m s) and the number of windows.
pub fn free_flight_noise(tosses: &[Toss], d: &Detection, inertia: f64, clearance: f64) -> (f64, usize) {
    let span = d.before + d.after;
    let (mut sum, mut n) = (0.0, 0usize);
    for toss in tosses {
        let s = &toss.samples;
        if s.len() < span + 5 {
            continue;
        }
        // Non-overlapping windows, clear of the repeated first samples.
        let mut a = 2;
        while a + span + 1 < s.len() {
            let b = a + span;
            if (a.saturating_sub(2)..=(b + 2).min(s.len() - 1)).all(|k| s[k].lowest().1 - d.board > clearance)
            {
                let mid = &s[(a + b) / 2];
                let r = mid.corner_offset(mid.lowest().0);
                let dv = sub(sub(s[b].velocity, s[a].velocity), scale(span as f64 * DT, G_VEC));
                let dw = sub(s[b].omega, s[a].omega);
                let res = sub(scale(inertia, dw), cross(r, scale(MASS, dv)));
                sum += dot(res, res);
                n += 1;
                a = b + 1;
            } else {
                a += 1;
            }
        }
    }
    ((sum / n.max(1) as f64).sqrt(), n)
}

/// The residual the data's noise alone would leave, relative as in
/// [`balance_residual`]: per single-corner impact, the velocities' noise
/// (`velocity_noise`, from [`free_flight_noise`]) and the contact point's,
/// `|(r − r_after) × m Δv| / √2` (the two estimates of `r` each carry about
/// half of their difference's variance), in quadrature:
/// `sqrt(Σ (velocity_noise² + |δr × m Δv|²/2) / Σ |r × m Δv|²)`.
pub fn noise_residual(bounces: &[Bounce], velocity_noise: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for b in bounces.iter().filter(|b| b.class == Class::Corner) {
        let dr = cross(sub(b.r, b.r_after), b.impulse());
        num += velocity_noise * velocity_noise + dot(dr, dr) / 2.0;
        den += dot(b.angular_impulse(), b.angular_impulse());
    }
    (num / den).sqrt()
}

/// The RMS of `|r × m Δv|` over the single-corner bounces (N m s).
pub fn rms_angular_impulse(bounces: &[Bounce]) -> f64 {
    let pairs = corner_pairs(bounces);
    (pairs.iter().map(|(_, l)| dot(*l, *l)).sum::<f64>() / pairs.len().max(1) as f64).sqrt()
}

/// The balance with the centre of mass unknown too: the file's position is
/// the cube's geometric centre (its resting height is the same on every
/// face), so a centre of mass `δ` (body frame) off it changes `r` to
/// `r − Rδ` and the measured `Δv` to `Δv_G − Δω × Rδ`. To first order in `δ`,
/// `r × m Δv = I₀ Δω + Rδ × m Δv + m r × (Δω × Rδ)`, linear in `(I₀, δ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetFit {
    pub n: usize,
    /// `I₀` about the centre of mass (kg m²).
    pub inertia: f64,
    /// `δ`, body frame (m).
    pub offset: [f64; 3],
    /// Standard errors of `I₀` and `δ` from the residuals.
    pub inertia_se: f64,
    pub offset_se: [f64; 3],
    /// The relative residual as in [`balance_residual`], with this model.
    pub residual: f64,
}

/// Fits [`OffsetFit`] over the single-corner bounces.
pub fn fit_inertia_and_offset(bounces: &[Bounce]) -> OffsetFit {
    use nalgebra::{DMatrix, DVector, Matrix3};
    let skew = |a: [f64; 3]| Matrix3::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0);
    let corners: Vec<&Bounce> = bounces.iter().filter(|b| b.class == Class::Corner).collect();
    let n = corners.len();
    let mut a = DMatrix::<f64>::zeros(3 * n, 4);
    let mut y = DVector::<f64>::zeros(3 * n);
    for (i, b) in corners.iter().enumerate() {
        let rm = Matrix3::from_fn(|r, c| b.rotation[r][c]);
        let m = -skew(b.impulse()) * rm + MASS * skew(b.r) * skew(b.domega()) * rm;
        let (dw, l) = (b.domega(), b.angular_impulse());
        for r in 0..3 {
            a[(3 * i + r, 0)] = dw[r];
            for c in 0..3 {
                a[(3 * i + r, 1 + c)] = m[(r, c)];
            }
            y[3 * i + r] = l[r];
        }
    }
    let normal = a.transpose() * &a;
    let Some(inverse) = normal.clone().try_inverse() else {
        return OffsetFit {
            n,
            inertia: f64::NAN,
            offset: [f64::NAN; 3],
            inertia_se: f64::NAN,
            offset_se: [f64::NAN; 3],
            residual: f64::NAN,
        };
    };
    let x = &inverse * a.transpose() * &y;
    let res = &a * &x - &y;
    let dof = (3 * n).saturating_sub(4).max(1) as f64;
    let s2 = res.norm_squared() / dof;
    let se = |i: usize| (s2 * inverse[(i, i)]).sqrt();
    OffsetFit {
        n,
        inertia: x[0],
        offset: [x[1], x[2], x[3]],
        inertia_se: se(0),
        offset_se: [se(1), se(2), se(3)],
        residual: res.norm() / y.norm(),
    }
}

/// The tosses' resting faces: how often each face, `[−x, +x, −y, +y, −z,
/// +z]` (body frame), ends down over the tosses' last samples, and the
/// median height of the tracked centre (m) on each. A centre of mass off
/// the middle favours the face it is nearest; a tracked point off the
/// geometric centre would rest at different heights on opposite faces.
pub fn resting_faces(tosses: &[Toss]) -> ([usize; 6], [f64; 6]) {
    let mut heights: [Vec<f64>; 6] = Default::default();
    for t in tosses {
        let Some(s) = t.samples.last() else { continue };
        // The body axis nearest the vertical; the face down is the one whose
        // outward normal points down.
        let row = s.rotation[2];
        let axis = (0..3)
            .max_by(|&a, &b| row[a].abs().total_cmp(&row[b].abs()))
            .expect("three axes");
        heights[2 * axis + usize::from(row[axis] < 0.0)].push(s.position[2]);
    }
    let count = [0, 1, 2, 3, 4, 5].map(|i| heights[i].len());
    let median = [0, 1, 2, 3, 4, 5].map(|i| {
        let mut h = heights[i].clone();
        h.sort_by(f64::total_cmp);
        h.get(h.len() / 2).copied().unwrap_or(f64::NAN)
    });
    (count, median)
}

/// The balance with a general inertia tensor about G, constant in the body
/// frame: `Rᵀ (r × m Δv) = I_body Rᵀ Δω`, six unknowns
/// `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` (kg m²) by least squares over the
/// single-corner bounces, and the relative residual. Tests the isotropy the
/// extraction and [`fit_inertia`] assume.
pub fn fit_inertia_tensor(bounces: &[Bounce]) -> ([f64; 6], f64) {
    use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
    let corners: Vec<&Bounce> = bounces.iter().filter(|b| b.class == Class::Corner).collect();
    let n = corners.len();
    let mut a = DMatrix::<f64>::zeros(3 * n, 6);
    let mut y = DVector::<f64>::zeros(3 * n);
    for (i, b) in corners.iter().enumerate() {
        let rt = Matrix3::from_fn(|r, c| b.rotation[c][r]);
        let w = rt * Vector3::from(b.domega());
        let l = rt * Vector3::from(b.angular_impulse());
        for r in 0..3 {
            y[3 * i + r] = l[r];
        }
        let (x, yy, z) = (3 * i, 3 * i + 1, 3 * i + 2);
        a[(x, 0)] = w[0];
        a[(x, 3)] = w[1];
        a[(x, 4)] = w[2];
        a[(yy, 1)] = w[1];
        a[(yy, 3)] = w[0];
        a[(yy, 5)] = w[2];
        a[(z, 2)] = w[2];
        a[(z, 4)] = w[0];
        a[(z, 5)] = w[1];
    }
    let Some(inverse) = (a.transpose() * &a).try_inverse() else {
        return ([f64::NAN; 6], f64::NAN);
    };
    let x = inverse * a.transpose() * &y;
    let residual = (&a * &x - &y).norm() / y.norm();
    ([x[0], x[1], x[2], x[3], x[4], x[5]], residual)
}

// Prediction of held-out tosses (docs/tosses.md).

/// The pitch radius `ρ_p` of the twist law's friction couple (m): 10 mm,
/// about a fifth of the half-width. Only `μ_z ρ_p` enters the couple's cap
/// `|M| ≤ μ_z ρ_p P_n`, so another `ρ_p` rescales the fitted `μ_z`.
pub const PITCH_RADIUS: f64 = 0.010;

/// The data's authors' coefficients for their simulator: restitution 0.125,
/// friction 0.18.
pub const AUTHORS: [f64; 2] = [0.125, 0.18];

/// A contact model predicting a bounce's post-impact state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Model {
    /// No impact: the post-impact state is the pre-impact one (the floor).
    NoImpact,
    /// Frictionless, `e` fitted.
    Frictionless,
    /// Coulomb friction with the authors' `e = 0.125`, `f = 0.18` ([`AUTHORS`]).
    Authors,
    /// Coulomb friction, `e` and `f` fitted.
    Coulomb,
    /// The bilinear tangential-restitution law, `e`, `f`, `e_t` fitted.
    Bilinear,
    /// Coulomb friction with the twist law about the normal, `e`, `f`,
    /// `e_z`, `μ_z` fitted ([`PITCH_RADIUS`]).
    Twist,
    /// The two-phase kinetic law, `R`, `μ_A`, `μ_R` fitted by
    /// `restitution::fit::spatial` ([`fit_two_phase`]).
    TwoPhase,
    /// The two-phase law with Coulomb friction in the approach (with
    /// `μ_R = 0` a time-stepping engine's contact), `R`, `f_A`, `μ_R` fitted
    /// by `restitution::fit::spatial`.
    CoulombApproach,
}

impl Model {
    /// All of them, in the table's order.
    pub const ALL: [Model; 8] = [
        Model::NoImpact,
        Model::Frictionless,
        Model::Authors,
        Model::Coulomb,
        Model::Bilinear,
        Model::Twist,
        Model::TwoPhase,
        Model::CoulombApproach,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Model::NoImpact => "no impact",
            Model::Frictionless => "frictionless, e fitted",
            Model::Authors => "Coulomb, authors' e 0.125, f 0.18",
            Model::Coulomb => "Coulomb, e f fitted",
            Model::Bilinear => "bilinear, e f e_t fitted",
            Model::Twist => "Coulomb + twist, e f e_z mu_z fitted",
            Model::TwoPhase => "two-phase, R mu_A mu_R fitted (LM)",
            Model::CoulombApproach => "two-phase Coulomb approach, R f_A mu_R fitted (LM)",
        }
    }

    /// The fitted coefficients' names.
    pub fn parameters(self) -> &'static [&'static str] {
        match self {
            Model::NoImpact | Model::Authors => &[],
            Model::Frictionless => &["e"],
            Model::Coulomb => &["e", "f"],
            Model::Bilinear => &["e", "f", "e_t"],
            Model::Twist => &["e", "f", "e_z", "mu_z"],
            Model::TwoPhase => &["R", "mu_A", "mu_R"],
            Model::CoulombApproach => &["R", "f_A", "mu_R"],
        }
    }

    /// The admissible range of each fitted coefficient (the friction
    /// coefficients' upper ends are far beyond any fit: 3 for `f`, 10 for
    /// `μ_z`).
    pub fn bounds(self) -> Vec<(f64, f64)> {
        self.parameters()
            .iter()
            .map(|&p| match p {
                "e" | "e_z" | "R" => (0.0, 1.0),
                "f" => (0.0, 3.0),
                "e_t" => (-1.0, 1.0),
                _ => (0.0, 10.0),
            })
            .collect()
    }

    /// The law and twist law at coefficients `p` (`None` for no impact).
    pub fn law(self, p: &[f64]) -> Option<(restitution::Law, Option<restitution::Twist>)> {
        use restitution::{Law, Twist};
        let coulomb = |e: f64, f: f64| Law::Friction {
            restitution: e,
            friction: f,
        };
        match self {
            Model::NoImpact => None,
            Model::Frictionless => Some((Law::Frictionless { restitution: p[0] }, None)),
            Model::Authors => Some((coulomb(AUTHORS[0], AUTHORS[1]), None)),
            Model::Coulomb => Some((coulomb(p[0], p[1]), None)),
            Model::Bilinear => Some((
                Law::TangentialRestitution {
                    restitution: p[0],
                    friction: p[1],
                    tangential_restitution: p[2],
                },
                None,
            )),
            Model::TwoPhase => Some((
                Law::KineticRestitution {
                    value: p[0],
                    approach_impulse_ratio: p[1],
                    rebound_impulse_ratio: p[2],
                },
                None,
            )),
            Model::CoulombApproach => Some((
                Law::KineticFriction {
                    value: p[0],
                    approach_friction: p[1],
                    rebound_impulse_ratio: p[2],
                },
                None,
            )),
            Model::Twist => Some((
                coulomb(p[0], p[1]),
                Some(Twist {
                    restitution: p[2],
                    friction: p[3],
                    pitch_radius: PITCH_RADIUS,
                }),
            )),
        }
    }
}

/// A bounce as a spatial impact: the cube (mass [`MASS`], isotropic inertia
/// `inertia`, G at the origin, the pre-impact state at the impact instant)
/// against the board below (`b: None`) at its contact point `r` (the corner;
/// an edge's or face's touching corners' mean), normal `+z`.
pub fn spatial_impact(
    b: &Bounce,
    inertia: f64,
    law: restitution::Law,
    torsion: Option<restitution::Twist>,
) -> restitution::SpatialImpact {
    use restitution::{RigidBody, SpatialContact, SpatialImpact};
    SpatialImpact {
        a: RigidBody {
            mass: MASS,
            inertia: [inertia, inertia, inertia, 0.0, 0.0, 0.0],
            position: [0.0; 3],
            velocity: b.pre.velocity,
            angular_velocity: b.pre.omega,
        },
        b: None,
        contact: SpatialContact {
            point: b.r,
            normal: [0.0, 0.0, 1.0],
        },
        law,
        torsion,
    }
}

/// The post-impact state `model` predicts at coefficients `p`, solved with
/// `restitution::solve(…, Outputs::ALL, Precision::Fast)`; the error if the
/// model refuses the impact.
pub fn predict(b: &Bounce, inertia: f64, model: Model, p: &[f64]) -> Result<State, restitution::ImpactError> {
    use restitution::{Outputs, Precision, solve};
    let Some((law, torsion)) = model.law(p) else {
        return Ok(b.pre);
    };
    let outcome = solve(
        &spatial_impact(b, inertia, law, torsion),
        Outputs::ALL,
        Precision::Fast,
    )?;
    Ok(State {
        velocity: outcome.bodies[0].velocity,
        omega: outcome.bodies[0].angular_velocity,
    })
}

/// The velocity of the contact point `G + r` in a state.
pub fn contact_point_velocity(s: &State, r: [f64; 3]) -> [f64; 3] {
    add(s.velocity, cross(s.omega, r))
}

/// Prediction errors over a set of bounces, as sums of squares: of the
/// post-impact velocity of G (m/s), of the contact point (m/s) and of the
/// angular velocity (rad/s), with the same sums of the measured changes
/// (the no-impact prediction's errors).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Score {
    /// Bounces predicted.
    pub n: usize,
    /// Of which the model refused; each is predicted as no impact (its error
    /// the measured change), not left out.
    pub refused: usize,
    pub g: f64,
    pub c: f64,
    pub w: f64,
    pub dg: f64,
    pub dc: f64,
    pub dw: f64,
}

impl Score {
    fn rms(&self, ss: f64) -> f64 {
        (ss / self.n.max(1) as f64).sqrt()
    }
    /// RMS error of G's velocity (m/s).
    pub fn rms_g(&self) -> f64 {
        self.rms(self.g)
    }
    /// RMS error of the contact point's velocity (m/s).
    pub fn rms_c(&self) -> f64 {
        self.rms(self.c)
    }
    /// RMS error of the angular velocity (rad/s).
    pub fn rms_w(&self) -> f64 {
        self.rms(self.w)
    }
    /// G and contact point together, `sqrt(Σ (|e_G|² + |e_C|²) / n)` (m/s):
    /// the RMS length of the six-vector of both points' velocity errors (the
    /// convention of the engine comparison in docs/tosses.md; divide by √2
    /// for the RMS per point).
    pub fn rms_gc(&self) -> f64 {
        self.rms(self.g + self.c)
    }
    /// The RMS of the measured changes, in the same order (no impact's errors).
    pub fn rms_changes(&self) -> [f64; 4] {
        [
            self.rms(self.dg),
            self.rms(self.dc),
            self.rms(self.dw),
            self.rms(self.dg + self.dc),
        ]
    }
    /// Each RMS error over the RMS of its measured change: G, contact point,
    /// angular velocity, G and contact point together (1 for no impact).
    pub fn relative(&self) -> [f64; 4] {
        [
            (self.g / self.dg).sqrt(),
            (self.c / self.dc).sqrt(),
            (self.w / self.dw).sqrt(),
            ((self.g + self.c) / (self.dg + self.dc)).sqrt(),
        ]
    }
    /// The sum of two scores (pooled sums of squares).
    pub fn plus(&self, o: &Score) -> Score {
        Score {
            n: self.n + o.n,
            refused: self.refused + o.refused,
            g: self.g + o.g,
            c: self.c + o.c,
            w: self.w + o.w,
            dg: self.dg + o.dg,
            dc: self.dc + o.dc,
            dw: self.dw + o.dw,
        }
    }
}

/// `model`'s errors at coefficients `p` over `bounces`.
pub fn score(bounces: &[&Bounce], inertia: f64, model: Model, p: &[f64]) -> Score {
    let mut s = Score::default();
    for b in bounces {
        let predicted = predict(b, inertia, model, p).unwrap_or_else(|_| {
            s.refused += 1;
            b.pre
        });
        let sq = |a: [f64; 3], b: [f64; 3]| dot(sub(a, b), sub(a, b));
        let (vc_pre, vc_post) = (
            contact_point_velocity(&b.pre, b.r),
            contact_point_velocity(&b.post, b.r),
        );
        s.n += 1;
        s.g += sq(predicted.velocity, b.post.velocity);
        s.c += sq(contact_point_velocity(&predicted, b.r), vc_post);
        s.w += sq(predicted.omega, b.post.omega);
        s.dg += sq(b.pre.velocity, b.post.velocity);
        s.dc += sq(vc_pre, vc_post);
        s.dw += sq(b.pre.omega, b.post.omega);
    }
    s
}

/// Minimises `f` over the box `bounds`: the best point of a grid of `grid`
/// points per coordinate (or `start`, if better), then Nelder–Mead with the
/// points clamped into the box, until the simplex's values agree to 1e-10
/// relatively or `max_evaluations` (beyond the grid's) are spent. Returns
/// the point and its value.
pub fn minimise(
    f: &mut dyn FnMut(&[f64]) -> f64,
    bounds: &[(f64, f64)],
    grid: usize,
    start: Option<&[f64]>,
    max_evaluations: usize,
) -> (Vec<f64>, f64) {
    let d = bounds.len();
    let clamp = |x: &[f64]| -> Vec<f64> {
        x.iter()
            .zip(bounds)
            .map(|(v, (lo, hi))| v.clamp(*lo, *hi))
            .collect()
    };
    if d == 0 {
        return (Vec::new(), f(&[]));
    }
    // The grid.
    let mut best: (Vec<f64>, f64) = (Vec::new(), f64::INFINITY);
    if let Some(s) = start {
        let s = clamp(s);
        let v = f(&s);
        best = (s, v);
    }
    let points = grid.max(1);
    for index in 0..points.pow(d as u32) {
        let x: Vec<f64> = (0..d)
            .map(|i| {
                let k = index / points.pow(i as u32) % points;
                let (lo, hi) = bounds[i];
                if points == 1 {
                    (lo + hi) / 2.0
                } else {
                    lo + (hi - lo) * k as f64 / (points - 1) as f64
                }
            })
            .collect();
        let v = f(&x);
        if v < best.1 {
            best = (x, v);
        }
    }
    // Nelder–Mead from the best grid point, steps a tenth of each range.
    let mut simplex: Vec<(Vec<f64>, f64)> = vec![best.clone()];
    for i in 0..d {
        let mut x = best.0.clone();
        let (lo, hi) = bounds[i];
        let step = (hi - lo) / 10.0;
        x[i] = if x[i] + step <= hi {
            x[i] + step
        } else {
            x[i] - step
        };
        let v = f(&x);
        simplex.push((x, v));
    }
    let mut evaluations = d;
    while evaluations < max_evaluations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (lowest, highest) = (simplex[0].1, simplex[d].1);
        if (highest - lowest).abs() <= 1e-10 * lowest.abs().max(1e-300) {
            break;
        }
        let centroid: Vec<f64> = (0..d)
            .map(|i| simplex[..d].iter().map(|p| p.0[i]).sum::<f64>() / d as f64)
            .collect();
        let towards = |t: f64| -> Vec<f64> {
            clamp(
                &(0..d)
                    .map(|i| centroid[i] + t * (simplex[d].0[i] - centroid[i]))
                    .collect::<Vec<_>>(),
            )
        };
        let reflected = towards(-1.0);
        let fr = f(&reflected);
        evaluations += 1;
        if fr < simplex[0].1 {
            let expanded = towards(-2.0);
            let fe = f(&expanded);
            evaluations += 1;
            simplex[d] = if fe < fr { (expanded, fe) } else { (reflected, fr) };
        } else if fr < simplex[d - 1].1 {
            simplex[d] = (reflected, fr);
        } else {
            let contracted = if fr < simplex[d].1 {
                towards(-0.5)
            } else {
                towards(0.5)
            };
            let fc = f(&contracted);
            evaluations += 1;
            if fc < fr.min(simplex[d].1) {
                simplex[d] = (contracted, fc);
            } else {
                // Shrink towards the best.
                let first = simplex[0].0.clone();
                for p in simplex.iter_mut().skip(1) {
                    p.0 = clamp(
                        &(0..d)
                            .map(|i| first[i] + 0.5 * (p.0[i] - first[i]))
                            .collect::<Vec<_>>(),
                    );
                    p.1 = f(&p.0);
                    evaluations += 1;
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex.swap_remove(0)
}

/// Fits `model`'s coefficients to `train` at `inertia`: the least sum of
/// squared errors of the predicted post-impact velocities of G and of the
/// contact point (a refusal counts as no impact), by [`minimise`]: a grid of
/// 11 values of `e` (frictionless) or 6 × 6 of `(e, f)` (Coulomb); the
/// bilinear and twist laws start from the Coulomb fit `coulomb` with a grid
/// of 3 per coordinate. Returns the coefficients and their training score.
pub fn fit_model(
    train: &[&Bounce],
    inertia: f64,
    model: Model,
    coulomb: Option<&[f64]>,
) -> (Vec<f64>, Score) {
    let mut objective = |p: &[f64]| {
        let s = score(train, inertia, model, p);
        s.g + s.c
    };
    let bounds = model.bounds();
    let (p, _) = match model {
        Model::NoImpact | Model::Authors => (Vec::new(), 0.0),
        Model::Frictionless => minimise(&mut objective, &bounds, 11, None, 60),
        Model::Coulomb => minimise(&mut objective, &bounds, 6, None, 120),
        Model::Bilinear | Model::Twist => {
            let mut start = coulomb.map_or(vec![0.3, 0.2], <[f64]>::to_vec);
            start.extend(if model == Model::Bilinear {
                vec![-1.0]
            } else {
                vec![0.0, 0.0]
            });
            minimise(&mut objective, &bounds, 3, Some(&start), 200)
        }
        Model::TwoPhase | Model::CoulombApproach => match fit_two_phase(train, inertia, model) {
            Ok(p) => (p, 0.0),
            Err(why) => panic!("{}: {why}", model.name()),
        },
    };
    let s = score(train, inertia, model, &p);
    (p, s)
}

/// The standard uncertainties [`fit_two_phase`] weights the measured
/// changes with: 1 m/s for `ΔV`, and for `Δω` the same at the corner's lever
/// `√3 h`, so that both weigh as velocities of G and of the contact point.
pub const SIGMA_V: f64 = 1.0;
/// See [`SIGMA_V`].
pub const SIGMA_W: f64 = SIGMA_V / (1.732_050_807_568_877_2 * HALF_WIDTH);

/// Fits a two-phase `model` to `train` at `inertia` with
/// `restitution::fit::spatial` (weighted least squares of the measured `ΔV`
/// and `Δω`, [`SIGMA_V`], [`SIGMA_W`], Levenberg–Marquardt): the
/// coefficients, or the fit's refusal.
pub fn fit_two_phase(train: &[&Bounce], inertia: f64, model: Model) -> Result<Vec<f64>, String> {
    match model {
        Model::TwoPhase | Model::CoulombApproach => Ok(fit_spatial(train, inertia, model)?.values()),
        _ => Err(format!("{} is not a two-phase law", model.name())),
    }
}

/// A law fitted through `restitution::fit::spatial`, with standard errors.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialEstimates {
    /// The model fitted.
    pub model: Model,
    /// Each coefficient (named as in [`Model::parameters`]): value and
    /// standard error.
    pub estimates: Vec<(&'static str, f64, f64)>,
    /// Impacts fitted.
    pub n: usize,
    /// `χ²` at [`SIGMA_V`], [`SIGMA_W`], and its degrees of freedom.
    pub chi_squared: f64,
    pub degrees_of_freedom: usize,
    /// The uncertainty of a component of `ΔV` (m/s) at which `χ²` equals its
    /// degrees of freedom, `SIGMA_V · sqrt(χ²/dof)` (that of `Δω` in the
    /// same ratio): the residuals' own scatter.
    pub sigma_v: f64,
}

impl SpatialEstimates {
    /// The coefficients' values, in [`Model::parameters`] order.
    pub fn values(&self) -> Vec<f64> {
        self.estimates.iter().map(|e| e.1).collect()
    }

    /// The standard errors, in the same order.
    pub fn standard_errors(&self) -> Vec<f64> {
        self.estimates.iter().map(|e| e.2).collect()
    }
}

/// Fits `model` (Coulomb, bilinear or a two-phase law) to `bounces` at
/// `inertia` through `restitution::fit::spatial`, as [`fit_two_phase`] does
/// (weighted least squares of the measured `ΔV` and `Δω`, [`SIGMA_V`],
/// [`SIGMA_W`], Levenberg–Marquardt), with the standard errors: the fit's
/// covariance `(Jᵀ J)⁻¹` at uncertainties scaled so that `χ²` equals its
/// degrees of freedom (the library's errors × `sqrt(χ²/dof)`; the
/// coefficients do not depend on that scale). The six components of an
/// impact are taken as independent.
pub fn fit_spatial(bounces: &[&Bounce], inertia: f64, model: Model) -> Result<SpatialEstimates, String> {
    use restitution::fit::{Measured, SpatialChange, SpatialLaw, SpatialObservation};
    let law = match model {
        Model::Coulomb => SpatialLaw::Friction,
        Model::Bilinear => SpatialLaw::TangentialRestitution,
        Model::TwoPhase => SpatialLaw::KineticRestitution,
        Model::CoulombApproach => SpatialLaw::KineticFriction,
        _ => return Err(format!("{} is not fitted through the spatial fit", model.name())),
    };
    let measured = |a: [f64; 3], b: [f64; 3], sigma: f64| {
        [0, 1, 2].map(|i| Measured {
            value: b[i] - a[i],
            uncertainty: sigma,
        })
    };
    let observations: Vec<SpatialObservation> = bounces
        .iter()
        .map(|b| {
            let impact = spatial_impact(
                b,
                inertia,
                restitution::Law::Frictionless { restitution: 0.0 },
                None,
            );
            SpatialObservation {
                a: impact.a,
                b: None,
                contact: impact.contact,
                measured: vec![SpatialChange {
                    velocity_change: measured(b.pre.velocity, b.post.velocity, SIGMA_V),
                    angular_velocity_change: Some(measured(b.pre.omega, b.post.omega, SIGMA_W)),
                }],
            }
        })
        .collect();
    let fit = restitution::fit::spatial(&observations, law, None).map_err(|e| e.to_string())?;
    let scale = (fit.chi_squared / fit.degrees_of_freedom.max(1) as f64).sqrt();
    Ok(SpatialEstimates {
        model,
        estimates: model
            .parameters()
            .iter()
            .zip(&fit.estimates)
            .map(|(&name, (_, e))| (name, e.value, e.standard_error * scale))
            .collect(),
        n: bounces.len(),
        chi_squared: fit.chi_squared,
        degrees_of_freedom: fit.degrees_of_freedom,
        sigma_v: SIGMA_V * scale,
    })
}

/// Two folds of the tosses, each physical toss in one: the distinct toss
/// numbers among `bounces`, shuffled with `seed` (Fisher–Yates) and halved.
/// Returns each toss's fold (0 or 1).
pub fn fold_of_tosses(bounces: &[Bounce], seed: u64) -> std::collections::BTreeMap<usize, usize> {
    let mut ids: Vec<usize> = bounces.iter().map(|b| b.toss).collect();
    ids.sort_unstable();
    ids.dedup();
    let mut rng = super::Rng::new(seed);
    for i in (1..ids.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        ids.swap(i, j);
    }
    let half = ids.len() / 2;
    ids.into_iter()
        .enumerate()
        .map(|(i, id)| (id, usize::from(i >= half)))
        .collect()
}

/// One model's two-fold prediction of held-out tosses.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOut {
    pub model: Model,
    /// The coefficients fitted on each fold's training tosses (fold `k`
    /// trains on the tosses not in fold `k` and predicts fold `k`).
    pub coefficients: [Vec<f64>; 2],
    /// The inertia used in each fold (kg m²): `I₀` fitted ([`fit_inertia`])
    /// on that fold's training tosses alone.
    pub inertia: [f64; 2],
    /// The training score of each fold (single-corner impacts).
    pub train: [Score; 2],
    /// The held-out scores by class, both folds pooled: every bounce is
    /// predicted once, by coefficients (and inertia) fitted on the other
    /// fold's single-corner impacts.
    pub corner: Score,
    pub edge: Score,
    pub face: Score,
}

/// The two-fold prediction of held-out tosses for each of `models`: the
/// tosses of `bounces` (distinct tosses: one copy of each repeat) split by
/// [`fold_of_tosses`]`(seed)`; in each direction `I₀` and the coefficients
/// are fitted on the training fold's single-corner impacts and every
/// held-out bounce is predicted (corner, edge and face impacts, the latter
/// two at their touching corners' mean).
pub fn held_out(bounces: &[Bounce], models: &[Model], seed: u64) -> Vec<HeldOut> {
    let folds = fold_of_tosses(bounces, seed);
    let part = |k: usize, train: bool, class: Class| -> Vec<&Bounce> {
        bounces
            .iter()
            .filter(|b| (folds[&b.toss] == k) != train && b.class == class)
            .collect()
    };
    let inertia = [0, 1].map(|k| {
        let train: Vec<Bounce> = part(k, true, Class::Corner).into_iter().cloned().collect();
        fit_inertia(&train, 0, seed).inertia
    });
    let coulomb =
        [0, 1].map(|k| fit_model(&part(k, true, Class::Corner), inertia[k], Model::Coulomb, None).0);
    models
        .iter()
        .map(|&model| {
            let fits = [0, 1].map(|k| {
                let train = part(k, true, Class::Corner);
                if model == Model::Coulomb {
                    let s = score(&train, inertia[k], model, &coulomb[k]);
                    (coulomb[k].clone(), s)
                } else {
                    fit_model(&train, inertia[k], model, Some(&coulomb[k]))
                }
            });
            let test = |class: Class| {
                let [a, b] = [0, 1].map(|k| score(&part(k, false, class), inertia[k], model, &fits[k].0));
                a.plus(&b)
            };
            HeldOut {
                model,
                coefficients: [fits[0].0.clone(), fits[1].0.clone()],
                inertia,
                train: [fits[0].1, fits[1].1],
                corner: test(Class::Corner),
                edge: test(Class::Edge),
                face: test(Class::Face),
            }
        })
        .collect()
}

/// An edge impact's edge direction (unit, world, at the impact): from its
/// first touching corner to its second; `None` for other classes.
pub fn edge_axis(b: &Bounce) -> Option<[f64; 3]> {
    let [i, j] = b.corners[..] else { return None };
    let e = rotate(&b.rotation, sub(CORNERS[j], CORNERS[i]));
    Some(scale(1.0 / norm(e), e))
}

/// Components of `v` along the orthonormal axes `(u, (z × u)/|z × u|, z)`:
/// for an edge impact `u` its edge, the second axis horizontal across it.
pub fn edge_components(v: [f64; 3], u: [f64; 3]) -> [f64; 3] {
    let z = [0.0, 0.0, 1.0];
    let across = cross(z, u);
    let across = scale(1.0 / norm(across), across);
    [dot(v, u), dot(v, across), v[2]]
}
