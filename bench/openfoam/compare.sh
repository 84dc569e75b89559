#!/bin/bash
# Copyright (c) 2026 SpringMotion developers.
#
# SpringMotion's `spring-motion deform` next to OpenFOAM's moveDynamicMesh on
# the same Gmsh meshes (bench/openfoam/README.md). Installs Debian's openfoam
# package when it is missing, prints the machine state, then runs compare.py
# with the arguments given (--quick: 10 steps instead of 100; --cases 2d|3d;
# --bisect: also the largest completing amplitudes, slow; --help).
# Needs build/src/cli/spring-motion (cmake --build build --target spring-motion).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

if ! command -v moveDynamicMesh > /dev/null || ! command -v gmshToFoam > /dev/null; then
  apt-cache policy openfoam
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y openfoam
fi
if ! /usr/bin/python3 -c "import gmsh, numpy" 2> /dev/null; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y python3-gmsh python3-numpy
fi

# Debian's OpenFOAM (v1912) lives in /usr/bin and /usr/lib; its applications
# only need WM_PROJECT_DIR to find etc/controlDict. Sourcing its etc/bashrc
# would also work but complains about helper scripts Debian does not ship.
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
[ -f "$WM_PROJECT_DIR/etc/controlDict" ] || {
  echo "compare.sh: no $WM_PROJECT_DIR/etc/controlDict (dpkg -L openfoam | grep etc/bashrc)" >&2
  exit 1
}

echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
echo "uptime: $(uptime)"
echo "cpus: $(nproc), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
echo "openfoam: $(dpkg-query -W -f '${Version}' openfoam 2> /dev/null || echo '?'), gmsh: $(dpkg-query -W -f '${Version}' python3-gmsh 2> /dev/null || echo '?')"
echo "command: bench/openfoam/compare.sh $*"
exec /usr/bin/python3 "$here/compare.py" "$@"
