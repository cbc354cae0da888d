"""The ctypes layer matches include/orient.h: it is what scripts/gen-python.py makes from
the header, and, read independently of the generator, its constants, enums, struct
fields in order and the argument count of every bound function are the header's."""

import ctypes
import os
import re
import subprocess
import sys
from pathlib import Path

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


def _generate(root, header_text, tmp_path):
    """scripts/gen-python.py on `header_text`: its exit status, output and stderr."""
    header = tmp_path / "orient.h"
    header.write_text(header_text)
    run = subprocess.run(
        # The generator is a build-machine script: under qemu-user (an aarch64 wheel's
        # tests) the emulated interpreter cannot start itself again, the host's can.
        [os.environ.get("ORIENT_HOST_PYTHON", sys.executable), str(root / "scripts" / "gen-python.py"), str(header), "-"],
        capture_output=True,
        text=True,
    )
    return run.returncode, run.stdout, run.stderr


def test_the_installed_ctypes_layer_is_what_the_generator_makes_from_the_header(root, tmp_path):
    status, text, err = _generate(root, header(root), tmp_path)
    assert status == 0, err
    assert Path(n.__file__).read_text() == text, "_native.py is stale: run scripts/gen-python.py"


def test_the_generator_follows_header_additions(root, tmp_path):
    text = header(root)
    added = (
        text.replace("#define ORIENT_MAX_PARAMS", "#define ORIENT_TEST_ADDED 77\n\n#define ORIENT_MAX_PARAMS", 1)
        .replace("  double z;\n} OrientVec3;", "  double z;\n  /**\n   * New.\n   */\n  uint8_t extra[4];\n} OrientVec3;", 1)
        .replace(
            "#ifdef __cplusplus\n}",
            "OrientStatus orient_test_added(const OrientFilter *filter, size_t n, double *out);\n\n#ifdef __cplusplus\n}",
            1,
        )
    )
    assert added != text
    status, out, err = _generate(root, added, tmp_path)
    assert status == 0, err
    for expected in [
        "TEST_ADDED = 77",
        '"orient_test_added": (c_int32, [c_void_p, c_size_t, POINTER(c_double)]),',
        "        # New.\n",
        '("extra", c_uint8 * 4),',
    ]:
        assert expected in out, expected


def test_the_generator_refuses_what_it_does_not_know(root, tmp_path):
    text = header(root)
    for old, new, message in [
        ("uint32_t orient_abi_version(void);", "wchar_t orient_abi_version(void);", "unknown type"),
        ("typedef struct OrientVec3 {", "typedef union OrientVec3 {", "unhandled"),
    ]:
        assert old in text
        status, _, err = _generate(root, text.replace(old, new, 1), tmp_path)
        assert status != 0 and message in err, (message, err)
