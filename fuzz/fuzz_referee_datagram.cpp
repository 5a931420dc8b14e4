// Datagrams the referee listener receives (its parse path,
// src/net/referee_listener.cpp).
#include "fuzz_input.h"
#include "net/referee_listener.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static dv::ssl::Referee packet;
  dv::parseRefereeDatagram(dv::fuzz::text(data, size), packet);
  return 0;
}
