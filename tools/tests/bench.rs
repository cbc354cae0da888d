//! The bench's floors (its bare Madgwick and Mahony arithmetic, timed beside the cores)
//! must compute the cores' numbers; the timing run stops otherwise. Checked here so that
//! a change to a core that the floor does not follow fails the tests, not the bench.

#[test]
fn the_bench_floors_compute_the_cores_numbers() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_bench")).arg("--check").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("the floors compute the cores' numbers"));
}
