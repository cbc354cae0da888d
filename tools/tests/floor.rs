//! The bench's floors (its bare Madgwick and Mahony arithmetic, timed beside the cores,
//! `orient_tools::floor`) must compute the cores' numbers; the timing run stops otherwise.
//! Checked here, in the test process itself (so also under qemu for the board targets),
//! so that a change to a core that the floor does not follow fails the tests, not the
//! bench.

use orient_tools::eval::Recording;

#[test]
fn the_bench_floors_compute_the_cores_numbers() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/data/broad_01_excerpt.csv");
    let rec = Recording::read(path.as_ref(), true).expect("demo recording");
    orient_tools::floor::check_all(&rec.samples()[..2000]);
}
