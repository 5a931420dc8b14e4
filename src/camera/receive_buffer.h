#pragma once
// The kernel's cap on a socket's receive buffer. A GigE Vision frame is a
// burst of thousands of UDP packets; when the stream socket's buffer cannot
// hold a frame or two, packets drop at full rate. Linux silently caps the
// size asked for at net.core.rmem_max, so the cap is read and reported.
#include <cstddef>
#include <string>

namespace dv {

// Bytes in /proc/sys/net/core/rmem_max; -1 where it cannot be read.
long readRmemMax();

// Receive buffer to ask for a stream of `payload`-byte frames: room for a
// few frames, within sane limits.
size_t streamSocketBufferBytes(size_t payload);

// Empty when `rmem_max` allows `requested` (or is unknown); else one line
// for `source` saying so and how to raise it.
std::string rmemCapMessage(const std::string& source, size_t requested, long rmem_max);

}  // namespace dv
