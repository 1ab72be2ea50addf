#pragma once
// Measured surge front of a collapsing water column: the physical reference of the dam-break test
// (tests/sim/fluid_dam_break_test.cpp) and of `spume report`'s fluid study. Data only.
//
// J. C. Martin, W. J. Moyce, "An experimental study of the collapse of liquid columns on a rigid
// horizontal plane", Phil. Trans. R. Soc. Lond. A 244 (1952) 312-324: the n^2 = 2 column (width a =
// 2.25 in, height 2a), as commonly reproduced in the SPH/MPS literature. Non-dimensional front
// Z = z / a (z: distance of the front from the back wall) over T = t sqrt(2 g / a). The Z values step
// by 1/9 of a, as readings at 1/4 in marks would.
#include <array>

namespace spume {

struct SurgeFrontPoint {
  double T, Z;
};

inline constexpr std::array<SurgeFrontPoint, 10> kMartinMoyce1952 = {{{0.41, 1.11},
                                                                      {0.84, 1.22},
                                                                      {1.19, 1.44},
                                                                      {1.43, 1.67},
                                                                      {1.63, 1.89},
                                                                      {1.83, 2.11},
                                                                      {1.98, 2.33},
                                                                      {2.20, 2.56},
                                                                      {2.32, 2.78},
                                                                      {2.51, 3.00}}};

}  // namespace spume
