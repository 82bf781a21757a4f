#!/bin/sh
# The compiler launcher of targets with a precompiled header (cmake/FfdkitOptions.cmake,
# ffdkit_precompile_headers): ccache-pch.sh CCACHE COMPILER ARGS...
# ccache caches compiles that use a precompiled header only with sloppiness pch_defines,time_macros
# (its manual, "Precompiled headers"), and hashes the header (a few hundred MB) for each of them:
# its inode cache remembers that hash. The compile that makes the precompiled header runs in
# ccache's depend mode, keyed by the headers the compiler's .d file names: in ccache's other modes
# the previous .gch in the build folder, which GCC's preprocessor names, would be part of the key
# (ccache issue 1196), so a rebuild missed and could even be given a .gch made from other headers.
export CCACHE_SLOPPINESS=pch_defines,time_macros CCACHE_INODECACHE=true
header=""
case " $* " in
  *" -x c++-header "*) export CCACHE_DEPEND=true; header=1 ;;
esac
case "$2" in
  *clang*) ;;
  *) exec "$@" ;;
esac

# Clang. Its precompiled header names the files it was made from by their full paths, the
# CMake-generated header in the build folder among them, and cannot be used once one of them is
# gone. So it is cached per build folder (CCACHE_BASEDIR off: the build folder's path is part of
# the key), and ccache hashes, for the compiles that use it, a checksum of what it was made from
# (pch_external_checksum: <header>.pch.sum, written below: the compile line and the contents of
# the files the compiler's .d file names, with the build folder's path left out) instead of the
# header itself, so those compiles are shared with the other build folders. include_file_mtime,
# include_file_ctime: the header is made moments before the compiles that use it.
# CMake names the header it includes first by its full path after -Xclang, which ccache does not
# make relative to CCACHE_BASEDIR: paths in the build folder are handed to the compiler relative
# to it (the folder the compiler runs in), so that the key is the same in every build folder.
export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
export CCACHE_PCH_EXTSUM=true
here="$(pwd)"
if [ -z "$header" ]; then
  for arg do
    shift
    case "$arg" in
      "$here"/*) arg="${arg#"$here"/}" ;;
    esac
    set -- "$@" "$arg"
  done
  exec "$@"
fi
output="" depfile="" previous=""
for arg in "$@"; do
  case "$previous" in
    -o) output="$arg" ;;
    -MF) depfile="$arg" ;;
  esac
  previous="$arg"
done
CCACHE_BASEDIR="" "$@" || exit
{
  printf '%s\n' "$@" | sed "s|$here|.|g"
  sed -e 's/\\$//' -e 's/^[^ ]*: *//' "$depfile" | tr ' ' '\n' | sed '/^$/d' | sort -u |
    while read -r file; do
      printf '%s %s\n' "$(sha256sum < "$file" | cut -c1-64)" "$file" | sed "s|$here|.|g"
    done
} | sha256sum > "$output.sum"
