#!/bin/sh
# Fails when a C++ file is not formatted as .clang-format says (clang-format 14, Debian 12).
# `sh scripts/check-format.sh --fix` formats them in place instead.
set -eu
cd "$(dirname "$0")/.."
command -v clang-format-14 >/dev/null 2>&1 || { echo "check-format: clang-format-14 is missing (sh scripts/setup.sh installs it)" >&2; exit 1; }
files=$(git ls-files '*.cpp' '*.hpp')
if [ "${1:-}" = "--fix" ]; then
  echo "$files" | xargs clang-format-14 -i
  exit 0
fi
# In batches on every core; clang-format names each file it would change in its warnings.
bad=$(echo "$files" | xargs -P "$(nproc)" -n 40 clang-format-14 --dry-run -Werror 2>&1 |
  sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u | tr '\n' ' ')
if [ -n "$bad" ]; then
  echo "check-format: not formatted (run sh scripts/check-format.sh --fix): $bad" >&2
  exit 1
fi
echo "check-format: $(echo "$files" | wc -l) files formatted as .clang-format says"
