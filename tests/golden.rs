//! The Rust API reproduces the stored golden vectors bit for bit.

mod common;

use common::golden;
use orient::Filter;

#[test]
fn rust_api_reproduces_every_golden_case_bit_for_bit() {
    let text = std::fs::read_to_string(golden::PATH).expect("golden file");
    let cases = golden::parse(&text);
    assert!(cases.len() >= 4, "golden file has {} cases", cases.len());
    for case in &cases {
        let mut f = Filter::new(&case.config()).unwrap();
        for (i, row) in case.rows.iter().enumerate() {
            f.update(&row.sample()).unwrap_or_else(|e| panic!("{} sample {i}: {e}", case.name));
            let q = f.quaternion();
            let bits = |q: orient::Quat| [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()];
            assert_eq!(bits(q), bits(row.expected), "{} sample {i}: {q:?} vs {:?}", case.name, row.expected);
        }
    }
}

#[test]
fn golden_file_round_trips_through_the_writer() {
    let text = std::fs::read_to_string(golden::PATH).unwrap();
    assert_eq!(golden::write(&golden::parse(&text)), text);
}
