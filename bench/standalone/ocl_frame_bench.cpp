// Stand-alone OpenCL frame benchmark: needs only libOpenCL.so.1 at run time
// (libstdc++/libgcc are linked statically), so it runs on GPU machines that
// have none of the project's other libraries.
//
// It draws a synthetic Bayer RGGB frame (green carpet with texture, colored
// discs of ball and robot-marker size) with plain loops, builds a rectification
// table for a slightly rotated and scaled view in plain C++, and times the
// OpenCL pipeline: pinned upload alone, pageable upload alone, every stage
// from profiling events and the end-to-end time of one frame (upload from
// pinned memory to the sorted peak list on the host), median and p99.
//
//   dotvision_ocl_bench [--platform P] [--device D] [--frames N]
//                       [--width W] [--height H] [--full-bayer] [--stretch S]
//                       [--list] [--dump]
// --stretch S: the whitened gradient (pipeline/view_stretch.h) of a view
// stretching blobs S times along 30 degrees, in the lower half of the grid.
// --full-bayer: a sample per pixel (pipeline/bayer_full.h) instead of per
// 2x2 cell; the view then spans four times the grid cells.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/opencl/ocl_engine.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/streak_windows.h"
#include "pipeline/whitening_form.h"

namespace {

struct Disc {
  double u, v, radius;  // full-resolution pixels
  int r, g, b;
};

// Small deterministic hash noise for the carpet texture.
int noise(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 73856093u ^ static_cast<uint32_t>(y) * 19349663u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<int>(h & 15) - 8;
}

std::vector<Disc> sceneDiscs(int w, int h) {
  // A grid of "robots" (center blob + four side blobs) and some balls; sizes
  // as on a camera 4 m above the field (about 2.45 mm per pixel).
  std::vector<Disc> discs;
  const double mm = 1 / 2.45;
  const int colors[][3] = {{230, 220, 40}, {40, 90, 230}, {240, 60, 200}, {60, 230, 80}, {250, 120, 20}};
  for (double cy = 220; cy < h - 200; cy += 330) {
    for (double cx = 220; cx < w - 200; cx += 360) {
      const int team = static_cast<int>(cx + cy) % 2;
      discs.push_back({cx, cy, 25 * mm, colors[team][0], colors[team][1], colors[team][2]});
      const double side[4][2] = {{-54, 35}, {54, 35}, {-35, -54}, {35, -54}};
      for (int s = 0; s < 4; ++s) {
        const int c = 2 + ((s + static_cast<int>(cx)) % 2);
        discs.push_back({cx + side[s][0] * mm, cy + side[s][1] * mm, 20 * mm, colors[c][0],
                         colors[c][1], colors[c][2]});
      }
      discs.push_back({cx + 160, cy + 140, 21.5 * mm, colors[4][0], colors[4][1], colors[4][2]});
    }
  }
  return discs;
}

// RGGB mosaic of the scene, written row by row into `raw` (w x h bytes).
void drawFrame(uint8_t* raw, int w, int h, const std::vector<Disc>& discs) {
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int n = noise(u / 6, v / 6);
      const int rgb[3] = {50 + n, 120 + n, 45 + n};
      const int ch = (v & 1) + (u & 1);  // 0 R, 1 G, 2 B
      raw[static_cast<size_t>(v) * w + u] = static_cast<uint8_t>(rgb[ch]);
    }
  for (const auto& d : discs) {
    const int u0 = std::max(0, static_cast<int>(d.u - d.radius - 1));
    const int u1 = std::min(w - 1, static_cast<int>(d.u + d.radius + 1));
    const int v0 = std::max(0, static_cast<int>(d.v - d.radius - 1));
    const int v1 = std::min(h - 1, static_cast<int>(d.v + d.radius + 1));
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        if ((u - d.u) * (u - d.u) + (v - d.v) * (v - d.v) > d.radius * d.radius) continue;
        const int rgb[3] = {d.r, d.g, d.b};
        raw[static_cast<size_t>(v) * w + u] = static_cast<uint8_t>(rgb[(v & 1) + (u & 1)]);
      }
  }
}

