#pragma once
// Lens terms beyond the league's model (LensTerms: k2, k3, p1, p2) fitted on
// the line pixels, after the league-model refinement. The terms are kept only
// when the lines support them: the Bayesian information criterion of the
// fit with the four extra parameters must beat the league model's
//   n ln(C_lens / C_league) + 4 ln n < 0
// where both models are fitted to the same objective: where short stretches
// of the model lines (bins of about 4 px) put the painted line's center,
// C their mean robust cost, n the number of bins counted as independent
// samples (n_bins (1 - rho) / (1 + rho), rho the correlation of neighbouring
// bins' residuals). A lens the league's model fits stays exactly that model
// (the calibration's numbers unchanged) and no threshold is tuned.
#include <vector>

#include "geometry/calibration/line_fit.h"

namespace dv {

struct LensFitResult {
  CameraParams params;           // the start, or with the lens terms when taken
  CameraParams league;           // the start: the league model's calibration
  bool lens_used = false;
  double league_rms_px = 0;      // rms distance of the matched line pixels, league model
  double lens_rms_px = 0;        // the same with the lens terms
  double information_gain = 0;   // -(n ln(C_lens / C_league) + 4 ln n); > 0 takes the terms
  int pixels = 0;                // matched at the final gate
};

LensFitResult fitLensOnLines(const CameraParams& league, const std::vector<ImagePx>& line_pixels,
                             const FieldLineModel& model, const std::vector<PointCorrespondence>& points,
                             const LineFitOptions& options);

}  // namespace dv
