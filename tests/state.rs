//! Snapshots: a run split at sample N (save, load into a fresh filter, continue) equals
//! an unbroken run bit for bit, for every kind, through the Rust API and the C ABI; a
//! blob that is corrupted, truncated, of another kind or another version is refused and
//! changes nothing.

mod common;

use common::sim::{c_sample, simulate, Moment};
use orient::ffi::*;
use orient::filters::state::StateError;
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};

fn samples() -> Vec<Sample> {
    simulate(Quat::IDENTITY, 12.0, 100.0, (0.002, 0.05, 0.3), |t| Moment {
        omega: if t < 3.0 {
            Vec3::ZERO
        } else {
            Vec3::new(0.5 * (0.7 * t).sin(), 0.3, -0.4 * (0.5 * t).cos())
        },
        bias: Vec3::new(0.01, -0.004, 0.006),
        ..Default::default()
    })
    .samples
}

fn bits(q: Quat) -> [u64; 4] {
    [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
}

#[test]
fn split_runs_equal_unbroken_runs_for_every_kind() {
    let s = samples();
    for kind in Kind::ALL {
        let config = Config::new(kind).unwrap();
        for split in [0, 50, 150, 700] {
            let mut whole = Filter::new(&config).unwrap();
            let mut first = Filter::new(&config).unwrap();
            for x in &s[..split] {
                whole.update(x).unwrap();
                first.update(x).unwrap();
            }
            let mut blob = vec![0u8; first.state_size()];
            let n = first.save(&mut blob).unwrap();
            assert_eq!(n, blob.len());
            let mut second = Filter::new(&config).unwrap();
            second.load(&blob).unwrap();
            assert_eq!(second, first, "{kind:?} split {split}: loaded state differs");
            for x in &s[split..] {
                whole.update(x).unwrap();
                second.update(x).unwrap();
                assert_eq!(bits(whole.quaternion()), bits(second.quaternion()), "{kind:?} split {split}");
            }
        }
    }
}

#[test]
fn damaged_blobs_are_refused_and_change_nothing() {
    let s = samples();
    for kind in Kind::ALL {
        let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
        for x in &s[..400] {
            f.update(x).unwrap();
        }
        let mut blob = vec![0u8; f.state_size()];
        f.save(&mut blob).unwrap();
        let mut target = Filter::new(&Config::new(kind).unwrap()).unwrap();
        target.update(&s[0]).unwrap();
        let before = target.clone();
        assert_eq!(target.load(&blob[..blob.len() - 1]), Err(StateError::Truncated));
        assert_eq!(target.load(&blob[..7]), Err(StateError::Truncated));
        assert_eq!(target.load(&[]), Err(StateError::Truncated));
        // Every single-bit flip somewhere in the blob (a stride keeps GMVDK's 16 KiB fast).
        let stride = (blob.len() / 500).max(1);
        for i in (0..blob.len()).step_by(stride) {
            let mut bad = blob.clone();
            bad[i] ^= 1 << (i % 8);
            assert!(target.load(&bad).is_err(), "{kind:?}: flipped bit in byte {i} accepted");
        }
        // Another version (checksum redone so that only the version is wrong).
        let other = orient::filters::state::VERSION + 1;
        let mut v2 = blob.clone();
        v2[4..6].copy_from_slice(&other.to_le_bytes());
        let end = v2.len() - 8;
        let sum = orient::filters::state::checksum(&v2[..end]);
        v2[end..].copy_from_slice(&sum.to_le_bytes());
        assert_eq!(target.load(&v2), Err(StateError::Version(other)));
        assert_eq!(target, before, "{kind:?}: a refused load changed the filter");
        // Another kind.
        for other in Kind::ALL.into_iter().filter(|k| *k != kind) {
            let mut g = Filter::new(&Config::new(other).unwrap()).unwrap();
            assert!(matches!(g.load(&blob), Err(StateError::Kind(_))), "{kind:?} into {other:?}");
        }
        // Too small an output buffer.
        let mut small = vec![0u8; blob.len() - 1];
        assert_eq!(f.save(&mut small), Err(StateError::BufferTooSmall(blob.len())));
    }
}

#[test]
fn split_runs_through_the_c_abi() {
    let s: Vec<OrientSample> = samples().iter().map(c_sample).collect();
    for kind in Kind::ALL.map(|k| OrientKind::from(k) as i32) {
        unsafe {
            let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
            assert_eq!(orient_config_default(kind, c.as_mut_ptr()), OrientStatus::Ok);
            let (mut whole, mut first, mut second) =
                (std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut());
            for h in [&mut whole, &mut first, &mut second] {
                assert_eq!(orient_filter_new(c.as_ptr(), h), OrientStatus::Ok);
            }
            let split = 500;
            let mut out = vec![OrientQuaternion::default(); s.len()];
            assert_eq!(
                orient_filter_update_batch(
                    whole,
                    s.as_ptr(),
                    s.len(),
                    out.as_mut_ptr(),
                    std::ptr::null_mut()
                ),
                OrientStatus::Ok
            );
            assert_eq!(
                orient_filter_update_batch(
                    first,
                    s.as_ptr(),
                    split,
                    std::ptr::null_mut(),
                    std::ptr::null_mut()
                ),
                OrientStatus::Ok
            );
            let mut size = 0;
            assert_eq!(orient_filter_state_size(first, &mut size), OrientStatus::Ok);
            let mut blob = vec![0u8; size];
            let mut written = 0;
            assert_eq!(
                orient_filter_save(first, blob.as_mut_ptr(), size - 1, &mut written),
                OrientStatus::BufferTooSmall
            );
            assert_eq!(orient_filter_save(first, blob.as_mut_ptr(), size, &mut written), OrientStatus::Ok);
            assert_eq!(written, size);
            assert_eq!(orient_filter_free(first), OrientStatus::Ok);
            let mut bad = blob.clone();
            bad[20] ^= 4;
            assert_eq!(orient_filter_load(second, bad.as_ptr(), bad.len()), OrientStatus::InvalidState);
            assert_eq!(orient_filter_load(second, blob.as_ptr(), blob.len() - 3), OrientStatus::InvalidState);
            assert_eq!(orient_filter_load(second, std::ptr::null(), 10), OrientStatus::NullPointer);
            assert_eq!(orient_filter_load(second, blob.as_ptr(), blob.len()), OrientStatus::Ok);
            let mut rest = vec![OrientQuaternion::default(); s.len() - split];
            let n = s.len() - split;
            assert_eq!(
                orient_filter_update_batch(
                    second,
                    s[split..].as_ptr(),
                    n,
                    rest.as_mut_ptr(),
                    std::ptr::null_mut()
                ),
                OrientStatus::Ok
            );
            for (i, (a, b)) in out[split..].iter().zip(&rest).enumerate() {
                let same = a.w.to_bits() == b.w.to_bits()
                    && a.x.to_bits() == b.x.to_bits()
                    && a.y.to_bits() == b.y.to_bits()
                    && a.z.to_bits() == b.z.to_bits();
                assert!(same, "kind {kind}: sample {} differs after the split", split + i);
            }
            orient_filter_free(whole);
            orient_filter_free(second);
        }
    }
}

/// The blob with one 8-byte payload value replaced and the checksum made valid again:
/// what a forger (or a bug writing blobs elsewhere) could hand to `load`.
fn forged(blob: &[u8], value_index: usize, bits: u64) -> Vec<u8> {
    use orient::filters::state::{checksum, HEADER, TRAILER};
    let mut b = blob.to_vec();
    let at = HEADER + 8 * value_index;
    b[at..at + 8].copy_from_slice(&bits.to_le_bytes());
    let end = b.len() - TRAILER;
    let sum = checksum(&b[..end]);
    b[end..].copy_from_slice(&sum.to_le_bytes());
    b
}

/// Whatever a blob with a valid checksum says, `load` either refuses it (and changes
/// nothing) or gives a filter that works: every one of its values replaced in turn by
/// values no filter could hold (a bias of 1e300, a covariance entry of -1, a quaternion
/// component of 7, ...), and the filter that loads it must take 300 good samples with a
/// finite unit quaternion and save a blob that loads again.
#[test]
#[cfg_attr(miri, ignore = "long loops")]
fn forged_blobs_with_a_valid_checksum_load_only_as_a_working_filter() {
    use orient::filters::state::{HEADER, TRAILER};
    let s = samples();
    let forgeries: [f64; 9] = [1e300, -1e300, 7.0, -1.0, 0.0, 0.5, 1e12, -3e-5, 4.0];
    let (mut refused, mut loaded) = (0, 0);
    for kind in Kind::ALL {
        let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
        for x in &s[..600] {
            f.update(x).unwrap();
        }
        let mut blob = vec![0u8; f.state_size()];
        f.save(&mut blob).unwrap();
        let values = (blob.len() - HEADER - TRAILER) / 8;
        // The configuration comes first (frame, init, initial quaternion, 128 slots): a
        // forged one that passes the range checks is a configuration a host could set,
        // with samples refused for its reasons (a sensor range of 7, say). The state
        // follows: every value, for the small kinds; a spread for GMVDK's long μ window.
        let config_values = 2 + 4 + orient::MAX_PARAMS;
        // Under emulation a spread of every kind's values (qemu is 20-50 times slower).
        let step = match (values > 400, common::native::cross()) {
            (true, true) => 29,
            (true, false) => 7,
            (false, true) => 5,
            (false, false) => 1,
        };
        for i in (config_values..values).step_by(step) {
            for v in forgeries {
                let b = forged(&blob, i, v.to_bits());
                let mut g = f.clone();
                match g.load(&b) {
                    Err(_) => {
                        assert_eq!(g, f, "{kind:?} value {i} = {v}: refused, yet changed");
                        refused += 1;
                    }
                    Ok(()) => {
                        loaded += 1;
                        for (k, x) in s[600..900].iter().enumerate() {
                            g.update(x)
                                .unwrap_or_else(|e| panic!("{kind:?} value {i} = {v}: sample {k}: {e}"));
                            let q = g.quaternion();
                            assert!(
                                q.is_finite() && (q.norm() - 1.0).abs() < 1e-9,
                                "{kind:?} value {i} = {v}: {q:?}"
                            );
                        }
                        let mut again = vec![0u8; g.state_size()];
                        g.save(&mut again).unwrap();
                        Filter::new(&g.config())
                            .unwrap()
                            .load(&again)
                            .unwrap_or_else(|e| panic!("{kind:?} value {i} = {v}: own blob refused: {e:?}"));
                    }
                }
            }
        }
    }
    println!("forged blobs: {refused} refused, {loaded} loaded and worked");
    assert!(refused > 0 && loaded > 0);
}

/// A blob of one kind relabelled as another (kind byte changed, checksum made valid) is
/// refused, even where the two kinds' payloads have the same length.
#[test]
fn a_blob_relabelled_as_another_kind_is_refused() {
    use orient::filters::state::{checksum, TRAILER};
    let s = samples();
    for from in Kind::ALL {
        let mut f = Filter::new(&Config::new(from).unwrap()).unwrap();
        for x in &s[..400] {
            f.update(x).unwrap();
        }
        let mut blob = vec![0u8; f.state_size()];
        f.save(&mut blob).unwrap();
        for (to_index, to) in Kind::ALL.iter().enumerate() {
            if *to == from {
                continue;
            }
            let mut b = blob.clone();
            b[6] = to_index as u8 + 1;
            let end = b.len() - TRAILER;
            let sum = checksum(&b[..end]);
            b[end..].copy_from_slice(&sum.to_le_bytes());
            let mut g = Filter::new(&Config::new(*to).unwrap()).unwrap();
            let before = g.clone();
            assert!(g.load(&b).is_err(), "a {from:?} blob loads as {to:?}");
            assert_eq!(g, before);
        }
    }
}

/// A host frame that equals the default but for the sign of a zero (a mounting of
/// (1, -0, 0, 0), a declination of -0) saves the bytes a filter loaded from its blob saves:
/// a load keeps no host frames equal (`==`) to the defaults, so such zeros are made +0
/// when set (the outputs are the same either way). The fuzz target found it
/// (fuzz/regressions/mounting-negative-zero).
#[test]
fn a_negative_zero_host_frame_saves_what_its_loaded_copy_saves() {
    for kind in Kind::ALL {
        for set in 0..2 {
            let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
            match set {
                0 => f.set_mounting(Quat::new(1.0, -0.0, 0.0, 0.0)).unwrap(),
                _ => f.set_declination(-0.0).unwrap(),
            }
            let mut a = vec![0u8; f.state_size()];
            f.save(&mut a).unwrap();
            let mut g = Filter::new(&Config::new(kind).unwrap()).unwrap();
            g.load(&a).unwrap();
            let mut b = vec![0u8; g.state_size()];
            g.save(&mut b).unwrap();
            assert!(a == b, "{kind:?}, case {set}: the loaded copy saves other bytes");
        }
    }
}
