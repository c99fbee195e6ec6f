//! The inertia of a body in space on the wire: the tensor's own entries, a
//! sphere, or principal moments with a rotation, read by one `Deserialize`
//! that names the member that is missing or wrong, and turned into the
//! tensor's six entries.

use axum::http::StatusCode;
use serde::Deserialize;
use utoipa::ToSchema;

use super::spatial::Vector3Dto;
use crate::http::problem::ApiError;

/// The inertia tensor about the mass centre, in world axes: its own matrix
/// entries (`xy = −∫ x y dm`); symmetric positive definite.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TensorDto {
    /// I_xx = ∫(y² + z²) dm.
    pub xx: f64,
    /// I_yy.
    pub yy: f64,
    /// I_zz.
    pub zz: f64,
    /// I_xy = −∫ x y dm.
    pub xy: f64,
    /// I_xz.
    pub xz: f64,
    /// I_yz.
    pub yz: f64,
}

/// A uniform sphere about its centre: `I = (2/5) m r²` solid, `(2/3) m r²` hollow.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SphereDto {
    /// r > 0.
    #[schema(exclusive_minimum = 0.0, example = 0.033)]
    pub radius: f64,
    /// A thin shell (tennis ball, basketball) rather than a solid ball.
    #[serde(default)]
    pub hollow: bool,
}

/// A rotation as a quaternion `w + x i + y j + z k` (normalised by the server).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct QuaternionDto {
    /// Scalar part.
    pub w: f64,
    /// i part.
    pub x: f64,
    /// j part.
    pub y: f64,
    /// k part.
    pub z: f64,
}

/// Principal moments in the body's axes, turned into world axes by `rotation`
/// (identity when absent): the tensor is `R diag(moments) Rᵀ` in f64.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PrincipalDto {
    /// The principal moments about the body's x, y, z axes (> 0).
    pub moments: Vector3Dto,
    /// The body's orientation.
    pub rotation: Option<QuaternionDto>,
}

/// An inertia tensor: the canonical six entries, a sphere, or principal moments.
///
/// Read by its own `Deserialize` (below), which tells the forms apart by
/// their members and names the member that is missing or wrong; the schema
/// is the untagged one of the three forms.
#[derive(Debug, Clone, Copy, ToSchema)]
#[serde(untagged)]
pub enum InertiaDto {
    /// The tensor's own entries (the canonical form).
    Tensor(TensorDto),
    /// `{"sphere": {"radius", "hollow"}}`.
    Sphere {
        /// The sphere.
        sphere: SphereDto,
    },
    /// `{"principal": {"moments", "rotation"}}`.
    Principal {
        /// The moments and the rotation.
        principal: PrincipalDto,
    },
}

/// The forms an inertia takes, for messages.
const INERTIA_FORMS: &str = "the tensor's six entries {\"xx\", \"yy\", \"zz\", \"xy\", \"xz\", \"yz\"}, \
     {\"sphere\": {\"radius\", \"hollow\"}} or {\"principal\": {\"moments\", \"rotation\"}}";

/// The tensor form's members, in [`TensorDto`]'s order.
const TENSOR_ENTRIES: [&str; 6] = ["xx", "yy", "zz", "xy", "xz", "yz"];

impl<'de> Deserialize<'de> for InertiaDto {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(InertiaVisitor)
    }
}

/// Reads an inertia member by member: `sphere` or `principal` alone, else the
/// six tensor entries; a missing entry is named (`missing field \`xy\``, so
/// that its pointer is the entry's), an unknown member with the forms accepted.
struct InertiaVisitor;

