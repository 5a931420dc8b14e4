#pragma once
// Frames a camera numbered but never delivered, from two successive frame
// ids. GigE Vision 1.x block ids are 16 bits and wrap from 65535 to 1 (0 is
// invalid); a jump back that is not a wrap (the camera restarted) counts
// nothing.
#include <cstdint>

namespace dv {

inline uint64_t missedFrameIds(uint64_t previous, uint64_t current) {
  if (previous == 0 || current == 0) return 0;
  if (current > previous) return current - previous - 1;
  if (previous <= 0xffff) {
    const uint64_t wrapped = (0xffff - previous) + (current - 1);
    if (wrapped < 0x1000) return wrapped;  // a short gap across the wrap
  }
  return 0;  // restarted numbering
}

}  // namespace dv
