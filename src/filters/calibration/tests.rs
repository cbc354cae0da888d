use super::*;

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_model_is_matrix_times_offset_removed() {
    let m = Model {
        matrix: [[2.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]],
        offset: Vec3::new(1.0, 1.0, 1.0),
    };
    assert_eq!(m.apply(Vec3::new(2.0, 3.0, 5.0)), Vec3::new(2.0, 4.0, 4.0));
    let singular = Model { matrix: [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]], offset: Vec3::ZERO };
    assert_eq!(singular.check(Field::Mag), Err(Error::ZeroVector(Field::Mag)));
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_gyro_offset_is_the_still_mean() {
    let mut g = GyroOffset::default();
    assert_eq!(g.offset(), None);
    for i in 0..100 {
        let s = if i % 2 == 0 { 0.001 } else { -0.001 };
        g.add(Vec3::new(0.01 + s, -0.02, 0.03 - s)).unwrap();
    }
    let o = g.offset().unwrap();
    assert!((o - Vec3::new(0.01, -0.02, 0.03)).norm() < 1e-12);
    assert!((g.spread() - 0.001 * (2.0f64 / 3.0).sqrt()).abs() < 1e-5, "{}", g.spread());
    assert_eq!(g.add(Vec3::new(f64::NAN, 0.0, 0.0)), Err(Error::NonFinite(Field::Gyro)));
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn too_few_or_planar_samples_give_no_fit() {
    let mut c = MagCalibrator::new();
    for i in 0..9 {
        c.add(Vec3::new(i as f64, 1.0, 2.0)).unwrap();
    }
    assert!(c.solve().is_none());
    let mut c = MagCalibrator::new();
    for i in 0..100 {
        let a = i as f64 * 0.1;
        c.add(Vec3::new(a.cos(), a.sin(), 0.0)).unwrap();
    }
    assert!(c.solve().is_none(), "a circle does not fix an ellipsoid");
    assert_eq!(MagCalibrator::new().add(Vec3::ZERO), Err(Error::ZeroVector(Field::Mag)));
}
