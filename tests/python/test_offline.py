"""Filter.smooth (orient_smooth_arrays): the offline mode from Python."""

import numpy as np
import orient
import pytest

N = 600
ROLL = 0.4
C, S = np.cos(ROLL), np.sin(ROLL)
# Rolled about x and held still: gravity and the earth field seen in the sensor frame.
ACC = np.tile([0.0, 9.81 * S, 9.81 * C], (N, 1))
MAG = np.tile([0.0, 20.0 * C - 40.0 * S, -20.0 * S - 40.0 * C], (N, 1))
GYR = np.zeros((N, 3))


@pytest.mark.parametrize("kind", [orient.Madgwick, orient.Ekf, orient.Robust])
def test_smooth_finds_the_tilt_and_leaves_the_filter_alone(kind):
    f = kind()
    before = f.quaternion.copy()
    q = f.smooth(GYR, ACC, MAG, dt=0.01)
    assert q.shape == (N, 4)
    expect = np.array([np.cos(ROLL / 2), np.sin(ROLL / 2), 0.0, 0.0])
    assert np.all(np.abs(q @ expect) > np.cos(0.005))
    assert (f.quaternion == before).all()
    assert (f.smooth(GYR, ACC, MAG, dt=np.full(N, 0.01)) == q).all()


def test_smooth_names_the_bad_sample():
    acc = ACC.copy()
    acc[7, 1] = np.nan
    with pytest.raises(orient.OrientError) as e:
        orient.Robust().smooth(GYR, acc, MAG, dt=0.01)
    assert e.value.index == 7


def test_module_smooth_uses_the_offline_defaults():
    q = orient.smooth(GYR, ACC, MAG, dt=0.01)
    plain = orient.Robust().smooth(GYR, ACC, MAG, dt=0.01)
    slow = orient.Robust(tau_mag=27.0).smooth(GYR, ACC, MAG, dt=0.01)
    assert (q == slow).all()
    assert q.shape == plain.shape == (N, 4)


def test_smooth_memory_states_what_the_library_allocates():
    assert orient.smooth_memory(0) == 32768
    assert orient.smooth_memory(N) == 8 * N + 32768
    most = (2**63 - 1) // 32
    assert orient.smooth_memory(most) == 8 * most + 32768
    with pytest.raises(orient.OrientError) as e:
        orient.smooth_memory(most + 1)
    assert e.value.status == orient.Status.COUNT_TOO_LARGE
    assert orient.Status.OUT_OF_MEMORY == 21
