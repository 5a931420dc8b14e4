#include "eval/detection_files.h"

#include <zlib.h>

#include <fstream>

#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "geometry/proto_json.h"
#include "io/ssl_log.h"

namespace dv {

namespace {

// The first bytes of the (decompressed) file, to tell a log from JSONL.
std::string leadingBytes(const std::string& path, int n) {
  gzFile f = gzopen(path.c_str(), "rb");  // reads plain files transparently
  if (!f) throw InputError(path, "cannot open the file");
  std::string out(static_cast<size_t>(n), '\0');
  const int got = gzread(f, out.data(), static_cast<unsigned>(n));
  gzclose(f);
  out.resize(got > 0 ? static_cast<size_t>(got) : 0);
  return out;
}

template <typename LineFn>
void forEachLine(const std::string& path, LineFn fn) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the file");
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    fn(line, line_no);
  }
  if (in.bad()) throw InputError(path, "read error after line " + std::to_string(line_no));
}

std::string lineSource(const std::string& path, int line_no) {
  return path + ":" + std::to_string(line_no);
}

DetectionFile readDetectionJsonl(const std::string& path) {
  DetectionFile out;
  ssl::SSL_WrapperPacket packet;
  forEachLine(path, [&](const std::string& line, int line_no) {
    try {
      parseCanonicalJson(line, packet, lineSource(path, line_no));
    } catch (const InputError& wrapper_error) {
      // Accept a bare detection frame too, but report the wrapper's complaint
      // when the line is neither.
      ssl::SSL_DetectionFrame frame;
      try {
        parseCanonicalJson(line, frame, lineSource(path, line_no));
      } catch (const InputError&) {
        throw wrapper_error;
      }
      out.frames.push_back(std::move(frame));
      return;
    }
    if (packet.has_detection()) out.frames.push_back(packet.detection());
  });
  return out;
}

DetectionFile readDetectionLog(const std::string& path) {
  DetectionFile out;
  SslLogReader reader(path);
  LogRecord record;
  ssl::SSL_WrapperPacket packet;
  while (true) {
    const int64_t offset = reader.offset();
    try {
      if (!reader.next(record)) break;
    } catch (const InputError& e) {
      // A recorder killed mid-write leaves a partial last record; what came
      // before it is still good data.
      out.warnings.push_back(std::string(e.what()) + " (kept the " +
                             std::to_string(out.frames.size()) + " detection frames before it)");
      break;
    }
    if (record.type != LogMessageType::Vision2014) continue;
    // Partial parse, then the check: protobuf's own parse would print its
    // "libprotobuf ERROR" line before this message.
    if (!packet.ParsePartialFromString(record.payload)) {
      throw InputError(path, "record at byte " + std::to_string(offset) +
                                 ": payload is not a valid SSL_WrapperPacket");
    }
    if (!packet.IsInitialized()) {
      throw InputError(path, "record at byte " + std::to_string(offset) +
                                 ": SSL_WrapperPacket lacks required fields (" +
                                 packet.InitializationErrorString() + ")");
    }
    if (packet.has_detection()) out.frames.push_back(packet.detection());
  }
  return out;
}

}  // namespace

DetectionFile readTruthJsonl(const std::string& path) {
  DetectionFile out;
  forEachLine(path, [&](const std::string& line, int line_no) {
    ssl::SSL_DetectionFrame frame;
    parseCanonicalJson(line, frame, lineSource(path, line_no));
    out.frames.push_back(std::move(frame));
  });
  return out;
}

DetectionFile readDetectionFile(const std::string& path) {
  const std::string head = leadingBytes(path, 12);
  // A damaged log header goes to the log reader, which names the damage.
  DetectionFile out = looksLikeSslLogHeader(head) ? readDetectionLog(path) : readDetectionJsonl(path);
  if (out.frames.empty()) out.warnings.push_back(path + ": holds no detection frames");
  return out;
}

}  // namespace dv
