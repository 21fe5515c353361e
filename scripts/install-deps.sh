#!/usr/bin/env bash
# Installs the Debian packages vismap needs, only those missing.
set -euo pipefail
pkgs=(cmake g++ make time pkg-config libcgal-dev libgmp-dev libmpfr-dev libboost-dev libgtest-dev libbenchmark-dev
      libmimalloc-dev libcairo2-dev python3 python3-dev pybind11-dev python3-numpy   # (the Python module)
      python3-pytest python3-matplotlib python3-ezdxf poppler-utils librsvg2-bin)   # (the tests: pytest, the README's example, drawings read back)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
