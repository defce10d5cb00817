#!/usr/bin/env bash
# Installs PETSc (with its MPI, OpenMPI on Debian and Ubuntu), Scotch and pkg-config from the
# distribution's packages, unless pkg-config already finds PETSc; then prints the version.
# The default build of hemicontact never needs this: only the cargo feature `petsc` does
# (docs/distributed.md).
#
# Usage: scripts/install-petsc.sh   (as root, or with sudo available)
# Fails (non-zero exit) if PETSc cannot be installed or found afterwards.
set -euo pipefail
if ! pkg-config --exists PETSc 2>/dev/null; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    petsc-dev libscotch-dev pkg-config >/dev/null
fi
echo "PETSc $(pkg-config --modversion PETSc) found by pkg-config"
