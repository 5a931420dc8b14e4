// Stage 4: summed-area table (thesis A.3) in modular 32-bit arithmetic, as
// pipeline/summed_area.cpp. Integer addition is associative, so the parallel
// scans below give exactly the sequential table. `sat` is (width+1) x
// (height+1); row 0 is zeroed once at creation, column 0 here.
// The table sums 2x2 boxes of G (box cell (x, y) = G at x..x+1, y..y+1, at
// position (x + 1/2, y + 1/2)); the last column repeats the row total and the
// last row has no box (all 0), exactly as the CPU reference.

// Pass 1: one work-group per grid row, an inclusive scan in chunks of the
// group size (a power of two) with a running carry.
__kernel void sat_rows(__global const int* gdot, int width, int height, __global uint* sat,
                       __local uint* scan) {
  const int y = get_group_id(0);
  const int lid = get_local_id(0), n = get_local_size(0);
  const size_t stride = (size_t)width + 1;
  __global uint* out = sat + (size_t)(y + 1) * stride;
  __global const int* r0 = gdot + (size_t)y * width;
  __global const int* r1 = r0 + width;
  const bool last_row = y + 1 >= height;
  if (lid == 0) out[0] = 0u;
  uint carry = 0u;
  for (int base = 0; base < width; base += n) {
    const int x = base + lid;
    scan[lid] = (x + 1 < width && !last_row)
                    ? (uint)r0[x] + (uint)r0[x + 1] + (uint)r1[x] + (uint)r1[x + 1]
                    : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int s = 1; s < n; s <<= 1) {
      const uint add = lid >= s ? scan[lid - s] : 0u;
      barrier(CLK_LOCAL_MEM_FENCE);
      scan[lid] += add;
      barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (x < width) out[x + 1] = carry + scan[lid];
    carry += scan[n - 1];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

// Pass 2: column prefix. A work-group holds get_local_size(0) adjacent columns
// (coalesced rows) and get_local_size(1) row chunks: each item sums its chunk,
// the chunk totals are prefixed in local memory, and each item then rewrites
// its chunk with the running sum.
__kernel void sat_columns(__global uint* sat, int width, int height, __local uint* totals) {
  const int cx = get_local_id(0), cy = get_local_id(1);
  const int ncols = get_local_size(0), nchunks = get_local_size(1);
  const int x = get_global_id(0);
  const size_t stride = (size_t)width + 1;
  const int chunk = (height + nchunks - 1) / nchunks;
  const int y0 = 1 + cy * chunk, y1 = min(height + 1, y0 + chunk);
  const bool live = x <= width;
  uint sum = 0u;
  if (live)
    for (int y = y0; y < y1; ++y) sum += sat[y * stride + x];
  totals[cy * ncols + cx] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  uint run = 0u;
  for (int c = 0; c < cy; ++c) run += totals[c * ncols + cx];
  if (live)
    for (int y = y0; y < y1; ++y) {
      run += sat[y * stride + x];
      sat[y * stride + x] = run;
    }
}
