#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Checks the include rules of the header-only library (docs/architecture.md).

Every `#include "ebgeom/..."` (or <ebgeom/...>) line in include/ebgeom must
  - name a header that exists;
  - point to the same module or to a module the including one may use (LAYERS below): the
    floors only point down, e.g. core/ includes nothing above core/, bvh/ never includes sdf/;
  - an umbrella header (include/ebgeom/<module>.hpp) follows its module's rule;
  - write the full path "ebgeom/<module>/<file>.hpp" (no relative includes);
and the headers must not include each other in a cycle. The library never includes a component
(scene/, jobs/: COMPONENTS below). A component's sources, and the Python module's (python/src),
include only "ebgeom/..." headers: the library's, their own, or those of the components below them
(jobs/ builds on scene/, never the reverse), never a tool's; a component's tests may also include
the shared test utilities (tests/support/).

Usage: check-includes.py [REPO_ROOT]   (default: the folder above this script)
       check-includes.py --self-test    (checks that the checker catches violations)
Exit status 0 when the tree follows the rules, 1 otherwise (one line per violation).
Needs any python3 and nothing else.
"""

import os
import re
import shutil
import sys
import tempfile

# Which modules each module may include (besides itself). Keep in step with
# docs/architecture.md. `version.hpp` at the top is a leaf that every module may include.
LAYERS = {
    "core": set(),
    "geom": {"core"},
    "mesh": {"core", "geom"},
    "bvh": {"core", "geom"},
    "octree": {"core"},
    "io": {"core", "geom", "mesh"},
    "sdf": {"core", "geom", "mesh", "bvh"},
    "eval": {"core", "geom", "mesh", "bvh", "octree", "io", "sdf"},
    "adapters": {"core", "geom", "mesh", "bvh", "octree", "io", "sdf", "eval"},
}
LEAVES = {"version.hpp"}  # top-level headers anyone may include, which include no ebgeom header
UMBRELLA = "ebgeom.hpp"  # the whole library: may include anything
# Forwarding headers left at a header's old path for one release: each holds exactly one include,
# its new path, whatever the layers say; no library header may include an old path.
FORWARDERS = {
    "eval/grid_blocks.hpp": "eval/grid_tiles.hpp",
    "mesh/dcel_distance.hpp": "sdf/dcel_distance.hpp",
    "mesh/point_in_polygon.hpp": "geom/point_in_polygon.hpp",
    "mesh/polygon_geometry.hpp": "geom/polygon_geometry.hpp",
}

INCLUDE_RE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


def module_of(rel):
    """Module of a header path relative to include/ebgeom ('sdf/mesh_sdf.hpp' -> 'sdf')."""
    parts = rel.split("/")
    if len(parts) == 1:
        if rel == UMBRELLA:
            return "*"
        if rel in LEAVES:
            return "leaf"
        return rel[:-4] if rel.endswith(".hpp") else rel  # umbrella of a module: 'bvh.hpp'
    return parts[0]


def check(root):
    """Returns the list of violations (strings) under root/include/ebgeom."""
    base = os.path.join(root, "include", "ebgeom")
    if not os.path.isdir(base):
        return ["%s: no include/ebgeom folder" % root]
    headers = {}
    for dirpath, _, files in os.walk(base):
        for f in files:
            if f.endswith((".hpp", ".h")):
                full = os.path.join(dirpath, f)
                headers[os.path.relpath(full, base).replace(os.sep, "/")] = full
    errors = []
    graph = {}
    for rel in sorted(headers):
        mod = module_of(rel)
        if rel in FORWARDERS:
            with open(headers[rel], encoding="utf-8", errors="replace") as fh:
                targets = [m.group(2) for m in map(INCLUDE_RE.match, fh) if m]
            if targets != ["ebgeom/" + FORWARDERS[rel]]:
                errors.append("include/ebgeom/%s: a forwarding header must include exactly "
                              "ebgeom/%s and nothing else" % (rel, FORWARDERS[rel]))
            graph[rel] = [FORWARDERS[rel]] if FORWARDERS[rel] in headers else []
            continue
        if mod not in LAYERS and mod not in ("*", "leaf"):
            errors.append("include/ebgeom/%s: module '%s' is not in the layer table of "
                          "scripts/check-includes.py (add it there and to docs/architecture.md)"
                          % (rel, mod))
            continue
        graph[rel] = []
        with open(headers[rel], encoding="utf-8", errors="replace") as fh:
            for lineno, line in enumerate(fh, 1):
                m = INCLUDE_RE.match(line)
                if not m:
                    continue
                target = m.group(2)
                where = "include/ebgeom/%s:%d" % (rel, lineno)
                if m.group(1) == '"' and not target.startswith("ebgeom/") and (
                        "/" in target or target.endswith((".hpp", ".h"))):
                    errors.append("%s: relative include \"%s\"; write \"ebgeom/...\"" %
                                  (where, target))
                    continue
                if not target.startswith("ebgeom/"):
                    continue  # a standard or system header
                trel = target[len("ebgeom/"):]
                if trel.split("/")[0] in COMPONENTS:
                    errors.append("%s: includes %s: the header-only library may not use the %s "
                                  "component (%s/)" % (where, target, trel.split("/")[0],
                                                       trel.split("/")[0]))
                    continue
                if trel not in headers:
                    errors.append("%s: includes %s, which does not exist" % (where, target))
                    continue
                graph[rel].append(trel)
                if trel in FORWARDERS:
                    errors.append("%s: includes the old path %s; include ebgeom/%s" %
                                  (where, target, FORWARDERS[trel]))
                    continue
                tmod = module_of(trel)
                if mod == "*" or tmod == "leaf":
                    if mod == "leaf":
                        errors.append("%s: %s must include no ebgeom header" % (where, rel))
                    continue
                if mod == "leaf":
                    errors.append("%s: %s must include no ebgeom header" % (where, rel))
                elif tmod == "*":
                    errors.append("%s: includes the whole-library umbrella %s" % (where, target))
                elif tmod != mod and tmod not in LAYERS[mod]:
                    allowed = ", ".join(sorted(LAYERS[mod] | {mod})) or mod
                    errors.append("%s: %s/ may not include %s (upward or sideways; %s/ may "
                                  "include %s)" % (where, mod, target, mod, allowed))
    # cycles between headers (depth-first search, colours: 0 new, 1 open, 2 done)
    colour = dict.fromkeys(graph, 0)
    for start in sorted(graph):
        if colour[start]:
            continue
        stack = [(start, iter(graph[start]))]
        path = [start]
        colour[start] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                colour[node] = 2
                stack.pop()
                path.pop()
            elif colour.get(nxt, 2) == 1:
                cyc = path[path.index(nxt):] + [nxt]
                errors.append("include cycle: " + " -> ".join(cyc))
            elif colour.get(nxt, 2) == 0:
                colour[nxt] = 1
                stack.append((nxt, iter(graph[nxt])))
                path.append(nxt)
    return errors + check_components(root, headers)


# The compiled components outside the header-only library, and the code that links them: the
# folders of each one's sources, and the components whose headers ("ebgeom/<name>/...", found in
# <name>/include) it may include besides the library's. Keep in step with docs/architecture.md.
COMPONENTS = {
    "scene": (("scene/include", "scene/src", "scene/tests"), {"scene"}),
    "jobs": (("jobs/include", "jobs/src", "jobs/tests"), {"scene", "jobs"}),
}
LINKERS = {
    "python": (("python/src",), {"scene", "jobs"}),
}


def check_components(root, headers):
    """The includes of the components and of the Python module (COMPONENTS, LINKERS)."""
    errors = []
    support = os.path.join(root, "tests", "support")
    for name, (dirs, may) in sorted(list(COMPONENTS.items()) + list(LINKERS.items())):
        what = ("the %s component" % name) if name in COMPONENTS else ("the %s module" % name)
        for top in dirs:
            for dirpath, _, files in os.walk(os.path.join(root, top)):
                for f in sorted(files):
                    if not f.endswith((".hpp", ".h", ".cpp")):
                        continue
                    full = os.path.join(dirpath, f)
                    rel = os.path.relpath(full, root).replace(os.sep, "/")
                    is_test = top.endswith("/tests")
                    with open(full, encoding="utf-8", errors="replace") as fh:
                        for lineno, line in enumerate(fh, 1):
                            m = INCLUDE_RE.match(line)
                            if not m or m.group(1) != '"':
                                continue
                            target = m.group(2)
                            where = "%s:%d" % (rel, lineno)
                            if not target.startswith("ebgeom/"):
                                if is_test and os.path.isfile(os.path.join(support, target)):
                                    continue  # a shared test utility (tests/support/)
                                if "/" in target or target.endswith((".hpp", ".h")):
                                    errors.append("%s: includes \"%s\"; %s includes only "
                                                  "\"ebgeom/...\" headers (the library's or a "
                                                  "component's), never a tool's" %
                                                  (where, target, what))
                                continue
                            trel = target[len("ebgeom/"):]
                            comp = trel.split("/")[0]
                            if comp in COMPONENTS:
                                if comp not in may:
                                    errors.append("%s: includes %s: %s may not use the %s "
                                                  "component (it may use %s)" %
                                                  (where, target, what, comp,
                                                   ", ".join(sorted(may))))
                                elif not os.path.isfile(os.path.join(root, comp, "include",
                                                                     target)):
                                    errors.append("%s: includes %s, which does not exist" %
                                                  (where, target))
                            elif trel not in headers:
                                errors.append("%s: includes %s, which does not exist" %
                                              (where, target))
    return errors


def self_test():
    """Small trees with one violation each must fail; the clean one and the real tree pass."""
    def tree(files):
        d = tempfile.mkdtemp(prefix="ebgeom-includes-")
        for rel, text in files.items():
            p = os.path.join(d, rel) if rel.split("/")[0] in (
                "scene", "jobs", "python", "tests") else os.path.join(d, "include", "ebgeom", rel)
            os.makedirs(os.path.dirname(p), exist_ok=True)
            with open(p, "w", encoding="utf-8") as fh:
                fh.write(text)
        return d

    inc = '#include "ebgeom/%s"\n'
    clean = {
        "version.hpp": "#pragma once\n",
        "mesh/dcel_distance.hpp": inc % "sdf/dcel_distance.hpp",
        "sdf/dcel_distance.hpp": inc % "core/vec.hpp",
        "core/vec.hpp": "#pragma once\n#include <cmath>\n" + inc % "version.hpp",
        "core.hpp": inc % "core/vec.hpp",
        "bvh/wide_bvh.hpp": inc % "core/vec.hpp",
        "bvh.hpp": inc % "bvh/wide_bvh.hpp",
        "sdf/mesh_sdf.hpp": inc % "bvh/wide_bvh.hpp" + inc % "core/vec.hpp",
        "sdf.hpp": inc % "sdf/mesh_sdf.hpp",
        "ebgeom.hpp": inc % "sdf.hpp" + inc % "bvh.hpp",
        "scene/include/ebgeom/scene/scene.hpp": inc % "sdf/mesh_sdf.hpp",
        "scene/src/scene.cpp": inc % "scene/scene.hpp",
        "jobs/include/ebgeom/jobs/npz.hpp": inc % "sdf/mesh_sdf.hpp",
        "jobs/include/ebgeom/jobs/sdf_job.hpp": inc % "scene/scene.hpp" + inc % "jobs/npz.hpp",
        "jobs/src/npz.cpp": inc % "jobs/npz.hpp",
        "jobs/tests/npz_test.cpp": inc % "jobs/npz.hpp" + '#include "zip_reader.hpp"\n',
        "tests/support/zip_reader.hpp": "#pragma once\n",
        "python/src/module.cpp": inc % "jobs/sdf_job.hpp" + inc % "scene/scene.hpp",
    }
    bad = {
        "upward include from core": {"core/vec.hpp": inc % "sdf/mesh_sdf.hpp"},
        "umbrella pointing up": {"bvh.hpp": inc % "bvh/wide_bvh.hpp" + inc % "sdf/mesh_sdf.hpp"},
        "sideways include": {"bvh/wide_bvh.hpp": inc % "octree/octree.hpp",
                             "octree/octree.hpp": inc % "core/vec.hpp"},
        "missing header": {"sdf/mesh_sdf.hpp": inc % "bvh/gone.hpp"},
        "relative include": {"sdf/mesh_sdf.hpp": '#include "../core/vec.hpp"\n'},
        "cycle inside a module": {"core/a.hpp": inc % "core/b.hpp", "core/b.hpp": inc % "core/a.hpp"},
        "unknown module": {"newthing/x.hpp": inc % "core/vec.hpp"},
        "leaf including": {"version.hpp": inc % "core/vec.hpp"},
        "forwarder with a second include": {
            "mesh/point_in_polygon.hpp": inc % "geom/point_in_polygon.hpp" + inc % "core/vec.hpp",
            "geom/point_in_polygon.hpp": inc % "core/vec.hpp"},
        "header including an old path": {
            "mesh/point_in_polygon.hpp": inc % "geom/point_in_polygon.hpp",
            "geom/point_in_polygon.hpp": inc % "core/vec.hpp",
            "sdf/mesh_sdf.hpp": inc % "mesh/point_in_polygon.hpp"},
        "library including the scene component": {"sdf/mesh_sdf.hpp": inc % "scene/scene.hpp"},
        "scene component including a tool header": {"scene/src/scene.cpp": '#include "common.hpp"\n'},
        "scene component including a missing header": {"scene/src/scene.cpp": inc % "scene/gone.hpp"},
        "library including the jobs component": {"sdf/mesh_sdf.hpp": inc % "jobs/npz.hpp"},
        "scene component including the jobs component": {
            "scene/src/scene.cpp": inc % "scene/scene.hpp" + inc % "jobs/npz.hpp"},
        "jobs component including a tool header": {"jobs/src/npz.cpp": '#include "common.hpp"\n'},
        "jobs component including a missing header": {"jobs/src/npz.cpp": inc % "jobs/gone.hpp"},
        "jobs test including a missing test utility": {
            "jobs/tests/npz_test.cpp": '#include "gone_reader.hpp"\n'},
        "Python module including a tool header": {
            "python/src/module.cpp": '#include "sdf_job.hpp"\n'},
    }
    failures = []
    d = tree(clean)
    if check(d):
        failures.append("clean tree reported: %s" % check(d))
    shutil.rmtree(d)
    for name, change in bad.items():
        files = dict(clean)
        files.update(change)
        d = tree(files)
        if not check(d):
            failures.append("not caught: " + name)
        shutil.rmtree(d)
    # the real tree passes, and fails once core/ includes a header of sdf/
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if os.path.isdir(os.path.join(here, "include", "ebgeom")):
        d = tempfile.mkdtemp(prefix="ebgeom-includes-")
        shutil.copytree(os.path.join(here, "include"), os.path.join(d, "include"))
        with open(os.path.join(d, "include", "ebgeom", "core", "vec.hpp"), "a") as fh:
            fh.write('#include "ebgeom/sdf/concepts.hpp"\n')
        if not any("core/ may not include ebgeom/sdf/concepts.hpp" in e for e in check(d)):
            failures.append("not caught: upward include added to the real core/vec.hpp")
        shutil.rmtree(d)
    for f in failures:
        print("self-test: " + f)
    print("check-includes self-test: %s" % ("FAILED" if failures else "ok (%d cases)" % (len(bad) + 2)))
    return 1 if failures else 0


def main(argv):
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    errors = check(root)
    for e in errors:
        print(e)
    if errors:
        print("check-includes: %d violation(s) of the include rules (docs/architecture.md)" %
              len(errors))
        return 1
    print("check-includes: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
