#pragma once
// Function templates built for AVX2 and a default, picked at run time.
// clang 14 takes no target_clones on a template (the sanitizer build's
// compiler): one default build there.
#if defined(__clang__)
#define DV_TEMPLATE_AVX2_CLONES
#else
#define DV_TEMPLATE_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif
