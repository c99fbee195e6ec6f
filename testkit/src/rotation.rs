//! Rotations, for the tests that turn a scene in space.

/// A rotation matrix, by rows.
pub type Rotation = [[f64; 3]; 3];

/// The rotation of the unit quaternion along `q` (normalised here; rounds).
pub fn from_quaternion(q: [f64; 4]) -> Rotation {
    let size = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / size);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// `r v`.
pub fn rotate(r: &Rotation, v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

/// `rᵀ v`: back to the unrotated frame.
pub fn rotate_back(r: &Rotation, v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[0][i] * v[0] + r[1][i] * v[1] + r[2][i] * v[2])
}

/// A random rotation: the quaternion's four components drawn by `draw`
/// (uniform in [-1, 1]).
pub fn random(mut draw: impl FnMut() -> f64) -> Rotation {
    from_quaternion(std::array::from_fn(|_| draw()))
}

/// A uniformly random rotation: a quaternion drawn uniformly from the unit
/// ball (by rejection, away from the origin); `draw` is uniform in [-1, 1].
pub fn uniform(mut draw: impl FnMut() -> f64) -> Rotation {
    loop {
        let q: [f64; 4] = std::array::from_fn(|_| draw());
        let n2: f64 = q.iter().map(|v| v * v).sum();
        if n2 > 0.01 && n2 <= 1.0 {
            break from_quaternion(q);
        }
    }
}
