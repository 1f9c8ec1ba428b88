//! The wire types have the documented size, alignment and field offsets
//! (`docs/wire_format.md`), and convert losslessly.

use std::mem::{align_of, offset_of, size_of};

use nalgebra::Vector3;
use proptest::prelude::*;
use shearcut::transport::wire::{
    WireCommand, WireError, WireMeasurement, WirePlantCounts, WireStatus, WireTruth,
};
use shearcut_plant::{PlantTruth, Wrench};
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand, LimitViolation};

#[test]
fn command_layout_is_the_documented_one() {
    assert_eq!(size_of::<WireCommand>(), 48);
    assert_eq!(align_of::<WireCommand>(), 8);
    assert_eq!(offset_of!(WireCommand, sequence), 0);
    assert_eq!(offset_of!(WireCommand, time), 8);
    assert_eq!(offset_of!(WireCommand, velocity), 16);
    assert_eq!(offset_of!(WireCommand, flags), 40);
    assert_eq!(offset_of!(WireCommand, reserved), 44);
}

/// The measurement carries only what an arm reports (wire format v2).
#[test]
fn measurement_layout_is_the_documented_one() {
    assert_eq!(size_of::<WireMeasurement>(), 136);
    assert_eq!(align_of::<WireMeasurement>(), 8);
    let offsets = [
        (offset_of!(WireMeasurement, sequence), 0),
        (offset_of!(WireMeasurement, time), 8),
        (offset_of!(WireMeasurement, position), 16),
        (offset_of!(WireMeasurement, velocity), 40),
        (offset_of!(WireMeasurement, wrench), 64),
        (offset_of!(WireMeasurement, fault_value), 112),
        (offset_of!(WireMeasurement, status), 120),
        (offset_of!(WireMeasurement, fault), 124),
        (offset_of!(WireMeasurement, missed_commands), 128),
        (offset_of!(WireMeasurement, reserved), 132),
    ];
    for (i, (got, want)) in offsets.iter().enumerate() {
        assert_eq!(got, want, "field {i}");
    }
}

#[test]
fn plant_counts_layout_is_the_documented_one() {
    assert_eq!(size_of::<WirePlantCounts>(), 16);
    assert_eq!(align_of::<WirePlantCounts>(), 8);
    assert_eq!(offset_of!(WirePlantCounts, successor_deferrals), 0);
    assert_eq!(offset_of!(WirePlantCounts, successor_waits), 8);
}

#[test]
fn truth_layout_is_the_documented_one() {
    assert_eq!(size_of::<WireTruth>(), 96);
    assert_eq!(align_of::<WireTruth>(), 8);
    let offsets = [
        (offset_of!(WireTruth, sequence), 0),
        (offset_of!(WireTruth, wrench), 8),
        (offset_of!(WireTruth, crack_depth), 56),
        (offset_of!(WireTruth, contact_length), 64),
        (offset_of!(WireTruth, work), 72),
        (offset_of!(WireTruth, deformation), 80),
        (offset_of!(WireTruth, fractured_sections), 88),
    ];
    for (i, (got, want)) in offsets.iter().enumerate() {
        assert_eq!(got, want, "field {i}");
    }
}

fn measurement(x: [f64; 8], status: ArmStatus) -> ArmReading {
    ArmReading {
        time: x[0],
        position: Vector3::new(x[1], x[2], x[3]),
        velocity: Vector3::new(x[4], -x[5], x[6]),
        wrench: [x[7], x[0], x[1], x[2], x[3], x[4]],
        status,
    }
}

fn truth(x: [f64; 8]) -> PlantTruth {
    PlantTruth {
        wrench: Wrench {
            force: Vector3::new(x[5], x[6], x[7]),
            torque: Vector3::new(x[1], -x[2], x[3]),
        },
        crack_depth: x[4],
        contact_length: x[5],
        fractured_sections: 7,
        work: x[6],
        deformation: x[7],
    }
}

proptest! {
    #[test]
    fn measurements_cross_the_wire_bit_for_bit(
        // Every field within what an arm reports (WireMeasurement::BOUNDS:
        // 10 is inside all of them); beyond, a reading is refused (below).
        x in prop::array::uniform8(-10.0f64..=10.0),
        kind in 0u8..5,
    ) {
        let status = match kind {
            0 => ArmStatus::Moving,
            1 => ArmStatus::LimitViolation(LimitViolation::Velocity(x[0])),
            2 => ArmStatus::LimitViolation(LimitViolation::Acceleration(x[1])),
            3 => ArmStatus::LimitViolation(LimitViolation::Jerk(x[2])),
            _ => ArmStatus::LimitViolation(LimitViolation::NotFinite),
        };
        let m = measurement(x, status);
        let back = WireMeasurement::new(42, &m, 3).reading().unwrap();
        // Debug prints each f64 in its shortest round-trip form.
        prop_assert_eq!(format!("{m:?}"), format!("{back:?}"));
        let t = truth(x);
        let wire = WireTruth::new(42, &t);
        prop_assert_eq!(wire.sequence, 42);
        prop_assert_eq!(format!("{t:?}"), format!("{:?}", wire.truth()));
    }

    #[test]
    fn commands_cross_the_wire_bit_for_bit(v in prop::array::uniform3(any::<f64>())) {
        let c = KnifeCommand { velocity: Vector3::from(v) };
        let w = WireCommand::new(9, 0.25, &c);
        let back = w.knife_command();
        for (b, x) in back.velocity.iter().zip(v) {
            prop_assert_eq!(b.to_bits(), x.to_bits());
        }
        prop_assert!(!w.is_end_of_run());
    }
}

#[test]
fn a_braked_plant_is_not_a_measurement() {
    let m = measurement([0.5; 8], ArmStatus::Moving);
    let w = WireMeasurement::new(1, &m, 20).stopped(
        WireStatus::Braked,
        shearcut::transport::wire::WireFault::MissedCommands,
        20.0,
    );
    assert_eq!(w.reading(), Err(WireError::Braked(20)));
    assert!(WireCommand::end_of_run(3, 1.0).is_end_of_run());
}

/// Sets one field of a measurement.
type SetField = fn(&mut WireMeasurement, f64);

/// A hostile or broken bridge: NaN, ±inf and values no arm reports in any
/// field are refused with the field named, never turned into a reading.
#[test]
fn a_measurement_no_arm_could_report_is_refused() {
    let good = WireMeasurement::new(
        3,
        &measurement(
            [0.1, 0.02, -0.3, 0.004, 1.5, -2.0, 0.3, 0.01],
            ArmStatus::Moving,
        ),
        0,
    );
    assert!(good.reading().is_ok());
    let cases: [(&str, SetField); 6] = [
        ("time", |m, v| m.time = v),
        ("position", |m, v| m.position[1] = v),
        ("velocity", |m, v| m.velocity[2] = v),
        ("wrench.force", |m, v| m.wrench[0] = v),
        ("wrench.torque", |m, v| m.wrench[5] = v),
        ("fault_value", |m, v| m.fault_value = v),
    ];
    for (field, set) in cases {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300] {
            if field == "fault_value" && bad == 1e300 {
                continue; // finite fault values are the plant's to report
            }
            let mut m = good;
            set(&mut m, bad);
            match m.reading() {
                Err(WireError::OutOfRange { field: f, .. }) => assert_eq!(f, field, "{bad}"),
                other => panic!("{field} = {bad}: {other:?}"),
            }
        }
    }
    // On the bound is accepted, just past it is not.
    let mut m = good;
    m.position[0] = 10.0;
    assert!(m.reading().is_ok());
    m.position[0] = 10.0f64.next_up();
    assert!(m.reading().is_err());
}
