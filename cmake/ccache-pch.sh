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
case " $* " in
  *" -x c++-header "*) export CCACHE_DEPEND=true ;;
esac
exec "$@"
