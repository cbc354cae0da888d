"""tests/golden/filters.golden (format: tests/common/golden.rs) through the Python
package: every quaternion bit for bit, through update() and, where every sample carries
the same sensors, through update_batch()."""

import struct

import numpy as np
import orient

SAMPLE_ACCEL, SAMPLE_MAG = 2, 4


def unhex(s):
    return struct.unpack("<d", struct.pack("<Q", int(s, 16)))[0]


def parse(path):
    cases, current = [], None
    for line in path.read_text().splitlines():
        t = line.split()
        if not t or t[0].startswith("#"):
            continue
        if t[0] == "case":
            count = int(t[9])
            current = dict(
                name=t[1], kind=int(t[2]), frame=int(t[3]), init=int(t[4]),
                initial=[unhex(x) for x in t[5:9]],
                params=[(int(t[10 + 2 * i]), unhex(t[11 + 2 * i])) for i in range(count)],
                rows=[],
            )
        elif t[0] == "s":
            v = [unhex(x) for x in t[1:11]]
            current["rows"].append(dict(dt=v[0], gyr=v[1:4], acc=v[4:7], mag=v[7:10], flags=int(t[11]),
                                        expected=[unhex(x) for x in t[12:16]]))
        elif t[0] == "end":
            cases.append(current)
    return cases


def bits(a):
    return np.asarray(a, dtype=np.float64).view(np.uint64)


def make(case):
    kind = orient.Kind(case["kind"])
    names = {p.id: p.name for p in orient.params(kind)}
    settings = {names[i]: v for i, v in case["params"]}
    initial = [None, "identity", case["initial"]][case["init"]]
    frame = orient.Frame(case["frame"]).name.lower()
    return orient.Filter(kind, frame=frame, initial=initial, **settings)


def load(root):
    return parse(root / "tests" / "golden" / "filters.golden")


def test_the_golden_file_has_every_kind(root):
    kinds = {c["kind"] for c in load(root)}
    assert kinds == {k.value for k in orient.Kind}


def test_single_updates_reproduce_every_golden_quaternion_bit_for_bit(root):
    for case in load(root):
        f = make(case)
        for i, r in enumerate(case["rows"]):
            acc = r["acc"] if r["flags"] & SAMPLE_ACCEL else None
            mag = r["mag"] if r["flags"] & SAMPLE_MAG else None
            q = f.update(r["gyr"], acc, mag, dt=r["dt"])
            assert (bits(q) == bits(r["expected"])).all(), f"{case['name']} sample {i}"


def test_batches_reproduce_the_golden_quaternions_bit_for_bit(root):
    uniform = 0
    for case in load(root):
        rows = case["rows"]
        sensors = {r["flags"] for r in rows}
        if len(sensors) != 1:
            continue
        uniform += 1
        (flags,) = sensors
        col = lambda key: np.array([r[key] for r in rows])  # noqa: E731
        result = make(case).update_batch(
            col("gyr"),
            col("acc") if flags & SAMPLE_ACCEL else None,
            col("mag") if flags & SAMPLE_MAG else None,
            dt=col("dt"),
        )
        assert (bits(result.quaternion) == bits(col("expected"))).all(), case["name"]
    assert uniform >= 6
