#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Writes the malformed (and tolerated) mesh fixtures of tests/data/io and their manifest.

Each manifest line: <file> <expected ErrorCode name or ok> <line or -> <byte offset or ->.
Run from this folder: python3 make_fixtures.py (the outputs are committed)."""
import struct

TET = ("solid t\n facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n"
       "   vertex 1 0 0\n  endloop\n endfacet\n facet normal 0 -1 0\n  outer loop\n"
       "   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 0 1\n  endloop\n endfacet\n"
       " facet normal 1 1 1\n  outer loop\n   vertex 1 0 0\n   vertex 0 1 0\n   vertex 0 0 1\n"
       "  endloop\n endfacet\n facet normal -1 0 0\n  outer loop\n   vertex 0 0 0\n"
       "   vertex 0 0 1\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n")
TET_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
PLY_HEAD = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n")
PLY_VERTS = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
PLY_FACES = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"
VTK_HEAD = "# vtk DataFile Version 3.0\ntet\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\n"

manifest = []


def text(name, content, code, line="-", offset="-", crlf=False, bom=False):
    data = content.replace("\n", "\r\n") if crlf else content
    raw = data.encode()
    if bom:
        raw = b"\xef\xbb\xbf" + raw
    open(name, "wb").write(raw)
    manifest.append(f"{name} {code} {line} {offset}")


def binary(name, raw, code, offset="-"):
    open(name, "wb").write(raw)
    manifest.append(f"{name} {code} - {offset}")


def stl_binary(tris, header=b"binary", count=None, trailing=b""):
    out = header.ljust(80, b" ")[:80] + struct.pack("<I", len(tris) if count is None else count)
    for t in tris:
        out += struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0)
    return out + trailing


TRIS = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 0), (1, 0, 0), (0, 0, 1)),
        ((1, 0, 0), (0, 1, 0), (0, 0, 1)), ((0, 0, 0), (0, 0, 1), (0, 1, 0))]

# ---- tolerated inputs ----
text("stl_crlf.stl", TET, "ok", crlf=True)
text("stl_bom.stl", TET, "ok", bom=True)
text("stl_two_solids.stl", TET.replace("endsolid t\n", "endsolid t\nsolid second\n") + "", "truncated", 32)
text("stl_two_solids_ok.stl", TET[: TET.index(" facet normal 1 1 1")] + "endsolid t\nsolid u\n" +
     TET[TET.index(" facet normal 1 1 1"):], "ok")
text("obj_crlf_continuation.obj", "# tet\r\nv 0 0 0\r\nv 1 0 \\\r\n 0\r\nv 0 1 0 0.5 0.5 0.5\nv 0 0 1\n"
     "vt 0 0\nvn 0 0 1\nf 1 3 \\\n 2\ng part\nusemtl m\ns 1\nf 1/1 2/2 4/3\nf 2//1 3//1 4//1\no obj\n"
     "f -4 -1 -2 # comment\n", "ok")
text("ply_bom_crlf.ply", PLY_HEAD + PLY_VERTS + PLY_FACES, "ok", crlf=True, bom=True)
binary("stl_solid_header_binary.stl", stl_binary(TRIS, header=b"solid binary"), "ok")
binary("stl_trailing_bytes.stl", stl_binary(TRIS, trailing=b"\0" * 7), "ok")

# ---- STL ----
text("stl_truncated.stl", TET[: TET.index("   vertex 0 0 1\n  endloop")], "truncated", 13)
text("stl_nan.stl", TET.replace("vertex 0 0 1\n  endloop\n endfacet\n facet normal 1",
                                "vertex 0 nan 1\n  endloop\n endfacet\n facet normal 1"), "non_finite", 13)
text("stl_two_vertex_facet.stl", TET.replace("   vertex 0 1 0\n   vertex 1 0 0\n", "   vertex 0 1 0\n", 1),
     "degenerate", 6)
text("stl_bad_keyword.stl", TET.replace("outer loop", "outer lop", 1), "syntax", 3)
text("stl_bad_number.stl", TET.replace("vertex 0 1 0", "vertex 0 1.0.0 0", 1), "bad_number", 5)
binary("stl_huge_count.stl", stl_binary(TRIS, count=2**31) + b"\0" * 700, "size_mismatch", 80)
binary("stl_short_header.stl", b"\0" * 50, "truncated", 50)
nan = float("nan")
binary("stl_binary_nan.stl", stl_binary([TRIS[0], ((0, 0, 0), (1, nan, 0), (0, 0, 1))]), "non_finite",
       84 + 50 + 24)
binary("stl_zero_triangles.stl", stl_binary([]), "empty", 80)

# ---- OBJ ----
text("obj_zero_index.obj", TET_OBJ.replace("f 1 2 4", "f 1 0 4"), "bad_index", 6)
text("obj_out_of_range.obj", TET_OBJ.replace("f 2 3 4", "f 2 3 5"), "bad_index", 7)
text("obj_relative_out_of_range.obj", TET_OBJ.replace("f 2 3 4", "f -1 -2 -5"), "bad_index", 7)
text("obj_face_two.obj", TET_OBJ.replace("f 1 4 3", "f 1 4"), "degenerate", 8)
text("obj_inf.obj", TET_OBJ.replace("v 0 1 0", "v 0 inf 0"), "non_finite", 3)
text("obj_bad_number.obj", TET_OBJ.replace("v 0 0 1", "v 0 abc 1"), "bad_number", 4)
text("obj_missing_coordinate.obj", TET_OBJ.replace("v 1 0 0", "v 1 0"), "syntax", 2)
text("obj_no_faces.obj", "v 0 0 0\nv 1 0 0\n", "empty", 3)
text("obj_huge_index.obj", TET_OBJ.replace("f 1 2 4", "f 1 2 99999999999999999999999"), "bad_number", 6)
text("empty.obj", "", "empty", "-", 0)

# ---- PLY ----
text("ply_huge_count.ply", PLY_HEAD.replace("vertex 4", "vertex 1000000000000") + PLY_VERTS + PLY_FACES,
     "size_mismatch", 3)
text("ply_unknown_type.ply", PLY_HEAD.replace("float y", "float128 y") + PLY_VERTS + PLY_FACES,
     "unsupported", 5)
text("ply_duplicate_element.ply", PLY_HEAD.replace("element face 4", "element vertex 4") + PLY_VERTS,
     "syntax", 7)
text("ply_bad_magic.ply", "plx\n" + PLY_HEAD[4:] + PLY_VERTS + PLY_FACES, "bad_magic", 1)
text("ply_bad_index.ply", PLY_HEAD + PLY_VERTS + PLY_FACES.replace("3 1 2 3", "3 1 2 4"), "bad_index", 16)
text("ply_negative_index.ply", PLY_HEAD + PLY_VERTS + PLY_FACES.replace("3 1 2 3", "3 1 -2 3"),
     "bad_index", 16)
text("ply_face_two.ply", PLY_HEAD + PLY_VERTS + PLY_FACES.replace("3 0 1 3\n", "2 0 1\n"), "degenerate", 15)
text("ply_truncated.ply", PLY_HEAD + PLY_VERTS + PLY_FACES[:20], "truncated", 16)
text("ply_nan.ply", PLY_HEAD + PLY_VERTS.replace("0 1 0", "0 NaN 0") + PLY_FACES, "non_finite", 12)
text("ply_no_end_header.ply", PLY_HEAD.replace("end_header\n", ""), "truncated", 9)
text("ply_property_before_element.ply", "ply\nformat ascii 1.0\nproperty float x\n", "syntax", 3)
text("ply_no_z.ply", PLY_HEAD.replace("property float z\n", "") + PLY_VERTS + PLY_FACES, "syntax", 3)
ply_bin = (PLY_HEAD.replace("ascii", "binary_little_endian").encode() +
           struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1) +
           b"".join(struct.pack("<B3i", 3, *f) for f in [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]))
binary("ply_binary_ok.ply", ply_bin, "ok")
binary("ply_binary_truncated.ply", ply_bin[:-6], "truncated", len(ply_bin) - 8)
binary("ply_binary_bad_index.ply", ply_bin[:-4] + struct.pack("<i", 7), "bad_index", len(ply_bin) - 4)

# ---- VTK ----
text("vtk_structured_points.vtk", "# vtk DataFile Version 3.0\ngrid\nASCII\nDATASET STRUCTURED_POINTS\n"
     "DIMENSIONS 2 2 2\n", "unsupported", 4)
text("vtk_bad_index.vtk", VTK_HEAD + "POLYGONS 2 8\n3 0 1 2\n3 0 1 9\n", "bad_index", 9)
text("vtk_size_mismatch.vtk", VTK_HEAD + "POLYGONS 2 9\n3 0 1 2\n3 0 1 3\n", "size_mismatch", 7)
text("vtk_bad_magic.vtk", "# vtx DataFile Version 3.0\n", "bad_magic", 1)
text("vtk_huge_points.vtk", VTK_HEAD.replace("POINTS 4", "POINTS 4000000000"), "size_mismatch", 5)
text("vtk_unknown_section.vtk", VTK_HEAD + "POLYHEDRA 1 4\n", "syntax", 7)

# ---- OFF ----
OFF_VERTS = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
OFF_FACES = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"
TET_OFF = "OFF\n4 4 6\n" + OFF_VERTS + OFF_FACES  # lines: 1 OFF, 2 counts, 3-6 vertices, 7-10 faces
text("off_comments_bom_crlf.off", "# a tetrahedron\nOFF # keyword\n\n4 4 6 # counts\n# vertices\n" +
     OFF_VERTS + "\n" + OFF_FACES, "ok", crlf=True, bom=True)
text("off_colours.off", "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
     "0 0 1 9 9 9 255\n3 0 2 1 1 0 0\n3 0 1 3 0.5 0.5 0.5 1\n3 1 2 3\n3 0 3 2 7\n", "ok")
text("off_normals.off", "NOFF\n4 4 0\n0 0 0 0 0 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n" +
     OFF_FACES, "ok")
text("off_counts_on_keyword_line.off", "OFF 4 4\n" + OFF_VERTS + OFF_FACES, "ok")


def off_binary(verts, faces, counts=None):
    nv, nf = counts if counts else (len(verts), len(faces))
    out = b"OFF BINARY\n" + struct.pack(">3i", nv, nf, 0)
    for v in verts:
        out += struct.pack(">3f", *v)
    for f in faces:
        out += struct.pack(">i", len(f)) + struct.pack(">%di" % len(f), *f) + struct.pack(">i", 0)
    return out


OFF_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
OFF_F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
off_bin = off_binary(OFF_V, OFF_F)  # 11 header + 12 counts + 48 vertices + 4 faces of 20 bytes
binary("off_binary_ok.off", off_bin, "ok")
text("off_bad_magic.off", "OFX\n4 4 6\n" + OFF_VERTS + OFF_FACES, "bad_magic", 1)
text("off_4d.off", "4OFF\n4 4 6\n" + OFF_VERTS + OFF_FACES, "unsupported", 1)
text("off_no_counts.off", "OFF\n", "truncated", 2)
text("off_truncated_counts.off", "OFF\n4", "truncated", 2)
text("off_count_not_a_number.off", TET_OFF.replace("4 4 6", "four 4 6"), "bad_number", 2)
text("off_negative_count.off", TET_OFF.replace("4 4 6", "-4 4 6"), "bad_number", 2)
text("off_extra_count.off", TET_OFF.replace("4 4 6", "4 4 6 7"), "syntax", 2)
text("off_huge_vertex_count.off", TET_OFF.replace("4 4 6", "4000000000 4 6"), "size_mismatch", 2)
text("off_huge_face_count.off", TET_OFF.replace("4 4 6", "4 1099511627776 6"), "size_mismatch", 2)
text("off_count_overflow.off", TET_OFF.replace("4 4 6", "4 99999999999999999999999 6"), "bad_number", 2)
text("off_counts_lie.off", "OFF\n4 5 6\n" + OFF_VERTS.replace("0 ", "0.000 ") + OFF_FACES,
     "truncated", 11)
text("off_no_faces.off", TET_OFF.replace("4 4 6", "4 0 6"), "empty", 2)
text("off_nan.off", TET_OFF.replace("0 1 0", "0 nan 0"), "non_finite", 5)
text("off_overflow.off", TET_OFF.replace("0 1 0", "0 1e999 0"), "bad_number", 5)
text("off_missing_coordinate.off", TET_OFF.replace("1 0 0\n", "1 0\n"), "syntax", 4)
text("off_bad_index.off", TET_OFF.replace("3 1 2 3", "3 1 2 4"), "bad_index", 9)
text("off_negative_index.off", TET_OFF.replace("3 1 2 3", "3 1 -2 3"), "bad_index", 9)
text("off_index_not_a_number.off", TET_OFF.replace("3 1 2 3", "3 1 x 3"), "bad_number", 9)
text("off_face_two.off", TET_OFF.replace("3 0 1 3", "2 0 1"), "degenerate", 8)
text("off_face_huge_corner_count.off", TET_OFF.replace("3 0 1 3", "99999999999 0 1 3"),
     "size_mismatch", 8)
text("off_face_short.off", TET_OFF.replace("3 0 1 3", "4 0 1 3"), "syntax", 8)
binary("off_binary_nan.off", off_binary([OFF_V[0], OFF_V[1], (0, nan, 0), OFF_V[3]], OFF_F),
       "non_finite", 23 + 24)
binary("off_binary_bad_index.off", off_binary(OFF_V, OFF_F[:2] + [(1, 9, 3)] + OFF_F[3:]),
       "bad_index", 71 + 40 + 8)
binary("off_binary_truncated.off", off_bin[:-6], "truncated", 131)
binary("off_binary_huge_count.off", off_binary(OFF_V, OFF_F, counts=(2**31 - 1, 4)),
       "size_mismatch", 11)
binary("off_binary_header_only.off", b"OFF BINARY\n\0\0", "truncated", 13)
binary("off_binary_face_one.off", off_binary(OFF_V, OFF_F[:1] + [(0,)] + OFF_F[2:]), "degenerate",
       91)

binary("garbage.bin", bytes(range(7, 200)), "bad_magic", 0)

open("expected.txt", "w").write("\n".join(manifest) + "\n")
