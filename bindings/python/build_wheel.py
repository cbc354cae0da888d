#!/usr/bin/env python3
"""Builds the orient-imu wheel: the package in bindings/python/orient plus the release
shared library, bundled beside it (the package loads it with ctypes).

    python3 bindings/python/build_wheel.py --lib target/release/liborient.so --out DIR

Standard library only (a wheel is a zip with METADATA, WHEEL and RECORD, PEP 427): no
build backend to install. The version comes from Cargo.toml. The tag is
py3-none-<platform> (no CPython ABI is used; the library is specific to the platform).
Prints the wheel's path.
"""

import argparse
import base64
import hashlib
import re
import sysconfig
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
NAME = "orient_imu"

METADATA = """Metadata-Version: 2.1
Name: orient-imu
Version: {version}
Summary: IMU/MARG orientation filters (Madgwick, Mahony, complementary, EKF, GMVDK, robust) with NumPy batch calls
License: MIT OR Apache-2.0
Requires-Python: >=3.9
Requires-Dist: numpy>=1.20
Provides-Extra: plot
Requires-Dist: matplotlib>=3.5; extra == "plot"

orient's filters over its C library (bundled): `import orient`. See the project README.
"""


def cargo_version() -> str:
    text = (ROOT / "Cargo.toml").read_text()
    return re.search(r'^version = "([^"]+)"', text, re.M).group(1)


def record_line(arcname: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{arcname},sha256={digest},{len(data)}"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--lib", required=True, type=Path, help="the built liborient shared library")
    ap.add_argument("--out", required=True, type=Path, help="directory for the wheel")
    args = ap.parse_args()
    version = cargo_version()
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    tag = f"py3-none-{platform}"
    dist_info = f"{NAME}-{version}.dist-info"
    files = {}
    for path in sorted((HERE / "orient").iterdir()):
        if path.suffix in (".py", ".typed"):
            files[f"orient/{path.name}"] = path.read_bytes()
    lib_name = {".dylib": "liborient.dylib", ".dll": "orient.dll"}.get(args.lib.suffix, "liborient.so")
    files[f"orient/{lib_name}"] = args.lib.read_bytes()
    files[f"{dist_info}/METADATA"] = METADATA.format(version=version).encode()
    files[f"{dist_info}/WHEEL"] = (
        f"Wheel-Version: 1.0\nGenerator: orient build_wheel.py\nRoot-Is-Purelib: false\nTag: {tag}\n"
    ).encode()
    records = [record_line(name, data) for name, data in files.items()]
    records.append(f"{dist_info}/RECORD,,")
    files[f"{dist_info}/RECORD"] = ("\n".join(records) + "\n").encode()
    args.out.mkdir(parents=True, exist_ok=True)
    wheel = args.out / f"{NAME}-{version}-{tag}.whl"
    with zipfile.ZipFile(wheel, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.external_attr = (0o755 if name.endswith((".so", ".dylib", ".dll")) else 0o644) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    print(wheel)


if __name__ == "__main__":
    main()
