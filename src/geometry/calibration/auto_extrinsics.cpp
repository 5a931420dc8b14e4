#include "geometry/calibration/auto_extrinsics.h"

namespace dv {

AutoExtrinsicsResult findPoseAutomatically(const LineObservation&, const PixelDistortion&,
                                           const FieldModel&, const FieldRect&, int, int,
                                           const AutoExtrinsicsOptions&) {
  AutoExtrinsicsResult r;
  r.reason = "automatic mode not available yet";
  return r;
}

}  // namespace dv
