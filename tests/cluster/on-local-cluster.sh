#!/usr/bin/env bash
# tests/cluster/run.sh on the one-node Slurm of scripts/slurm/local-cluster.sh:
# brings it up unless it already is, and down after only if it brought it up.
# Exits 77 (ctest: skipped) where it cannot run: not root, or Slurm and munge
# not installed (scripts/install-deps.sh --cluster).
#
#   tests/cluster/on-local-cluster.sh [BUILD_DIR]     (ctest cluster/slurm, make test-cluster)
set -uo pipefail
cd "$(dirname "$0")/../.."
cluster=scripts/slurm/local-cluster.sh
if [[ $(id -u) -ne 0 ]] || ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "tests/cluster: skipped: needs root and Slurm + munge (bash scripts/install-deps.sh --cluster)"
  exit 77
fi
was_up=0
bash "$cluster" status >/dev/null 2>&1 && was_up=1
bash "$cluster" up || exit 1
bash tests/cluster/run.sh "${1:-build}"
status=$?
((was_up)) || bash "$cluster" down
exit $status
