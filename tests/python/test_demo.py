"""scripts/demo.sh tells the truth: it names the recording and why, the recommended kind
beats Madgwick on it in 9D and 6D, the verdict it prints follows the scores it printed,
and its picture is a valid SVG with every series and band lane (found by their labels)."""

import os
import re
import subprocess
import xml.etree.ElementTree as ET

import pytest

SVG = "{http://www.w3.org/2000/svg}"


def run_demo(root, replay_tool, tmp_path, shared):
    env = dict(os.environ, ORIENT_DEMO_REPLAY=str(replay_tool), ORIENT_DEMO_OUT=str(tmp_path),
               ORIENT_SHARED_DATA=str(shared))
    return subprocess.run([str(root / "scripts" / "demo.sh")], env=env, check=True, capture_output=True,
                          text=True).stdout


@pytest.mark.parametrize("which", ["shared", "bundled"])
def test_the_demo_names_its_recording_and_its_claim_is_true(which, root, replay_tool, shared_data, tmp_path):
    shared = shared_data if which == "shared" else tmp_path / "no-shared"
    out = run_demo(root, replay_tool, tmp_path, shared)
    expected = "BROAD trial 15 (fast translation)" if which == "shared" else "bundled excerpt of BROAD trial 32"
    assert expected in out and "why: " in out, out
    # The scores the replay tool printed: robust, madgwick 9D; then 6D with the offset removed.
    totals = [float(x) for x in re.findall(r"total +([\d.]+) +heading", out)]
    assert len(totals) == 6, out
    robust_9d, madgwick_9d, robust_6d, madgwick_6d = totals[0], totals[1], totals[3], totals[5]
    assert robust_9d * 2 < madgwick_9d and robust_6d < madgwick_6d, out
    assert f"9D: robust {robust_9d:.2f} deg, madgwick {madgwick_9d:.2f} deg total error: the recommended kind is more accurate" in out
    assert f"6D: robust {robust_6d:.2f} deg, madgwick {madgwick_6d:.2f} deg total error: the recommended kind is more accurate" in out

    path = re.search(r"^picture: (\S+)", out, re.M).group(1)
    svg = ET.parse(path).getroot()
    assert svg.tag == SVG + "svg"
    labels = {(t.text or "").strip() for t in svg.iter(SVG + "text")}
    for kind in ("robust", "madgwick"):
        for angle in ("total", "heading", "inclination"):
            assert f"{kind} {angle}" in labels, (kind, angle)
        for band in ("rest", "mag unused", "accel unused", "gap"):
            assert f"{kind} {band}" in labels, (kind, band)
    assert sum(1 for _ in svg.iter(SVG + "polyline")) >= 6
