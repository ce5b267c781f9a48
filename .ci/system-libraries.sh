#!/usr/bin/env bash
# The system libraries the tests need beyond Python's: openseespy (the OpenSees comparison) links
# BLAS and LAPACK (Debian: libblas3, liblapack3). Installs them with apt-get when they are missing.
set -euo pipefail
if ldconfig -p 2>/dev/null | grep -q "liblapack.so.3" && ldconfig -p 2>/dev/null | grep -q "libblas.so.3"; then
    exit 0
fi
sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
if ! command -v apt-get >/dev/null; then
    echo "system-libraries: BLAS/LAPACK (libblas.so.3, liblapack.so.3) are missing and there is no apt-get:" \
         "install them with your system's package manager (openseespy needs them)" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get install -y -q libblas3 liblapack3 >/dev/null 2>&1 \
    || { $sudo apt-get update -q >/dev/null && $sudo apt-get install -y -q libblas3 liblapack3 >/dev/null; }
