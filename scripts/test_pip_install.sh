#!/usr/bin/env bash
# Installs the Python module with pip into a fresh virtual environment, as a
# user would (python/README.md), from a clone of the repository's committed
# state, then imports it from elsewhere and moves a mesh one time step.
#   bash scripts/test_pip_install.sh        (about 5 minutes: pip builds the module with CMake)
# Needs what scripts/install_dependencies.sh installs (python3-venv, -pip,
# -setuptools, -wheel, pybind11-dev); nothing is downloaded.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$(date +%s)
git clone -q "$repo" "$work/src"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" "$work/venv/bin/pip" install -q --no-build-isolation --no-index "$work/src"
cd "$work"
"$work/venv/bin/python" - "$repo/tests/data/cli/plate_v41.msh" <<'PY'
import math
import sys

import numpy as np
import spring_motion as sm

assert "venv" in sm.__file__, sm.__file__  # the installed module, not a build tree's
mesh = sm.read_mesh(sys.argv[1])
d = sm.Deformer(mesh, moving="wing")
p = mesh.points[d.moving_vertices] - (1.5, 1.0)
a = math.radians(5)
turned = np.stack([math.cos(a) * p[:, 0] - math.sin(a) * p[:, 1], math.sin(a) * p[:, 0] + math.cos(a) * p[:, 1]], axis=1)
step = d.move(turned - p)
assert step.valid, step
print("spring_motion %s from %s: one step, %d iterations" % (sm.__version__, sm.__file__, step.iterations))
PY
echo "== pip install and import in a fresh virtual environment: $(( $(date +%s) - start )) s"
