#!/bin/sh
# tools/keygen inside a git work tree (CTest tools_keygen_work_tree): a key git would commit gets a
# WARNING naming the tree, an ignored one a note, one outside any tree nothing; and this repository's
# own .gitignore ignores *.key, so `tools/keygen robot.key` (README.md's tour) leaves nothing to commit.
#   keygen_work_tree.sh REPO WORK_DIR
set -u
repo="$1"; work="$2"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work/tree" || exit 1
outside="$(mktemp -d)" || exit 1      # not under the build folder, which sits in this work tree
trap 'rm -rf "$outside"' EXIT
git -C "$work/tree" init -q . || fail "git init"

"$repo/tools/keygen" "$work/tree/plain.key" 2>"$work/err1" || fail "keygen in a tree exited $?"
grep -q "WARNING: .*plain.key is inside the git work tree .*does NOT ignore it" "$work/err1" \
  || fail "no warning for a key git would commit: $(cat "$work/err1")"

echo '*.key' >"$work/tree/.gitignore"
"$repo/tools/keygen" "$work/tree/ignored.key" 2>"$work/err2" || fail "keygen exited $?"
grep -q "note: .*ignored.key is inside the git work tree .*git ignores it" "$work/err2" \
  || fail "no note for an ignored key: $(cat "$work/err2")"
if grep -q WARNING "$work/err2"; then fail "an ignored key got the warning: $(cat "$work/err2")"; fi

if git -C "$outside" rev-parse --show-toplevel >/dev/null 2>&1; then
  fail "$outside (mktemp -d) is inside a git work tree: no place outside one to check"
fi
"$repo/tools/keygen" "$outside/free.key" 2>"$work/err3" || fail "keygen exited $?"
[ ! -s "$work/err3" ] || fail "a key outside any work tree got a message: $(cat "$work/err3")"

if git -C "$repo" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git -C "$repo" check-ignore -q robot.key || fail "$repo/.gitignore does not ignore robot.key"
  echo "ok: $repo ignores robot.key"
else
  echo "ok (the source is not a git work tree: its .gitignore is not checked here)"
fi
echo "ok: keygen warns in a work tree, notes an ignored key, says nothing outside"
