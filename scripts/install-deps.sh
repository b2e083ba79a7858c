#!/usr/bin/env bash
# Installs perinom's build and test dependencies from Debian packages (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  g++ cmake make pkg-config \
  libeigen3-dev libsuitesparse-dev libsundials-dev catch2 libvtk9-dev \
  libyaml-cpp-dev libnanoflann-dev \
  python3 python3-numpy python3-matplotlib >/dev/null
echo "perinom: dependencies installed"
