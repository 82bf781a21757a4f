// Internal to ffd/: multiversioned hot loops.
#pragma once

// The hot loops are compiled for baseline x86-64, AVX2 + FMA and AVX-512, and picked at load
// time (GCC function multiversioning), so the library stays portable without -march flags.
// FFDKIT_NO_VECTOR_CLONES (the sanitizer build, ffd/CMakeLists.txt) compiles each loop once,
// for baseline x86-64: the same source checked by the sanitizers, at a third of the compile time.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(FFDKIT_NO_VECTOR_CLONES)
#define FFDKIT_VECTOR_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define FFDKIT_VECTOR_CLONES
#endif
// Helpers are forced inline so that they are compiled for the target of the clone that calls them.
#define FFDKIT_INLINE [[gnu::always_inline]] inline