// Tables for a view of the sample image rotated by 2 degrees and scaled
// by 1.03, as the CPU reference's RemapTable stores them (1/256 fractions).
void buildTables(dv::OclEngineConfig& c) {
  const int step = c.full_bayer ? 1 : 2;
  const int sw = c.image_width / step, sh = c.image_height / step;
  const double s = 1.03, a = 2 * 3.14159265358979 / 180, ca = std::cos(a) * s, sa = std::sin(a) * s;
  c.grid_width = static_cast<int>(sw / s * 0.96);
  c.grid_height = static_cast<int>(sh / s * 0.96);
  const size_t cells = static_cast<size_t>(c.grid_width) * c.grid_height;
  c.remap_index.assign(cells, 0);
  c.remap_frac.assign(cells, 0);
  c.peak_mask.assign(cells, 0);
  int x_begin = sw, x_end = 0, y_begin = sh, y_end = 0;
  for (int y = 0; y < c.grid_height; ++y)
    for (int x = 0; x < c.grid_width; ++x) {
      const double gx = x - c.grid_width / 2.0, gy = y - c.grid_height / 2.0;
      double sx = sw / 2.0 + ca * gx - sa * gy, sy = sh / 2.0 + sa * gx + ca * gy;
      sx = std::clamp(sx, 0.0, sw - 1.0);
      sy = std::clamp(sy, 0.0, sh - 1.0);
      const long qx = std::lround(sx * 256), qy = std::lround(sy * 256);
      int x0 = static_cast<int>(qx >> 8), fx = static_cast<int>(qx & 255);
      int y0 = static_cast<int>(qy >> 8), fy = static_cast<int>(qy & 255);
      if (x0 > sw - 2) x0 = sw - 2, fx = 255;
      if (y0 > sh - 2) y0 = sh - 2, fy = 255;
      const size_t k = static_cast<size_t>(y) * c.grid_width + x;
      c.remap_index[k] = y0 * sw + x0;
      x_begin = std::min(x_begin, x0), x_end = std::max(x_end, x0 + 2);
      y_begin = std::min(y_begin, y0), y_end = std::max(y_end, y0 + 2);
      c.remap_frac[k] = static_cast<uint16_t>(fx | (fy << 8));
      c.peak_mask[k] = x >= c.margin && y >= c.margin && x < c.grid_width - c.margin &&
                       y < c.grid_height - c.margin;
    }
  c.region_x_begin = x_begin, c.region_x_end = x_end, c.region_y_begin = y_begin, c.region_y_end = y_end;
}

struct Stat {
  explicit Stat(const char* n) : name(n) {}
  const char* name;
  std::vector<double> v;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(std::ceil(p * v.size())) - (p > 0 ? 1 : 0));
  return v[i];
}

}  // namespace

