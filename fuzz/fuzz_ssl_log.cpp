// SSL log files: the header, every record and the index (src/io/ssl_log.cpp).
#include "fuzz_input.h"
#include "io/ssl_log.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dv::fuzz::inputFile(data, size, "fuzz.log");
  dv::fuzz::expectOnlyInputErrors([&] {
    dv::SslLogReader reader(path);
    dv::LogRecord record;
    while (reader.next(record)) {
    }
  });
  dv::fuzz::expectOnlyInputErrors([&] { dv::readSslLogIndex(path); });
  return 0;
}
