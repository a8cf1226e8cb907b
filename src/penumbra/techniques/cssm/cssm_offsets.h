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
//   37: penumbra's, the 21 plus (+-2, 0), (0, +-2) (the gap around the
//       centre), (+-6, +-3) and (+-3, -+6) (between the rings) and
//       (+-8, +-8), (+-12, 0), (0, +-12) (an outer ring): less noise for
//       more blur (scripts/shadow-maps-fig2.sh, docs/PERFORMANCE.md)
namespace penumbra {

inline constexpr int kMaxCssmOffsets = 37;
inline constexpr int kCssmOffsets[kMaxCssmOffsets][2] = {
    {0, 0},  {3, 3},  {-3, 3},  {3, -3}, {-3, -3}, {4, 0},  {-4, 0},  {0, 4},   {0, -4},  {7, 0},  {-7, 0},
    {0, 7},  {0, -7}, {5, 5},   {-5, 5}, {5, -5},  {-5, -5}, {10, 0}, {-10, 0}, {0, 10},  {0, -10},
    {2, 0},  {-2, 0}, {0, 2},   {0, -2}, {6, 3},   {-6, -3}, {3, -6}, {-3, 6},  {8, 8},   {-8, 8}, {8, -8},
    {-8, -8}, {12, 0}, {-12, 0}, {0, 12}, {0, -12},
};

}  // namespace penumbra
