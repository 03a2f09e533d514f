#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Unpacks the EBGeometry snapshot from ../shared/peers (never copied into ebgeom; GPL-3.0) into
# build/peers. Prints the directory to pass as -DEBGEOM_EBGEOMETRY_DIR=...
# Usage: sh bench/fetch-ebgeometry.sh [PEERS_DIR=../shared/peers]
set -e
cd "$(dirname "$0")/.."
peers=${1:-../shared/peers}
tarball=$(ls "$peers"/EBGeometry-*.tar.gz 2>/dev/null | head -n 1)
[ -n "$tarball" ] || { echo "no EBGeometry-*.tar.gz in $peers" >&2; exit 1; }
mkdir -p build/peers
name=$(basename "$tarball" .tar.gz)
[ -d "build/peers/$name" ] || tar -xzf "$tarball" -C build/peers
echo "$(pwd)/build/peers/$name"
