#!/usr/bin/env python3
"""Generates the C# P/Invoke layer (bindings/csharp/Orient.Native.cs) from the cbindgen
header (include/orient.h), so the C# declarations cannot drift from the C ABI.

    scripts/gen-csharp.py                 rewrites bindings/csharp/Orient.Native.cs
    scripts/gen-csharp.py --stdout        prints it instead
    scripts/gen-csharp.py HEADER OUT      reads and writes other paths (OUT "-": stdout)

What comes out, one to one with the header: every `#define ORIENT_*` as a constant of
`Consts` (camel-cased: ORIENT_PARAM_MAHONY_KP -> Consts.ParamMahonyKp); every enum as an
`enum : int` without the ORIENT_<ENUM>_ prefix (ORIENT_STATUS_OK -> Status.Ok); every
struct as a `[StructLayout(LayoutKind.Sequential)] partial struct` with the C field types
(fixed buffers for arrays, IntPtr for strings the library owns); every function as a
Cdecl `[DllImport]` whose pointer parameters are C# pointers (`T*`), opaque handles IntPtr.
Unity rules: blittable types only (a C `bool` is refused: IL2CPP cannot pass it without
marshalling), no delegates, `__Internal` where the player links the static library.

Python 3 standard library only; it reads the header as cbindgen 0.29 writes it and
stops with an error on anything it does not know, rather than guessing.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCALARS = {
    "double": "double", "float": "float",
    "int8_t": "sbyte", "uint8_t": "byte", "int16_t": "short", "uint16_t": "ushort",
    "int32_t": "int", "uint32_t": "uint", "int64_t": "long", "uint64_t": "ulong",
    "size_t": "UIntPtr", "uintptr_t": "UIntPtr", "intptr_t": "IntPtr", "char": "byte",
}
ENUM_BASE = {"int32_t": "int", "uint32_t": "uint", "int16_t": "short", "uint16_t": "ushort",
             "int8_t": "sbyte", "uint8_t": "byte", "int64_t": "long", "uint64_t": "ulong"}
KEYWORDS = set("""abstract as base bool break byte case catch char checked class const continue
decimal default delegate do double else enum event explicit extern false finally fixed float
for foreach goto if implicit in int interface internal is lock long namespace new null object
operator out override params private protected public readonly ref return sbyte sealed short
sizeof stackalloc static string struct switch this throw true try typeof uint ulong unchecked
unsafe ushort using virtual void volatile while""".split())


class HeaderError(Exception):
    pass


def camel(snake):
    """struct_size -> StructSize, PARAM_MAHONY_KP -> ParamMahonyKp."""
    return "".join(w[:1].upper() + w[1:].lower() for w in snake.split("_") if w)


def lower_camel(snake):
    c = camel(snake)
    name = c[:1].lower() + c[1:]
    return "@" + name if name in KEYWORDS else name


def screaming(pascal):
    """ParamFlag -> PARAM_FLAG."""
    return re.sub(r"(?<!^)(?=[A-Z])", "_", pascal).upper()


def cs_name(c_type):
    if not c_type.startswith("Orient"):
        raise HeaderError("type %s does not start with Orient" % c_type)
    return c_type[len("Orient"):]


class Header:
    def __init__(self):
        self.defines = []    # (name, value, doc)
        self.enums = []      # (c_name, base, [(member, value, doc)], doc)
        self.structs = []    # (c_name, [(c_type, name, array, doc)], doc)
        self.opaque = set()
        self.functions = []  # (ret, name, [(c_type, name)], doc)


def doc_lines(block):
    """The text of a /** ... */ block, one entry per line."""
    body = block.strip()[3:-2]
    lines = []
    for line in body.splitlines():
        line = line.strip()
        if line.startswith("*"):
            line = line[1:]
            if line.startswith(" "):
                line = line[1:]
        lines.append(line.rstrip())
    while lines and not lines[0]:
        lines.pop(0)
    while lines and not lines[-1]:
        lines.pop()
    return lines


def parse(text):
    h = Header()
    lines = text.splitlines()
    i = 0
    doc = []
    in_extern = False

    def comment_block(start):
        """Index after the comment starting at lines[start], and its text."""
        j = start
        while "*/" not in lines[j]:
            j += 1
            if j >= len(lines):
                raise HeaderError("unterminated comment at line %d" % (start + 1))
        return j + 1, "\n".join(lines[start:j + 1])

    def body(start, done):
        """The lines of a { } body from lines[start] to the first one done() accepts:
        [(index, stripped line, the doc comment before it)], and that last index."""
        j, items, item_doc = start, [], []
        while not done(lines[j]):
            t = lines[j].strip()
            if t.startswith("/**"):
                j, block = comment_block(j)
                item_doc = doc_lines(block)
                continue
            items.append((j, t, item_doc))
            item_doc = []
            j += 1
        return items, j

    while i < len(lines):
        line = lines[i]
        s = line.strip()
        where = "include/orient.h:%d: %s" % (i + 1, s)
        if not s:
            i += 1
        elif s.startswith("/**"):
            i, block = comment_block(i)
            doc = doc_lines(block)
        elif s.startswith("/*"):
            i, _ = comment_block(i)
            doc = []
        elif s.startswith("#define "):
            parts = s.split(None, 2)
            if len(parts) == 3 and parts[1].startswith("ORIENT_"):
                h.defines.append((parts[1], parts[2], doc))
            elif len(parts) != 2:
                raise HeaderError("unhandled #define: " + where)
            doc = []
            i += 1
        elif s.startswith("#"):
            i += 1  # include guard, includes, __cplusplus blocks
        elif s.startswith("typedef struct ") and s.endswith(";") and "{" not in s:
            m = re.fullmatch(r"typedef struct (Orient\w+) (\1);", s)
            if not m:
                raise HeaderError("unhandled typedef: " + where)
            h.opaque.add(m.group(1))
            doc = []
            i += 1
        elif re.fullmatch(r"typedef \w+ (Orient\w+);", s):
            name = re.fullmatch(r"typedef \w+ (Orient\w+);", s).group(1)
            if name not in [e[0] for e in h.enums]:
                raise HeaderError("typedef of something that is not an enum: " + where)
            i += 1  # C's `typedef int32_t OrientStatus;` for an enum
        elif s.startswith("typedef enum "):
            i += 1  # C23's `typedef enum OrientStatus OrientStatus;`
        elif re.fullmatch(r"enum Orient\w+", s):
            name, base, members = s.split()[1], None, []
            enum_doc, doc = doc, []
            items, i = body(i + 1, lambda l: l.strip() == "};")
            for j, t, item_doc in items:
                m = re.fullmatch(r": (\w+)", t)
                if m:
                    if m.group(1) not in ENUM_BASE:
                        raise HeaderError("enum base %s: include/orient.h:%d" % (m.group(1), j + 1))
                    base = ENUM_BASE[m.group(1)]
                elif re.fullmatch(r"(ORIENT_\w+) = (-?\d+),", t):
                    member, value = re.fullmatch(r"(ORIENT_\w+) = (-?\d+),", t).groups()
                    members.append((member, value, item_doc))
                elif not (t.startswith("#") or t in ("{", "")):
                    raise HeaderError("unhandled enum line: include/orient.h:%d: %s" % (j + 1, t))
            if base is None:
                raise HeaderError("enum %s has no fixed underlying type (give it #[repr(i32)])" % name)
            h.enums.append((name, base, members, enum_doc))
            i += 1
        elif re.fullmatch(r"typedef struct Orient\w+ \{", s):
            name = s.split()[2]
            struct_doc, doc, fields = doc, [], []
            items, i = body(i + 1, lambda l: l.startswith("}"))
            for j, t, item_doc in items:
                m = re.fullmatch(r"(.+?)\s*\b(\w+)(?:\[(\w+)\])?;", t)
                if not m:
                    raise HeaderError("unhandled struct field: include/orient.h:%d: %s" % (j + 1, t))
                fields.append((m.group(1), m.group(2), m.group(3), item_doc))
            if lines[i].strip() != "} %s;" % name:
                raise HeaderError("struct %s ends with %r" % (name, lines[i]))
            h.structs.append((name, fields, struct_doc))
            i += 1
        elif s == 'extern "C" {':
            in_extern = True
            i += 1
        elif s.startswith("}") and "extern" in s:
            in_extern = False
            i += 1
        elif in_extern:
            start = i
            decl = s
            while not decl.endswith(";"):
                i += 1
                decl += " " + lines[i].strip()
            m = re.fullmatch(r"(.+?)\b(orient_\w+)\((.*)\);", decl)
            if not m:
                raise HeaderError("unhandled declaration: include/orient.h:%d: %s" % (start + 1, decl))
            params = []
            if m.group(3).strip() != "void":
                for p in m.group(3).split(","):
                    pm = re.fullmatch(r"(.+?)\s*\b(\w+)", p.strip())
                    if not pm:
                        raise HeaderError("unhandled parameter %r of %s" % (p, m.group(2)))
                    params.append((pm.group(1), pm.group(2)))
            h.functions.append((m.group(1).strip(), m.group(2), params, doc))
            doc = []
            i += 1
        else:
            raise HeaderError("unhandled line: " + where)
    return h


def cs_type(c_type, h, where, role):
    """The C# type of a C type; role is "param", "return" or "field"."""
    t = re.sub(r"\bconst\b|\bstruct\b", " ", c_type)
    stars = t.count("*")
    base = t.replace("*", " ").split()
    if len(base) != 1:
        raise HeaderError("%s: cannot map type %r" % (where, c_type))
    base = base[0]
    if base == "bool":
        raise HeaderError("%s: C bool is not blittable under IL2CPP; use uint8_t or int32_t" % where)
    if base in h.opaque:
        if stars == 0:
            raise HeaderError("%s: opaque %s by value" % (where, base))
        return "IntPtr" + "*" * (stars - 1)
    if base == "char" and stars == 1 and role in ("return", "field"):
        return "IntPtr"  # a NUL-terminated string the library owns: Marshal.PtrToStringAnsi
    if base == "void":
        return "void" + "*" * stars
    if base in SCALARS:
        name = SCALARS[base]
    elif base in [e[0] for e in h.enums] or base in [s[0] for s in h.structs]:
        name = cs_name(base)
    else:
        raise HeaderError("%s: unknown type %r" % (where, c_type))
    if stars and role == "field":
        return "IntPtr"
    return name + "*" * stars


