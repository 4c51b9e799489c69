#!/usr/bin/env bash
# Style and static checks, as .ci/run runs them:
#  - clang-format (.clang-format) on every C++ file: a file that is not formatted fails;
#  - clang-tidy (.clang-tidy: bugprone-*, performance-*, functions over 80 lines) on the C++
#    files under src/ and apps/ that the last commit changed (twelve at most: each takes ten to
#    twenty seconds to parse): a warning in one fails (a file a commit touches leaves clean).
# Usage: scripts/lint.sh [BUILD_DIR with compile_commands.json, default build]
set -uo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
status=0
mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^tests/fixtures/')
# Every file in one clang-format call per core; the unformatted ones are named.
mapfile -t bad < <(printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc)" -n 40 sh -c 'for f; do clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || echo "$f"; done' sh)
if [ ${#bad[@]} -gt 0 ]; then
  echo "lint: not formatted (clang-format -i FILE): ${bad[*]}"
  status=1
else
  echo "lint: ${#files[@]} C++ files formatted"
fi
if [ -f "$BUILD/compile_commands.json" ] && command -v clang-tidy >/dev/null; then
  mapfile -t changed < <(git diff --name-only HEAD~1 HEAD 2>/dev/null | grep -E '^(src|apps)/.*\.cpp$' | head -12)
  # One command per file: unity batches split, without GCC's precompiled headers.
  db=$(mktemp -d)
  python3 scripts/per_file_compile_db.py "$BUILD" "$db"
  warned=0
  for f in "${changed[@]}"; do
    [ -f "$f" ] || continue
    if clang-tidy -p "$db" --quiet "$f" 2>/dev/null | grep -E 'warning:' | sed 's/^/lint: /' | grep .; then
      warned=$((warned + 1))
    fi
  done
  rm -rf "$db"
  echo "lint: clang-tidy on ${#changed[@]} changed files, $warned with warnings"
  [ "$warned" = 0 ] || status=1
fi
exit $status