int main(int argc, char** argv) {
  dv::OclDeviceRequest req;
  int frames = 500, width = 2448, height = 2048;
  bool list = false, dump = false, full_bayer = false;
  double stretch = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "dotvision_ocl_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--platform") req.platform = next();
    else if (a == "--device") req.device = next();
    else if (a == "--frames") frames = std::max(1, std::atoi(next().c_str()));
    else if (a == "--width") width = std::atoi(next().c_str());
    else if (a == "--height") height = std::atoi(next().c_str());
    else if (a == "--list") list = true;
    else if (a == "--full-bayer") full_bayer = true;
    else if (a == "--dump") dump = true;
    else if (a == "--stretch") stretch = std::atof(next().c_str());
    else {
      std::fprintf(stderr, "dotvision_ocl_bench: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (width < 64 || height < 64 || width % 2 || height % 2) {
    std::fprintf(stderr, "dotvision_ocl_bench: width/height must be even and >= 64\n");
    return 2;
  }
  std::string why;
  const auto devices = dv::listOpenClDevices(&why);
  if (list || devices.empty()) {
    std::printf("%s\n", devices.empty() ? why.c_str() : dv::describeOpenClDevices(devices).c_str());
    return devices.empty() ? 1 : 0;
  }
  try {
    if (req.platform.empty() && req.device.empty()) {
      // Prefer a GPU when nothing was asked for.
      for (const auto& d : devices)
        if (d.is_gpu) {
          req.platform = std::to_string(d.platform_index);
          req.device = std::to_string(d.device_index);
          break;
        }
    }
    const auto dev = dv::selectOpenClDevice(req);
    std::printf("device: %s (%s), %s, unified memory: %s\n", dev.device_name.c_str(),
                dev.platform_name.c_str(), dev.driver_version.c_str(), dev.host_unified_memory ? "yes" : "no");
    const auto t_build = std::chrono::steady_clock::now();
    auto ctx = std::make_shared<dv::OclContext>(dev);
    std::printf("program: %s in %.0f ms\n", ctx->programFromCache() ? "loaded from cache" : "compiled",
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_build).count());

    dv::OclEngineConfig cfg;
    cfg.image_width = width;
    cfg.image_height = height;
    cfg.bayer = true;
    cfg.full_bayer = full_bayer;
    // dRGB as the CPU reference (1.5 x an orthonormal basis normal to gray),
    // coefficients in 1/1024.
    const float s2 = 1.5f / std::sqrt(2.0f), s6 = 1.5f / std::sqrt(6.0f);
    const float a[3] = {s2, -s2, 0}, b[3] = {s6, s6, -2 * s6};
    for (int i = 0; i < 3; ++i) {
      cfg.chroma_a[i] = static_cast<int>(std::lround(a[i] * 1024));
      cfg.chroma_b[i] = static_cast<int>(std::lround(b[i] * 1024));
    }
    const double scale = 4.9;  // mm per grid cell
    cfg.gradient_scale = std::ceil(25 / scale) / 3.0;
    cfg.quadrant_radius = std::max(2, static_cast<int>(std::lround(25 / scale)));
    cfg.inner_corner = std::clamp(static_cast<int>(std::lround(10 / scale)), 0, cfg.quadrant_radius - 1);
    cfg.margin = cfg.quadrant_radius + static_cast<int>(std::floor(cfg.gradient_scale)) + 2;
    cfg.energy_window = cfg.quadrant_radius;
    cfg.energy_floor = 0.01f;
    cfg.color_radius = std::max(1.0, 13 / scale);
    // Thresholds and list sizes as the product's defaults, so the peak and
    // weak-peak stages do the product's work.
    const dv::PipelineOptions defaults;
    cfg.threshold = static_cast<float>(defaults.threshold);
    cfg.max_blobs = defaults.max_blobs;
    cfg.weak_threshold = static_cast<float>(defaults.weak_threshold);
    cfg.max_weak_blobs = defaults.max_weak_blobs;
    buildTables(cfg);
    // The fast-ball pass over the whole view (every lattice cell whose
    // footprint lies on the grid; the view has no unseen border).
    const dv::StreakWindows sw = dv::streakWindows(scale, cfg.grid_width, cfg.grid_height);
    std::vector<uint8_t> streak_mask(static_cast<size_t>(sw.lattice_width) * sw.lattice_height, 0);
    for (int j = 0; j < sw.lattice_height; ++j)
      for (int i = 0; i < sw.lattice_width; ++i) {
        const int cx = i * dv::kStreakLatticeStep, cy = j * dv::kStreakLatticeStep;
        streak_mask[static_cast<size_t>(j) * sw.lattice_width + i] =
            cx > sw.margin && cy > sw.margin && cx < sw.coarse_width - 1 - sw.margin &&
            cy < sw.coarse_height - 1 - sw.margin;
      }
    dv::applyStreakWindows(sw, std::move(streak_mask), cfg);
    if (stretch > 1) {
      // Whitened blocks in the lower half, plain blocks above (both paths).
      const int bx = (cfg.grid_width + cfg.form_block - 1) / cfg.form_block;
      const int by = (cfg.grid_height + cfg.form_block - 1) / cfg.form_block;
      cfg.form_blocks_x = bx;
      cfg.gradient_forms.assign(6 * static_cast<size_t>(bx) * by, 0.f);
      cfg.form_plain.assign(static_cast<size_t>(bx) * by, 1);
      cfg.form_plain_row.assign(by, 1);
      const double a = 30 * 3.14159265358979 / 180;
      for (int j = 0; j < by; ++j)
        for (int i = 0; i < bx; ++i) {
          float* c = &cfg.gradient_forms[6 * (static_cast<size_t>(j) * bx + i)];
          const bool whitened = j >= by / 2;
          dv::whiteningForm(whitened ? stretch - 1 : 0, std::cos(a), std::sin(a), c);
          cfg.form_plain[static_cast<size_t>(j) * bx + i] = !whitened;
          if (whitened) cfg.form_plain_row[j] = 0;
        }
    }
    std::printf("frame %dx%d Bayer RGGB -> grid %dx%d, gradient %.2f cells, quadrant %d cells, stretch %.3f\n",
                width, height, cfg.grid_width, cfg.grid_height, cfg.gradient_scale, cfg.quadrant_radius, stretch);

    dv::OclEngine engine(ctx, cfg);
    const auto discs = sceneDiscs(width, height);
    std::vector<uint8_t> frame(engine.frameBytes());
    drawFrame(frame.data(), width, height, discs);

    // Pageable upload for comparison: plain host memory.
    double pageable = 0;
    {
      cl_int st;
      cl_mem dst = clCreateBuffer(ctx->context(), CL_MEM_READ_ONLY, frame.size(), nullptr, &st);
      std::vector<double> t;
      for (int i = 0; i < 50 && st == CL_SUCCESS; ++i) {
        cl_event e;
        clEnqueueWriteBuffer(ctx->queue(), dst, CL_TRUE, 0, frame.size(), frame.data(), 0, nullptr, &e);
        cl_ulong t0, t1;
        clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr);
        clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr);
        clReleaseEvent(e);
        t.push_back((t1 - t0) * 1e-6);
      }
      if (dst) clReleaseMemObject(dst);
      pageable = percentile(t, 0.5);
    }

    Stat upload_only{"pinned upload alone"}, upload{"upload (in frame)"}, bayer{"bayer+luma"},
        rectify{"rectify+chroma"}, gradient{"gradient dot"}, sat{"summed-area table"}, score{"blob score"},
        peaks{"peaks"}, streak{"fast-ball streaks"}, download{"peak list download"}, device{"device span"}, e2e{"end to end (host)"};
    int found = 0, streaks = 0;
    const int warmup = 20;
    for (int i = 0; i < warmup + frames; ++i) {
      const double up = engine.timeUploadOnly();
      // The camera driver writes into the pinned buffer; here we copy the
      // prepared frame (not timed: it is the camera's DMA in a real system).
      uint8_t* dst = engine.frameBuffer();
      if (!dst) throw dv::OclError(engine.error());
      std::memcpy(dst, frame.data(), frame.size());
      if (!engine.run()) throw dv::OclError(engine.error());
      if (i < warmup) continue;
      const auto& t = engine.times();
      upload_only.v.push_back(up);
      upload.v.push_back(t.upload_ms);
      bayer.v.push_back(t.bayer_ms);
      rectify.v.push_back(t.rectify_ms);
      gradient.v.push_back(t.gradient_ms);
      sat.v.push_back(t.sat_ms);
      score.v.push_back(t.score_ms);
      peaks.v.push_back(t.peaks_ms);
      streak.v.push_back(t.streak_ms);
      download.v.push_back(t.download_ms);
      device.v.push_back(t.device_ms);
      e2e.v.push_back(t.wall_ms);
      found = static_cast<int>(engine.peaks().size());
      streaks = static_cast<int>(engine.streakPeaks().size());
    }
    std::printf("peaks found: %d, streak candidates: %d (discs drawn: %zu)\n", found, streaks, discs.size());
    if (dump) {
      // Stage fingerprints, to compare devices: integer stages must agree exactly.
      auto fnv = [](const void* p, size_t n) {
        uint64_t h = 1469598103934665603ull;
        for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<const uint8_t*>(p)[i]) * 1099511628211ull;
        return static_cast<unsigned long long>(h);
      };
      const auto packed = engine.readPackedChroma();
      const auto chroma = engine.readChroma();
      const auto g = engine.readGradient();
      const auto sat = engine.readSat();
      const auto sc = engine.readScore();
      std::printf("luma mean %.6f\npacked %016llx\nchroma %016llx\ngradient %016llx\nsat %016llx\nscore %016llx\n",
                  engine.lastLumaMean(), fnv(packed.data(), packed.size() * 4), fnv(chroma.data(), chroma.size() * 4),
                  fnv(g.data(), g.size() * 4), fnv(sat.data(), sat.size() * 4), fnv(sc.data(), sc.size() * 4));
      for (size_t i = 0; i < engine.peaks().size() && i < 5; ++i) {
        const auto& p = engine.peaks()[i];
        std::printf("peak %.4f %.4f score %.6f rgb %.2f %.2f %.2f\n", p.x, p.y, p.score, p.r, p.g, p.b);
      }
    }
    std::printf("pageable upload alone: median %.4f ms\n", pageable);
    std::printf("%-22s %10s %10s   (ms, %d frames)\n", "", "median", "p99", frames);
    for (const Stat* s : {&upload_only, &upload, &bayer, &rectify, &gradient, &sat, &score, &peaks, &streak, &download,
                          &device, &e2e})
      std::printf("%-22s %10.4f %10.4f\n", s->name, percentile(s->v, 0.5), percentile(s->v, 0.99));
    const double e2e_med = percentile(e2e.v, 0.5), up_med = percentile(upload_only.v, 0.5);
    std::printf("end to end - pinned upload alone: %.4f ms (%.2fx the upload)\n", e2e_med - up_med,
                up_med > 0 ? e2e_med / up_med : 0.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dotvision_ocl_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
