#pragma once
// Reading detection frames for evaluation: ground truth as JSONL (one
// canonical-JSON SSL_DetectionFrame per line) and detections as JSONL (one
// SSL_WrapperPacket per line) or as an SSL log file (plain or gzip).
#include <string>
#include <vector>

#include "dotvision/ssl_detection.pb.h"

namespace dv {

struct DetectionFile {
  std::vector<ssl::SSL_DetectionFrame> frames;
  // Problems that did not stop reading (a log cut short after some records),
  // each naming the file and the place.
  std::vector<std::string> warnings;
};

// One SSL_DetectionFrame per non-empty line. Throws InputError naming the
// file and the line for a malformed line, or when the file cannot be read.
DetectionFile readTruthJsonl(const std::string& path);

// Detections from JSONL (SSL_WrapperPacket per line; a bare SSL_DetectionFrame
// line is accepted too; geometry-only packets are skipped) or from an SSL
// log (recognised by its header, also inside gzip). Vision2014 records are
// decoded; other record types are ignored. A log that ends in the middle of a
// record keeps the complete records and reports the cut as a warning; a
// record that is not a valid SSL_WrapperPacket throws InputError with its
// byte offset. A file without any detection frame gets a warning (an empty
// or wrong file would otherwise score as recall 0 without a word); a damaged
// log header is reported as such.
DetectionFile readDetectionFile(const std::string& path);

}  // namespace dv
