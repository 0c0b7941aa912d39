#!/usr/bin/env bash
# Installs every Debian package asbuilt needs to build, test and benchmark.
# Idempotent: a fast no-op when everything is present; runs `apt-get update`
# only when something is missing. Works as root on a fresh Debian 12 machine
# (uses sudo otherwise).
#
#   scripts/install-deps.sh          build + test dependencies
#   scripts/install-deps.sh --bench  also what `make bench` compares against
#                                    (Python PyTorch, hyperfine)
#   scripts/install-deps.sh --photos also gimp-data, whose patterns (1.4 MB of
#                                    the package's 14 MB download, 87 MB installed)
#                                    `dataset synth --levers photo_textures` reads;
#                                    blender (above) brings the HDR skies
#   scripts/install-deps.sh --cluster also Slurm (slurm-wlm: slurmctld, slurmd,
#                                    slurm-client) and munge, for the one-node
#                                    test cluster (scripts/slurm/local-cluster.sh,
#                                    `make test-cluster`)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev
  libopencv-dev libopencv-contrib-dev
  libtorch-dev libopenblas0-openmp libgloo-dev
  libembree-dev libtbb-dev
  libcairo2-dev libcpp-httplib-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev clang-format clang-tidy
  python3 python3-ezdxf librsvg2-bin
  libifcplusplus-dev libboost-dev
  blender
  chromium
)
for flag in "$@"; do
  case "$flag" in
    --bench) packages+=(python3-torch hyperfine) ;;
    --photos) packages+=(gimp-data) ;;
    --cluster) packages+=(slurm-wlm slurmctld slurmd slurm-client munge procps) ;;
  esac
done
# Node.js (for the MCP SDK client test). Some images ship nodesource's nodejs,
# which bundles npm and conflicts with Debian's npm package: only ask for
# Debian's when no npm is on the PATH.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
