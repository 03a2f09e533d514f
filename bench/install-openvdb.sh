#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Installs Debian 12's OpenVDB (libopenvdb-dev, with TBB, Blosc and Boost) for the OpenVDB peer of
# bench/grid_bench.cpp (meshToVolume), only when it is missing. Idempotent.
# Usage: sh bench/install-openvdb.sh   (as root, or with sudo available)
set -e
pkg=libopenvdb-dev
dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && SUDO=sudo
echo "installing: $pkg" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $pkg >/dev/null
