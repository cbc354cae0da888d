//! The Rust API in a few lines: a filter per kind on the demo recording, the final
//! orientation and its error against the optical ground truth.
//! (The recording is read with the repository's tools crate, `orient-tools`; everything
//! after that is the `orient` API.)
//!
//!     cargo run --release --example quickstart

use orient::{Config, Filter, Frame, Kind};
use orient_tools::eval::Recording;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/broad_01_excerpt.csv");
    let recording = Recording::read(path.as_ref(), true)?;
    for kind in Kind::ALL {
        let mut config = Config::new(kind)?;
        config.frame = Frame::Enu;
        let mut filter = Filter::new(&config)?;
        for sample in recording.samples() {
            filter.update(&sample)?;
        }
        let q = filter.quaternion();
        let truth = *recording.truth.last().unwrap();
        let e = filter.euler();
        println!(
            "{:<13} yaw {:7.2}° pitch {:6.2}° roll {:7.2}°  error vs truth {:5.2}°",
            kind.name(),
            e.yaw.to_degrees(),
            e.pitch.to_degrees(),
            e.roll.to_degrees(),
            q.angle_to(truth.normalized()).to_degrees()
        );
    }
    Ok(())
}
