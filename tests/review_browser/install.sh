#!/usr/bin/env bash
# Installs playwright-core (pinned by package-lock.json) for the review/browser test;
# the browser is Debian's chromium (scripts/install-deps.sh), never a download.
# Idempotent: a no-op when node_modules matches the lock file; skipped (with a
# note) when node or npm is missing. Called by `make deps` / `make test`.
set -euo pipefail
dir="$(cd "$(dirname "$0")" && pwd)"
if ! command -v npm >/dev/null 2>&1 || ! command -v node >/dev/null 2>&1; then
  echo "review_browser: node/npm not found; the review/browser test will not run" >&2
  exit 0
fi
stamp="$dir/node_modules/.asbuilt-lock-sha256"
want="$(sha256sum "$dir/package-lock.json" | cut -d' ' -f1)"
if [[ -f "$stamp" && "$(cat "$stamp")" == "$want" ]]; then
  exit 0
fi
echo "review_browser: npm ci (playwright-core, pinned by package-lock.json)" >&2
npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error >&2
echo "$want" > "$stamp"
