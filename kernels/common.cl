// Shared by all kernel files; placed first in the program.
//
// Layout of the small results buffer the stages share: counters first, then
// the peak records of peaks.cl. The host reads the counters and the first
// peaks back in one transfer.
#define DV_RESULT_PEAK_COUNT 0
#define DV_RESULT_LUMA_SUM 1
#define DV_RESULT_LUMA_FLOOR 2
#define DV_RESULT_HEADER 4
