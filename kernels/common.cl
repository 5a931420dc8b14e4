// Shared by all kernel files; placed first in the program.
//
// Layout of the small results buffer the stages share: counters first, then
// the peak records of peaks.cl. The host reads the counters and the first
// peaks back in one transfer.
#define DV_RESULT_PEAK_COUNT 0
#define DV_RESULT_LUMA_SUM 1
#define DV_RESULT_LUMA_MEAN 2
#define DV_RESULT_HEADER 4

// The gradient dot product's fixed point (pipeline/kernels.h).
#define DV_GRADIENT_FIXED_POINT 16384.0f

#ifdef DV_TEST_BUILD_FAILURE
#error "build failure requested by a test (DV_TEST_BUILD_FAILURE)"
#endif
