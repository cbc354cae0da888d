//! The statuses each function may return, as derived from include/orient.h by
//! tests/common/header_statuses.rs (the fuzz target checks every call against it).
//! `cargo test -p orient --test header_statuses -- --nocapture` prints the table.

#[path = "common/header_statuses.rs"]
mod header_statuses;

use header_statuses::Table;

#[test]
fn table_from_the_header() {
    let t = Table::parse(include_str!("../include/orient.h"));
    println!("{}", t.render());
    // Spot checks of each rule against sentences of the header.
    assert!(t.allows("orient_filter_set_declination", 10), "named: TOO_LARGE beyond pi");
    assert!(!t.allows("orient_filter_set_declination", 9), "ZERO_VECTOR is not named");
    assert!(t.allows("orient_filter_declination", 1) && t.allows("orient_filter_declination", 2));
    assert!(!t.allows("orient_filter_declination", 7));
    assert!(t.allows("orient_rig_align_heading", 13), "deferred: as orient_rig_calibrate");
    assert!(t.allows("orient_rig_calibrate_each", 16), "deferred: as orient_rig_calibrate");
    assert!(t.allows("orient_filter_reset_heading", 13), "deferred: opens with set_heading(");
    assert!(t.allows("orient_filter_linear_accel_earth", 14), "deferred: opens with linear_accel(");
    assert!(t.allows("orient_filter_save", 19), "BUFFER_TOO_SMALL's doc names it");
    assert!(t.allows("orient_filter_new", 17), "OrientConfig's doc: VERSION_MISMATCH");
    assert!(t.allows("orient_smooth_arrays", 8) && t.allows("orient_filters_update", 12));
    assert!(t.allows("orient_mag_calibrator_add", 10), "named: the filters' magnetometer bound");
    assert!(t.allows("orient_gyro_offset", 10), "named: the gyroscope's physical bound");
    assert!(!t.allows("orient_filter_flags", 10), "TOO_LARGE is not named");
    assert!(!t.allows("orient_mag_calibrator_rejected", 7), "NON_FINITE is not named");
}
