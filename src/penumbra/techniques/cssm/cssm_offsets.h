#pragma once
// The lookup offsets Delta_j of a CSSM query (Weidner & Linsen, section 4),
// in texels of the map (the paper gives them for its 1024^2 maps; penumbra
// keeps them in texels at every resolution, so that a finer map blurs less):
//   13 (default, the paper's): (0, 0), (+-3, +-3), (+-4, 0), (0, +-4),
//                              (+-7, 0), (0, +-7)
//   7:  the first seven of that list, (0, 0), (+-3, +-3), (+-4, 0) (the
//       paper keeps "the 7 smallest offsets" for Fig. 2b without listing
//       them; by distance the choice would not be symmetric either)
//   21: the 13 plus (+-5, +-5), (+-10, 0), (0, +-10) (the paper adds
//       "further larger offsets" for Fig. 2a without listing them; these
//       close the ring at distance 7 and add one at 10)
namespace penumbra {

inline constexpr int kMaxCssmOffsets = 21;
inline constexpr int kCssmOffsets[kMaxCssmOffsets][2] = {
    {0, 0},  {3, 3},  {-3, 3},  {3, -3}, {-3, -3}, {4, 0},  {-4, 0},  {0, 4},   {0, -4},  {7, 0},  {-7, 0},
    {0, 7},  {0, -7}, {5, 5},   {-5, 5}, {5, -5},  {-5, -5}, {10, 0}, {-10, 0}, {0, 10},  {0, -10},
};

}  // namespace penumbra
