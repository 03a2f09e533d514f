#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Unpacks the fcpw snapshot from ../shared/peers (never copied into ebgeom) into build/peers and
# installs Eigen, which fcpw needs. Prints the directory to pass as -DEBGEOM_FCPW_DIR=...
# Usage: sh bench/fetch-fcpw.sh [PEERS_DIR=../shared/peers]
set -e
cd "$(dirname "$0")/.."
peers=${1:-../shared/peers}
tarball=$(ls "$peers"/fcpw-*.tar.gz 2>/dev/null | head -n 1)
[ -n "$tarball" ] || { echo "no fcpw-*.tar.gz in $peers" >&2; exit 1; }
sh scripts/install-deps.sh libeigen3-dev
mkdir -p build/peers
name=$(basename "$tarball" .tar.gz)
[ -d "build/peers/$name" ] || tar -xzf "$tarball" -C build/peers
echo "$(pwd)/build/peers/$name"
