#!/bin/sh
# The compiler launcher of targets with a precompiled header (cmake/FfdkitOptions.cmake,
# ffdkit_precompile_headers): ccache-pch.sh CCACHE COMPILER ARGS...
# ccache caches compiles that use a precompiled header only with sloppiness pch_defines,time_macros
# (its manual, "Precompiled headers"), and hashes the header (a few hundred MB) for each of them:
# its inode cache remembers that hash. The compile that makes the precompiled header runs in
# ccache's depend mode, keyed by the headers the compiler's .d file names: in ccache's other modes
# the previous .gch in the build folder, which GCC's preprocessor names, would be part of the key
# (ccache issue 1196), so a rebuild missed and could even be given a .gch made from other headers.
# Clang (its targets compile with -Xclang -fno-pch-timestamp, which ccache needs there): ccache
# also needs sloppiness include_file_mtime,include_file_ctime, or it would not cache a compile that
# uses the precompiled header compiled a moment before (a file newer than the compile's start).
#
# Clang also records in the precompiled header the path of each file it read, and checks them when
# the header is used. CMake has it read <build>/CMakeFiles/<target>.dir/cmake_pch.hxx, which
# includes the header the target names: a precompiled header that ccache compiled in another build
# folder (scripts/test.sh's sanitizer app stage takes the libraries from the sanitizer stage's
# cache) would name that folder's file, and fail to load once that folder is gone. So the header is
# compiled from the source file cmake_pch.hxx names, and the compiles that use it name both by paths
# relative to the build folder: command lines and inputs are the same in every build folder of a
# checkout, and ccache serves them all.
export CCACHE_SLOPPINESS=pch_defines,time_macros CCACHE_INODECACHE=true
case " $* " in
  *" -fno-pch-timestamp "*)
    CCACHE_SLOPPINESS="$CCACHE_SLOPPINESS,include_file_mtime,include_file_ctime"
    emit_pch=false
    case " $* " in *" -emit-pch "*) emit_pch=true ;; esac
    for arg do
      shift
      case "$arg" in
        "$PWD"/*/cmake_pch.hxx | "$PWD"/*/cmake_pch.hxx.cxx)
          if $emit_pch; then
            arg=$(sed -n 's/^#include "\(.*\)"$/\1/p' "${arg%.cxx}")
          else
            arg="${arg#"$PWD"/}"
          fi ;;
        "$PWD"/*/cmake_pch.hxx.pch) arg="${arg#"$PWD"/}" ;;
      esac
      set -- "$@" "$arg"
    done ;;
esac
case " $* " in
  *" -x c++-header "*) export CCACHE_DEPEND=true ;;
esac
exec "$@"
