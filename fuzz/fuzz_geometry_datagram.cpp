// Datagrams the geometry publisher receives from processors
// (GeometryPublisher::handleDatagram), from an allowed sender.
#include <arpa/inet.h>
#include <spdlog/spdlog.h>

#include <memory>

#include "fuzz_input.h"
#include "net/geometry_publisher.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static std::unique_ptr<dv::GeometryPublisher> publisher = [] {
    spdlog::set_level(spdlog::level::off);
    dv::GeometryPublisherOptions o;
    o.listen_addr = "127.0.0.1";
    o.listen_port = 0;
    o.interface_addr = "127.0.0.1";
    o.port = 10999;  // nothing is published: start() is never called
    o.num_cameras = 8;
    return std::make_unique<dv::GeometryPublisher>(dv::Geometry{dv::FieldModel::divisionB(), {}}, o);
  }();
  publisher->handleDatagram(reinterpret_cast<const char*>(data), size, inet_addr("127.0.0.1"));
  return 0;
}
