"""A shared BROAD trial through the Python package, against the replay tool
(tools/src/bin/replay): the same quaternions bit for bit and the same scores."""

import re
import subprocess

import numpy as np
import orient
import pytest
from orient import eval as ev

TRIAL = "15_undisturbed_fast_translation_A.csv"


def run_replay(tool, args):
    out = subprocess.run([str(tool), *args], check=True, capture_output=True, text=True).stdout
    rows = re.findall(r"total +([\d.]+) +heading +([\d.]+) +inclination +([\d.]+) +\((\d+) samples\)", out)
    return out, [(float(a), float(b), float(c), int(d)) for a, b, c, d in rows]


def printed(s):
    return (round(s.total, 2), round(s.heading, 2), round(s.inclination, 2), s.count)


@pytest.mark.parametrize("kind, no_mag", [("robust", False), ("madgwick", True), ("ekf", False)])
def test_a_broad_trial_replays_bit_for_bit_and_scores_as_the_replay_tool(kind, no_mag, shared_data, replay_tool, tmp_path):
    path = shared_data / "broad" / TRIAL
    out_csv = tmp_path / "replay.csv"
    args = ["--filter", kind, "--out", str(out_csv), str(path)] + (["--no-mag"] if no_mag else [])
    text, scores = run_replay(replay_tool, args)
    theirs = np.loadtxt(out_csv, delimiter=",", skiprows=1, usecols=(1, 2, 3, 4))

    rec = ev.read_recording(path, with_mag=not no_mag)
    result = ev.replay(orient.Filter(kind), rec, with_mag=not no_mag)
    assert (result.status == 0).all()
    assert result.quaternion.shape == theirs.shape
    assert (result.quaternion.view(np.uint64) == theirs.view(np.uint64)).all()

    ours = ev.score(result.quaternion, rec.truth, rec.movement)
    assert printed(ours) == scores[0], text
    assert ours.count > 25000 and ours.total < 50
    if no_mag:
        fixed, offset = ev.remove_heading_offset(result.quaternion, rec.truth, rec.movement)
        assert printed(ev.score(fixed, rec.truth, rec.movement)) == scores[1], text
        assert f"heading offset {np.degrees(offset):+.1f} deg removed" in text
    else:
        assert len(scores) == 1


def test_error_angles_of_known_rotations():
    truth = np.tile([1.0, 0.0, 0.0, 0.0], (3, 1))
    yaw, tilt = np.radians(10.0), np.radians(4.0)
    est = np.array([[np.cos(yaw / 2), 0, 0, np.sin(yaw / 2)], [np.cos(tilt / 2), np.sin(tilt / 2), 0, 0], [1, 0, 0, 0]])
    a = np.degrees(ev.error_angles(est, truth))
    assert np.allclose(a, [[10, 10, 0], [4, 0, 4], [0, 0, 0]], atol=1e-9)
    s = ev.score(est, truth, np.array([True, True, False]))
    assert s.count == 2 and abs(s.total - np.sqrt((100 + 16) / 2)) < 1e-9
