// Fast balls (pipeline/streak_score.cpp, operation by operation): box means
// of the chroma on a coarse grid, the streak score at four orientations, and
// its peaks with the centroid of the streak's excess chroma and the mean
// color there. Peaks go to their own list (counter first, then records laid
// out as dv_peak in peaks.cl, cell_x/cell_y the coarse peak cell); the host
// orders them and drops those at a blob.
#pragma OPENCL FP_CONTRACT OFF

#define DV_STREAK_ORIENTATIONS 4

// Per orientation: step along (dx, dy), inner half run, side and end steps.
typedef struct {
  int step_x[DV_STREAK_ORIENTATIONS], step_y[DV_STREAK_ORIENTATIONS];
  int inner[DV_STREAK_ORIENTATIONS], side[DV_STREAK_ORIENTATIONS], end[DV_STREAK_ORIENTATIONS];
} dv_streak_shape;

__kernel void streak_coarse(__global const float2* chroma, int width, int factor, int coarse_width,
                            int coarse_height, __global float2* coarse, __global uint* list) {
  const int cx = get_global_id(0), cy = get_global_id(1);
  // The peak stage of the last frame is done (in-order queue): clear its count.
  if (cx == 0 && cy == 0) list[0] = 0u;
  if (cx >= coarse_width || cy >= coarse_height) return;
  // The first grid row of the box, as the CPU reference.
  const float norm = 1.0f / (float)factor;
  float sa = 0, sb = 0;
  const size_t row = (size_t)cy * factor * width + (size_t)cx * factor;
  for (int i = 0; i < factor; ++i) {
    const float2 c = chroma[row + i];
    sa += c.x;
    sb += c.y;
  }
  coarse[(size_t)cy * coarse_width + cx] = (float2)(sa * norm, sb * norm);
}

inline void dv_streak_footprint(__global const float2* coarse, int cw, __constant dv_streak_shape* s, int o,
                                int x, int y, float2* inner, float2 sur[4]) {
  const int ux = s->step_x[o], uy = s->step_y[o];
  const int vx = -uy, vy = ux;
  const int n = s->inner[o];
  float ia = 0, ib = 0;
  for (int k = -n; k <= n; ++k) {
    const float2 c = coarse[(size_t)(y + k * uy) * cw + (x + k * ux)];
    ia += c.x;
    ib += c.y;
  }
  const float inv = 1.0f / (float)(2 * n + 1);
  *inner = (float2)(ia * inv, ib * inv);
  const int sd = s->side[o], e = s->end[o];
  sur[0] = coarse[(size_t)(y + sd * vy) * cw + (x + sd * vx)];
  sur[1] = coarse[(size_t)(y - sd * vy) * cw + (x - sd * vx)];
  sur[2] = coarse[(size_t)(y + e * uy) * cw + (x + e * ux)];
  sur[3] = coarse[(size_t)(y - e * uy) * cw + (x - e * ux)];
}

// One work item per lattice cell (i, j) = coarse cell (2i, 2j).
__kernel void streak_score(__global const float2* coarse, int cw, int ch, int lw, int lh, int margin,
                           __constant dv_streak_shape* shape, float floor_, int gate_reach, float gate,
                           __global float* score, __global uchar* orientation) {
  const int li = get_global_id(0), lj = get_global_id(1);
  if (li >= lw || lj >= lh) return;
  const int x = 2 * li, y = 2 * lj;
  float best = 0;
  uchar best_o = 0;
  bool pass = false;
  if (x >= margin && x < cw - margin && y >= margin && y < ch - margin) {
    // The gate (gateRow): the cell against the mean of four cells along the axes.
    const size_t i = (size_t)y * cw + x;
    const float2 c = coarse[i], l = coarse[i - gate_reach], r = coarse[i + gate_reach];
    const float2 u = coarse[i - (size_t)gate_reach * cw], d = coarse[i + (size_t)gate_reach * cw];
    const float ma = 0.25f * (((l.x + r.x) + u.x) + d.x);
    const float mb = 0.25f * (((l.y + r.y) + u.y) + d.y);
    const float da = c.x - ma, db = c.y - mb;
    pass = da * da + db * db > gate;
  }
  if (pass) {
    for (int o = 0; o < DV_STREAK_ORIENTATIONS; ++o) {
      float2 inner, s[4];
      dv_streak_footprint(coarse, cw, shape, o, x, y, &inner, s);
      float da[4], db[4], ma = 0, mb = 0, sq = 0;
      for (int k = 0; k < 4; ++k) {
        da[k] = inner.x - s[k].x;
        db[k] = inner.y - s[k].y;
        ma += da[k];
        mb += db[k];
        sq += da[k] * da[k] + db[k] * db[k];
      }
      ma *= 0.25f;
      mb *= 0.25f;
      float lo = da[0] * ma + db[0] * mb;
      for (int k = 1; k < 4; ++k) lo = fmin(lo, da[k] * ma + db[k] * mb);
      const float v = lo / (0.25f * sq + floor_);
      if (v > best) {
        best = v;
        best_o = (uchar)o;
      }
    }
  }
  score[(size_t)lj * lw + li] = best;
  orientation[(size_t)lj * lw + li] = best_o;
}

