#pragma once
// Bands of grid rows that the CPU pipeline takes from the raw mosaic to the
// blob score in one pass each (Bayer 2x2 subsampling with the quadrant score):
// a band makes the chroma samples its cells read into a box of its own, then
// rectifies its rows and scores them as it goes, so neither the sample image
// nor the chroma planes go out to memory and come back. Bands overlap by the
// reach of the score window and the gradient: those rows are rectified by
// both bands (into a private buffer by the one that does not own them), and
// so are the samples under them. Heights fall from first to last band
// (the last ones taken are short). Built once per camera.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/remap_table.h"

namespace dv {

struct BandPlan {
  struct Band {
    int y_begin = 0, y_end = 0;  // grid rows the band owns: it writes their chroma and score
    int lo = 0, hi = 0;          // grid rows it rectifies: its own plus `reach` either side
    // Samples it makes, in the subsampled image: i (column), j (row).
    int i_begin = 0, i_end = 0, j_begin = 0, j_end = 0;
    int stride = 0;              // row stride of its sample box (in table order)
    size_t index_offset = 0;     // its table in BandPlan::index, rows lo..hi
  };
  std::vector<Band> bands;
  // Per band, for each cell of rows [lo, hi): the top-left sample in the
  // band's box. The fractions are the camera table's.
  std::vector<int32_t> index;
  size_t box_size = 0;  // samples in the largest box
  int reach = 0;        // rows

  // table: the table the rectification reads (transposed or not, as
  // `transposed` says). reach: score radius + gradient reach + 1.
  static BandPlan build(const RemapTable& table, bool transposed, int bands, int reach);
  // Rows of halo a band may need (for private buffers).
  int haloRows() const { return 2 * reach; }
};

}  // namespace dv
