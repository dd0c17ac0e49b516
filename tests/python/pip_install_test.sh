#!/usr/bin/env bash
# `pip install plugin/python` into a fresh virtual environment (with the system's NumPy),
# from the build directory given (so the install copies the built extension), then
# `import dynrad` there and a solve. Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
set -euo pipefail
source_dir=$1
build_dir=$2
python=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" -m venv --system-site-packages "$work/venv"
DYNRAD_BUILD_DIR="$build_dir" "$work/venv/bin/pip" install --no-index --no-build-isolation -q "$source_dir/plugin/python"
cd "$work"  # not the checkout: the installed package must be found
"$work/venv/bin/python" - "$source_dir/samples/cornell_box.obj" <<'PY'
import sys
import dynrad
r = dynrad.solve(sys.argv[1], quality="draft")
assert dynrad.__file__.startswith(sys.prefix), dynrad.__file__
assert r["radiosity"].shape[1] == 3 and r["radiosity"].shape[0] > 100, r["radiosity"].shape
assert r["report"]["stopped_by"] in ("error target", "error floor", "converged"), r["report"]["stopped_by"]
print("pip install: dynrad", dynrad.__version__, "from", dynrad.__file__, "lit", r["radiosity"].shape[0], "vertices")
PY