__kernel void streak_peaks(__global const float* score, __global const uchar* orientation,
                           __global const uchar* mask, int cw, int lw, int lh, float threshold,
                           __constant dv_streak_shape* shape, __global const float2* coarse, int factor,
                           __global const float2* chroma, int width, int height, float refine_along,
                           float refine_across, __global const uchar* raw, int raw_stride, int bayer,
                           int4 sites, int src_width, int src_height, __global const int* remap_index,
                           __global const ushort* remap_frac, dv_real color_radius,
                           __global uint* list, int capacity) {
  // Lattice cell (li, lj); its coarse cell (x, y).
  const int li = get_global_id(0), lj = get_global_id(1);
  if (li < 1 || lj < 1 || li >= lw - 1 || lj >= lh - 1) return;
  const size_t cell = (size_t)lj * lw + li;
  const float c = score[cell];
  if (!(c > threshold) || !mask[cell]) return;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!dx && !dy) continue;
      const float n = score[(size_t)(lj + dy) * lw + (li + dx)];
      const bool before = dy < 0 || (dy == 0 && dx < 0);
      if (before ? !(c > n) : !(c >= n)) return;
    }
  const uint slot = atomic_inc(&list[0]);
  if (slot >= (uint)capacity) return;
  const int x = 2 * li, y = 2 * lj;

  // Centroid of the excess chroma (refineStreak).
  const int o = orientation[cell];
  float2 inner, s[4];
  dv_streak_footprint(coarse, cw, shape, o, x, y, &inner, s);
  const float ba = 0.25f * (s[0].x + s[1].x + s[2].x + s[3].x);
  const float bb = 0.25f * (s[0].y + s[1].y + s[2].y + s[3].y);
  const float da = inner.x - ba, db = inner.y - bb;
  const float d2 = da * da + db * db;
  const dv_real f = factor;
  const dv_real cx = x * f + (dv_real)0.5 * (f - 1), cy = y * f + (dv_real)0.5 * (f - 1);
  dv_real gx = cx, gy = cy;
  if (d2 > 0) {
    const dv_real sx0 = shape->step_x[o], sy0 = shape->step_y[o];
    const dv_real len = sqrt(sx0 * sx0 + sy0 * sy0);
    const dv_real ux = sx0 / len, uy = sy0 / len;
    const dv_real ra = refine_along, rc = refine_across;
    const dv_real reach = sqrt(ra * ra + rc * rc);
    const int x0 = max(0, (int)ceil(cx - reach)), x1 = min(width - 1, (int)floor(cx + reach));
    const int y0 = max(0, (int)ceil(cy - reach)), y1 = min(height - 1, (int)floor(cy + reach));
    const float ka = da / d2, kb = db / d2;
    dv_real sw = 0, sxw = 0, syw = 0;
    for (int yy = y0; yy <= y1; ++yy) {
      for (int xx = x0; xx <= x1; ++xx) {
        const dv_real ox = xx - cx, oy = yy - cy;
        const dv_real along = ox * ux + oy * uy, across = -ox * uy + oy * ux;
        if (fabs(along) > ra || fabs(across) > rc) continue;
        const float2 v = chroma[(size_t)yy * width + xx];
        const float proj = (v.x - ba) * ka + (v.y - bb) * kb - 0.25f;
        if (!(proj > 0)) continue;
        sw += proj;
        sxw += proj * ox;
        syw += proj * oy;
      }
    }
    if (sw > 0) {
      gx = cx + sxw / sw;
      gy = cy + syw / sw;
    }
  }

  // Mean color over the disc at the centroid (as find_peaks).
  const float3 rgb = dv_disc_mean_rgb(raw, raw_stride, bayer, sites, src_width, src_height, remap_index,
                                      remap_frac, width, height, gx, gy, color_radius);
  dv_store_peak(list, slot, (float)gx, (float)gy, c, li, lj, rgb);
}
