#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Fails when a tracked source file lacks its SPDX licence line (the project is BSD-3-Clause,
# LICENSE at the root). Test fixtures and fuzz corpora are data, not source, and are skipped.
set -eu
cd "$(dirname "$0")/.."
missing=$(git ls-files | grep -E '(\.(hpp|cpp|h|H|cu|cuh|cmake|sh|py|pyi|in)$|(^|/)CMakeLists\.txt$|(^|/)GNUmakefile$|(^|/)Make\.package$|^\.ci/run$)' |
  grep -vE '^(tests/data/io/[^/]*\.(stl|ply|obj|vtk)|fuzz/corpus/)' |
  while read -r f; do head -n 5 "$f" | grep -q 'SPDX-License-Identifier: BSD-3-Clause' || echo "$f"; done)
if [ -n "$missing" ]; then
  echo "files without 'SPDX-License-Identifier: BSD-3-Clause' in their first 5 lines:" >&2
  echo "$missing" >&2
  exit 1
fi
echo "SPDX lines: all source files carry BSD-3-Clause"
