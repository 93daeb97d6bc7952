# Sourced by the tools that run one program of the build (tools/spy, tools/log2csv):
#   tvo_build_target <repo_root> <cmake target>...
# builds just those targets in <repo_root>/build (up to date: a quick no-op); a tree that was never
# configured gets tools/build first (setup, configure, build). The build's chatter goes to stderr.
tvo_build_target() {
  local repo_root="$1"; shift
  local build_dir="$repo_root/build"
  if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
    "$repo_root/tools/build" >&2 || return 1
  fi
  cmake --build "$build_dir" --parallel 2 --target "$@" >&2
}