def summary(doc, indent):
    if not doc:
        return []
    esc = [l.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;") for l in doc]
    pad = " " * indent
    return [pad + "/// <summary>"] + [(pad + "/// " + l).rstrip() for l in esc] + [pad + "/// </summary>"]


def const_decl(name, value, where):
    v = value.strip()
    m = re.fullmatch(r"(0x[0-9A-Fa-f]+|\d+)[uU]?", v)
    if m:
        return "public const uint %s = %s;" % (camel(name[len("ORIENT_"):]), m.group(1))
    if re.fullmatch(r"-\d+", v):
        return "public const int %s = %s;" % (camel(name[len("ORIENT_"):]), v)
    if re.fullmatch(r"-?\d+\.\d*(?:[eE][-+]?\d+)?", v):
        return "public const double %s = %s;" % (camel(name[len("ORIENT_"):]), v)
    if re.fullmatch(r'"[^"\\]*"', v):
        return "public const string %s = %s;" % (camel(name[len("ORIENT_"):]), v)
    raise HeaderError("%s: cannot map the value %r" % (where, value))


PREAMBLE = """\
// <auto-generated>
// Orient.Native.cs: the P/Invoke layer, generated from include/orient.h by
// scripts/gen-csharp.py. Do not edit: regenerate with scripts/gen-csharp.py;
// scripts/check-csharp.sh (run by scripts/test-all.sh and cargo test) fails when this
// file differs from what the header gives. The idiomatic layer is Orient.cs.
//
// One to one with the header: the #define constants (Consts), the enums (enum : int),
// the structs (sequential layout, the C field types, fixed buffers for arrays, IntPtr for
// the library's static strings) and the functions (Cdecl; pointer parameters are C#
// pointers, the OrientFilter handle is IntPtr). Structs are partial: Orient.cs adds
// constructors.
//
// IL2CPP-safe: blittable types only (no bool, no managed arrays or strings), no
// callbacks, and `__Internal` as the library where the player links the static library.
// </auto-generated>
using System;
using System.Runtime.InteropServices;

namespace Orient.Native
{"""

LIBRARY = """\
        // iOS and Android players link the static liborient.a into the app (IL2CPP on
        // Android: the Mono backend cannot use a static library), and Unity names code
        // linked into its own binary "__Internal". Everywhere else (the Editor, Windows,
        // macOS, Linux) the shared library is loaded by name: orient.dll, liborient.dylib,
        // liborient.so.
#if (UNITY_IOS || UNITY_ANDROID || UNITY_WEBGL) && !UNITY_EDITOR
        public const string Library = "__Internal";
#else
        public const string Library = "orient";
#endif"""


def generate(h):
    out = [PREAMBLE]
    for name, base, members, doc in h.enums:
        prefix = "ORIENT_" + screaming(cs_name(name)) + "_"
        out += summary(doc or [name + "."], 4)
        out.append("    public enum %s : %s" % (cs_name(name), base))
        out.append("    {")
        for member, value, mdoc in members:
            if not member.startswith(prefix):
                raise HeaderError("%s: member %s lacks the prefix %s" % (name, member, prefix))
            out += summary(mdoc, 8)
            out.append("        %s = %s," % (camel(member[len(prefix):]), value))
        out.append("    }")
        out.append("")
    out += summary(["The header's #define constants."], 4)
    out.append("    public static class Consts")
    out.append("    {")
    for idx, (name, value, doc) in enumerate(h.defines):
        if idx:
            out.append("")
        out += summary(doc, 8)
        out.append("        " + const_decl(name, value, name))
    out.append("    }")
    for name, fields, doc in h.structs:
        out.append("")
        out += summary(doc or [name + "."], 4)
        out.append("    [StructLayout(LayoutKind.Sequential)]")
        fixed = any(f[2] for f in fields)
        out.append("    public %spartial struct %s" % ("unsafe " if fixed else "", cs_name(name)))
        out.append("    {")
        for idx, (c_type, fname, array, fdoc) in enumerate(fields):
            where = "%s.%s" % (name, fname)
            if idx:
                out.append("")
            out += summary(fdoc, 8)
            t = cs_type(c_type, h, where, "field")
            if array:
                size = array if array.isdigit() else dict((d[0], d[1]) for d in h.defines).get(array)
                if size is None or not size.isdigit():
                    raise HeaderError("%s: array size %s is not a number" % (where, array))
                if t not in ("double", "float", "byte", "sbyte", "short", "ushort", "int", "uint", "long", "ulong"):
                    raise HeaderError("%s: C# fixed buffers hold primitive types only, not %s" % (where, t))
                out.append("        public fixed %s %s[%s];" % (t, camel(fname), size))
            else:
                out.append("        public %s %s;" % (t, camel(fname)))
        out.append("    }")
    out.append("")
    out += summary(["The C functions, one to one. Pointer parameters are C# pointers (pass",
                    "`&local`, or a `fixed` array); handles are IntPtr (Orient.cs keeps them in a",
                    "SafeHandle)."], 4)
    out.append("    public static unsafe class NativeMethods")
    out.append("    {")
    out.append(LIBRARY)
    for ret, name, params, doc in h.functions:
        out.append("")
        out += summary(doc, 8)
        args = ", ".join("%s %s" % (cs_type(t, h, "%s(%s)" % (name, p), "param"), lower_camel(p))
                         for t, p in params)
        out.append("        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]")
        out.append("        public static extern %s %s(%s);" % (cs_type(ret, h, name, "return"), name, args))
    out.append("    }")
    out.append("}")
    return "\n".join(out) + "\n"


def main(argv):
    header = os.path.join(ROOT, "include/orient.h")
    target = os.path.join(ROOT, "bindings/csharp/Orient.Native.cs")
    if argv == ["--stdout"]:
        target = "-"
    elif len(argv) == 2:
        header, target = argv
    elif argv:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(header, encoding="utf-8") as f:
            text = generate(parse(f.read()))
    except HeaderError as e:
        print("gen-csharp.py: %s" % e, file=sys.stderr)
        return 1
    if target == "-":
        sys.stdout.write(text)
    else:
        with open(target, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
