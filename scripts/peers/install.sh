#!/usr/bin/env bash
# Installs the peer solvers that scripts/peers/*.py drive (README "Peers").
#
#   scripts/peers/install.sh [--no-siconos]
#
# * PyPI peers, with pip into the `python3` on PATH (or $PYTHON): numpy,
#   scipy, OSQP, Clarabel, ProxSuite, quadprog, CVXOPT, cromosim — pinned to
#   the versions measured in README.
# * Siconos, Debian's python3-siconos (not on PyPI), for the system
#   /usr/bin/python3 (~55 s with apt-get update on these machines). Needs
#   root; when apt is unavailable it says so and the Siconos peers are
#   skipped.
set -euo pipefail
PY="${PYTHON:-python3}"

echo "== peers from PyPI ($PY)"
"$PY" -m pip install -q --disable-pip-version-check --root-user-action=ignore \
  "numpy==2.4.6" "scipy==1.17.1" "osqp==1.1.3" "clarabel==0.11.1" "proxsuite==0.8.0" \
  "quadprog==0.1.14" "cvxopt==1.3.3" "cromosim==2.1.0"

if [ "${1:-}" = "--no-siconos" ]; then
  exit 0
fi
echo "== Siconos (Debian python3-siconos, for /usr/bin/python3)"
if /usr/bin/python3 -c "import siconos.kernel" 2>/dev/null; then
  echo "already installed"
elif command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
  apt-get update -q >/dev/null || true
  if ! DEBIAN_FRONTEND=noninteractive apt-get install -y -q python3-siconos >/dev/null; then
    echo "apt-get install python3-siconos failed: the Siconos peers will be skipped"
  fi
else
  echo "no apt-get as root here: the Siconos peers will be skipped"
fi
