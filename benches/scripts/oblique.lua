-- The oblique request of benches/load.rs, for wrk.
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
wrk.body = [[{"body": {"mass": 1.0, "inertia": 0.00125},
  "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
  "velocity": {"normal": -1.0, "tangential": 2.0, "angular": 0.0},
  "restitution": 0.93, "friction": 0.123}]]