impl<'de> serde::de::Visitor<'de> for InertiaVisitor {
    type Value = InertiaDto;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "an inertia: {INERTIA_FORMS}")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<InertiaDto, A::Error> {
        use serde::de::Error;
        let mut entries = [None; 6];
        let mut first = true;
        while let Some(key) = map.next_key::<String>()? {
            if first && (key == "sphere" || key == "principal") {
                let inertia = if key == "sphere" {
                    InertiaDto::Sphere {
                        sphere: map.next_value()?,
                    }
                } else {
                    InertiaDto::Principal {
                        principal: map.next_value()?,
                    }
                };
                if let Some(other) = map.next_key::<String>()? {
                    return Err(A::Error::custom(format!(
                        "unknown field `{other}`: a {key} inertia has the one member `{key}`; inertia takes {INERTIA_FORMS}"
                    )));
                }
                return Ok(inertia);
            }
            first = false;
            let Some(i) = TENSOR_ENTRIES.iter().position(|&e| e == key) else {
                return Err(A::Error::custom(format!(
                    "unknown field `{key}`: inertia takes {INERTIA_FORMS}"
                )));
            };
            if entries[i].is_some() {
                return Err(A::Error::custom(format!("duplicate field `{key}`")));
            }
            entries[i] = Some(map.next_value::<f64>()?);
        }
        let mut values = [0.0; 6];
        for (i, entry) in entries.into_iter().enumerate() {
            values[i] = entry.ok_or_else(|| {
                A::Error::custom(format!(
                    "missing field `{}`: the tensor form needs all six entries; inertia takes {INERTIA_FORMS}",
                    TENSOR_ENTRIES[i]
                ))
            })?;
        }
        let [xx, yy, zz, xy, xz, yz] = values;
        Ok(InertiaDto::Tensor(TensorDto {
            xx,
            yy,
            zz,
            xy,
            xz,
            yz,
        }))
    }
}

fn invalid(pointer: String, detail: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "out-of-range",
        "Input out of range",
        detail,
    )
    .at(&pointer)
}

impl InertiaDto {
    /// The canonical entries `[xx, yy, zz, xy, xz, yz]` (the conveniences
    /// evaluated in f64), for body `k` of mass `mass`.
    pub(super) fn tensor(&self, k: usize, mass: f64) -> Result<[f64; 6], ApiError> {
        Ok(match *self {
            InertiaDto::Tensor(t) => [t.xx, t.yy, t.zz, t.xy, t.xz, t.yz],
            InertiaDto::Sphere { sphere } => {
                if !(sphere.radius.is_finite() && sphere.radius > 0.0) {
                    return Err(invalid(
                        format!("/bodies/{k}/inertia/sphere/radius"),
                        format!(
                            "a sphere's radius must be a finite number above 0, got {}",
                            sphere.radius
                        ),
                    ));
                }
                let moment =
                    if sphere.hollow { 2.0 / 3.0 } else { 0.4 } * mass * sphere.radius * sphere.radius;
                [moment, moment, moment, 0.0, 0.0, 0.0]
            }
            InertiaDto::Principal { principal } => {
                let moments: [f64; 3] = principal.moments.into();
                for (axis, m) in ["x", "y", "z"].into_iter().zip(moments) {
                    if !(m.is_finite() && m > 0.0) {
                        return Err(invalid(
                            format!("/bodies/{k}/inertia/principal/moments/{axis}"),
                            format!("a principal moment must be a finite number above 0, got {m}"),
                        ));
                    }
                }
                let r = match principal.rotation {
                    None => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                    Some(q) => {
                        let size = (q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z).sqrt();
                        if !(size.is_finite() && size > 0.0) {
                            return Err(invalid(
                                format!("/bodies/{k}/inertia/principal/rotation"),
                                "the rotation must be a finite, non-zero quaternion".to_owned(),
                            ));
                        }
                        let [w, x, y, z] = [q.w, q.x, q.y, q.z].map(|c| c / size);
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
                };
                let entry = |i: usize, j: usize| (0..3).map(|c| r[i][c] * moments[c] * r[j][c]).sum::<f64>();
                [
                    entry(0, 0),
                    entry(1, 1),
                    entry(2, 2),
                    entry(0, 1),
                    entry(0, 2),
                    entry(1, 2),
                ]
            }
        })
    }
}
