// GET /api/cameras/ID/colors: the camera's learned color classes, the pair
// separations and its recent blobs' colors, all as chromaticity (r, g, b
// scaled to sum to about 300; color_classes.h), for the Colors page.
#include <nlohmann/json.hpp>

#include "app/console_http.h"
#include "app/console_state.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv::app {

void addColorsApi(httplib::Server& server, ConsoleState& state) {
  server.Get(R"(/api/cameras/(\d+)/colors)", [&state](const httplib::Request& req, httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    CameraFeed::Colors c;
    if (!feed->colors(c))  // the first ask starts the copies: the next frame brings them
      return sendJson(res, {{"camera_id", feed->cameraId()}, {"classes", nullptr}, {"blobs", nlohmann::json::array()}});
    const auto vec = [](const ColorVec& v) { return nlohmann::json::array({v.c[0], v.c[1], v.c[2]}); };
    nlohmann::json classes = nlohmann::json::object();
    for (int i = 0; i < Detector::kClassColorCount; ++i) classes[Detector::classColorName(i)] = vec(c.classes[i]);
    nlohmann::json blobs = nlohmann::json::array();
    for (const CameraFeed::BlobColor& b : c.blobs) blobs.push_back({b.color.c[0], b.color.c[1], b.color.c[2], b.score});
    sendJson(res, {{"camera_id", feed->cameraId()},
                   {"classes", classes},
                   {"separations",
                    {{"yellow_blue", c.separations.yellow_blue},
                     {"green_pink", c.separations.green_pink},
                     {"orange_field", c.separations.orange_field}}},
                   {"blobs", blobs}});
  });
}

}  // namespace dv::app
