#pragma once
// Image tiles with the objects whose projected bounding box touches them, so
// a ray only tests the few objects that can be on its pixel. Compressed rows:
// the items of tile i are items[start[i] .. start[i+1]).
#include <algorithm>
#include <cstdint>
#include <vector>

namespace dv {

// Inclusive pixel box; empty when u1 < u0.
struct PixelBox {
  int u0 = 0, v0 = 0, u1 = -1, v1 = -1;
  bool empty() const { return u1 < u0 || v1 < v0; }
  void add(const PixelBox& b) {
    if (b.empty()) return;
    if (empty()) {
      *this = b;
      return;
    }
    u0 = std::min(u0, b.u0), v0 = std::min(v0, b.v0);
    u1 = std::max(u1, b.u1), v1 = std::max(v1, b.v1);
  }
};

class TileBins {
 public:
  static constexpr int kTile = 16;  // px

  void reset(int width, int height) {
    tiles_x_ = (width + kTile - 1) / kTile;
    tiles_y_ = (height + kTile - 1) / kTile;
    boxes_.clear();
  }
  // Adds object `id` covering `box` (clipped to the image).
  void add(uint32_t id, const PixelBox& box) {
    if (box.empty()) return;
    const int tx0 = std::max(0, box.u0 / kTile), ty0 = std::max(0, box.v0 / kTile);
    const int tx1 = std::min(tiles_x_ - 1, box.u1 / kTile);
    const int ty1 = std::min(tiles_y_ - 1, box.v1 / kTile);
    if (box.u1 < 0 || box.v1 < 0 || tx0 > tx1 || ty0 > ty1) return;
    boxes_.push_back({id, tx0, ty0, tx1, ty1});
  }
  // Builds the per-tile lists after all add() calls.
  void finish() {
    start_.assign(size_t(tiles_x_) * tiles_y_ + 1, 0);
    for (const auto& b : boxes_)
      for (int ty = b.ty0; ty <= b.ty1; ++ty)
        for (int tx = b.tx0; tx <= b.tx1; ++tx) ++start_[size_t(ty) * tiles_x_ + tx + 1];
    for (size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    items_.assign(start_.back(), 0);
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (const auto& b : boxes_)
      for (int ty = b.ty0; ty <= b.ty1; ++ty)
        for (int tx = b.tx0; tx <= b.tx1; ++tx) items_[fill[size_t(ty) * tiles_x_ + tx]++] = b.id;
  }
  int tileIndex(int u, int v) const { return (v / kTile) * tiles_x_ + u / kTile; }
  const uint32_t* begin(int tile) const { return items_.data() + start_[tile]; }
  const uint32_t* end(int tile) const { return items_.data() + start_[tile + 1]; }
  bool emptyTile(int tile) const { return start_[tile] == start_[tile + 1]; }

 private:
  struct Entry {
    uint32_t id;
    int tx0, ty0, tx1, ty1;
  };
  int tiles_x_ = 0, tiles_y_ = 0;
  std::vector<Entry> boxes_;
  std::vector<uint32_t> start_, items_;
};

}  // namespace dv
