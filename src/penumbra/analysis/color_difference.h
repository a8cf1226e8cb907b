#pragma once
// Colour differences between two CIE L*a*b* colours. One unit is roughly a
// just-noticeable difference for CIEDE2000; CIE76 overstates differences of
// saturated colours and is kept for comparison with older papers.
#include "penumbra/analysis/color_space.h"

namespace penumbra {

// CIE 1976: Euclidean distance in L*a*b*.
double delta_e_76(const Lab& first, const Lab& second);

// CIEDE2000 with kL = kC = kH = 1, in the formulation of G. Sharma, W. Wu and
// E. N. Dalal, "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations", Color Research and
// Application 30(1), 2005 (equations 1-22). Symmetric in its arguments.
double delta_e_2000(const Lab& first, const Lab& second);

}  // namespace penumbra
