#!/usr/bin/env python3
"""Generates the Python ctypes layer (bindings/python/orient/_native.py) from the cbindgen
header (include/orient.h), so the Python declarations cannot drift from the C ABI.

    scripts/gen-python.py                 rewrites bindings/python/orient/_native.py
    scripts/gen-python.py --stdout        prints it instead
    scripts/gen-python.py HEADER OUT      reads and writes other paths (OUT "-": stdout)

What comes out, one to one with the header: every `#define ORIENT_*` as a module
constant without the ORIENT_ prefix (ORIENT_FLAG_GAP -> FLAG_GAP); every enum as an
`enum.IntEnum` named without Orient, its members without the ORIENT_<ENUM>_ prefix
(ORIENT_STATUS_OK -> Status.OK); every struct as a ctypes `Structure` of the same name
with the C field types; every function in PROTOTYPES as (restype, argtypes), which the
loader at the end sets on the library. Pointer parameters are typed: POINTER(T) for a
struct or number, c_char_p for a string, c_void_p for the opaque OrientFilter handle
(POINTER(c_void_p) for an array of handles or an out-handle). Enums cross as c_int32.
The header's documentation comes along as comments and docstrings; the functions' own
is in the header.

Python 3 standard library only. The header is read by scripts/gen-csharp.py's parser,
which stops with an error on anything it does not know rather than guessing.
"""
import importlib.util
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

_spec = importlib.util.spec_from_file_location("gen_csharp", os.path.join(ROOT, "scripts", "gen-csharp.py"))
gen_csharp = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(gen_csharp)
HeaderError = gen_csharp.HeaderError

SCALARS = {
    "double": "c_double", "float": "c_float", "bool": "c_bool", "char": "c_char",
    "int8_t": "c_int8", "uint8_t": "c_uint8", "int16_t": "c_int16", "uint16_t": "c_uint16",
    "int32_t": "c_int32", "uint32_t": "c_uint32", "int64_t": "c_int64", "uint64_t": "c_uint64",
    "size_t": "c_size_t", "uintptr_t": "c_size_t", "intptr_t": "c_ssize_t",
}
ENUM_BASE = {"int": "c_int32", "uint": "c_uint32", "short": "c_int16", "ushort": "c_uint16",
             "sbyte": "c_int8", "byte": "c_uint8", "long": "c_int64", "ulong": "c_uint64"}


def py_const(name):
    return name[len("ORIENT_"):]


def py_type(c_type, h, where, role, used):
    """The ctypes type of a C type; role is "param", "return" or "field". Adds the
    ctypes names it needs to `used`."""
    t = re.sub(r"\bconst\b|\bstruct\b", " ", c_type)
    stars = t.count("*")
    base = t.replace("*", " ").split()
    if len(base) != 1:
        raise HeaderError("%s: cannot map type %r" % (where, c_type))
    base = base[0]
    enums = {e[0]: e[1] for e in h.enums}
    if base in h.opaque:
        if stars == 0:
            raise HeaderError("%s: opaque %s by value" % (where, base))
        name = "c_void_p"
        stars -= 1
    elif base == "char" and stars == 1:
        name, stars = "c_char_p", 0  # a NUL-terminated string
    elif base == "void":
        if stars == 0:
            if role != "return":
                raise HeaderError("%s: void %s" % (where, role))
            return "None"
        name, stars = "c_void_p", stars - 1
    elif base in SCALARS:
        name = SCALARS[base]
    elif base in enums:
        name = ENUM_BASE[enums[base]]
    elif base in [s[0] for s in h.structs]:
        name = base
    else:
        raise HeaderError("%s: unknown type %r" % (where, c_type))
    if stars and role == "field":
        name, stars = "c_void_p", 0  # a pointer the library owns
    if name.startswith("c_"):
        used.add(name)
    for _ in range(stars):
        used.add("POINTER")
        name = "POINTER(%s)" % name
    return name


def comment(doc, indent, marker="#:"):
    pad = " " * indent
    return [(pad + marker + " " + line).rstrip() for line in doc]


