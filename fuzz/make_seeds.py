#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Writes the seed corpus fuzz/corpus/<format>/ (small valid files in every supported spelling).
Crashers found by fuzzing are added next to them by hand (named crash-<sha1>). Run from fuzz/."""
import os
import struct

V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]


def put(d, name, data):
    os.makedirs(f"corpus/{d}", exist_ok=True)
    open(f"corpus/{d}/{name}", "wb").write(data.encode() if isinstance(data, str) else data)


def stl_ascii():
    s = "solid t\n"
    for f in F:
        s += "facet normal 0 0 0\n outer loop\n"
        for i in f:
            s += "  vertex %g %g %g\n" % V[i]
        s += " endloop\nendfacet\n"
    return s + "endsolid t\n"


def stl_binary(header=b"bin"):
    out = header.ljust(80, b" ") + struct.pack("<I", len(F))
    for f in F:
        out += struct.pack("<3f", 0, 0, 0)
        for i in f:
            out += struct.pack("<3f", *V[i])
        out += b"\0\0"
    return out


def ply(fmt, extras=False, strips=False):
    e = ">" if fmt == "binary_big_endian" else "<"
    h = f"ply\nformat {fmt} 1.0\ncomment seed\n"
    if extras:
        h += "element material 1\nproperty list uchar float rgb\n"
    h += "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    if extras:
        h += "property list uchar int n\nproperty double q\n"
    if strips:
        h += "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
    else:
        h += "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    body = b""
    txt = ""
    if extras:
        body += struct.pack(e + "B3f", 3, .1, .2, .3)
        txt += "3 0.1 0.2 0.3\n"
    for v in V:
        body += struct.pack(e + "3f", *v)
        txt += "%g %g %g" % v
        if extras:
            body += struct.pack(e + "BiId"[0:1] + "ii" + "d", 2, 1, 2, .5)
            txt += " 2 1 2 0.5"
        txt += "\n"
    if strips:
        strip = [0, 2, 1, 3, -1, 0, 3, 2, 1, 0]
        body += struct.pack(e + "i", len(strip)) + struct.pack(e + "%di" % len(strip), *strip)
        txt += " ".join(map(str, [len(strip)] + strip)) + "\n"
    else:
        for f in F:
            body += struct.pack(e + "B3i", 3, *f)
            txt += "3 %d %d %d\n" % f
    return h.encode() + (txt.encode() if fmt == "ascii" else body)


def obj():
    s = "# seed\no t\ng g1\n" + "".join("v %g %g %g\n" % v for v in V) + "vt 0 0\nvn 0 0 1\n"
    s += "f 1/1/1 3/1/1 2/1/1\nf 1//1 2//1 4//1\nf 2/1 3/1 \\\n 4/1\nf -4 -1 -2 # c\n"
    return s


def off(kw="OFF", extras=False):
    s = "# seed\n%s\n%d %d 0\n" % (kw, len(V), len(F))
    s += "".join(("%g %g %g" % v) + (" 0.5 0.5 0.5 1" if extras else "") + "\n" for v in V)
    s += "".join(("3 %d %d %d" % f) + (" 1 0 0" if extras else "") + "\n" for f in F)
    return s


def off_binary():
    out = b"OFF BINARY\n" + struct.pack(">3i", len(V), len(F), 0)
    out += b"".join(struct.pack(">3f", *v) for v in V)
    out += b"".join(struct.pack(">4i", 3, *f) + struct.pack(">i", 1) + struct.pack(">f", .5) for f in F)
    return out


def vtk(binary=False, v51=False, strips=False):
    s = b"# vtk DataFile Version 3.0\nseed\n" + (b"BINARY\n" if binary else b"ASCII\n")
    s += b"DATASET POLYDATA\nPOINTS 4 float\n"
    if binary:
        s += b"".join(struct.pack(">3f", *v) for v in V) + b"\n"
    else:
        s += "".join("%g %g %g\n" % v for v in V).encode()
    cells = [[0, 2, 1, 3], [1, 0, 3, 2]] if strips else [list(f) for f in F]
    kw = b"TRIANGLE_STRIPS" if strips else b"POLYGONS"
    if v51:
        offs = [0]
        for c in cells:
            offs.append(offs[-1] + len(c))
        conn = [i for c in cells for i in c]
        s += kw + b" %d %d\nOFFSETS vtktypeint64\n" % (len(offs), len(conn))
        s += (struct.pack(">%dq" % len(offs), *offs) + b"\n") if binary else (" ".join(map(str, offs)) + "\n").encode()
        s += b"CONNECTIVITY vtktypeint64\n"
        s += (struct.pack(">%dq" % len(conn), *conn) + b"\n") if binary else (" ".join(map(str, conn)) + "\n").encode()
    else:
        s += kw + b" %d %d\n" % (len(cells), sum(len(c) + 1 for c in cells))
        for c in cells:
            s += struct.pack(">%di" % (len(c) + 1), len(c), *c) if binary else (" ".join(map(str, [len(c)] + c)) + "\n").encode()
    return s + b"POINT_DATA 4\n"


put("stl", "ascii.stl", stl_ascii())
put("stl", "ascii_crlf.stl", stl_ascii().replace("\n", "\r\n"))
put("stl", "binary.stl", stl_binary())
put("stl", "binary_solid_header.stl", stl_binary(b"solid looks like text"))
for fmt in ["ascii", "binary_little_endian", "binary_big_endian"]:
    put("ply", f"{fmt}.ply", ply(fmt))
    put("ply", f"{fmt}_extras.ply", ply(fmt, extras=True))
    put("ply", f"{fmt}_strips.ply", ply(fmt, strips=True))
put("obj", "tet.obj", obj())
for b in [False, True]:
    for v51 in [False, True]:
        for st in [False, True]:
            put("vtk", f"{'bin' if b else 'ascii'}{'_51' if v51 else ''}{'_strips' if st else ''}.vtk", vtk(b, v51, st))
put("mesh", "ascii.stl", stl_ascii())
put("mesh", "binary.stl", stl_binary())
put("mesh", "extras.ply", ply("binary_little_endian", extras=True))
put("mesh", "tet.obj", obj())
put("mesh", "bin.vtk", vtk(True))
put("off", "tet.off", off())
put("off", "colours.off", off("COFF", extras=True))
put("off", "binary.off", off_binary())
put("mesh", "tet.off", off())
put("mesh", "binary.off", off_binary())
