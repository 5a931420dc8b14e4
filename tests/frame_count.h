#pragma once
// Reads a frame source to its end, counting the frames it gives and
// keeping what it printed to stderr: the readers' tests hold both (a bad
// file is skipped with the project's reason, never OpenCV's own lines).
#include <gtest/gtest.h>

#include <string>

#include "io/frame_source.h"

namespace dv::test {

struct FramesRead {
  int frames = 0;
  std::string printed;  // stderr while reading
};

inline FramesRead readAllFrames(FrameSource& source) {
  FramesRead out;
  Frame f;
  ::testing::internal::CaptureStderr();
  while (source.next(f)) ++out.frames;
  out.printed = ::testing::internal::GetCapturedStderr();
  return out;
}

}  // namespace dv::test
