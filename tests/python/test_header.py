"""The ctypes layer matches include/orient.h: constants, enums, struct fields in order,
and the argument count of every bound function."""

import ctypes
import re

import orient
from orient import _native as n


def header(root):
    return (root / "include" / "orient.h").read_text()


def code_only(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return "\n".join(l.split("//")[0] for l in text.splitlines() if not l.lstrip().startswith("#"))


def test_constants_the_package_uses_have_the_header_values(root):
    defines = dict(re.findall(r"^#define ORIENT_(\w+) (\d+)$", header(root), re.M))
    used = {
        name: getattr(n, name) for name in dir(n) if re.fullmatch(r"(SAMPLE|FLAG|DIAG|UNCERTAINTY)_[A-Z_]+", name)
    }
    used.update(ABI_VERSION=n.ABI_VERSION, MAX_PARAMS=n.MAX_PARAMS)
    assert len(used) == 27  # issue 20: FLAG_SATURATED, FLAG_SAME_INSTANT, UNCERTAINTY_*
    for name, value in used.items():
        assert int(defines[name]) == value, name
    # Every flag and diagnostics bit of the header is here.
    for name in defines:
        if name.startswith(("SAMPLE_", "FLAG_", "DIAG_", "UNCERTAINTY_")):
            assert name in used, name


def test_enums_match_the_header_exactly(root):
    text = header(root)
    for enum_cls, prefix in [(n.Status, "STATUS"), (n.Kind, "KIND"), (n.Frame, "FRAME"), (n.Init, "INIT")]:
        members = dict(re.findall(rf"^\s+ORIENT_{prefix}_(\w+) = (\d+),$", text, re.M))
        assert members, prefix
        assert {m.name: m.value for m in enum_cls} == {k: int(v) for k, v in members.items()}, prefix


C_TYPES = {"double": ctypes.c_double, "uint32_t": ctypes.c_uint32, "int32_t": ctypes.c_int32}


def test_structs_match_the_header_field_by_field(root):
    text = code_only(header(root))
    structs = dict(re.findall(r"typedef struct (Orient\w+) \{(.*?)\} \1;", text, re.S))
    for name in ["OrientQuaternion", "OrientVec3", "OrientConfig", "OrientParamInfo", "OrientSample",
                 "OrientEuler", "OrientDiagnostics", "OrientUncertainty"]:
        fields = []
        for decl in structs[name].split(";"):
            decl = decl.strip()
            if decl:
                m = re.fullmatch(r"(?:const )?(?:struct )?([\w]+ ?\*?) ?(\w+)(?:\[(\w+)\])?", decl)
                assert m, decl
                fields.append(m.group(2))
        py = getattr(n, name)
        assert [f[0] for f in py._fields_] == fields, name
    assert ctypes.sizeof(n.OrientSample) == 88
    assert ctypes.sizeof(n.OrientConfig) == 1072
    assert [f[0] for f in n.OrientDiagnostics._fields_] == list(orient.DIAGNOSTICS_DTYPE.names)
    assert orient.DIAGNOSTICS_DTYPE.itemsize == ctypes.sizeof(n.OrientDiagnostics)


def test_every_bound_function_exists_in_the_header_with_its_argument_count(root):
    flat = " ".join(code_only(header(root)).split())
    decls = {}
    for piece in flat.split(";"):
        m = re.search(r"(orient_\w+)\((.*)\)\s*$", piece)
        if m:
            args = m.group(2).strip()
            decls[m.group(1)] = 0 if args in ("", "void") else len(args.split(","))
    assert len(decls) >= 33
    for name, (_, argtypes) in n.PROTOTYPES.items():
        assert decls.get(name) == len(argtypes), name
