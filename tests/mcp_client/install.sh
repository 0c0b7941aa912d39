#!/usr/bin/env bash
# Installs the pinned MCP SDK (package-lock.json) for the mcp/sdk_client test.
# Idempotent: a no-op when node_modules matches the lock file; skipped (with a
# note) when node or npm is missing. Called by `make deps` / `make test`.
set -euo pipefail
dir="$(cd "$(dirname "$0")" && pwd)"
if ! command -v npm >/dev/null 2>&1 || ! command -v node >/dev/null 2>&1; then
  echo "mcp_client: node/npm not found; the mcp/sdk_client test will not run" >&2
  exit 0
fi
stamp="$dir/node_modules/.asbuilt-lock-sha256"
want="$(sha256sum "$dir/package-lock.json" | cut -d' ' -f1)"
if [[ -f "$stamp" && "$(cat "$stamp")" == "$want" ]]; then
  exit 0
fi
echo "mcp_client: npm ci (@modelcontextprotocol/sdk, pinned by package-lock.json)" >&2
npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error >&2
echo "$want" > "$stamp"
