#!/usr/bin/env bash
# Installs the Debian packages Tribos builds against. Idempotent and quiet
# when everything is present. libopenblas0-serial becomes the system BLAS and
# LAPACK (Debian alternatives): CHOLMOD's supernodal factor and solves run
# about twice as fast as with the reference BLAS (docs/benchmarks.md); the
# serial flavour keeps one thread per MPI rank.
set -euo pipefail
packages=(cmake g++ make pkg-config
  trilinos-all-dev libmetis-dev libhdf5-openmpi-dev libopenmpi-dev openmpi-bin
  libptscotch-dev libscotch-dev libmumps-dev libboost-dev libsuitesparse-dev
  libopenblas0-serial hdf5-tools python3-numpy python3-h5py python3-matplotlib libgmsh-dev gmsh libexodusii-dev libssl-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "Installing: ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO=sudo
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
