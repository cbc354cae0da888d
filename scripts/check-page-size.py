#!/usr/bin/env python3
"""Checks that shared libraries load on kernels with 16 KB pages: every PT_LOAD segment's
p_align, read from the ELF program headers, must be at least 16384. Android 15 devices
may run 16 KB pages and app stores require it of apps targeting them; aarch64 Linux
kernels with 16 KB or 64 KB pages exist too.

    scripts/check-page-size.py [--min BYTES] LIB.so...   exits 1 if any is below
    scripts/check-page-size.py --report LIB.so...        prints, never fails

Standard library only (no readelf needed). Prints one line per library.
"""
import argparse
import struct
import sys

PT_LOAD = 1


def load_aligns(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x7fELF":
        raise ValueError("not an ELF file")
    is64 = data[4] == 2
    end = "<" if data[5] == 1 else ">"
    if is64:
        phoff, = struct.unpack_from(end + "Q", data, 0x20)
        phentsize, phnum = struct.unpack_from(end + "HH", data, 0x36)
    else:
        phoff, = struct.unpack_from(end + "I", data, 0x1C)
        phentsize, phnum = struct.unpack_from(end + "HH", data, 0x2A)
    machine, = struct.unpack_from(end + "H", data, 0x12)
    aligns = []
    for i in range(phnum):
        off = phoff + i * phentsize
        p_type, = struct.unpack_from(end + "I", data, off)
        if p_type != PT_LOAD:
            continue
        # Elf64_Phdr: p_align is the last of 8 fields (offset 48); Elf32_Phdr: offset 28.
        p_align, = struct.unpack_from(end + ("Q" if is64 else "I"), data, off + (48 if is64 else 28))
        aligns.append(p_align)
    return machine, aligns


MACHINES = {3: "x86", 40: "arm", 62: "x86_64", 183: "aarch64"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--min", type=int, default=16384)
    ap.add_argument("--report", action="store_true", help="print only; never fail")
    ap.add_argument("libs", nargs="+")
    args = ap.parse_args()
    bad = 0
    for path in args.libs:
        machine, aligns = load_aligns(path)
        ok = bool(aligns) and min(aligns) >= args.min
        verdict = "ok  " if ok else ("note" if args.report else "FAIL")
        print("%s %s (%s): %d LOAD segments, p_align %s" % (
            verdict, path, MACHINES.get(machine, machine), len(aligns), sorted(set(aligns))))
        bad += not ok
    if bad and not args.report:
        print("%d librar%s not aligned to %d bytes" % (bad, "y" if bad == 1 else "ies", args.min))
        sys.exit(1)


if __name__ == "__main__":
    main()