def docstring(doc, indent):
    pad = " " * indent
    if not doc:
        return []
    text = [l.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') for l in doc]
    if len(text) == 1:
        return [pad + '"""%s"""' % text[0]]
    return [pad + '"""' + text[0]] + [(pad + l).rstrip() for l in text[1:]] + [pad + '"""']


def const_value(name, value):
    v = value.strip()
    m = re.fullmatch(r"(0x[0-9A-Fa-f]+|-?\d+)[uU]?", v)
    if m:
        return m.group(1)
    if re.fullmatch(r"-?\d+\.\d*(?:[eE][-+]?\d+)?", v) or re.fullmatch(r'"[^"\\]*"', v):
        return v
    raise HeaderError("%s: cannot map the value %r" % (name, value))


PREAMBLE = '''\
# Generated from include/orient.h by scripts/gen-python.py; do not edit. Regenerate with
# scripts/gen-python.py; scripts/check-python-native.sh (run by scripts/test-all.sh)
# fails when this file differs from what the header gives.
"""ctypes declarations of the C API in include/orient.h, and the loaded library.

One to one with the header: the #define constants (without ORIENT_), the enums
(IntEnum), the structs (ctypes Structures of the same names and fields) and the
functions (PROTOTYPES, set on the library when it is loaded). Parameter names, units,
defaults and ranges are read from the library at run time (orient_param_info). The
idiomatic layer is _filter.py.
"""

import ctypes
import enum
import os
import sys
from ctypes import %s
from pathlib import Path
'''

LOADER = '''

def _library_path() -> Path:
    """ORIENT_LIBRARY if set, else the library bundled beside this file."""
    override = os.environ.get("ORIENT_LIBRARY")
    if override:
        return Path(override)
    names = {"win32": "orient.dll", "darwin": "liborient.dylib"}
    return Path(__file__).with_name(names.get(sys.platform, "liborient.so"))


def _load() -> ctypes.CDLL:
    path = _library_path()
    lib = ctypes.CDLL(str(path))
    for name, (restype, argtypes) in PROTOTYPES.items():
        fn = getattr(lib, name)
        fn.restype = restype
        fn.argtypes = argtypes
    if lib.orient_abi_version() != ABI_VERSION:
        raise ImportError(
            f"{path}: C ABI version {lib.orient_abi_version()}, this package needs {ABI_VERSION}"
        )
    return lib


lib = _load()
'''


def generate(h):
    used = {"Structure"}
    body = []
    defines = {name: py_const(name) for name, _, _ in h.defines}
    body.append("")
    for idx, (name, value, doc) in enumerate(h.defines):
        if idx:
            body.append("")
        body += comment(doc, 0)
        body.append("%s = %s" % (py_const(name), const_value(name, value)))
    for name, base, members, doc in h.enums:
        short = gen_csharp.cs_name(name)
        prefix = "ORIENT_" + gen_csharp.screaming(short) + "_"
        body += ["", ""]
        body.append("class %s(enum.IntEnum):" % short)
        body += docstring(doc or [name + "."], 4)
        body.append("")
        for member, value, mdoc in members:
            if not member.startswith(prefix):
                raise HeaderError("%s: member %s lacks the prefix %s" % (name, member, prefix))
            body += comment(mdoc, 4)
            body.append("    %s = %s" % (member[len(prefix):], value))
    for name, fields, doc in h.structs:
        body += ["", ""]
        body.append("class %s(Structure):" % name)
        body += docstring(doc or [name + "."], 4)
        body.append("")
        body.append("    _fields_ = [")
        for c_type, fname, array, fdoc in fields:
            where = "%s.%s" % (name, fname)
            t = py_type(c_type, h, where, "field", used)
            if array:
                size = array if array.isdigit() else defines.get(array)
                if size is None:
                    raise HeaderError("%s: array size %s is not a number or a #define" % (where, array))
                t = "%s * %s" % (t, size)
            body += comment(fdoc, 8, "#")
            body.append('        ("%s", %s),' % (fname, t))
        body.append("    ]")
    body += ["", ""]
    body.append("#: Every function of the header: name -> (restype, argtypes).")
    body.append("PROTOTYPES = {")
    for ret, name, params, _ in h.functions:
        args = [py_type(t, h, "%s(%s)" % (name, p), "param", used) for t, p in params]
        restype = py_type(ret, h, name, "return", used)
        line = '    "%s": (%s, [%s]),' % (name, restype, ", ".join(args))
        if len(line) <= 100:
            body.append(line)
        else:
            body.append('    "%s": (' % name)
            body.append("        %s," % restype)
            body.append("        [")
            body += ["            %s," % a for a in args]
            body.append("        ],")
            body.append("    ),")
    body.append("}")
    imports = ", ".join(sorted(used, key=lambda s: (s != "POINTER", s != "Structure", s)))
    return PREAMBLE % imports + "\n".join(body) + "\n" + LOADER


def main(argv):
    header = os.path.join(ROOT, "include/orient.h")
    target = os.path.join(ROOT, "bindings/python/orient/_native.py")
    if argv == ["--stdout"]:
        target = "-"
    elif len(argv) == 2:
        header, target = argv
    elif argv:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(header, encoding="utf-8") as f:
            text = generate(gen_csharp.parse(f.read()))
    except HeaderError as e:
        print("gen-python.py: %s" % e, file=sys.stderr)
        return 1
    if target == "-":
        sys.stdout.write(text)
    else:
        with open(target, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
