use super::*;

/// Every output of a case is read by its own reader and by no other
/// case's; each body list holds exactly that body's outputs.
#[test]
fn each_outcome_reads_its_declared_outputs_and_only_those() {
    fn check<O: Answers>() {
        for &output in Output::ALL {
            assert_eq!(
                O::reader(output).is_some(),
                O::OUTPUTS.contains(&output),
                "{output:?}"
            );
        }
        for (i, o) in O::OUTPUTS.iter().enumerate() {
            assert!(!O::OUTPUTS[i + 1..].contains(o), "{o:?} twice");
        }
    }
    check::<BarrierOutcome>();
    check::<TorsionalOutcome>();
    check::<BodiesOutcome>();
    check::<SpatialOutcome>();
    for (k, prefix) in ["/bodies/0/", "/bodies/1/"].into_iter().enumerate() {
        let planar = BodiesOutcome::OUTPUTS
            .iter()
            .filter(|o| o.path().starts_with(prefix));
        assert!(planar.eq(BODY_OUTPUTS[k].iter()));
        let spatial = SpatialOutcome::OUTPUTS
            .iter()
            .filter(|o| o.path().starts_with(prefix));
        assert!(spatial.eq(SPATIAL_BODY_OUTPUTS[k].iter()));
    }
}

/// Body B's numbers are `NaN` in a barrier impact's outcome, a regime is a name.
#[test]
fn readers_answer_nan_for_a_missing_body_and_names_for_regimes() {
    let barrier = SpatialOutcome {
        body_count: 1,
        ..SpatialOutcome::default()
    };
    let Some(Value::Number(x)) = barrier.value(Output::FinalVelocityBX) else {
        panic!("a number")
    };
    assert!(x.is_nan());
    assert_eq!(barrier.value(Output::FinalVelocityAX), Some(Value::Number(0.0)));
    assert_eq!(barrier.value(Output::Regime), Some(Value::Text("frictionless")));
    assert_eq!(barrier.value(Output::SwitchSpin), None);
    assert_eq!(BarrierOutcome::default().value(Output::FinalSpin), None);
}
