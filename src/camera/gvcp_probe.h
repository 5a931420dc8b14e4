#pragma once
// A quick "are you there?" for a GigE Vision camera: one GVCP register
// read on a socket of its own, with a short timeout. Aravis 0.8's own reads
// retry for seconds (and share a lock with its heartbeat), too slow to
// notice an unplugged camera within a second. Any answer counts, also an
// error answer (a camera held exclusively by us refuses other readers).
#include <string>

namespace dv {

// True when the camera at IPv4 `ip` (UDP port 3956) answers a read of its
// version register within `timeout_s`, trying `attempts` times.
bool gvcpCameraAnswers(const std::string& ip, double timeout_s = 0.2, int attempts = 2);

}  // namespace dv
