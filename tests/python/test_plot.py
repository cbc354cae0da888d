"""Bands from flags and diagnostics, and the matplotlib picture (an SVG whose series
and bands are found by their ids)."""

import xml.etree.ElementTree as ET

import numpy as np
import orient
import pytest
from orient import eval as ev

SVG = "{http://www.w3.org/2000/svg}"


def still_then_turning(n=600, dt=0.01):
    t = np.arange(n) * dt
    gyr = np.zeros((n, 3))
    gyr[300:, 2] = 0.5
    acc = np.tile([0.0, 0.0, 9.81], (n, 1))
    mag = np.tile([0.0, 20.0, -40.0], (n, 1))
    mag[400:450] *= 2.0  # a magnetic disturbance: the norm doubles
    return t, gyr, acc, mag


def test_bands_follow_rest_and_rejected_magnetometer():
    t, gyr, acc, mag = still_then_turning()
    f = orient.Robust()
    r = f.update_batch(gyr, acc, mag, dt=0.01)
    b = ev.bands(t, r)
    assert "rest" in b and b["rest"][0][1] < 3.0 + 1e-9  # rest ends when the turn starts
    assert any(t0 <= 4.0 and 4.0 <= t1 for t0, t1 in b["mag unused"]), b
    assert "gap" not in b
    gap = orient.Madgwick().update_batch(gyr[:10], acc[:10], dt=np.r_[[0.01] * 5, 2.0, [0.01] * 4])
    assert ev.bands(np.arange(10.0), gap, has_mag=False)["gap"] == [(5.0, 5.0)]


def test_plot_writes_an_svg_with_every_series_and_band(tmp_path):
    pytest.importorskip("matplotlib", reason="matplotlib is optional; scripts/test-python.sh installs it")
    from orient.plot import plot_errors

    t, gyr, acc, mag = still_then_turning()
    truth = orient.Madgwick(initial="identity").update_batch(gyr, acc, dt=0.01).quaternion
    rec = ev.Recording(t=t, gyr=gyr, acc=acc, mag=mag, truth=truth, movement=np.ones(len(t), bool))
    results = {k: ev.replay(orient.Filter(k), rec) for k in ("robust", "madgwick")}
    out = tmp_path / "errors.svg"
    plot_errors(rec, results, str(out))
    ids = {el.get("id") for el in ET.parse(out).getroot().iter() if el.get("id")}
    for k in results:
        for angle in ("total", "heading", "inclination"):
            assert f"{k}-{angle}" in ids, (k, angle)
    assert "robust-band-rest-0" in ids and "robust-band-mag unused-0" in ids
