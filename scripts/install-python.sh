#!/usr/bin/env bash
# Makes the Python module of this build importable from any directory by the
# system python3 (docs/python.md): a one-line .pth file in its site-packages
# that names build/python. Run after scripts/build.sh; needs root (the
# site-packages folder is the system's). Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
python=/usr/bin/python3
module_dir=$PWD/build/python
ls "$module_dir"/mbfe*.so >/dev/null 2>&1 || { echo "install-python: no module in $module_dir (build first)" >&2; exit 1; }
site=$("$python" -c 'import site; print(site.getsitepackages()[0])')
if [[ ! -w $site && $(id -u) -ne 0 ]]; then
  echo "install-python: $site is not writable; run as root, or use PYTHONPATH=$module_dir" >&2
  exit 1
fi
mkdir -p "$site"
echo "$module_dir" >"$site/mbfe.pth"
(cd / && "$python" -c 'import mbfe') || { echo "install-python: $python cannot import mbfe from /" >&2; exit 1; }
echo "install-python: $python imports mbfe from any directory ($site/mbfe.pth -> $module_dir)"
