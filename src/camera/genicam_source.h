#pragma once
// A GenICam camera (GigE Vision or USB3 Vision) through Aravis, as a
// CameraSource: `--source genicam://ID`. ID is the Aravis device id, the
// serial number, the GigE address or MAC, or empty for the only camera
// present.
//
// At open: continuous acquisition, auto exposure and auto gain off, a
// usable color pixel format (the camera's own if it is one, else its best
// Bayer or RGB format; monochrome-only cameras are refused), the camera's
// maximum frame rate up to GenicamOptions::max_fps, and for GigE the packet
// size negotiated for the link. Settings (by GenICam feature name) then
// override these. Frames keep the Bayer layout the camera reports.
#include <memory>
#include <string>
#include <vector>

#include "io/camera_source.h"

namespace dv {

struct GenicamOptions {
  double max_fps = 75;   // start-up frame rate: the camera's maximum, capped here
  int buffers = 8;       // stream buffers allocated once per stream
  double stall_s = 0.5;  // no frame this long: ask the camera whether it still answers
};

class GenicamSource : public CameraSource {
 public:
  // Opens the camera. Throws InputError naming "genicam://ID": no such
  // camera (listing the ids present), it cannot be opened, or it offers no
  // color format.
  explicit GenicamSource(const std::string& id, GenicamOptions options = {});
  ~GenicamSource() override;
  GenicamSource(const GenicamSource&) = delete;
  GenicamSource& operator=(const GenicamSource&) = delete;

  // Starts the stream on the first call. Incomplete or corrupt buffers are
  // Skipped (counted); a camera that stops answering or whose control is
  // lost is Lost until reconnect() succeeds.
  GrabStatus grab(Frame& f, double timeout_s, std::string& why) override;
  // Re-opens the same camera (by its Aravis device id), re-applies the
  // start-up defaults and every setting applied so far, restarts the stream.
  bool reconnect(std::string& why) override;
  // Not concurrently with grab(); stops the stream while applying.
  std::vector<std::string> applySettings(const std::vector<CameraSetting>& settings) override;
  void interrupt() override;
  std::string describe() const override;
  bool live() const override { return true; }
  SourceCounters counters() const override;

  // The Aravis device id the ID resolved to ("Aravis-Fake-GV01").
  const std::string& deviceId() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dv
