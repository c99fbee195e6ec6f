//! The request files of `examples/`, read as JSON: the tests check the
//! scenes the documentation quotes rather than copies of them.

use serde_json::Value;

/// `examples/{name}` as JSON.
pub fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", crate::ROOT);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The intersection crash of `examples/planar_car_to_car.json` (a body for
/// `POST /v1/impacts/planar`).
pub fn cars() -> Value {
    example("planar_car_to_car.json")
}
