#!/usr/bin/env bash
# Checks the C++ sources against the checked-in .clang-format (issue 16): every tracked .cpp/.h
# under src/, apps/, tests/, bench/, include/, python/ and examples/ must be formatted, except the
# files listed in scripts/format-debt.txt (formatted before the check existed; a file leaves the
# list when it is next reformatted — the list may only shrink). Run by scripts/test.sh; run
# `clang-format -i FILE` to fix a file.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check-format: clang-format is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
mapfile -t debt < <(grep -v '^#' scripts/format-debt.txt | sed '/^$/d')
declare -A skip=()
for f in "${debt[@]}"; do skip["$f"]=1; done
bad=0
checked=0
while IFS= read -r f; do
  [ -n "${skip[$f]:-}" ] && continue
  checked=$((checked + 1))
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "check-format: $f is not formatted (clang-format -i $f)" >&2
    bad=$((bad + 1))
  fi
done < <(git ls-files '*.cpp' '*.h' | grep -E '^(src|apps|tests|bench|include|python|examples)/')
for f in "${debt[@]}"; do
  if [ -f "$f" ] && clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "check-format: $f is formatted now: remove it from scripts/format-debt.txt" >&2
    bad=$((bad + 1))
  fi
done
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "check-format: $checked files formatted (${#debt[@]} in the debt list)"
